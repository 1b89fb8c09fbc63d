// Numerical fluxes through cell faces for the shallow-water equations in horizontal coordinates
// with vertical thickness h (spec §4 with h_s = 0):
//   h_t + div(h u) = 0,
//   (h u)_t + div(h u u) + g_p h grad h = -g_n h grad b.
// One kernel serves both directions (dir 0: x faces, dir 1: y faces). Each face gets MUSCL states
// from the two cells beside it, the hydrostatic reconstruction of Audusse et al. (2004, SIAM J. Sci.
// Comput. 25, eq. 2.7-2.9) for well-balancing and positivity, and an HLL (Harten, Lax & van Leer
// 1983) or HLLC (Toro 2001, "Shock-capturing methods for free-surface shallow flows", ch. 10) flux.
//
// The hydrostatic pressure part of the normal-momentum flux is stored without its factor g, so that
// each cell multiplies it by its own slope-corrected g_p (spec §1); this keeps a lake at rest exact
// where g_p varies from cell to cell. Stored per face, in components of `face[c * nfaces + f]`:
//   0: mass flux  1: normal momentum flux without pressure  2: tangential momentum flux
//   3: HLL pressure flux P (the cell adds g_p * P)
//   4: hydrostatic correction for the minus-side cell  (h_face^2 - h*^2) / 2
//   5: hydrostatic correction for the plus-side cell   (h_face^2 - h*^2) / 2
#include "flow/flow_common.cl"

#define FACE_COMPONENTS 6

typedef struct {
  real fh, fqn, fqt, p;
} FaceFlux;

/// HLL/HLLC flux between left state (hl, ul, vl) and right state (hr, ur, vr), u normal, v tangential.
/// g sets the wave speeds (Toro 2001 two-rarefaction estimates with the dry-bed speeds).
inline FaceFlux riemann_flux(real hl, real ul, real vl, real hr, real ur, real vr, real g) {
  FaceFlux f = {0, 0, 0, 0};
  if (hl <= (real)0 && hr <= (real)0) return f;
  const real cl = sqrt(g * hl), cr = sqrt(g * hr);
  real sl, sr;
  if (hl <= (real)0) {
    sl = ur - (real)2 * cr;
    sr = ur + cr;
  } else if (hr <= (real)0) {
    sl = ul - cl;
    sr = ul + (real)2 * cl;
  } else {
    const real us = (real)0.5 * (ul + ur) + cl - cr;
    const real cs = (real)0.5 * (cl + cr) + (real)0.25 * (ul - ur);
    sl = fmin(ul - cl, us - cs);
    sr = fmax(ur + cr, us + cs);
  }
  const real ql = hl * ul, qr = hr * ur;
  const real pl = (real)0.5 * hl * hl, pr = (real)0.5 * hr * hr;
  if (sl >= (real)0) {
    f.fh = ql;
    f.fqn = ql * ul;
    f.fqt = ql * vl;
    f.p = pl;
    return f;
  }
  if (sr <= (real)0) {
    f.fh = qr;
    f.fqn = qr * ur;
    f.fqt = qr * vr;
    f.p = pr;
    return f;
  }
  const real inv = (real)1 / (sr - sl);
  f.fh = (sr * ql - sl * qr + sl * sr * (hr - hl)) * inv;
  f.fqn = (sr * ql * ul - sl * qr * ur + sl * sr * (qr - ql)) * inv;
  f.p = (sr * pl - sl * pr) * inv;
#if RIEMANN == 1
  // HLLC: the tangential velocity is a passive scalar carried across the contact wave s*.
  const real denom = hr * (ur - sr) - hl * (ul - sl);
  const real ss = fabs(denom) > (real)0 ? (sl * hr * (ur - sr) - sr * hl * (ul - sl)) / denom : (real)0.5 * (sl + sr);
  f.fqt = f.fh * (ss >= (real)0 ? vl : vr);
#else
  f.fqt = (sr * ql * vl - sl * qr * vr + sl * sr * (hr * vr - hl * vl)) * inv;
#endif
  return f;
}

/// Reconstructed values of cell (i,j) along `dir` (neighbours at offsets -1 and +1).
inline CellFaces cell_faces(__constant const FlowParams* p, __global const uchar* mask, __global const real* h,
                            __global const real* qx, __global const real* qy, __global const real* b, int i, int j,
                            int dir) {
  const int di = dir == 0 ? 1 : 0, dj = 1 - di;
  const int m_in = cell_inside(p, mask, i - di, j - dj), p_in = cell_inside(p, mask, i + di, j + dj);
  const Prim c = load_prim(p, h, qx, qy, b, cell_index(p, i, j), dir);
  Prim m = c, pl = c;
  if (m_in) m = load_prim(p, h, qx, qy, b, cell_index(p, i - di, j - dj), dir);
  if (p_in) pl = load_prim(p, h, qx, qy, b, cell_index(p, i + di, j + dj), dir);
  return reconstruct(m, m_in, c, pl, p_in);
}

/// Flux through face (i,j) of direction dir: the face between cell (i-1,j) and (i,j) for dir 0,
/// between (i,j-1) and (i,j) for dir 1. Face grid: (nx+1) x ny for dir 0, nx x (ny+1) for dir 1.
inline void face_flux(__constant const FlowParams* p, const int dir, __global const uchar* mask,
                      __global const real* h, __global const real* qx, __global const real* qy,
                      __global const real* b, __global const real* gp, __global real* face, int i, int j) {
  const int fnx = p->nx + (dir == 0 ? 1 : 0), fny = p->ny + (dir == 1 ? 1 : 0);
  const int nfaces = fnx * fny;
  const int f = j * fnx + i;
  const int di = dir == 0 ? 1 : 0, dj = 1 - di;
  const int li = i - di, lj = j - dj;  // minus-side cell
  const int l_in = cell_inside(p, mask, li, lj), r_in = cell_inside(p, mask, i, j);

  FaceFlux flux = {0, 0, 0, 0};
  real corr_l = 0, corr_r = 0;
  if (l_in || r_in) {
    // Face states of the inside cell(s); an outside cell becomes the ghost of its inside neighbour.
    real hl, el, ul, vl, hr, er, ur, vr, gl, gr;
    if (l_in) {
      const CellFaces cf = cell_faces(p, mask, h, qx, qy, b, li, lj, dir);
      hl = cf.h_hi; el = cf.e_hi; ul = cf.un_hi; vl = cf.ut_hi;
      gl = gp[cell_index(p, li, lj)];
    }
    if (r_in) {
      const CellFaces cf = cell_faces(p, mask, h, qx, qy, b, i, j, dir);
      hr = cf.h_lo; er = cf.e_lo; ur = cf.un_lo; vr = cf.ut_lo;
      gr = gp[cell_index(p, i, j)];
    }
    // Ghosts: a wall mirrors the inside state with the normal velocity reversed; an open boundary is
    // outflow only: it copies the inside state (zero gradient) while the inside flow moves towards
    // it, and acts as a wall while the flow moves away, so no water ever enters through it.
    int wall = 0;
    if (!l_in) {
      wall = boundary_kind(p, li, lj) == BOUNDARY_WALL || ur > (real)0;
      hl = hr; el = er; vl = vr; gl = gr;
      ul = wall ? -ur : ur;
    }
    if (!r_in) {
      wall = boundary_kind(p, i, j) == BOUNDARY_WALL || ul < (real)0;
      hr = hl; er = el; vr = vl; gr = gl;
      ur = wall ? -ul : ul;
    }
    // Hydrostatic reconstruction: bed at the face is the higher of the two face beds.
    const real bl = el - hl, br = er - hr;
    const real bs = fmax(bl, br);
    const real hls = fmax((real)0, el - bs), hrs = fmax((real)0, er - bs);
    flux = riemann_flux(hls, ul, vl, hrs, ur, vr, fmax(gl, gr));
    if (wall) {
      flux.fh = 0;   // a wall passes no mass and no tangential momentum
      flux.fqt = 0;
    }
    corr_l = (real)0.5 * (hl * hl - hls * hls);
    corr_r = (real)0.5 * (hr * hr - hrs * hrs);
  }
  face[0 * nfaces + f] = flux.fh;
  face[1 * nfaces + f] = flux.fqn;
  face[2 * nfaces + f] = flux.fqt;
  face[3 * nfaces + f] = flux.p;
  face[4 * nfaces + f] = corr_l;
  face[5 * nfaces + f] = corr_r;
}

/// One work-group per active tile: each cell computes the face on its minus side, and the last cell
/// of the tile (or of the raster) also the face on its plus side, so every face of an active tile is
/// fresh. A face between two active tiles may be computed by both, with identical results.
__kernel void flow_face_flux(__constant const FlowParams* p, const int dir, __global const uchar* mask,
                             __global const int* tile_list, __global const real* h, __global const real* qx,
                             __global const real* qy, __global const real* b, __global const real* gp,
                             __global real* face) {
  const int2 c = tile_cell(p, tile_list);
  if (c.x >= p->nx || c.y >= p->ny) return;
  face_flux(p, dir, mask, h, qx, qy, b, gp, face, c.x, c.y);
  const int along = dir == 0 ? c.x : c.y, n = dir == 0 ? p->nx : p->ny;
  if (along == n - 1 || (along % TILE) == TILE - 1)
    face_flux(p, dir, mask, h, qx, qy, b, gp, face, c.x + (dir == 0), c.y + (dir == 1));
}
