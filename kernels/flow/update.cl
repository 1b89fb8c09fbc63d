// Finite-volume update of one SSP-RK2 stage (Shu & Osher 1988):
//   U_out = a * U_base + (1 - a) * (U_stage + dt * L(U_stage)),
// stage 1: a = 0 (U_base unused), stage 2: a = 1/2 with U_base the state at the start of the step.
// L(U) is the flux divergence of flux.cl plus the well-balanced bed source of Audusse et al. (2004,
// eq. 2.11): for cell i in direction x,
//   dt/dx * [ g_p (P_E + c_E^-) - g_p (P_W + c_W^+) - g_p (h_W+ + h_E-)/2 (b_E- - b_W+) ],
// with P the HLL pressure flux and c the hydrostatic corrections, and the centred term
// (g_p - g_n) h db/dx that is zero unless the cos^4 depth-pressure option makes g_p differ from g_n.
// The volume that leaves through boundary faces [m^3] is added to out_step[cell] with weight w_out
// (dt/2 per stage).
#include "flow/flow_common.cl"

#define FACE_COMPONENTS 6

inline real face_c(__global const real* face, int nfaces, int c, int f) { return face[c * nfaces + f]; }

__kernel void flow_update(__constant const FlowParams* p, __global const uchar* mask, __global const int* tile_list,
                          __global const real* face_x, __global const real* face_y, __global const real* b,
                          __global const real* gp, __global const real* gn, __global const real* h_base,
                          __global const real* qx_base, __global const real* qy_base, __global const real* h_st,
                          __global const real* qx_st, __global const real* qy_st, __global real* h_out,
                          __global real* qx_out, __global real* qy_out, __global real* out_step, const real dt,
                          const real a, const real w_out, const int first_stage) {
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  if (i >= p->nx || j >= p->ny || !cell_inside(p, mask, i, j)) return;
  const int k = cell_index(p, i, j);
  const int nfx = (p->nx + 1) * p->ny, nfy = p->nx * (p->ny + 1);
  const int fw = j * (p->nx + 1) + i, fe = fw + 1;  // x faces west / east of the cell
  const int fs = j * p->nx + i, fn = fs + p->nx;    // y faces south / north of the cell
  const real g = gp[k];
  const real dtdx = dt / p->dx;

  // Mass: flux divergence.
  const real fhw = face_c(face_x, nfx, 0, fw), fhe = face_c(face_x, nfx, 0, fe);
  const real fhs = face_c(face_y, nfy, 0, fs), fhn = face_c(face_y, nfy, 0, fn);
  real dh = -dtdx * (fhe - fhw + fhn - fhs);

  // Momentum: advective flux, pressure with the cell's own g_p, hydrostatic corrections.
  const real mx_e = face_c(face_x, nfx, 1, fe) + g * (face_c(face_x, nfx, 3, fe) + face_c(face_x, nfx, 4, fe));
  const real mx_w = face_c(face_x, nfx, 1, fw) + g * (face_c(face_x, nfx, 3, fw) + face_c(face_x, nfx, 5, fw));
  const real my_n = face_c(face_y, nfy, 1, fn) + g * (face_c(face_y, nfy, 3, fn) + face_c(face_y, nfy, 4, fn));
  const real my_s = face_c(face_y, nfy, 1, fs) + g * (face_c(face_y, nfy, 3, fs) + face_c(face_y, nfy, 5, fs));
  real dqx = -dtdx * (mx_e - mx_w + face_c(face_y, nfy, 2, fn) - face_c(face_y, nfy, 2, fs));
  real dqy = -dtdx * (my_n - my_s + face_c(face_x, nfx, 2, fe) - face_c(face_x, nfx, 2, fw));

  // Centred well-balanced bed source from the cell's own reconstruction in each direction.
  const real hc = h_st[k];
  if (hc > (real)0) {
    for (int dir = 0; dir < 2; ++dir) {
      const int di = dir == 0 ? 1 : 0, dj = 1 - di;
      const int m_in = cell_inside(p, mask, i - di, j - dj), p_in = cell_inside(p, mask, i + di, j + dj);
      const Prim c = load_prim(p, h_st, qx_st, qy_st, b, k, dir);
      Prim m = c, pl = c;
      if (m_in) m = load_prim(p, h_st, qx_st, qy_st, b, cell_index(p, i - di, j - dj), dir);
      if (p_in) pl = load_prim(p, h_st, qx_st, qy_st, b, cell_index(p, i + di, j + dj), dir);
      const CellFaces cf = reconstruct(m, m_in, c, pl, p_in);
      const real b_lo = cf.e_lo - cf.h_lo, b_hi = cf.e_hi - cf.h_hi;
      real s = g * (real)0.5 * (cf.h_lo + cf.h_hi) * (b_hi - b_lo);
      // (g_p - g_n) h db/dx, centred; exactly zero when g_p == g_n (default depth pressure).
      const real dg = g - gn[k];
      if (dg != (real)0 && m_in && p_in)
        s -= dg * hc * (real)0.5 * (b[cell_index(p, i + di, j + dj)] - b[cell_index(p, i - di, j - dj)]);
      if (dir == 0) dqx -= dtdx * s; else dqy -= dtdx * s;
    }
  }

  real hn = h_st[k] + dh;
  real qxn = qx_st[k] + dqx;
  real qyn = qy_st[k] + dqy;
  if (a != (real)0) {
    hn = a * h_base[k] + ((real)1 - a) * hn;
    qxn = a * qx_base[k] + ((real)1 - a) * qxn;
    qyn = a * qy_base[k] + ((real)1 - a) * qyn;
  }
  // Positivity holds under the CFL condition; a negative value can only be round-off.
  if (hn <= p->h_dry) {
    qxn = 0;
    qyn = 0;
    hn = fmax(hn, (real)0);
  }
  h_out[k] = hn;
  qx_out[k] = qxn;
  qy_out[k] = qyn;

  // Outflow through boundary faces (outward mass flux), tallied for the volume balance.
  real out = 0;
  if (!cell_inside(p, mask, i - 1, j)) out -= fhw;
  if (!cell_inside(p, mask, i + 1, j)) out += fhe;
  if (!cell_inside(p, mask, i, j - 1)) out -= fhs;
  if (!cell_inside(p, mask, i, j + 1)) out += fhn;
  // Face fluxes are per unit width: the volume through a face is flux * dx * time.
  out *= w_out * p->dx;
  if (first_stage) out_step[k] = out;
  else out_step[k] += out;
}
