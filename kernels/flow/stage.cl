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
// One work-group per active tile (TILE x TILE work-items), in three phases:
// 1. the tile and a halo of HALO cells are read once into local memory;
// 2. every face the tile needs is computed once, by one work-item, into local memory (a face used
//    to be computed by both cells beside it; the function and its inputs are the same, so the
//    results are bitwise those of the two-sided evaluation, and interior fluxes cancel exactly);
// 3. each work-item sums its cell's faces and sources and writes the update.
// Work-items outside the domain help with phases 1 and 2 and stop before phase 3.
// The volume that leaves through boundary faces [m^3] goes to out_step[cell] with weight w_out
// (dt/2 per stage, assigned in the step's first stage and added in the others).
//
// dir_mask selects the directions whose faces the stage computes: 3 (both) for the unsplit scheme;
// 1 (x) or 2 (y) for one sweep of the dimensionally split scheme (Time Scheme=split, Strang 1968
// with the sweep order alternated between steps). A forward-Euler stage of the second-order scheme
// is positive when dt (|u| + c) / dx <= 1/2 along each direction with both directions' faces taken
// together (unsplit) or along the sweep (split): the reconstruction splits a cell's thickness into
// face values h_lo + h_hi = 2h, each of which may drain through its face within the step (Audusse et
// al. 2004, thm. 2.1). The bound holds for the speeds of the face states, the time step uses the
// cells' (a face thickness up to 2h has up to sqrt(2) times its cell's c); the unsplit scheme's sum
// over both directions leaves margin, the split sweeps have none (a soak found a film on a 14 x 2
// grid that gained 75 % of its volume in one split step at Courant number 1/2).
//
// DRAINING (= SPLIT: on for the split sweeps, which then take Courant numbers up to 1):
// positivity by the draining time of Bollermann, Noelle & Lukacova-Medvidova (2011, Commun. Comput.
// Phys. 10, eq. 3.5; Bollermann et al. 2013, SIAM J. Sci. Comput. 35, sec. 3.3). A cell whose
// outgoing mass fluxes O (per unit width, over its two faces of the sweep) would take more than it
// holds within the stage, dt O / dx > h, empties in its draining time h dx / O < dt; every flux out
// of it is scaled by theta = h dx / (dt O), the fraction of the stage in which it still has water.
// A face's mass flux and its advective momentum fluxes (normal and tangential) take the theta of the
// face's upwind cell (by the sign of its mass flux); the hydrostatic pressure and the bed-jump
// corrections are not transport and stay, so a lake at rest (no mass flux, theta = 1) is untouched.
// Then h + dt/dx (inflow - theta O) >= h - h = 0 at any Courant number, and where no cell drains
// (theta = 1 everywhere) the stage is the plain one bit for bit. The stability limit is then that of
// the wave speeds, Courant number 1 per sweep. theta needs the outflow of the tile's neighbour cells
// along the sweep, hence one more halo cell.
#include "flow/riemann.cl"
#include "flow/hancock.cl"

// The split sweeps (-DSPLIT=1) always limit draining cells; the unsplit stage never does.
#define DRAINING SPLIT
#if DRAINING && HANCOCK
#define HALO 4    // the predictor's view of the faces needs the neighbours' MUSCL faces (local_faces)
#define RING 1
#define FACE_SLOTS 1
#elif DRAINING
#define HALO 3
#define RING 1        // cells beyond the tile, along the sweep, whose draining factor is needed
#define FACE_SLOTS 1  // one direction per launch (the split scheme's sweeps)
#else
#define HALO 2
#define RING 0
#define FACE_SLOTS 2
#endif
#define SPAN (TILE + 2 * HALO)
#define NFA (TILE + 1 + 2 * RING)  // faces per row along a direction
#define NFACE (NFA * TILE)         // faces per direction
// Local memory per work-group at TILE 16: 5 SPAN^2 + 6 FACE_SLOTS NFACE (+ the draining factors,
// + 3 NPF predictor faces with HANCOCK) reals and SPAN^2 bytes: 42.5 KB in double and 21.5 KB in
// float without DRAINING, 36.7 / 18.6 KB with it, 47.4 / 24.0 KiB with HANCOCK (HALO 4), under
// the 48 KiB a work-group may hold statically on NVIDIA devices.

/// Primitive state of the cell at local position (a, b) of the tile + halo block, along `dir`.
INLINE Prim local_prim(__local const real* lh, __local const real* le, __local const real* lu,
                       __local const real* lv, int a, int b, int dir) {
  const int s = b * SPAN + a;
  Prim c;
  c.h = lh[s];
  c.e = le[s];
  c.un = dir == 0 ? lu[s] : lv[s];
  c.ut = dir == 0 ? lv[s] : lu[s];
  return c;
}

INLINE Side side_hi(CellFaces f, real g) { Side s = {f.h_hi, f.e_hi, f.un_hi, f.ut_hi, g}; return s; }
INLINE Side side_lo(CellFaces f, real g) { Side s = {f.h_lo, f.e_lo, f.un_lo, f.ut_lo, g}; return s; }

/// MUSCL face values of the local cell (a, b) along `dir` (neighbours at -1 and +1).
INLINE CellFaces muscl_faces(__local const real* lh, __local const real* le, __local const real* lu,
                             __local const real* lv, __local const uchar* lin, int a, int b, int dir, real h_dry) {
  const int da = dir == 0, db = dir == 1;
  const int m_in = lin[(b - db) * SPAN + a - da], p_in = lin[(b + db) * SPAN + a + da];
  const Prim c = local_prim(lh, le, lu, lv, a, b, dir);
  const Prim m = m_in ? local_prim(lh, le, lu, lv, a - da, b - db, dir) : c;
  const Prim p = p_in ? local_prim(lh, le, lu, lv, a + da, b + db, dir) : c;
  return dry_faces(reconstruct_surface(m, m_in, c, p, p_in), h_dry);
}

#if HANCOCK
#define NPFA (TILE + 2 * RING + 3)  // faces per row along the sweep that the predicted cells touch
#define NPF (NPFA * TILE)
/// Index among the predictor faces (phase 1b) of the lo face of the local cell (a, b); its hi face
/// is the next one. Face k of a row lies between the cells HALO - RING - 2 + k and the next.
INLINE int predictor_lo_face(int a, int b, int dir) {
  const int along = dir == 0 ? a : b, across = dir == 0 ? b : a;
  return (along - (HALO - RING - 1)) + (across - HALO) * NPFA;
}
#endif

/// The face values the stage's fluxes use: the MUSCL ones, in the MUSCL-Hancock build advanced by
/// half a step (flow/hancock.cl; r = dt / (2 dx), the cell's g_p) with what phase 1b found at its
/// two faces (pm: the corrector's mass flux of the unpredicted faces, pdm / pdp: the drops of the
/// face's minus and plus sides; hancock_face). Next to an outside cell, and where the cell's own
/// face is empty, the face's own h u and no drop.
INLINE CellFaces local_faces(__local const real* lh, __local const real* le, __local const real* lu,
                             __local const real* lv, __local const real* lg, __local const uchar* lin,
                             __local const real* pm, __local const real* pdm, __local const real* pdp, int a, int b,
                             int dir, real r, real h_dry) {
  const CellFaces f = muscl_faces(lh, le, lu, lv, lin, a, b, dir, h_dry);
#if HANCOCK
  const int da = dir == 0, db = dir == 1;
  const int m_in = lin[(b - db) * SPAN + a - da], p_in = lin[(b + db) * SPAN + a + da];
  const int lo = predictor_lo_face(a, b, dir), hi = lo + 1;
  const int use_lo = m_in && f.h_lo > (real)0, use_hi = p_in && f.h_hi > (real)0;
  const real q_lo = use_lo ? pm[lo] : f.h_lo * f.un_lo, q_hi = use_hi ? pm[hi] : f.h_hi * f.un_hi;
  const real drop_lo = use_lo ? pdp[lo] : (real)0, drop_hi = use_hi ? pdm[hi] : (real)0;
  const real dh = hancock_thickness_change(f, q_lo, q_hi, r);
  return dry_faces(hancock_predict(f, dh, drop_lo, drop_hi, lg[b * SPAN + a], r, h_dry), h_dry);
#else
  (void)lg;
  (void)pm;
  (void)pdm;
  (void)pdp;
  (void)r;
  return f;
#endif
}

/// Local position of the minus-side cell of face q in row r along `dir` (the plus side is the next
/// cell along `dir`). Face q = RING + t + 1 is the plus face of the tile's cell t of that row.
INLINE int2 face_minus_cell(int q, int r, int dir) {
  const int along = HALO - RING + q - 1, across = HALO + r;
  return dir == 0 ? (int2)(along, across) : (int2)(across, along);
}

__kernel __attribute__((reqd_work_group_size(TILE, TILE, 1)))
void flow_stage(__constant const FlowParams* p, __global const uchar* mask, __global const int* tile_list,
                __global const real* b, __global const real* gp, __global const real* gn,
                __global const real* far_level, __global const real* h_base, __global const real* qx_base, __global const real* qy_base,
                __global const real* h_st, __global const real* qx_st, __global const real* qy_st,
                __global real* h_out, __global real* qx_out, __global real* qy_out, __global real* out_step,
                const real dt, const real a, const real w_out, const int first_stage, const int dir_mask) {
  __local real lh[SPAN * SPAN], le[SPAN * SPAN], lu[SPAN * SPAN], lv[SPAN * SPAN], lg[SPAN * SPAN];
  __local uchar lin[SPAN * SPAN];
  // The faces (Face of riemann.cl, one array per member), per direction slot.
  __local real ffh[FACE_SLOTS * NFACE], ffqn[FACE_SLOTS * NFACE], ffqt[FACE_SLOTS * NFACE],
      ffp[FACE_SLOTS * NFACE], ffcm[FACE_SLOTS * NFACE], ffcp[FACE_SLOTS * NFACE];
#if DRAINING
  __local real theta[(TILE + 2 * RING) * TILE];  // draining factors of the cells along the sweep
#endif
#if HANCOCK
  // The predictor's view of the faces along the sweep (phase 1b): mass flux, the sides' drops.
  __local real pm[NPF], pdm[NPF], pdp[NPF];
#else
  __local real* pm = 0;
  __local real* pdm = 0;
  __local real* pdp = 0;
#endif
  const int tile = tile_list[get_group_id(0)];
  const int x0 = (tile % p->tiles_x) * TILE - HALO, y0 = (tile / p->tiles_x) * TILE - HALO;
  const int lid = get_local_id(1) * TILE + get_local_id(0);
  const real dtdx = dt / p->dx, hr = (real)0.5 * dtdx;  // hr: the Hancock predictor's dt / (2 dx)

  // 1. Tile and halo into local memory: h, eta = h + b, u, v, g_p and the inside flag.
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

#if HANCOCK
  // 1b. What the corrector's face would do with the unpredicted values, once per face the predicted
  // cells touch (flow/hancock.cl, hancock_face).
  {
    const int dir = (dir_mask & 1) ? 0 : 1;  // the sweep's direction
    const int da = dir == 0, db = dir == 1;
    for (int k = lid; k < NPF; k += TILE * TILE) {
      const int along = HALO - RING - 2 + k % NPFA, across = HALO + k / NPFA;
      const int am = dir == 0 ? along : across, bm = dir == 0 ? across : along;
      const int sm = bm * SPAN + am, sp = (bm + db) * SPAN + am + da;
      PredictorFace pf = {0, 0, 0};
      if (lin[sm] && lin[sp]) {
        const CellFaces fm = muscl_faces(lh, le, lu, lv, lin, am, bm, dir, p->h_dry);
        const CellFaces fp = muscl_faces(lh, le, lu, lv, lin, am + da, bm + db, dir, p->h_dry);
        pf = hancock_face(side_hi(fm, lg[sm]), side_lo(fp, lg[sp]));
      }
      pm[k] = pf.mass;
      pdm[k] = pf.drop_m;
      pdp[k] = pf.drop_p;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
#endif

  // 2. Each face once. An outside side is replaced by the ghost of the inside one (face_between);
  // at a level edge the outside is water at the inside cell's far level (its initial surface).
  for (int dir = 0; dir < 2; ++dir) {
    if (!((dir_mask >> dir) & 1)) continue;
    const int da = dir == 0, db = dir == 1, slot = FACE_SLOTS == 1 ? 0 : dir;
    for (int f = lid; f < NFACE; f += TILE * TILE) {
      const int q = f % NFA, r = f / NFA;
      const int2 cm = face_minus_cell(q, r, dir);
      const int am = cm.x, bm = cm.y, ap = am + da, bp = bm + db;
      const int sm = bm * SPAN + am, sp = bp * SPAN + ap;
      const int m_in = lin[sm], p_in = lin[sp];
      Face fc = {0, 0, 0, 0, 0, 0};
      if (m_in || p_in) {
        const CellFaces mf = local_faces(lh, le, lu, lv, lg, lin, pm, pdm, pdp, m_in ? am : ap, m_in ? bm : bp, dir, hr, p->h_dry);
        const CellFaces pf = p_in ? local_faces(lh, le, lu, lv, lg, lin, pm, pdm, pdp, ap, bp, dir, hr, p->h_dry) : mf;
        const int outside_a = m_in ? ap : am, outside_b = m_in ? bp : bm;
        const real far = (m_in && p_in) ? (real)0 : far_level[cell_index(p, x0 + (m_in ? am : ap), y0 + (m_in ? bm : bp))];
        fc = face_between(m_in, side_hi(mf, lg[sm]), p_in, side_lo(pf, lg[sp]),
                          boundary_kind(p, x0 + outside_a, y0 + outside_b), far);
      }
      const int o = slot * NFACE + f;
      ffh[o] = fc.fh;
      ffqn[o] = fc.fqn;
      ffqt[o] = fc.fqt;
      ffp[o] = fc.p;
      ffcm[o] = fc.corr_m;
      ffcp[o] = fc.corr_p;
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);

#if DRAINING
  // 2b. Draining factors of the cells along the sweep (the tile's and one beyond each end), then
  // each face the tile uses scaled by its upwind cell's factor (see the header).
  {
    const int dir = (dir_mask & 1) ? 0 : 1;
    for (int c = lid; c < (TILE + 2 * RING) * TILE; c += TILE * TILE) {
      const int t = c % (TILE + 2 * RING), r = c / (TILE + 2 * RING);
      const int2 cell = face_minus_cell(t + 1, r, dir);  // the plus side of face t is cell t
      const int s = cell.y * SPAN + cell.x;
      const real out_flux = fmax(ffh[r * NFA + t + 1], (real)0) - fmin(ffh[r * NFA + t], (real)0);
      const real h = lh[s];
      theta[c] = (lin[s] && dtdx * out_flux > h) ? h / (dtdx * out_flux) : (real)1;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int f = lid; f < NFACE; f += TILE * TILE) {
      const int q = f % NFA, r = f / NFA;
      if (q < RING || q > TILE + RING) continue;  // faces only the ring cells use
      const real th = theta[r * (TILE + 2 * RING) + (ffh[f] > (real)0 ? q - 1 : q)];
      ffh[f] *= th;
      ffqn[f] *= th;
      ffqt[f] *= th;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
#endif

  // 3. The update of the work-item's own cell.
  const int tx = get_local_id(0), ty = get_local_id(1);
  const int la = tx + HALO, lb = ty + HALO;
  const int i = x0 + la, j = y0 + lb;
  const int sc = lb * SPAN + la;
  if (!lin[sc]) return;  // off the raster or nodata (no barrier follows)
  const int k = cell_index(p, i, j);
  const real g = lg[sc];

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
    // The cell's minus and plus faces: row and position along the direction.
    const int row = dir == 0 ? ty : tx, along = dir == 0 ? tx : ty;
    const int om = (FACE_SLOTS == 1 ? 0 : dir) * NFACE + row * NFA + RING + along, op = om + 1;

    mass[dir] = ffh[op] - ffh[om];
    // Normal momentum: advective flux, pressure with the cell's own g_p, hydrostatic corrections,
    // and the centred well-balanced bed source from the cell's own reconstruction.
    real s = (ffqn[op] + g * (ffp[op] + ffcm[op])) - (ffqn[om] + g * (ffp[om] + ffcp[om]));
    if (lh[sc] > (real)0) {
      const CellFaces own = local_faces(lh, le, lu, lv, lg, lin, pm, pdm, pdp, la, lb, dir, hr, p->h_dry);
      s += g * (real)0.5 * (own.h_lo + own.h_hi) * ((own.e_hi - own.h_hi) - (own.e_lo - own.h_lo));
      const real dg = g - gn[k];  // exactly zero with the default depth pressure (g_p == g_n)
      if (dg != (real)0 && m_in && p_in)
        s -= dg * lh[sc] * (real)0.5 * ((le[sp] - lh[sp]) - (le[sm] - lh[sm]));
    }
    normal[dir] = s;
    tangential[dir] = ffqt[op] - ffqt[om];  // moves the other direction's momentum
    if (!m_in) out -= ffh[om];
    if (!p_in) out += ffh[op];
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
  // Positivity holds under the CFL condition (or by the draining factors); a negative value can
  // only be round-off.
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
