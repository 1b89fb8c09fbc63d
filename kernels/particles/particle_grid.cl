// Particle-grid transfers of the hybrid mode (spec §6): particles to grid (P2G) by gather, and grid
// to particles (G2P), both with the tensor-product cubic B-spline weights of OpenLISEM Hazard P.87.
//
// Weights. Terrain cell (i, j) spans [i dx, (i + 1) dx) x [j dx, (j + 1) dx), its centre is
// x_c = ((i + 1/2) dx, (j + 1/2) dx). A particle at x_p gives the cell the weight
//   w_pc = N((x_p - x_c) / dx) N((y_p - y_c) / dx),                                           (P.87)
//   N(d) = 1/2 |d|^3 - d^2 + 2/3   (|d| < 1),   (2 - |d|)^3 / 6   (1 <= |d| < 2),   0 beyond,
// the centred cubic B-spline on the unit-spaced cell centres. (The paper's copy prints the branch
// conditions garbled; this is the spline of Steffen et al. 2008 and Stomakhin et al. 2013 it cites.)
// In one dimension a particle touches at most the four cells k = floor(f) - 1 .. floor(f) + 2 with
// f = x_p / dx - 1/2 its position in cell-centre units, and sum_k N(f - k) = 1 (partition of unity)
// and sum_k k N(f - k) = f (linear functions are reproduced) for every f.
//
// Raster edge. A stencil cell k outside 0..n-1 is folded onto the edge cell clamp(k, 0, n - 1), per
// axis: the edge cell takes the weight of the virtual cells beyond it. The folded weights are still a
// partition of unity over the raster, so P2G conserves volume, mass and momentum exactly (to
// round-off) for every particle, including particles near the edges and corners and particles
// slightly outside the raster (they are removed at the end of their sub-step; until then their mass
// sits in the nearest edge cells). G2P with folded weights reads the edge value for a virtual cell,
// i.e. the field continued by a constant beyond the raster; it is exact for linear fields where the
// whole 4 x 4 stencil lies inside (1.5 dx <= x_p <= (n - 1.5) dx) and exact for constants anywhere.
// Folding keeps P2G and G2P transposes of each other: sum_c f_c P2G(q)_c = sum_p q_p G2P(f)_p.
//
// P2G by gather (no atomics). Each terrain cell sums over the particles that can reach it; one
// work-item does this for a block of 2 x 2 cells, reading each candidate particle once for the four
// (for h = dx a block visits as many neighbour cells as a single cell would, so this quarters the
// reads; each cell still adds the same particles in the same order as a gather of its own would). The
// particles that reach a cell lie within 2 dx of its centre, x in (x_c - 2 dx, x_c + 2 dx), likewise
// in y (for an edge cell the interval extends to the end of the neighbour grid on that side, for the
// folded weight). The neighbour grid (neighbours.cl) has cells of edge cell_size = 2h (1 + tiny), h
// the SPH smoothing length. A cell's interval is L = 4 dx / cell_size neighbour cells long and covers
// ceil(L) or ceil(L) + 1 columns: 3 for the usual h = dx on the solver's grid (box = raster plus 2h,
// so the interval ends fall near quarter cells), 5 for h = dx / 2, 2 or 3 for h = 2 dx; a block's
// interval is dx longer (still 3 columns for h = dx). The range is computed from the interval, so any
// ratio works. The interval ends are widened by 1/64 of a neighbour cell, more than the rounding of
// the computed cell coordinate (a few units of round-off times the cell count), so no particle with a
// non-zero weight is missed however the device rounds. Inside the range a position test against the
// supports widened by a quarter cell rejects most particles without a weight before the spline is
// evaluated (for h = dx a block visits 36 dx^2, and its cells' supports cover 25 dx^2 of that). The
// particles inside a neighbour cell are visited in sorted order, cells row by row: the summation order
// depends only on the sorted arrays, so the result is bitwise reproducible run to run. (A different
// input order of the same particles changes the order within one neighbour cell, which follows the
// index before sorting, and hence the sums by round-off only.)
//
// G2P: one work-item per particle interpolates cell fields with the same weights over its 4 x 4
// stencil. The velocity transfer blends PIC and FLIP (Brackbill's FLIP, Zhu & Bridson 2005):
//   v_p <- (1 - a) (v_p + dv(x_p)) + a v(x_p),
// with v the grid velocity after the grid step and dv its change during the step; a = 1 is PIC
// (the particle takes the grid velocity, dissipative), a = 0 is FLIP (the particle keeps its own
// velocity plus the grid's change, noisy but non-dissipative). Every cell of a particle's stencil
// with a non-zero weight received mass from that particle in P2G, so the velocities read are defined.
#include "common/real.cl"
#include "particles/neighbours.cl"

/// The centred cubic B-spline N(d) of P.87 (cell-centre units; support |d| < 2).
INLINE real pg_bspline(real d) {
  const real a = fabs(d);
  if (a < (real)1) return ((real)0.5 * a - (real)1) * a * a + (real)2 / (real)3;
  if (a < (real)2) {
    const real b = (real)2 - a;
    return b * b * b / (real)6;
  }
  return (real)0;
}

/// Position in cell-centre units along one axis: f = x / dx - 1/2 (cell k's centre is at f = k).
INLINE real pg_centre_coord(real x, real dx) { return x / dx - (real)0.5; }

/// The folded weight of cell i (0 <= i < n) along one axis for a particle at f (see the header):
/// N(f - i) for an inner cell, the sum of N(f - k) over the stencil cells k that fold onto i for the
/// edge cells 0 and n - 1. Clamping f to [-3, n + 2] changes nothing (beyond it every stencil cell
/// folds onto one edge cell and the weights sum to 1 either way) and keeps the int conversion finite.
INLINE real pg_axis_weight(real f, int i, int n) {
  if (i > 0 && i < n - 1) return pg_bspline(f - (real)i);
  const real fc = clamp(f, (real)-3, (real)(n + 2));
  const int kb = (int)floor(fc);
  real w = 0;
  for (int k = kb - 1; k <= kb + 2; ++k)
    if (clamp(k, 0, n - 1) == i) w += pg_bspline(fc - (real)k);
  return w;
}

/// Neighbour-grid columns (or rows) that hold every particle with a non-zero weight for the terrain
/// cells first..last of n along an axis: the interval (c_first - 2 dx, c_last + 2 dx) around their
/// centres, open-ended on the side of an edge cell, widened by 1/64 cell and clamped to the grid.
/// Returns (first column, last column), inclusive.
INLINE int2 pg_neighbour_span(int first, int last, int n, real dx, real lo_box, real cell_size, int cells) {
  const real margin = (real)0.015625;
  int2 r = (int2)(0, cells - 1);
  if (first > 0) {
    const real lo = ((real)first - (real)1.5) * dx;
    r.x = (int)clamp(floor((lo - lo_box) / cell_size - margin), (real)0, (real)(cells - 1));
  }
  if (last < n - 1) {
    const real hi = ((real)last + (real)2.5) * dx;
    r.y = (int)clamp(floor((hi - lo_box) / cell_size + margin), (real)0, (real)(cells - 1));
  }
  return r;
}

/// A terrain block of PG_BLOCK x PG_BLOCK cells (clipped at the raster's far edges): one work-item
/// of a P2G kernel. Its particles are read once for all its cells; each cell's sum still adds the
/// same particles in the same order as a gather for that cell alone would (visiting more particles
/// only adds terms that are skipped), so the blocking changes no result bit.
#define PG_BLOCK 2

typedef struct {
  int i0, j0;                // lower-left cell
  int ni, nj;                // cells in the block along x and y (1 or 2; ni = 0: no block)
  NeighbourCellRange cells;  // neighbour-grid cells to visit
  real4 reach;               // (x0, x1, y0, y1): particles outside have no weight in the block
} PgBlock;

/// Block b of an nx x ny raster (row-major over blocks); ni = 0 for a work-item past the end.
INLINE PgBlock pg_block(__constant const NeighbourGridParams* g, int b, int nx, int ny, real dx) {
  PgBlock k;
  const int bx = (nx + PG_BLOCK - 1) / PG_BLOCK, by = (ny + PG_BLOCK - 1) / PG_BLOCK;
  k.ni = 0, k.nj = 0, k.i0 = 0, k.j0 = 0;
  if (b >= bx * by) return k;
  k.i0 = PG_BLOCK * (b % bx), k.j0 = PG_BLOCK * (b / bx);
  k.ni = min(PG_BLOCK, nx - k.i0), k.nj = min(PG_BLOCK, ny - k.j0);
  const int i1 = k.i0 + k.ni - 1, j1 = k.j0 + k.nj - 1;
  const int2 sx = pg_neighbour_span(k.i0, i1, nx, dx, g->x_min, g->cell_size, g->cells_x);
  const int2 sy = pg_neighbour_span(k.j0, j1, ny, dx, g->y_min, g->cell_size, g->cells_y);
  k.cells.x0 = sx.x, k.cells.x1 = sx.y, k.cells.y0 = sy.x, k.cells.y1 = sy.y;
  // A cheap pre-filter: the support widened by a quarter cell (rounding never rejects a particle
  // with a weight), open-ended towards the raster edge for the edge cells.
  k.reach.s0 = k.i0 > 0 ? ((real)k.i0 - (real)1.75) * dx : -REAL_MAX;
  k.reach.s1 = i1 < nx - 1 ? ((real)i1 + (real)2.75) * dx : REAL_MAX;
  k.reach.s2 = k.j0 > 0 ? ((real)k.j0 - (real)1.75) * dx : -REAL_MAX;
  k.reach.s3 = j1 < ny - 1 ? ((real)j1 + (real)2.75) * dx : REAL_MAX;
  return k;
}

/// The weights of the particle at (xp, yp) for the block's cells: w[r * PG_BLOCK + m] for cell
/// (i0 + m, j0 + r) (0 for cells beyond the raster). Returns 0 when all of them are 0.
INLINE int pg_block_weights(const PgBlock* k, real xp, real yp, int nx, int ny, real dx, real* w) {
  const real fx = pg_centre_coord(xp, dx), fy = pg_centre_coord(yp, dx);
  real wx[PG_BLOCK], wy[PG_BLOCK];
  for (int m = 0; m < PG_BLOCK; ++m) {
    wx[m] = m < k->ni ? pg_axis_weight(fx, k->i0 + m, nx) : (real)0;
    wy[m] = m < k->nj ? pg_axis_weight(fy, k->j0 + m, ny) : (real)0;
  }
  int any = 0;
  for (int r = 0; r < PG_BLOCK; ++r)
    for (int m = 0; m < PG_BLOCK; ++m) {
      w[r * PG_BLOCK + m] = wx[m] * wy[r];
      any |= w[r * PG_BLOCK + m] != (real)0;
    }
  return any;
}

/// pg_block_weights for a particle inside the block's reach (the cheap pre-filter first), else 0.
INLINE int pg_particle_weights(const PgBlock* k, real xp, real yp, int nx, int ny, real dx, real* w) {
  if (xp <= k->reach.s0 || xp >= k->reach.s1 || yp <= k->reach.s2 || yp >= k->reach.s3) return 0;
  return pg_block_weights(k, xp, yp, nx, ny, dx, w);
}

/// Visits the particles p (uint, sorted index) of the neighbour cells of block k that weigh on it,
/// with their weights w[PG_BLOCK * PG_BLOCK] (declared here), in the fixed order of the tables:
///   PG_FOR_EACH_PARTICLE(k, ng, cell_start, cell_end, x, y, nx, ny, dx, p, w) { ... }
#define PG_FOR_EACH_PARTICLE(k, ng, start, end, x, y, nx, ny, dx, p, w)                                    \
  for (int pg_cy = (k).cells.y0; pg_cy <= (k).cells.y1; ++pg_cy)                                           \
    for (int pg_cx = (k).cells.x0; pg_cx <= (k).cells.x1; ++pg_cx)                                         \
      for (uint p = start[neighbour_cell_key(ng, pg_cx, pg_cy)], pg_end = end[neighbour_cell_key(ng, pg_cx, pg_cy)]; \
           p < pg_end; ++p)                                                                              \
        for (real w[PG_BLOCK * PG_BLOCK], *pg_ok = pg_particle_weights(&(k), x[p], y[p], nx, ny, dx, w) ? w : 0; \
             pg_ok; pg_ok = 0)

/// P2G of two particle weights and a momentum-like pair, for every terrain cell c:
///   out_a[c]  = scale_a sum_p w_pc a_p,
///   out_b[c]  = scale_b sum_p w_pc b_p,
///   out_bu[c] = scale_b sum_p w_pc b_p u_p,   out_bv[c] = scale_b sum_p w_pc b_p v_p,
/// over the particles of the neighbour grid's tables (arrays in sorted order); one work-item per
/// block of PG_BLOCK x PG_BLOCK cells. Confined phase: a = volume, scale_a = 1 / dx^2 (thickness),
/// b = mass, scale_b = 1 (mass, momentum). Released fluid: a = b = released volume, both scales
/// 1 / dx^2 (added thickness, added discharge). With accumulate != 0 the results are added to the
/// outputs instead of replacing them.
__kernel void particles_to_grid(const int nx, const int ny, const real dx, __constant const NeighbourGridParams* ng,
                                __global const uint* cell_start, __global const uint* cell_end,
                                __global const real* x, __global const real* y, __global const real* a,
                                __global const real* b, __global const real* u, __global const real* v,
                                const real scale_a, const real scale_b, const int accumulate, __global real* out_a,
                                __global real* out_b, __global real* out_bu, __global real* out_bv) {
  const PgBlock k = pg_block(ng, get_global_id(0), nx, ny, dx);
  if (k.ni == 0) return;
  real sa[PG_BLOCK * PG_BLOCK], sb[PG_BLOCK * PG_BLOCK], sbu[PG_BLOCK * PG_BLOCK], sbv[PG_BLOCK * PG_BLOCK];
  for (int q = 0; q < PG_BLOCK * PG_BLOCK; ++q) sa[q] = sb[q] = sbu[q] = sbv[q] = (real)0;
  PG_FOR_EACH_PARTICLE(k, ng, cell_start, cell_end, x, y, nx, ny, dx, p, w) {
    const real ap = a[p], bp = b[p], up = u[p], vp = v[p];
    for (int q = 0; q < PG_BLOCK * PG_BLOCK; ++q) {
      if (w[q] == (real)0) continue;
      const real wb = w[q] * bp;
      sa[q] += w[q] * ap;
      sb[q] += wb;
      sbu[q] += wb * up;
      sbv[q] += wb * vp;
    }
  }
  for (int r = 0; r < k.nj; ++r)
    for (int m = 0; m < k.ni; ++m) {
      const int c = (k.j0 + r) * nx + k.i0 + m, q = r * PG_BLOCK + m;
      out_a[c] = (accumulate ? out_a[c] : (real)0) + scale_a * sa[q];
      out_b[c] = (accumulate ? out_b[c] : (real)0) + scale_b * sb[q];
      out_bu[c] = (accumulate ? out_bu[c] : (real)0) + scale_b * sbu[q];
      out_bv[c] = (accumulate ? out_bv[c] : (real)0) + scale_b * sbv[q];
    }
}

/// P2G of an arbitrary particle field f weighted by q (mass or volume), one work-item per block:
///   mean == 0:  out[c] = sum_p w_pc q_p f_p,
///   mean != 0:  out[c] = sum_p w_pc q_p f_p / sum_p w_pc q_p  (0 where no particle reaches c).
__kernel void particles_field_to_grid(const int nx, const int ny, const real dx,
                                      __constant const NeighbourGridParams* ng, __global const uint* cell_start,
                                      __global const uint* cell_end, __global const real* x, __global const real* y,
                                      __global const real* q, __global const real* f, const int mean,
                                      __global real* out) {
  const PgBlock k = pg_block(ng, get_global_id(0), nx, ny, dx);
  if (k.ni == 0) return;
  real sq[PG_BLOCK * PG_BLOCK], sqf[PG_BLOCK * PG_BLOCK];
  for (int t = 0; t < PG_BLOCK * PG_BLOCK; ++t) sq[t] = sqf[t] = (real)0;
  PG_FOR_EACH_PARTICLE(k, ng, cell_start, cell_end, x, y, nx, ny, dx, p, w) {
    const real qp = q[p], fp = f[p];
    for (int t = 0; t < PG_BLOCK * PG_BLOCK; ++t) {
      if (w[t] == (real)0) continue;
      const real wq = w[t] * qp;
      sq[t] += wq;
      sqf[t] += wq * fp;
    }
  }
  for (int r = 0; r < k.nj; ++r)
    for (int m = 0; m < k.ni; ++m) {
      const int c = (k.j0 + r) * nx + k.i0 + m, t = r * PG_BLOCK + m;
      out[c] = mean ? (sq[t] != (real)0 ? sqf[t] / sq[t] : (real)0) : sqf[t];
    }
}

/// The 4 x 4 stencil of a particle for G2P: folded cell columns and rows and their weights.
typedef struct {
  int col[4], row[4];
  real wx[4], wy[4];
} PgStencil;

/// Stencil of the particle at (x, y); `ok` is 0 for a non-finite position (no weights).
INLINE PgStencil pg_stencil_of(real x, real y, int nx, int ny, real dx, int* ok) {
  PgStencil s;
  const real fx = pg_centre_coord(x, dx), fy = pg_centre_coord(y, dx);
  *ok = isfinite(fx) && isfinite(fy);
  const real cx = *ok ? clamp(fx, (real)-3, (real)(nx + 2)) : (real)0;
  const real cy = *ok ? clamp(fy, (real)-3, (real)(ny + 2)) : (real)0;
  const int kx = (int)floor(cx) - 1, ky = (int)floor(cy) - 1;
  for (int m = 0; m < 4; ++m) {
    s.col[m] = clamp(kx + m, 0, nx - 1);
    s.row[m] = clamp(ky + m, 0, ny - 1);
    s.wx[m] = pg_bspline(cx - (real)(kx + m));
    s.wy[m] = pg_bspline(cy - (real)(ky + m));
  }
  return s;
}

/// sum over the stencil of w f (rows outer, columns inner).
INLINE real pg_sample(const PgStencil* s, __global const real* f, int nx) {
  real sum = 0;
  for (int r = 0; r < 4; ++r) {
    real row = 0;
    const int base = s->row[r] * nx;
    for (int m = 0; m < 4; ++m) row += s->wx[m] * f[base + s->col[m]];
    sum += s->wy[r] * row;
  }
  return sum;
}

/// G2P of a cell field: out[p] = sum_c w_pc field[c] for particles 0..n-1 (0 at a non-finite position).
__kernel void grid_to_particles(const int nx, const int ny, const real dx, __global const real* field,
                                __global const real* x, __global const real* y, const uint n, __global real* out) {
  const uint p = get_global_id(0);
  if (p >= n) return;
  int ok;
  const PgStencil s = pg_stencil_of(x[p], y[p], nx, ny, dx, &ok);
  out[p] = ok ? pg_sample(&s, field, nx) : (real)0;
}

/// G2P of the grid velocity with the PIC/FLIP blend (header): for particles 0..n-1,
///   v_p <- (1 - pic) (v_p + dv(x_p)) + pic v(x_p),
/// u, v the cell velocity after the grid step, du, dv its change. Non-finite positions: unchanged.
__kernel void grid_velocity_to_particles(const int nx, const int ny, const real dx, __global const real* u,
                                         __global const real* v, __global const real* du, __global const real* dv,
                                         const real pic, __global const real* x, __global const real* y,
                                         const uint n, __global real* vx, __global real* vy) {
  const uint p = get_global_id(0);
  if (p >= n) return;
  int ok;
  const PgStencil s = pg_stencil_of(x[p], y[p], nx, ny, dx, &ok);
  if (!ok) return;
  const real flip = (real)1 - pic;
  vx[p] = flip * (vx[p] + pg_sample(&s, du, nx)) + pic * pg_sample(&s, u, nx);
  vy[p] = flip * (vy[p] + pg_sample(&s, dv, nx)) + pic * pg_sample(&s, v, nx);
}
