// Shared definitions of the shallow-water kernels: the parameter block (mirrored by
// src/flow/FlowParams.hpp), cell and face indexing, the tile map, limiters and the reconstruction.
//
// Build options: -DLIMITER=0 (minmod) | 1 (van Leer) | 2 (monotonised central) | 3 (none: first order),
//                -DRIEMANN=0 (HLL) | 1 (HLLC), -DTILE=16 (tile edge in cells),
//                -DSPLIT=0 (unsplit time scheme) | 1 (dimensionally split: per-direction CFL speed),
//                -DHANCOCK=0 | 1 (the split sweeps as one MUSCL-Hancock stage each: flow/hancock.cl).
#ifndef TALUS_FLOW_COMMON_CL
#define TALUS_FLOW_COMMON_CL
#include "common/real.cl"

#ifndef LIMITER
#define LIMITER 1
#endif
#ifndef RIEMANN
#define RIEMANN 1
#endif
#ifndef TILE
#define TILE 16
#endif
#ifndef SPLIT
#define SPLIT 0
#endif
#ifndef HANCOCK
#define HANCOCK 0
#endif

#define BOUNDARY_WALL 0
#define BOUNDARY_OPEN 1
#define BOUNDARY_LEVEL 2

/// Run constants in __constant memory. Layout checked against the host struct by static_assert.
typedef struct {
  int nx, ny;             // cells
  int tiles_x, tiles_y;   // tiles of TILE x TILE cells
  int edge_boundary;      // BOUNDARY_WALL, BOUNDARY_OPEN or BOUNDARY_LEVEL at the raster edge
  int nodata_boundary;    // same, at faces to nodata cells
  int skip_dry_tiles;     // 0: every tile active
  int pad0;
  real dx;                // cell size [m]
  real h_dry;             // below this thickness velocities are zero [m]
  real arrival_h;         // thickness that marks arrival [m]
  real pad1;
} FlowParams;

INLINE int cell_index(__constant const FlowParams* p, int i, int j) { return j * p->nx + i; }

/// 1 inside the domain (on the raster and not nodata), 0 outside.
INLINE int cell_inside(__constant const FlowParams* p, __global const uchar* mask, int i, int j) {
  if (i < 0 || j < 0 || i >= p->nx || j >= p->ny) return 0;
  return mask[j * p->nx + i] != 0;
}

/// Boundary type of the face from inside cell (i,j) to the outside cell (io,jo).
INLINE int boundary_kind(__constant const FlowParams* p, int io, int jo) {
  const int off_raster = io < 0 || jo < 0 || io >= p->nx || jo >= p->ny;
  return off_raster ? p->edge_boundary : p->nodata_boundary;
}

/// The cell of this work-item: work-group g handles the tile tile_list[g] (active tiles only, in
/// ascending order), one work-item per cell. Work-items past the raster edge get i >= nx or j >= ny.
INLINE int2 tile_cell(__constant const FlowParams* p, __global const int* tile_list) {
  const int tile = tile_list[get_group_id(0)];
  const int tx = tile % p->tiles_x, ty = tile / p->tiles_x;
  return (int2)(tx * TILE + (int)get_local_id(0), ty * TILE + (int)get_local_id(1));
}

/// Velocity from momentum. Kurganov & Petrova (2007, eq. 2.21) desingularise it as
/// u = sqrt(2) h q / sqrt(h^4 + max(h^4, eps^4)); with eps = h_dry that formula is exactly q / h
/// above the dry threshold, and below it the velocity is set to zero (the momentum of films thinner
/// than h_dry is discarded by the update), so the division never sees a tiny h.
INLINE real velocity(real h, real q, real h_dry) { return h > h_dry ? q / h : (real)0; }

/// Limited slope from the backward difference a and forward difference b.
INLINE real limited_slope(real a, real b) {
#if LIMITER == 0
  // minmod
  return (a * b <= (real)0) ? (real)0 : (fabs(a) < fabs(b) ? a : b);
#elif LIMITER == 1
  // van Leer: harmonic mean of the two differences
  return (a * b <= (real)0) ? (real)0 : (real)2 * a * b / (a + b);
#elif LIMITER == 3
  // no reconstruction: the first-order Godunov-type scheme (for comparisons)
  return (real)0;
#else
  // monotonised central (van Leer 1977): minmod(2a, 2b, (a+b)/2)
  if (a * b <= (real)0) return (real)0;
  const real c = (real)0.5 * (a + b);
  const real m = fmin(fmin(fabs((real)2 * a), fabs((real)2 * b)), fabs(c));
  return copysign(m, c);
#endif
}

/// Minmod of the one-sided differences a (backward) and b (forward): the bed's slope in a cell. On a
/// bed that falls (or rises) monotonically the reconstructed face beds then never jump against the
/// fall at a face, whatever the curvature, and a plane is exact.
INLINE real bed_minmod(real a, real b) {
  if (a * b <= (real)0) return (real)0;
  return fabs(a) < fabs(b) ? a : b;
}

/// Change of the reconstructed bed across cell c (plus face minus minus face) along one axis, from
/// the beds of its neighbours (bm, bp; m_in, p_in: inside the domain) and, next to an outside cell,
/// of the next cell inward on the other side (bmm with mm_in, read only where m_in; bpp, pp_in).
/// Inside, the minmod of the two one-sided differences. Next to an outside cell the one known
/// difference, limited by the next difference inward: the outside continues the inside's slope (a
/// plane stays exact), and a kink between the cell and its inner neighbour (a pit's wall beside the
/// raster edge) is a kink, not the cell's slope. (The bare one-sided difference made a layer at
/// rest in the edge cell beside an 18 m pit slide into it at 10 g: soak seed 14540127069293829764.)
/// The solids' reconstructed bed (solid_bed.cl, point 2) and the slope fields (bed_geometry.cl; on the
/// host limitedBedSlope, src/flow/SlopeGravity.cpp, which gives g_n) use it alike.
INLINE real bed_rise(real bmm, int mm_in, real bm, int m_in, real bc, real bp, int p_in, real bpp, int pp_in) {
  if (m_in && p_in) return bed_minmod(bc - bm, bp - bc);
  if (p_in) return pp_in ? bed_minmod(bp - bc, bpp - bp) : bp - bc;
  if (m_in) return mm_in ? bed_minmod(bc - bm, bm - bmm) : bc - bm;
  return (real)0;
}

/// Reconstructed values of one cell at its two faces along one direction.
typedef struct {
  real h_lo, h_hi;    // thickness at the minus / plus face
  real e_lo, e_hi;    // free surface eta = h + b at the faces
  real un_lo, un_hi;  // velocity normal to the faces
  real ut_lo, ut_hi;  // velocity along the faces
} CellFaces;

/// Primitive state of one cell: thickness, free surface, normal and tangential velocity.
typedef struct {
  real h, e, un, ut;
} Prim;

INLINE Prim load_prim(__constant const FlowParams* p, __global const real* h, __global const real* qx,
                      __global const real* qy, __global const real* b, int k, int dir) {
  Prim s;
  s.h = h[k];
  s.e = s.h + b[k];
  const real u = velocity(s.h, qx[k], p->h_dry);
  const real v = velocity(s.h, qy[k], p->h_dry);
  s.un = dir == 0 ? u : v;
  s.ut = dir == 0 ? v : u;
  return s;
}

/// Face values of cell c from its slopes of thickness, surface and the two velocities.
INLINE CellFaces faces_of(Prim c, real sh, real se, real su, real sv) {
  CellFaces f;
  f.h_lo = c.h - (real)0.5 * sh;
  f.h_hi = c.h + (real)0.5 * sh;
  f.e_lo = c.e - (real)0.5 * se;
  f.e_hi = c.e + (real)0.5 * se;
  f.un_lo = c.un - (real)0.5 * su;
  f.un_hi = c.un + (real)0.5 * su;
  f.ut_lo = c.ut - (real)0.5 * sv;
  f.ut_hi = c.ut + (real)0.5 * sv;
  return f;
}

/// A face no thicker than the dry threshold is dry: thickness 0 at the same face bed. Its velocity,
/// reconstructed apart from the thickness, would otherwise enter the Riemann solver's wave speeds
/// (Toro's two-rarefaction estimate takes it for any h > 0, the dry-bed speeds only at h = 0): a
/// face that the limiter empties to within rounding (h - s/2 with s at its bound 2h, a residue of
/// +-1e-18 m or exactly 0) changed its neighbour's mass flux by 2.5 % on which side of 0 the rounding
/// fell, so results hung on rounding (device and CPU reference parted by 1e-5 m on random scenes).
/// The cells' own rule is the same: a film at or below h_dry carries no velocity (velocity()).
INLINE CellFaces dry_faces(CellFaces f, real h_dry) {
  if (f.h_lo <= h_dry) {
    f.e_lo -= f.h_lo;
    f.h_lo = 0;
  }
  if (f.h_hi <= h_dry) {
    f.e_hi -= f.h_hi;
    f.h_hi = 0;
  }
  return f;
}

/// MUSCL reconstruction of a shallow-water cell (the water stage and the fluid of the two-phase
/// model): the free surface eta with the run's limiter, over the bed reconstructed with
/// minmod (bed_minmod), so the face thickness is h +- (s_eta - s_b) / 2 (the cell's volume is kept).
/// Reconstructing the bed as eta - h with the compressive limiters (MC and van Leer allow twice the
/// smaller one-sided difference) put false rises into a monotone bed wherever the water is thin
/// against the bed's change of slope (a sheet reaching a cliff edge): the rise held the sheet while
/// the bed slope inside the cell kept accelerating it, which created energy. A lake at rest has a
/// flat surface and so flat face surfaces (well-balanced).
///
/// The thickness slope s_eta - s_b is the difference of two differently limited slopes, and on a bed
/// rough at the scale of the cell the two differ by up to the bed's change of slope (the harmonic
/// mean or MC of the surface's differences is never smaller than the minmod of the bed's), always in
/// the same sense. With positivity as the only bound (before 2026-12-06) a sheet of uniform
/// thickness got thinner downstream faces in every rough cell, and the grid held it back: on a rough
/// 35-degree slope its 5 m map lay 0.95 (relative L1) from the 1.25 m one (docs/numerics.md,
/// tests/verification/test_rough_slope_sheet.cpp). So the thickness slope is bounded by the larger of
/// - the maximum principle of a MUSCL reconstruction (face thicknesses between the smallest and the
///   largest thickness of the cell and its two neighbours), and
/// - the thickness slope that the surface and the bed give when both are limited alike,
///   |s_eta - L(bed)| with the run's limiter L: what the water's own profile carries, free of the
///   mismatch of the two limiters (zero for a sheet of uniform thickness, whatever the bed);
/// and by positivity (2 h). The maximum principle alone (tenth to twelfth sessions) cut every peak
/// of the thickness to first order, also where the surface is monotone and smooth: a bore or flood
/// crest on a steep slope, whose surface reconstruction needs no limiting, was flattened at each
/// step: it lowered data/kot_dambreak's median peak depth at 5 m by a fifth (1.70 -> 1.38 m, against
/// 2.42 m at 1.25 m; docs/numerics.md, "Why the thickness needs its own bound"). Three cases:
/// 1. a bed slope s_b between 0 and the minmod one keeps |s_eta - s_b| within the bound: the
///    nearest to the minmod one is taken, so the bed is flattened only as far as needed (a
///    shoreline, where the lake keeps its flat face surfaces). The part of the bed's change that the
///    cell no longer carries is a jump of the face beds, which the subcell face bed of face_between
///    (riemann.cl) handles; a flattened bed never rises against the DEM's own direction (each cell's
///    face bed stays between its centre and the mid-point to its neighbour);
/// 2. none does, but the unflattened faces are positive (|s_eta - s_b| <= 2 h; a sheet on a rough or
///    a curved bed): the bed keeps its minmod slope and the thickness slope is clamped to the bound,
///    so the sheet follows its bed. At the edge of case 1's range both give the same faces, so the
///    choice does not hang on rounding (a uniform sheet on a plane sits on that edge);
/// 3. otherwise (a film thinner than the mismatch), in a dry cell and next to outside cells the cell
///    is first order: its face values are its cell values. (Case 2 there, a film following its
///    minmod bed, broke the stress suite's energy bound on two thin-film scenes; first order passes.)
INLINE CellFaces reconstruct_surface(Prim m, int m_in, Prim c, Prim pl, int p_in) {
  CellFaces f = {c.h, c.h, c.e, c.e, c.un, c.un, c.ut, c.ut};
  if (!(m_in && p_in && c.h > (real)0)) return f;
  const real db_m = (c.e - c.h) - (m.e - m.h), db_p = (pl.e - pl.h) - (c.e - c.h);
  const real sb_dem = bed_minmod(db_m, db_p);
#if HANCOCK
  // An empty neighbour whose bed stands above what the cell's water can reach, its surface plus the
  // kinetic head of its motion towards it, is a wall: its elevation is bed, not a sample of the
  // surface, and the surface's difference to it is that of a wall's mirror image, zero. (The
  // corrector's face sees the same: no part of the column passes above z*, riemann.cl.) With the
  // bed as a surface sample MC steepened a pond's surface towards a dry rise to twice minmod's, and
  // under the one-stage MUSCL-Hancock scheme a lake among dry islands grew round-off
  // (tools/validation/hancock_lake_1d.py, variant (b)). With the surface alone as the reach, every
  // front climbing a dry slope had a flat surface (Thacker's oscillation: L1(h) +50 %); the wet
  // side's difference alone (one-sided), or capped at minmod's, left the lake growing (6e-10 and
  // 1e-10 m/s after 5000 steps).
  const real um = fmax((real)0, -c.un), up = fmax((real)0, c.un);
  const int wall_m = m.h <= (real)0 && m.e > c.e + um * um / ((real)2 * GRAVITY);
  const int wall_p = pl.h <= (real)0 && pl.e > c.e + up * up / ((real)2 * GRAVITY);
  const real se = limited_slope(wall_m ? (real)0 : c.e - m.e, wall_p ? (real)0 : pl.e - c.e);
#else
  const real se = limited_slope(c.e - m.e, pl.e - c.e);
#endif
  // Face thicknesses h -+ (se - sb) / 2, with the bed's slope sb between 0 and the minmod one, and
  // |se - sb| <= bound: within [h_min, h_max] of the cell and its two neighbours, or within the
  // thickness slope of the surface and the bed limited alike, se - L(bed), if that is larger; never
  // beyond positivity, 2 h (see above).
  const real bound_range = (real)2 * fmin(fmax(fmax(m.h, pl.h), c.h) - c.h, c.h - fmin(fmin(m.h, pl.h), c.h));
  const real bound = fmin((real)2 * c.h, fmax(bound_range, fabs(se - limited_slope(db_m, db_p))));
  const real lo = fmax(se - bound, fmin((real)0, sb_dem));
  const real hi = fmin(se + bound, fmax((real)0, sb_dem));
  const int flattenable = lo <= hi;                                     // case 1
  if (!flattenable && !(fabs(se - sb_dem) <= (real)2 * c.h)) return f;  // case 3
  const real su = limited_slope(c.un - m.un, pl.un - c.un), sv = limited_slope(c.ut - m.ut, pl.ut - c.ut);
  if (flattenable) {
    const real sb = clamp(sb_dem, lo, hi);
    return faces_of(c, se - sb, se, su, sv);
  }
  const real sh = clamp(se - sb_dem, -bound, bound);  // case 2
  return faces_of(c, sh, sb_dem + sh, su, sv);
}

#endif
