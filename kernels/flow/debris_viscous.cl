// Viscous stress of the fluid phase of the two-phase model (spec §4, OpenLISEM Hazard P.30;
// Pudasaini 2012, eqs. 2.5 and 2.22), in flux form so interior faces cancel pairwise:
//   tau_f = nu_R [grad u_f + (grad u_f)^T] - nu_A [grad alpha_s (x) w + w (x) grad alpha_s],
//   w = u_f - u_s, and the depth-averaged momentum gains div(h_f tau_f) (per unit fluid density).
// The Reynolds numbers N_R (Newtonian part) and N_RA (interfacial, "non-Newtonian" part driven by
// solid-concentration gradients) are parameters, as in the paper's experiments (N_R = 15000,
// N_RA = 30). Pudasaini writes N_R = sqrt(g L) H rho_f / (alpha_f eta_f) with scales L and H; we take
// both scales local, L = H = the mixture depth, so
//   nu_R = sqrt(g_p H) H / (alpha_f N_R),   nu_A = sqrt(g_p H) H / (alpha_f N_RA),
// with alpha_f floored at VISC_MIN_ALPHA_F (Pudasaini's scaling assumes alpha_f = O(1); a fluid film
// soaking a mostly solid mass would otherwise get an unbounded viscosity).
// Faces: normal derivatives from the two cells, tangential ones averaged over the two cells'
// centred differences (one-sided next to dry or outside cells); the face coefficient h_f nu takes
// the mean mixture depth and fluid fraction and the harmonic mean of the fluid thicknesses (second
// order where the flow is smooth, and at most twice the thinner layer at a front). No viscous flux
// crosses a face to a dry, outside or wall cell (free slip), so momentum never diffuses into dry
// ground.
// The depth-averaged basal shear terms, -chi nu_R u_f / H^2 (Pudasaini's vertical shear of the fluid
// velocity) and -xi alpha_s nu_A w / H^2 (vertical profile of alpha_s; taken with the sign that damps
// the relative motion), are applied implicitly with the other stiff sources in debris_stage.cl.
#ifndef TALUS_DEBRIS_VISCOUS_CL
#define TALUS_DEBRIS_VISCOUS_CL
#include "flow/debris_closures.cl"

#define VISC_MIN_ALPHA_F ((real)0.1)

/// nu = sqrt(g H) H / (alpha_f N) for 1/N = inv_n [m^2/s].
INLINE real visc_nu(real g, real H, real alpha_f, real inv_n) {
  return sqrt(g * H) * H * inv_n / fmax(alpha_f, VISC_MIN_ALPHA_F);
}

/// What the viscous fluxes need of one cell.
typedef struct {
  int wet;            // fluid above the dry threshold inside the domain
  real hf, H, as;     // fluid thickness, mixture depth, solid fraction
  real uf, vf, us, vs;
} ViscCell;

INLINE ViscCell visc_cell(__constant const FlowParams* p, __constant const DebrisParams* dp,
                          __global const uchar* mask, __global const real* S, __global const real* hf,
                          __global const real* qfx, __global const real* qfy, int i, int j) {
  ViscCell c = {0, 0, 0, 0, 0, 0, 0, 0};
  if (!cell_inside(p, mask, i, j)) return c;
  const int n = p->nx * p->ny, k = cell_index(p, i, j);
  const real hs = fmax(S[k], (real)0), h = hf[k];
  c.hf = h;
  c.H = hs + fmax(h, (real)0);
  c.wet = h > p->h_dry;
  c.as = c.H > p->h_dry ? hs / c.H : (real)0;
  c.uf = velocity(h, qfx[k], p->h_dry);
  c.vf = velocity(h, qfy[k], p->h_dry);
  c.us = solid_velocity(hs, S[n + k], p->h_dry, dp->film_h);
  c.vs = solid_velocity(hs, S[2 * n + k], p->h_dry, dp->film_h);
  return c;
}

/// Centred difference (m, p both wet), one-sided (one of them), or 0, of the values qm, q0, qp at
/// spacing dx.
INLINE real visc_diff(int m_wet, real qm, real q0, int p_wet, real qp, real dx) {
  if (m_wet && p_wet) return (qp - qm) / ((real)2 * dx);
  if (p_wet) return (qp - q0) / dx;
  if (m_wet) return (q0 - qm) / dx;
  return (real)0;
}

/// Derivatives along the face tangent, at cell (i, j), of the fluid's normal velocity u_n (.x) and
/// of the solid fraction (.y), from the cell's two tangential neighbours.
INLINE real2 visc_tangential(__constant const FlowParams* p, __constant const DebrisParams* dp,
                             __global const uchar* mask, __global const real* S, __global const real* hf,
                             __global const real* qfx, __global const real* qfy, int i, int j, int dir,
                             ViscCell c0) {
  const int ti = dir == 1, tj = dir == 0;
  const ViscCell cm = visc_cell(p, dp, mask, S, hf, qfx, qfy, i - ti, j - tj);
  const ViscCell cp = visc_cell(p, dp, mask, S, hf, qfx, qfy, i + ti, j + tj);
  const real un_m = dir == 0 ? cm.uf : cm.vf, un_0 = dir == 0 ? c0.uf : c0.vf, un_p = dir == 0 ? cp.uf : cp.vf;
  return (real2)(visc_diff(cm.wet, un_m, un_0, cp.wet, un_p, p->dx),
                 visc_diff(cm.wet, cm.as, c0.as, cp.wet, cp.as, p->dx));
}

/// Face coefficient h_f nu [m^3/s] between two wet cells for 1/N = inv_n (0: 0).
INLINE real visc_mu(real g, ViscCell L, ViscCell R, real inv_n) {
  if (inv_n <= (real)0) return (real)0;
  const real H = (real)0.5 * (L.H + R.H);
  const real af = (real)0.5 * (((real)1 - L.as) + ((real)1 - R.as));
  const real h = (real)2 * L.hf * R.hf / (L.hf + R.hf);
  return h * visc_nu(g, H, af, inv_n);
}

/// Viscous momentum fluxes (normal, tangential component) of the fluid through the face between
/// cell (i, j) and its neighbour (i + 1, j) (dir 0) or (i, j + 1) (dir 1), in the sign convention of
/// the convective fluxes (dq = -dt/dx (F_p - F_m)). Evaluated identically by both cells.
INLINE real2 visc_face(__constant const FlowParams* p, __constant const DebrisParams* dp, __global const uchar* mask,
                       __global const real* S, __global const real* hf, __global const real* qfx,
                       __global const real* qfy, __global const real* gp, int i, int j, int dir) {
  const int di = dir == 0, dj = dir == 1;
  const ViscCell L = visc_cell(p, dp, mask, S, hf, qfx, qfy, i, j);
  const ViscCell R = visc_cell(p, dp, mask, S, hf, qfx, qfy, i + di, j + dj);
  if (!L.wet || !R.wet) return (real2)(0, 0);
  const real dx = p->dx;
  const real g = (real)0.5 * (gp[cell_index(p, i, j)] + gp[cell_index(p, i + di, j + dj)]);
  // Normal (n) and tangential (t) components of each cell's velocities.
  const real unL = dir == 0 ? L.uf : L.vf, utL = dir == 0 ? L.vf : L.uf;
  const real unR = dir == 0 ? R.uf : R.vf, utR = dir == 0 ? R.vf : R.uf;
  const real wnL = unL - (dir == 0 ? L.us : L.vs), wtL = utL - (dir == 0 ? L.vs : L.us);
  const real wnR = unR - (dir == 0 ? R.us : R.vs), wtR = utR - (dir == 0 ? R.vs : R.us);
  const real2 tL = visc_tangential(p, dp, mask, S, hf, qfx, qfy, i, j, dir, L);
  const real2 tR = visc_tangential(p, dp, mask, S, hf, qfx, qfy, i + di, j + dj, dir, R);
  const real dun_dn = (unR - unL) / dx, dut_dn = (utR - utL) / dx;
  const real dun_dt = (real)0.5 * (tL.x + tR.x);
  real Tnn = 0, Ttn = 0;
  if (dp->inv_nr > (real)0) {
    const real mu = visc_mu(g, L, R, dp->inv_nr);
    Tnn += mu * (real)2 * dun_dn;
    Ttn += mu * (dut_dn + dun_dt);
  }
  if (dp->inv_nra > (real)0) {
    const real mu = visc_mu(g, L, R, dp->inv_nra);
    const real da_dn = (R.as - L.as) / dx, da_dt = (real)0.5 * (tL.y + tR.y);
    const real wn = (real)0.5 * (wnL + wnR), wt = (real)0.5 * (wtL + wtR);
    Tnn -= mu * (real)2 * da_dn * wn;
    Ttn -= mu * (da_dn * wt + da_dt * wn);
  }
  return (real2)(-Tnn, -Ttn);
}

/// Viscous speed bound of cell (i, j) for the CFL condition (g >= g_p everywhere: a safe bound).
/// The explicit update of u_f by the face stresses has a rate of at most about
/// sum_faces 4 mu_f / (h_f dx^2) (normal stress 2 mu, tangential mu, cross terms); SSP-RK2 is stable
/// for dt * rate <= 2. The speed 16 max_f mu_f / (h_f dx) at CFL <= 0.5 keeps dt <= dx^2 h_f /
/// (32 max mu_f), a factor 2 inside that for any mix of faces. The interfacial part is bounded the
/// same way (|grad alpha_s| <= 1/dx, so its dependence on u_f is no stiffer than a diffusion with
/// its mu).
INLINE real visc_speed(__constant const FlowParams* p, __constant const DebrisParams* dp, __global const uchar* mask,
                       __global const real* S, __global const real* hf, __global const real* qfx,
                       __global const real* qfy, int i, int j) {
  const ViscCell c = visc_cell(p, dp, mask, S, hf, qfx, qfy, i, j);
  if (!c.wet) return (real)0;
  real mu = 0;
  for (int f = 0; f < 4; ++f) {
    const int ni = i + (f == 0) - (f == 1), nj = j + (f == 2) - (f == 3);
    const ViscCell o = visc_cell(p, dp, mask, S, hf, qfx, qfy, ni, nj);
    if (o.wet) mu = fmax(mu, visc_mu(GRAVITY, c, o, dp->inv_nr) + visc_mu(GRAVITY, c, o, dp->inv_nra));
  }
  return (real)16 * mu / (c.hf * p->dx);
}

/// Implicit basal shear terms over ds on the fluid discharge qf (see the header): chi damps u_f,
/// xi damps w = u_f - u_s (the solid velocity (usx, usy) is not changed).
INLINE void visc_basal(__constant const DebrisParams* dp, real g, real hs, real hf, real usx, real usy, real* qf,
                       real ds) {
  const real H = hs + hf, af = hf / H, as = hs / H, H2 = H * H;
  if (dp->chi > (real)0 && dp->inv_nr > (real)0) {
    const real f = (real)1 / ((real)1 + ds * dp->chi * visc_nu(g, H, af, dp->inv_nr) / H2);
    qf[0] *= f;
    qf[1] *= f;
  }
  if (dp->xi > (real)0 && dp->inv_nra > (real)0 && hs > (real)0) {
    const real f = (real)1 / ((real)1 + ds * dp->xi * as * visc_nu(g, H, af, dp->inv_nra) / H2);
    qf[0] = hf * (usx + (qf[0] / hf - usx) * f);
    qf[1] = hf * (usy + (qf[1] / hf - usy) * f);
  }
}

#endif
