// One SSP-RK2 stage of the shallow-water solver for one tile, fused: reconstruction, face fluxes,
// well-balanced sources and the update (Shu & Osher 1988):
//   U_out = a * U_base + (1 - a) * (U_st + dt * L(U_st)),
// stage 1: a = 0 (U_base unused), stage 2: a = 1/2 with U_base the state at the start of the step
// (of the sweep, in the split scheme).
// L(U) is the flux divergence plus the well-balanced bed source of Audusse et al. (2004, eq. 2.11):
// per direction, with P the HLL pressure flux and c the hydrostatic corrections of riemann.cl,
//   dt/dx * [ g_p (P_+ + c_+) - g_p (P_- + c_-) - g_p (h_lo + h_hi)/2 (b_hi - b_lo) ],
// and the centred term (g_p - g_n) h db/dx, zero unless the cos^4 depth-pressure option makes g_p
// differ from g_n (spec §1).
//
// One work-group per active tile (TILE x TILE work-items). The tile and a halo of two cells are read
// once into local memory; each work-item reconstructs its cell and its four neighbours and computes
// its four faces. A face is computed by both cells beside it with the same function on the same
// values, so both see the bitwise same flux (contraction is off, see common/real.cl) and interior
// fluxes cancel exactly. Work-items outside the domain only help loading.
// The volume that leaves through boundary faces [m^3] goes to out_step[cell] with weight w_out
// (dt/2 per stage, assigned in the step's first stage and added in the others).
//
// dir_mask selects the directions whose faces the stage computes: 3 (both) for the unsplit scheme;
// 1 (x) or 2 (y) for one sweep of the dimensionally split scheme (Time Scheme=split, Strang 1968
// with the sweep order alternated between steps), whose two 1D SSP-RK2 sweeps are each positive and
// well-balanced under a Courant number of 1/2 in their own direction.
#include "flow/riemann.cl"

#define HALO 2
#define SPAN (TILE + 2 * HALO)

/// Primitive state of the cell at local position (a, b) of the tile + halo block, along `dir`.
inline Prim local_prim(__local const real* lh, __local const real* le, __local const real* lu,
                       __local const real* lv, int a, int b, int dir) {
  const int s = b * SPAN + a;
  Prim c;
  c.h = lh[s];
  c.e = le[s];
  c.un = dir == 0 ? lu[s] : lv[s];
  c.ut = dir == 0 ? lv[s] : lu[s];
  return c;
}

/// MUSCL face values of the local cell (a, b) along `dir` (neighbours at -1 and +1).
inline CellFaces local_faces(__local const real* lh, __local const real* le, __local const real* lu,
                             __local const real* lv, __local const uchar* lin, int a, int b, int dir) {
  const int da = dir == 0, db = dir == 1;
  const int m_in = lin[(b - db) * SPAN + a - da], p_in = lin[(b + db) * SPAN + a + da];
  const Prim c = local_prim(lh, le, lu, lv, a, b, dir);
  const Prim m = m_in ? local_prim(lh, le, lu, lv, a - da, b - db, dir) : c;
  const Prim p = p_in ? local_prim(lh, le, lu, lv, a + da, b + db, dir) : c;
  return reconstruct_surface(m, m_in, c, p, p_in);
}

inline Side side_hi(CellFaces f, real g) { Side s = {f.h_hi, f.e_hi, f.un_hi, f.ut_hi, g}; return s; }
inline Side side_lo(CellFaces f, real g) { Side s = {f.h_lo, f.e_lo, f.un_lo, f.ut_lo, g}; return s; }

__kernel __attribute__((reqd_work_group_size(TILE, TILE, 1)))
void flow_stage(__constant const FlowParams* p, __global const uchar* mask, __global const int* tile_list,
                __global const real* b, __global const real* gp, __global const real* gn,
                __global const real* far_level, __global const real* h_base, __global const real* qx_base, __global const real* qy_base,
                __global const real* h_st, __global const real* qx_st, __global const real* qy_st,
                __global real* h_out, __global real* qx_out, __global real* qy_out, __global real* out_step,
                const real dt, const real a, const real w_out, const int first_stage, const int dir_mask) {
  __local real lh[SPAN * SPAN], le[SPAN * SPAN], lu[SPAN * SPAN], lv[SPAN * SPAN], lg[SPAN * SPAN];
  __local uchar lin[SPAN * SPAN];
  const int tile = tile_list[get_group_id(0)];
  const int x0 = (tile % p->tiles_x) * TILE - HALO, y0 = (tile / p->tiles_x) * TILE - HALO;
  const int lid = get_local_id(1) * TILE + get_local_id(0);

  // Tile and halo into local memory: h, eta = h + b, u, v, g_p and the inside flag.
  for (int s = lid; s < SPAN * SPAN; s += TILE * TILE) {
    const int gi = x0 + s % SPAN, gj = y0 + s / SPAN;
    const int in = cell_inside(p, mask, gi, gj);
    lin[s] = (uchar)in;
    if (in) {
      const int k = cell_index(p, gi, gj);
      const real hk = h_st[k];
      lh[s] = hk;
      le[s] = hk + b[k];
      lu[s] = velocity(hk, qx_st[k], p->h_dry);
      lv[s] = velocity(hk, qy_st[k], p->h_dry);
      lg[s] = gp[k];
    } else {
      lh[s] = 0; le[s] = 0; lu[s] = 0; lv[s] = 0; lg[s] = 0;
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);

  const int la = get_local_id(0) + HALO, lb = get_local_id(1) + HALO;
  const int i = x0 + la, j = y0 + lb;
  const int sc = lb * SPAN + la;
  if (!lin[sc]) return;  // off the raster or nodata (no barrier follows)
  const int k = cell_index(p, i, j);
  const real g = lg[sc];
  const real dtdx = dt / p->dx;

  // Per direction: mass flux difference, normal and tangential momentum terms. The two directions
  // are added only at the end, with commutative sums, so a scene and its x<->y transpose give
  // bitwise transposed results.
  real mass[2], normal[2], tangential[2], out = 0;
  for (int dir = 0; dir < 2; ++dir) {
    if (!((dir_mask >> dir) & 1)) {
      mass[dir] = normal[dir] = tangential[dir] = 0;
      continue;
    }
    const int da = dir == 0, db = dir == 1;
    const int sm = sc - db * SPAN - da, sp = sc + db * SPAN + da;
    const int m_in = lin[sm], p_in = lin[sp];
    const CellFaces own = local_faces(lh, le, lu, lv, lin, la, lb, dir);
    CellFaces nb = own;
    if (m_in) nb = local_faces(lh, le, lu, lv, lin, la - da, lb - db, dir);
    // At a level edge the outside is still water at the cell's far level (its initial surface); only
    // cells beside an outside cell read it.
    const real far = (m_in && p_in) ? (real)0 : far_level[k];
    const Face fm = face_between(m_in, side_hi(nb, lg[sm]), 1, side_lo(own, g), boundary_kind(p, i - da, j - db), far);
    nb = own;
    if (p_in) nb = local_faces(lh, le, lu, lv, lin, la + da, lb + db, dir);
    const Face fp = face_between(1, side_hi(own, g), p_in, side_lo(nb, lg[sp]), boundary_kind(p, i + da, j + db), far);

    mass[dir] = fp.fh - fm.fh;
    // Normal momentum: advective flux, pressure with the cell's own g_p, hydrostatic corrections,
    // and the centred well-balanced bed source from the cell's own reconstruction.
    real s = (fp.fqn + g * (fp.p + fp.corr_m)) - (fm.fqn + g * (fm.p + fm.corr_p));
    if (lh[sc] > (real)0) {
      s += g * (real)0.5 * (own.h_lo + own.h_hi) * ((own.e_hi - own.h_hi) - (own.e_lo - own.h_lo));
      const real dg = g - gn[k];  // exactly zero with the default depth pressure (g_p == g_n)
      if (dg != (real)0 && m_in && p_in)
        s -= dg * lh[sc] * (real)0.5 * ((le[sp] - lh[sp]) - (le[sm] - lh[sm]));
    }
    normal[dir] = s;
    tangential[dir] = fp.fqt - fm.fqt;  // moves the other direction's momentum
    if (!m_in) out -= fm.fh;
    if (!p_in) out += fp.fh;
  }
  const real dh = -dtdx * (mass[0] + mass[1]);
  const real dq[2] = {-dtdx * (normal[0] + tangential[1]), -dtdx * (normal[1] + tangential[0])};

  real hn = h_st[k] + dh;
  real qxn = qx_st[k] + dq[0];
  real qyn = qy_st[k] + dq[1];
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
  // Face fluxes are per unit width: the volume through a face is flux * dx * time.
  out *= w_out * p->dx;
  if (first_stage) out_step[k] = out;
  else out_step[k] += out;
}
