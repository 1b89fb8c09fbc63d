// One SSP-RK2 stage of the two-phase debris-flow grid model (spec §4, "grid mode"; Pudasaini 2012),
// for one cell per work-item, followed by the stiff point sources of that stage:
//   U_out = S_ds( a U_base + (1 - a) (U_st + dt L(U_st)) ),   ds = dt (stage 1), dt/2 (stage 2).
// Fluid (h_f, q_f): shallow water over the bed b + h_s with the mixture surface eta = b + h_s + h_f,
//   which is exactly the fluid-pressure force -g_p h_f dH/dx - g_n h_f db/dx - (1/2) g_p H^2 dalpha_s/dx
//   of spec §4 (hydrostatic reconstruction over b + h_s: a fluid or mixture at rest stays at rest).
// Solids (h_s, q_s): flux h_s u_s^2 + h_s Pi with the lateral pressure Pi = max(0, K (1 - gamma) g_p H/2
//   - 2 c sqrt(K) / rho_s) (Savage-Hutter with Bell's cohesion reduction, OpenLISEM P.43), the bed term
//   -(1 - gamma) g_n h_s db/dx and the buoyancy -gamma h_s (g_n db/dx + g_p dH/dx) from the gradient of
//   the fluid's surface (solid_bed.cl, point 7); the bed as the
//   solids feel it (terrain-following gravity with the bed's curvature, the reconstructed bed, the
//   faces between different beds and the walls they make) is in solid_bed.cl.
// Passive scalars carried with the solids (conserved as h_s * value, upwinded): the internal
//   friction angle phi, the solid density rho_s, the grain size d and the cohesion c, so a cohesive
//   release keeps its cohesion where it flows (and loose material stays loose where it flows over a
//   cohesive release's former footprint), and the lift-off speed w >= 0 of the curvature term
//   (solid_bed.cl, point 5; zero with the term off).
// Sources S (implicit, per stage, first order in time): the solids' basal law (basal_rheology.cl:
//   Coulomb friction tan(delta) (1 - B gamma_eff) g_n h_s by default, or Voellmy, mu(I), Bingham,
//   Herschel-Bulkley) and the drag with virtual mass, solved together as one momentum-conserving
//   exchange (phase_exchange.cl: water can set a deposit moving, a held deposit passes the drag to
//   the bed), then the basal viscous terms and Manning on the fluid; friction can stop motion but
//   never reverse it.
// Viscous stress of the fluid (P.30, compiled in with -DDEBRIS_VISCOUS=1): face fluxes of
//   debris_viscous.cl added to the fluid momentum fluxes.
// Particle bed (hybrid mode, compiled in with -DDEBRIS_OBSTACLE=1; spec §6): the confined phase of the
//   particles, transferred to the grid (thickness H_c and velocity u_c per cell, `pbed`), is part of
//   both phases' bed: the fluid flows over b + H_c + h_s, the solids over b + H_c, so water and loose
//   material flow around or over the blocks. The forces this bed exerts on the grid phases come back
//   to the particles as an impulse per cell (`impulse`, momentum per area over the step): the
//   hydrostatic-reconstruction and bed-slope forces of the fluid, the bed-slope force of the solids
//   (the parts due to H_c) and the basal friction of solids resting on moving particles (Coulomb
//   friction acts on the velocity relative to u_c). See docs/particles.md, "Particles as bed".
// Static solids: a cell whose solid motion friction stopped in the last stage is "locked"; no solid
//   mass crosses a face between two locked (or empty) cells, so material at rest whose driving force
//   stays below friction does not creep by numerical diffusion; pressure still acts, so a pile that
//   friction cannot hold starts to move in the next stage.
// The two-phase fluid keeps Audusse's reconstruction at every face (SUPERCRITICAL_FACES 0,
// flow/bernoulli_face.cl): the particle bed's momentum exchange takes the fluid's bed-step terms as
// Audusse's hydrostatic ones (react_f below), and with the supercritical approach the water and
// the block of ParticleBed.MomentumOfWaterAndBlockIsConserved lost 0.2 % of their momentum.
#define SUPERCRITICAL_FACES 0
#include "flow/debris_closures.cl"
#include "flow/riemann.cl"
#include "flow/solid_bed.cl"
#include "flow/manning.cl"
#include "flow/basal_rheology.cl"
#include "flow/phase_exchange.cl"
#ifndef DEBRIS_VISCOUS
#define DEBRIS_VISCOUS 0
#endif
#if DEBRIS_VISCOUS
#include "flow/debris_viscous.cl"
#endif

#ifndef DEBRIS_OBSTACLE
#define DEBRIS_OBSTACLE 0
#endif
#ifndef DEBRIS_CURVATURE
#define DEBRIS_CURVATURE 0
#endif

#define MSPAN (TILE + 2)  // the tile and its one-cell halo, for the material's trigonometry
#define NSOLID 8   // solid state components: h_s, q_sx, q_sy, h_s phi, h_s rho_s, h_s d, h_s c, h_s w
// The passive scalars among them (from component 3) that move: the lift-off speed only where the
// curvature term is compiled in (without it the component stays 0 and costs no flux).
#define NSCALAR (DEBRIS_CURVATURE ? 5 : 4)

/// The bed the grid phases see: the DEM, plus the particles' confined thickness in hybrid mode.
#if DEBRIS_OBSTACLE
#define BED(k) (b[k] + pbed[k])
#else
#define BED(k) (b[k])
#endif

/// Share of the bed step between cells k (higher) and o that the particles make: the part of the
/// fluid-bed difference B_k - B_o due to H_c, in [0, 1]; 0 unless cell k holds particles.
INLINE real particle_share(real dHc, real dB, real Hc_k) {
  if (!(Hc_k > (real)0) || !(dB > (real)0)) return (real)0;
  return clamp(dHc / dB, (real)0, (real)1);
}

/// Primitive state of one cell along a direction: solids and fluid. The solids reconstruct the bed b
/// itself (its faces then give the solid surface e_s = b + h_s), so the bed-slope force of a cell at
/// the edge of a solid mass is the true slope even where the solid surface has a kink.
typedef struct {
  real hs, es, us, vs;  // solid thickness, bed b (primitive) / solid surface b + h_s (faces), velocities
  real hf, ef, uf, vf;  // fluid thickness, mixture surface b + h_s + h_f, velocities
  real hc;              // particle bed H_c (hybrid mode; 0 otherwise)
  real zb;              // the solids' bed: cell value (primitive) / reconstructed face value (faces)
} Prim2;

typedef struct {
  Prim2 lo, hi;
} Faces2;

INLINE Prim2 load_prim2(__constant const FlowParams* p, __constant const DebrisParams* dp, __global const real* S,
                        __global const real* hf, __global const real* qfx, __global const real* qfy,
                        __global const real* b, __global const real* pbed, int k, int n, int dir) {
  Prim2 c;
  c.hs = S[k];
  c.es = BED(k);
  c.zb = c.es;
#if DEBRIS_OBSTACLE
  c.hc = pbed[k];
#else
  c.hc = 0;
#endif
  const real us = solid_velocity(c.hs, S[n + k], p->h_dry, dp->film_h), vs = solid_velocity(c.hs, S[2 * n + k], p->h_dry, dp->film_h);
  c.us = dir == 0 ? us : vs;
  c.vs = dir == 0 ? vs : us;
  c.hf = hf[k];
  c.ef = c.es + c.hs + c.hf;
  const real uf = velocity(c.hf, qfx[k], p->h_dry), vf = velocity(c.hf, qfy[k], p->h_dry);
  c.uf = dir == 0 ? uf : vf;
  c.vf = dir == 0 ? vf : uf;
  return c;
}

/// The fluid's surface of neighbour n as cell c's buoyancy sees it (solid_bed.cl, point 7): its
/// surface where it holds fluid; else (no fluid, or outside: c's own) the top of its column, but not
/// above c's surface (a dry bank higher than the water is a wall to it, and the water at rest beside it
/// pushes nothing).
INLINE real fluid_surface_seen(Prim2 n, int n_in, Prim2 c, real h_dry) {
  if (!n_in) return c.ef;
  if (n.hf > h_dry) return n.ef;
  return fmin(n.ef - n.hf, c.ef);
}

/// MUSCL reconstruction of both phases of cell c, with the rise of its solids' bed (bed_rise,
/// solid_bed.cl, point 2). The solids: by their surface where they carry lateral pressure
/// (`hydrostatic`: carries_lateral_pressure, taken once per cell in the stage's halo), else by their thickness over that bed (solid_bed.cl,
/// point 2a). The fluid is reconstructed as the water
/// is (reconstruct_surface, flow_common.cl: its surface with the run's limiter over the minmod of
/// its bed b + h_s, the thickness slope bounded), first order at its wet/dry fronts and on and next
/// to the particle bed: its bed is then flat within each cell, so every bed force on the fluid there
/// is a face correction that the particles take in full (no bed slope inside a cell without
/// particles, which nothing could take the reaction of). (Before 2026-12-07 it limited its thickness
/// and its surface apart, `reconstruct`, whose implied face beds rise falsely on steep, coarsely
/// resolved beds: fluid on cliffs gained energy, two-phase soak seed 6916895877032760343, the
/// mechanism the water's reconstruction was built against. Second order at its fronts, as the water
/// has it, broke the momentum balance of water and particle bed by 1.3e-12 of the momentum,
/// ParticleBed.MomentumOfWaterAndBlockIsConserved, for a reason not traced.)
INLINE Faces2 reconstruct2(Prim2 m, int m_in, Prim2 c, Prim2 p, int p_in, real rise, int hydrostatic) {
  const Prim s0 = {c.hs, c.es, c.us, c.vs};
  const Prim f0 = {c.hf, c.ef, c.uf, c.vf}, fm = {m.hf, m.ef, m.uf, m.vf}, fp = {p.hf, p.ef, p.uf, p.vf};
  const int on_bed = c.hc > (real)0 || (m_in && m.hc > (real)0) || (p_in && p.hc > (real)0);
  CellFaces s;
  if (hydrostatic) {
    // Material with lateral pressure: its surface over its bed, as the water's (solid_bed.cl, 2a).
    const Prim w0 = {c.hs, c.es + c.hs, c.us, c.vs}, wm = {m.hs, m.es + m.hs, m.us, m.vs}, wp = {p.hs, p.es + p.hs, p.us, p.vs};
    s = reconstruct_surface(wm, m_in, w0, wp, p_in);
    s.e_lo -= s.h_lo;  // the face beds
    s.e_hi -= s.h_hi;
  } else {
    // Its thickness on its own over the linear bed of point 2; velocities alike; first order at its
    // fronts and next to outside cells.
    real sh = 0, su = 0, sv = 0;
    if (m_in && p_in && m.hs > (real)0 && c.hs > (real)0 && p.hs > (real)0) {
      sh = limited_slope(c.hs - m.hs, p.hs - c.hs);
      su = limited_slope(c.us - m.us, p.us - c.us);
      sv = limited_slope(c.vs - m.vs, p.vs - c.vs);
    }
    s = faces_of(s0, sh, rise, su, sv);
  }
  const CellFaces f = reconstruct_surface(fm, m_in && !on_bed && m.hf > (real)0, f0, fp, p_in && !on_bed && p.hf > (real)0);
  Faces2 r;
  r.lo = (Prim2){s.h_lo, s.h_lo + s.e_lo, s.un_lo, s.ut_lo, f.h_lo, f.e_lo, f.un_lo, f.ut_lo, c.hc, s.e_lo};
  r.hi = (Prim2){s.h_hi, s.h_hi + s.e_hi, s.un_hi, s.ut_hi, f.h_hi, f.e_hi, f.un_hi, f.ut_hi, c.hc, s.e_hi};
  return r;
}

/// Per-cell material state: gamma (0 where no fluid), phi, delta, rho_s, d, cohesion over rho_s.
typedef struct {
  real gamma, phi, delta, rho_s, d, c_over_rho;
} Material;

INLINE real scalar_of(__global const real* S, int n, int comp, int k, real h_dry, real fallback) {
  const real hs = S[k];
  return hs > h_dry ? S[comp * n + k] / hs : fallback;
}

INLINE Material material_of(__constant const FlowParams* p, __constant const DebrisParams* dp, __global const real* S,
                            __global const real* hf, __global const real* delta, int k, int n) {
  Material m;
  m.phi = scalar_of(S, n, 3, k, p->h_dry, dp->phi_default);
  m.rho_s = scalar_of(S, n, 4, k, p->h_dry, dp->rho_s_default);
  m.d = scalar_of(S, n, 5, k, p->h_dry, dp->d_default);
  m.gamma = hf[k] > p->h_dry ? submerged_gamma(dp, m.rho_s, S[k], hf[k]) : (real)0;
  m.delta = dp->delta_from_phi ? m.phi : delta[k];
  m.c_over_rho = scalar_of(S, n, 6, k, p->h_dry, (real)0) / m.rho_s;
  return m;
}

/// A solid side of solid_bed.cl with the lateral pressure Pi [m^2/s^2] (per unit solid density and
/// thickness) of coefficient K: Pi = max(0, a H - c0), a = K (1 - gamma) g_p / 2, c0 = 2 c sqrt(K) / rho_s.
INLINE SolidSide solid_side(__constant const DebrisParams* dp, real h, real z, real un, real ut, real hf, real K, Material m,
                            real g, real gn) {
  const real gamma_sat = dp->rho_f / m.rho_s;
  const SolidSide s = {h, z, un, ut, (real)0.5 * K * ((real)1 - m.gamma) * g, (real)2 * m.c_over_rho * sqrt(K), hf,
                       gn * ((real)1 - m.gamma), gn * fmax((real)0, gamma_sat - m.gamma), 0};
  return s;
}

/// Whether a solid column (thickness hs, fluid hf, material m, coefficient K, g_p and g_n of its cell)
/// is reconstructed by its surface (solid_bed.cl, point 2a): where it is thicker than the dry
/// threshold and its lateral pressure Pi (solid_side) is positive at its own thickness.
INLINE int carries_lateral_pressure(__constant const FlowParams* p, __constant const DebrisParams* dp, Material m, real K,
                                    real hs, real hf, real g, real gn) {
  if (!(hs > p->h_dry)) return 0;
  const SolidSide s = solid_side(dp, hs, 0, 0, 0, hf, K, m, g, gn);
  return side_pi(s, hs) > (real)0;
}

/// The push a static column (thickness hs, material m, g_n of its cell) holds through one face beyond
/// its own pressure (solid_bed.cl, point 6): half its basal strength at rest over the cell's area, per
/// unit width [m^3/s^2].
INLINE real static_hold(__constant const FlowParams* p, __constant const DebrisParams* dp, real hs, Material m, real tan_delta,
                        real gn) {
  if (!(hs > p->h_dry)) return (real)0;
  BasalColumn c;
  c.h_st = hs;
  c.h = hs;
  c.g_n = gn;
  c.n_g = ((real)1 - dp->pore_b * m.gamma) * gn;
  c.cos_t = sqrt(gn / (real)GRAVITY);
  c.stretch = 1;
  c.rho = m.rho_s;
  c.tan_delta = tan_delta;
  return (real)0.5 * basal_strength(dp, c) * p->dx;
}

/// The turn onto cell k's tangent plane of solids arriving from cell o (solid_bed.cl, point 1): their
/// 3-D velocity (u_o, u_o . grad b_o) rotated into the tangent plane of k, its magnitude kept (the
/// normal impulse of a bed that the material follows). Returns the change of the horizontal velocity
/// and, in `lift`, u_o . (grad b_k - grad b_o), the change of vertical velocity that staying on the
/// bed asks (its sign: the bed presses, > 0, or holds the material down, < 0). Grouped so that x <-> y
/// transposed cells give bitwise the same values.
INLINE real2 arrival_turn(__constant const FlowParams* p, __constant const DebrisParams* dp, __global const real* S,
                          __global const real* fslope, __global const real* gn, int n, int k, int o, real* lift) {
  const real u = solid_velocity(S[o], S[n + o], p->h_dry, dp->film_h), v = solid_velocity(S[o], S[2 * n + o], p->h_dry, dp->film_h);
  const real sxk = fslope[k], syk = fslope[n + k], sxo = fslope[o], syo = fslope[n + o];
  const real d = u * (sxk - sxo) + v * (syk - syo);
  *lift = d;
  // The projection onto the tangent plane (normal (-grad b, 1) / sqrt(1 + |grad b|^2)) ...
  const real c2 = gn[k] / (real)GRAVITY;
  const real up = u - d * c2 * sxk, vp = v - d * c2 * syk;
  // ... scaled back to the arriving speed (com1DFA's reprojection keeps it too): the turn itself does
  // no work, only friction on its normal force does.
  const real wo = u * sxo + v * syo, wp = up * sxk + vp * syk;
  const real m2 = (u * u + v * v) + wo * wo, p2 = (up * up + vp * vp) + wp * wp;
  const real scale = p2 > (real)0 ? sqrt(m2 / p2) : (real)1;
  return (real2)(scale * up - u, scale * vp - v);
}

/// Kinetic energy per unit area of a cell's two phases moving along the bed of slope (sx, sy):
/// (rho_s (|q_s|^2 + (q_s . grad b)^2) / h_s + rho_f (...) / h_f) / 2 [J/m^2], the horizontal and the
/// vertical motion as the diagnostics count them (debris_diagnostics.cl), each phase where it is
/// thicker than h_dry.
INLINE real column_kinetic(__constant const DebrisParams* dp, real hs, const real* qs, real rho_s, real hf, const real* qf,
                           real sx, real sy, real h_dry) {
  real e = 0;
  if (hs > h_dry) {
    const real w = qs[0] * sx + qs[1] * sy;
    e += rho_s * ((qs[0] * qs[0] + qs[1] * qs[1]) + w * w) / hs;
  }
  if (hf > h_dry) {
    const real w = qf[0] * sx + qf[1] * sy;
    e += dp->rho_f * ((qf[0] * qf[0] + qf[1] * qf[1]) + w * w) / hf;
  }
  return (real)0.5 * e;
}

__kernel __attribute__((reqd_work_group_size(TILE, TILE, 1)))
void debris_stage(__constant const FlowParams* p, __constant const DebrisParams* dp,
                           __global const uchar* mask, __global const int* tile_list, __global const real* b,
                           __global const real* gp, __global const real* gn, __global const real* far_level,
                           __global const real* manning,
                           __global const real* fslope,
                           __global const real* delta,
                           __global const real* pbed, __global real* impulse,
                           __global const real* S_base, __global const real* hf_base, __global const real* qfx_base,
                           __global const real* qfy_base, __global const real* S_st, __global const real* hf_st,
                           __global const real* qfx_st, __global const real* qfy_st, __global const uchar* lock_st,
                           __global real* S_out, __global real* hf_out, __global real* qfx_out, __global real* qfy_out,
                           __global uchar* lock_out, __global real* out_step, const real dt, const real a,
                           const real w_out, const real ds, const int first_stage) {
  const int2 cc = tile_cell(p, tile_list);
  const int i = cc.x, j = cc.y;
  const int n = p->nx * p->ny;
  // The material's trigonometry, once per cell of the tile and its one-cell halo: the stage needs it
  // for each cell and its four neighbours (earth pressure, the static contacts' strength), and its
  // cos and tan were 37 % of the step when each use evaluated them again (docs/performance.md).
  // With it, whether its solids are reconstructed by their surface (solid_bed.cl, point 2a; with the
  // smallest K the law gives; never in hybrid runs, whose particles' share of the bed force is taken
  // against the DEM's linear bed).
  __local real l_ka[MSPAN * MSPAN], l_kroot[MSPAN * MSPAN], l_tand[MSPAN * MSPAN];
  __local uchar l_hyd[MSPAN * MSPAN];
  {
    const int x0 = i - (int)get_local_id(0) - 1, y0 = j - (int)get_local_id(1) - 1;
    for (int s = get_local_id(1) * TILE + get_local_id(0); s < MSPAN * MSPAN; s += TILE * TILE) {
      const int gi = x0 + s % MSPAN, gj = y0 + s / MSPAN;
      real ka = 0, kroot = 0, tand = 0;
      int hyd = 0;
      if (cell_inside(p, mask, gi, gj)) {
        const int kk = cell_index(p, gi, gj);
        const Material m = material_of(p, dp, S_st, hf_st, delta, kk, n);
        real K = dp->k_const;
        if (dp->earth_pressure != EARTH_CONSTANT) {
          const EarthPressureTerms t = earth_pressure_terms(m.phi, m.delta);
          ka = t.a;
          kroot = t.root;
          K = earth_pressure_at(t, (real)0);
        }
        tand = tan(m.delta);
        hyd = !DEBRIS_OBSTACLE && carries_lateral_pressure(p, dp, m, K, S_st[kk], hf_st[kk], gp[kk], gn[kk]);
      }
      l_ka[s] = ka;
      l_kroot[s] = kroot;
      l_tand[s] = tand;
      l_hyd[s] = (uchar)hyd;
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (i >= p->nx || j >= p->ny || !cell_inside(p, mask, i, j)) return;
  const int lc = ((int)get_local_id(1) + 1) * MSPAN + (int)get_local_id(0) + 1;  // this cell in the halo block
  const int k = cell_index(p, i, j);
  const real g = gp[k], gnk = gn[k];
  const real dtdx = dt / p->dx;
  const Material mc = material_of(p, dp, S_st, hf_st, delta, k, n);

  real dS[NSOLID] = {0, 0, 0, 0, 0, 0, 0, 0};
  real dhf = 0, dqf[2] = {0, 0}, out_s = 0, out_f = 0;
  real mass_s[2], mass_f[2], norm_s[2], norm_f[2], tang_s[2], tang_f[2], sc_flux[NSCALAR][2];
  Block blk_lo[2], blk_hi[2];  // what the minus / plus face can stop of the column (solid_bed.cl, point 4)
#if DEBRIS_OBSTACLE
  Block blk_lo_dem[2], blk_hi_dem[2];  // the same over the DEM alone (the particles' share of the walls)
#endif
#if DEBRIS_CURVATURE
  // The turn of the arriving solids (point 1), per direction: the momentum flux it changes (x, y) and
  // its normal part (the bed's push).
  real turn_x[2] = {0, 0}, turn_y[2] = {0, 0}, turn[2] = {0, 0};
#endif
#if DEBRIS_OBSTACLE
  // Force of the grid phases on the particles of this cell, per unit area and without dt/dx:
  // fluid part per unit fluid density, solid part in kg (times rho_s already).
  real react_f[2] = {0, 0}, react_s[2] = {0, 0};
  const real Hc_k = pbed[k];
#endif
  for (int dir = 0; dir < 2; ++dir) {
    const int di = dir == 0, dj = dir == 1;
    const int m_in = cell_inside(p, mask, i - di, j - dj), p_in = cell_inside(p, mask, i + di, j + dj);
    const int km = m_in ? cell_index(p, i - di, j - dj) : k, kp = p_in ? cell_index(p, i + di, j + dj) : k;
    const int lm = m_in ? lc - dj * MSPAN - di : lc, lp = p_in ? lc + dj * MSPAN + di : lc;  // their halo-block slots
    // Reconstructions of this cell and of its two neighbours along dir (each from its own neighbours).
    const Prim2 c0 = load_prim2(p, dp, S_st, hf_st, qfx_st, qfy_st, b, pbed, k, n, dir);
    const Prim2 cm = load_prim2(p, dp, S_st, hf_st, qfx_st, qfy_st, b, pbed, km, n, dir);
    const Prim2 cp = load_prim2(p, dp, S_st, hf_st, qfx_st, qfy_st, b, pbed, kp, n, dir);
    // The cells two away (inside only where the cell between is).
    const int mm_in = m_in && cell_inside(p, mask, i - 2 * di, j - 2 * dj);
    const int pp_in = p_in && cell_inside(p, mask, i + 2 * di, j + 2 * dj);
    const int kmm = mm_in ? cell_index(p, i - 2 * di, j - 2 * dj) : km, kpp = pp_in ? cell_index(p, i + 2 * di, j + 2 * dj) : kp;
    const Faces2 own = reconstruct2(cm, m_in, c0, cp, p_in, bed_rise(BED(kmm), mm_in, cm.es, m_in, c0.es, cp.es, p_in, BED(kpp), pp_in), l_hyd[lc]);
    Faces2 fm_cell = own, fp_cell = own;
    if (m_in) {
      const Prim2 cmm = mm_in ? load_prim2(p, dp, S_st, hf_st, qfx_st, qfy_st, b, pbed, kmm, n, dir) : cm;
      fm_cell = reconstruct2(cmm, mm_in, cm, c0, 1, bed_rise(cmm.es, 0, cmm.es, mm_in, cm.es, c0.es, 1, cp.es, p_in), l_hyd[lm]);
    }
    if (p_in) {
      const Prim2 cpp = pp_in ? load_prim2(p, dp, S_st, hf_st, qfx_st, qfy_st, b, pbed, kpp, n, dir) : cp;
      fp_cell = reconstruct2(c0, 1, cp, cpp, pp_in, bed_rise(cm.es, m_in, c0.es, 1, cp.es, cpp.es, pp_in, cpp.es, 0), l_hyd[lp]);
    }
    const int kind_m = boundary_kind(p, i - di, j - dj), kind_p = boundary_kind(p, i + di, j + dj);
    const real gm = gp[km], gpp = gp[kp];

    // Fluid faces: shallow water over b + h_s (the bed of the fluid is e - h = b + h_s).
    const Side fmL = {fm_cell.hi.hf, fm_cell.hi.ef, fm_cell.hi.uf, fm_cell.hi.vf, gm};
    const Side fmR = {own.lo.hf, own.lo.ef, own.lo.uf, own.lo.vf, g};
    const Side fpL = {own.hi.hf, own.hi.ef, own.hi.uf, own.hi.vf, g};
    const Side fpR = {fp_cell.lo.hf, fp_cell.lo.ef, fp_cell.lo.uf, fp_cell.lo.vf, gpp};
    // Level edges: the fluid's characteristic ghost against still water at the cell's initial
    // surface (riemann.cl, open_ghost; the solids see an open edge there). Only cells beside an
    // outside cell read it.
    const real far = (m_in && p_in) ? (real)0 : far_level[k];
    const Face Fm = face_between(m_in, fmL, 1, fmR, kind_m, far);
    const Face Fp = face_between(1, fpL, p_in, fpR, kind_p, far);

    // Solid faces: each side's lateral pressure with its cell's K (active where its solids extend
    // along dir, passive where they contract), from its face thickness of the mixture, and the
    // terrain factor of its cell (curvature of the bed, solid_bed.cl).
    const Material mm = m_in ? material_of(p, dp, S_st, hf_st, delta, km, n) : mc;
    const Material mp = p_in ? material_of(p, dp, S_st, hf_st, delta, kp, n) : mc;
    real Km, Kc, Kp;
    if (dp->earth_pressure == EARTH_CONSTANT) {
      Km = Kc = Kp = dp->k_const;
    } else {
      const EarthPressureTerms tm = {l_ka[lm], l_kroot[lm]}, tc = {l_ka[lc], l_kroot[lc]}, tp = {l_ka[lp], l_kroot[lp]};
      Km = earth_pressure_at(tm, passive_share(fm_cell.hi.us - fm_cell.lo.us, p->dx, gn[km], cm.hs + cm.hf));
      Kc = earth_pressure_at(tc, passive_share(own.hi.us - own.lo.us, p->dx, gnk, c0.hs + c0.hf));
      Kp = earth_pressure_at(tp, passive_share(fp_cell.hi.us - fp_cell.lo.us, p->dx, gn[kp], cp.hs + cp.hf));
    }
    SolidSide smL = solid_side(dp, fm_cell.hi.hs, fm_cell.hi.zb, fm_cell.hi.us, fm_cell.hi.vs, fm_cell.hi.hf, Km, mm,
                               gm, gn[km]);
    SolidSide smR = solid_side(dp, own.lo.hs, own.lo.zb, own.lo.us, own.lo.vs, own.lo.hf, Kc, mc, g, gnk);
    SolidSide spL = solid_side(dp, own.hi.hs, own.hi.zb, own.hi.us, own.hi.vs, own.hi.hf, Kc, mc, g, gnk);
    SolidSide spR = solid_side(dp, fp_cell.lo.hs, fp_cell.lo.zb, fp_cell.lo.us, fp_cell.lo.vs, fp_cell.lo.hf, Kp, mp,
                               gpp, gn[kp]);
    // Static contacts (solid_bed.cl, point 6): each side's share of its strength at rest.
    const int lk = lock_st[k];
    const int lock_m = lk && (!m_in || lock_st[km]), lock_p = lk && (!p_in || lock_st[kp]);
    if (lk) {
      const real hold_c = static_hold(p, dp, c0.hs, mc, l_tand[lc], gnk);
      smR.hold = spL.hold = hold_c;
      if (lock_m) smL.hold = m_in ? static_hold(p, dp, cm.hs, mm, l_tand[lm], gn[km]) : hold_c;
      if (lock_p) spR.hold = p_in ? static_hold(p, dp, cp.hs, mp, l_tand[lp], gn[kp]) : hold_c;
    }
    const SolidFace Sm = solid_face(m_in, smL, 1, smR, kind_m, lock_m);
    const SolidFace Sp = solid_face(1, spL, p_in, spR, kind_p, lock_p);
    blk_lo[dir] = Sm.blk_p;
    blk_hi[dir] = Sp.blk_m;

    mass_f[dir] = Fp.fh - Fm.fh;
    // Fluid normal momentum: as the single-phase stage, over the bed b + h_s.
    real sf = (Fp.fqn + g * (Fp.p + Fp.corr_m)) - (Fm.fqn + g * (Fm.p + Fm.corr_p));
#if DEBRIS_OBSTACLE
    {
      // The fluid's bed force on this cell's bed, from the face corrections of the neighbours'
      // fluid (a step up into this cell pushes their fluid away and this cell's bed on): the part
      // the particles make of each step.
      const real Bk = c0.ef - c0.hf, Bm = cm.ef - cm.hf, Bp = cp.ef - cp.hf;
      if (m_in) react_f[dir] += gm * Fm.corr_m * particle_share(Hc_k - pbed[km], Bk - Bm, Hc_k);
      if (p_in) react_f[dir] -= gpp * Fp.corr_p * particle_share(Hc_k - pbed[kp], Bk - Bp, Hc_k);
    }
#endif
    // (The fluid is first order on and next to the particle bed, so the bed-slope term below is zero
    // in every cell with particles: the face corrections above carry all of their share.)
    if (c0.hf > (real)0) {
      sf += g * (real)0.5 * (own.lo.hf + own.hi.hf) * ((own.hi.ef - own.hi.hf) - (own.lo.ef - own.lo.hf));
      const real dg = g - gnk;
      if (dg != (real)0 && m_in && p_in) sf -= dg * c0.hf * (real)0.5 * (b[kp] - b[km]);
    }
    mass_s[dir] = Sp.fh - Sm.fh;
#if DEBRIS_CURVATURE
    // The solids that flow in through each face, with the velocity and bed of the cell they come from.
    if (m_in && Sm.fh > (real)0) {
      real lift;
      const real2 dv = arrival_turn(p, dp, S_st, fslope, gn, n, k, km, &lift);
      turn_x[dir] += Sm.fh * dv.x;
      turn_y[dir] += Sm.fh * dv.y;
      turn[dir] += Sm.fh * lift;
    }
    if (p_in && Sp.fh < (real)0) {
      real lift;
      const real2 dv = arrival_turn(p, dp, S_st, fslope, gn, n, k, kp, &lift);
      turn_x[dir] -= Sp.fh * dv.x;
      turn_y[dir] -= Sp.fh * dv.y;
      turn[dir] -= Sp.fh * lift;
    }
#endif
    // Solid normal momentum: lateral pressure and the bed jumps at the faces (solid_bed.cl), the
    // bed slope within the cell with the submerged weight over the reconstructed bed, and the
    // buoyancy (solid_bed.cl, point 7).
    real ss = (Sp.fqn + Sp.p + Sp.corr_m) - (Sm.fqn + Sm.p + Sm.corr_p);
    if (c0.hs > (real)0) {
      const real rise = own.hi.zb - own.lo.zb;
      // (c0.hs is the mean of the two face thicknesses of the symmetric reconstruction)
      const real hbar = c0.hs;
      ss += gnk * ((real)1 - mc.gamma) * hbar * rise;
      // Buoyancy (solid_bed.cl, point 7): gamma_eff h_s (g_p grad eta + (g_n - g_p) grad b), the
      // fluid's surface eta centred, a neighbour without fluid seen as a wall (its top, at most ours).
      if (mc.gamma > (real)0) {
        const real span = (m_in && p_in) ? (real)0.5 : (real)1;
        const real em = fluid_surface_seen(cm, m_in, c0, p->h_dry), ep = fluid_surface_seen(cp, p_in, c0, p->h_dry);
        real grad = g * span * (ep - em);
        if (m_in && p_in) grad += (gnk - g) * (real)0.5 * (b[kp] - b[km]);
        ss += mc.gamma * c0.hs * grad;
      }
#if DEBRIS_OBSTACLE
      // The particles' part of the bed force within the cell: all but what the DEM alone exerts.
      react_s[dir] += mc.rho_s * gnk * ((real)1 - mc.gamma) * hbar * (rise - bed_rise(b[kmm], mm_in, b[km], m_in, b[k], b[kp], p_in, b[kpp], pp_in));
#endif
    }
#if DEBRIS_OBSTACLE
    {
      // The particles' part of the bed-jump forces and of the wall reactions: the faces again over
      // the DEM alone (face beds of the DEM's own reconstruction); the difference is the particles'.
      const real zb_m = b[km] + (real)0.5 * bed_rise(b[kmm], 0, b[kmm], mm_in, b[km], b[k], 1, b[kp], p_in);
      const real zb_p = b[kp] - (real)0.5 * bed_rise(b[km], m_in, b[k], 1, b[kp], b[kpp], pp_in, b[kpp], 0);
      const real rise_b = bed_rise(b[kmm], mm_in, b[km], m_in, b[k], b[kp], p_in, b[kpp], pp_in);
      SolidSide dL = smL, dR = smR, eL = spL, eR = spR;
      dL.z = zb_m;
      dR.z = b[k] - (real)0.5 * rise_b;
      eL.z = b[k] + (real)0.5 * rise_b;
      eR.z = zb_p;
      const SolidFace SmB = solid_face(m_in, dL, 1, dR, kind_m, lock_m);
      const SolidFace SpB = solid_face(1, eL, p_in, eR, kind_p, lock_p);
      react_s[dir] += mc.rho_s * ((Sp.corr_m - SpB.corr_m) - (Sm.corr_p - SmB.corr_p));
      blk_lo_dem[dir] = SmB.blk_p;
      blk_hi_dem[dir] = SpB.blk_m;
    }
#endif
    norm_f[dir] = sf;
    norm_s[dir] = ss;
    tang_f[dir] = Fp.fqt - Fm.fqt;
#if DEBRIS_VISCOUS
    {
      // Viscous stress of the fluid (debris_viscous.cl), through the same two faces.
      const real2 Vm = m_in ? visc_face(p, dp, mask, S_st, hf_st, qfx_st, qfy_st, gp, i - di, j - dj, dir) : (real2)(0, 0);
      const real2 Vp = p_in ? visc_face(p, dp, mask, S_st, hf_st, qfx_st, qfy_st, gp, i, j, dir) : (real2)(0, 0);
      norm_f[dir] += Vp.x - Vm.x;
      tang_f[dir] += Vp.y - Vm.y;
    }
#endif
    tang_s[dir] = Sp.fqt - Sm.fqt;
    // Scalars: upwind value times the solid mass flux.
    for (int c = 0; c < NSCALAR; ++c) {
      const real fallback = scalar_default(dp, c);
      const real vm = scalar_of(S_st, n, 3 + c, km, p->h_dry, fallback);
      const real v0 = scalar_of(S_st, n, 3 + c, k, p->h_dry, fallback);
      const real vp = scalar_of(S_st, n, 3 + c, kp, p->h_dry, fallback);
      sc_flux[c][dir] = Sp.fh * (Sp.fh >= (real)0 ? v0 : vp) - Sm.fh * (Sm.fh >= (real)0 ? vm : v0);
    }
    if (!m_in) out_f -= Fm.fh, out_s -= Sm.fh;
    if (!p_in) out_f += Fp.fh, out_s += Sp.fh;
  }
  dhf = -dtdx * (mass_f[0] + mass_f[1]);
  dqf[0] = -dtdx * (norm_f[0] + tang_f[1]);
  dqf[1] = -dtdx * (norm_f[1] + tang_f[0]);
  dS[0] = -dtdx * (mass_s[0] + mass_s[1]);
  dS[1] = -dtdx * (norm_s[0] + tang_s[1]);
  dS[2] = -dtdx * (norm_s[1] + tang_s[0]);
  for (int c = 0; c < NSCALAR; ++c) dS[3 + c] = -dtdx * (sc_flux[c][0] + sc_flux[c][1]);
#if DEBRIS_CURVATURE
  // The bed's impulse that turns the arriving solids onto this cell's tangent plane (point 1): per
  // unit area dt/dx sum_in F (u_turned - u_o).
  dS[1] += dtdx * (turn_x[0] + turn_x[1]);
  dS[2] += dtdx * (turn_y[0] + turn_y[1]);
  const real turn_dt = dtdx * (turn[0] + turn[1]);
#endif

  // RK combination.
  real Sn[NSOLID];
  for (int c = 0; c < NSOLID; ++c) {
    Sn[c] = S_st[c * n + k] + dS[c];
    if (a != (real)0) Sn[c] = a * S_base[c * n + k] + ((real)1 - a) * Sn[c];
  }
  real hfn = hf_st[k] + dhf, qf[2] = {qfx_st[k] + dqf[0], qfy_st[k] + dqf[1]};
  if (a != (real)0) {
    hfn = a * hf_base[k] + ((real)1 - a) * hfn;
    qf[0] = a * qfx_base[k] + ((real)1 - a) * qf[0];
    qf[1] = a * qfy_base[k] + ((real)1 - a) * qf[1];
  }
  const real hsn = fmax(Sn[0], (real)0);
  hfn = fmax(hfn, (real)0);
  // Solid momentum consistent with the desingularised velocity (zero below the dry threshold).
  real qs[2] = {hsn * solid_velocity(hsn, Sn[1], p->h_dry, dp->film_h),
                hsn * solid_velocity(hsn, Sn[2], p->h_dry, dp->film_h)};
  if (hfn <= p->h_dry) qf[0] = qf[1] = 0;
  // Walls take the normal momentum of the columns they block (solid_bed.cl, point 4).
  const real qs_walled[2] = {wall_reaction(qs[0], hsn, blk_lo[0], blk_hi[0]), wall_reaction(qs[1], hsn, blk_lo[1], blk_hi[1])};
#if DEBRIS_OBSTACLE
  // The wall reaction the particles give: what it takes beyond the DEM's walls alone.
  const real wall_px = wall_reaction(qs[0], hsn, blk_lo_dem[0], blk_hi_dem[0]) - qs_walled[0];
  const real wall_py = wall_reaction(qs[1], hsn, blk_lo_dem[1], blk_hi_dem[1]) - qs_walled[1];
#endif
  qs[0] = qs_walled[0];
  qs[1] = qs_walled[1];

  // Stiff sources over ds: drag (with virtual mass), then basal friction of each phase.
  Material mn = mc;
  mn.rho_s = hsn > p->h_dry ? Sn[4] / hsn : dp->rho_s_default;
  mn.phi = hsn > p->h_dry ? Sn[3] / hsn : dp->phi_default;
  mn.d = hsn > p->h_dry ? Sn[5] / hsn : dp->d_default;
  mn.gamma = hfn > p->h_dry ? submerged_gamma(dp, mn.rho_s, hsn, hfn) : (real)0;
  mn.delta = dp->delta_from_phi ? mn.phi : delta[k];
  // The basal law and the drag exchange, solved together (phase_exchange.cl): water flowing over
  // a deposit can set it moving, and a held deposit passes the drag on to the bed.
  // The bed moves where the solids rest on particles (hybrid mode): the basal law acts on the
  // velocity relative to the particles' u_c, and solids carried along are not static.
#if DEBRIS_OBSTACLE
  const real ucx = Hc_k > (real)0 ? pbed[n + k] : (real)0, ucy = Hc_k > (real)0 ? pbed[2 * n + k] : (real)0;
#else
  const real ucx = 0, ucy = 0;
#endif
  real basal_px = 0, basal_py = 0;  // impulse the bed takes from the solids over ds [kg/(m s)]
  // Kinetic energy per unit area before the stiff sources (their work, the energy budget's friction
  // and drag term; out_step row 2).
  const real ke_before = column_kinetic(dp, hsn, qs, mn.rho_s, hfn, qf, fslope[k], fslope[n + k], p->h_dry);
  uchar locked = 1;
  if (hsn > p->h_dry) {
    // The friction of the stage's own state (the thickness its bed force and pressure used): with
    // the new thickness a cell filling within the stage (every front cell) met the friction of its
    // new mass but the bed force of its old one, and Coulomb fronts lagged (docs/two_phase.md).
    // The basal law of the solids (basal_rheology.cl; Coulomb by default).
    const real rx = qs[0] - hsn * ucx, ry = qs[1] - hsn * ucy;
    BasalColumn col;
    col.h_st = S_st[k];
    col.h = hsn;
#if DEBRIS_CURVATURE
    // The bed's normal impulse over the stage (solid_bed.cl, point 5), per unit mass in vertical
    // velocity: what gravity and the turn ask of it, g ds + (1 - a) turn / h (the turn enters the
    // stage's state with the weight (1 - a) dt = ds), less the lift-off speed w the material has:
    // the bed only pushes. What the material is still moving away from the bed is kept as w, which
    // gravity and the next concave turns use up before the bed presses again (a landing).
    const real need = (real)GRAVITY * ds + ((real)1 - a) * turn_dt / hsn;
    const real w_off = Sn[7] / hsn;
    const real gload = ds > (real)0 ? gnk * fmax((real)0, need - w_off) / ((real)GRAVITY * ds) : gnk;
    if (ds > (real)0) Sn[7] = hsn * fmax((real)0, w_off - need);
#else
    const real gload = gnk;
#endif
    col.n_g = ((real)1 - dp->pore_b * mn.gamma) * gload;
    col.g_n = gload;
    col.cos_t = sqrt(gnk / (real)GRAVITY);
    col.stretch = along_bed_stretch(rx, ry, fslope[k], fslope[n + k]);
    col.rho = mn.rho_s;
    col.tan_delta = tan(mn.delta);
    const int coupled = dp->drag_law != DRAG_OFF && hfn > p->h_dry;
    const int held = phase_exchange(dp, mn.rho_s, mn.d, col, hsn, hfn, qs, qf, ucx, ucy, ds, coupled, &basal_px, &basal_py);
#if DEBRIS_OBSTACLE
    locked = held && ucx == (real)0 && ucy == (real)0;
#else
    locked = held;  // no particle bed: the solids' reference velocity is zero
#endif
  }
#if DEBRIS_VISCOUS
  if (hfn > p->h_dry) visc_basal(dp, g, hsn, hfn, hsn > p->h_dry ? qs[0] / hsn : (real)0,
                                 hsn > p->h_dry ? qs[1] / hsn : (real)0, qf, ds);
#endif
  if (hfn > p->h_dry && manning[k] > (real)0) {
    const real factor = manning_factor(manning[k], hfn, qf[0] / hfn, qf[1] / hfn, fslope[k], fslope[n + k], gnk / (real)GRAVITY, ds);
    qf[0] /= factor;
    qf[1] /= factor;
  }

#if DEBRIS_CURVATURE
  if (!(hsn > p->h_dry)) Sn[7] = 0;  // no column, no flight: the next material in the cell lands
#endif
  const real source_work = ke_before - column_kinetic(dp, hsn, qs, mn.rho_s, hfn, qf, fslope[k], fslope[n + k], p->h_dry);
  S_out[k] = hsn;
  S_out[n + k] = qs[0];
  S_out[2 * n + k] = qs[1];
  for (int c = 3; c < NSOLID; ++c) S_out[c * n + k] = hsn > (real)0 ? fmax(Sn[c], (real)0) : (real)0;
  hf_out[k] = hfn;
  qfx_out[k] = qf[0];
  qfy_out[k] = qf[1];
  lock_out[k] = locked;
#if DEBRIS_OBSTACLE
  {
    // Impulse on the particles over the step: the face and bed forces with the stage weight dt/2,
    // the friction change of stage 1 with 1/2 (it reaches the end state through U1/2), of stage 2
    // with 1. Where the cell holds particles they are the bed, so the solids' basal friction acts
    // on them (whether they move or not); elsewhere it acts on the DEM.
    const real wr = w_out / p->dx, wfric = Hc_k > (real)0 ? (first_stage ? (real)0.5 : (real)1) : (real)0;
    const real rho = mn.rho_s;
    const real wwall = first_stage ? (real)0.5 : (real)1;  // the wall reaction reaches the end state as friction does
    impulse[k] += wr * (dp->rho_f * react_f[0] + react_s[0]) + wfric * basal_px + wwall * rho * wall_px;
    impulse[n + k] += wr * (dp->rho_f * react_f[1] + react_s[1]) + wfric * basal_py + wwall * rho * wall_py;
  }
#endif
  const real wf = w_out * p->dx;
  // The sources' work reaches the end state as the wall reaction does: stage 1's through U1/2.
  const real ww = (first_stage ? (real)0.5 : (real)1) * p->dx * p->dx * source_work;
  if (first_stage) {
    out_step[k] = wf * out_f;
    out_step[n + k] = wf * out_s;
    out_step[2 * n + k] = ww;
  } else {
    out_step[k] += wf * out_f;
    out_step[n + k] += wf * out_s;
    out_step[2 * n + k] += ww;
  }
}
