// Basal rheologies of the solid phase (two-phase grid model, spec §4): the shear stress the bed
// exerts on the solids, applied implicitly over a stage's source step ds (debris_stage.cl). Each law
// maps the relative solid momentum magnitude q* after the explicit terms to the magnitude q after
// the basal stress, q + ds T(q) = q* with T >= 0 non-decreasing in q, so it can slow a flow to rest
// ("held", q = 0) but never reverse it. The parameters rheo[0..3] of DebrisParams are filled per law
// by the host table src/flow/Rheology.cpp (which names the run-file keys).
//
// Geometry (as Manning's term, manning.cl): Talus carries the vertical thickness h and the
// horizontal momentum q = h u. The flow moves along the bed with speed |U| = s |u|, s = sqrt(1 +
// (e.grad b)^2) (e the direction of u), over the bed-normal thickness H = h cos(theta). A basal
// stress tau acting against U on the bed area (1/cos(theta) per unit horizontal area) has the
// horizontal part tau / (s cos(theta)) per unit horizontal area: on a plane (s = 1/cos(theta)) it
// is tau itself, and with the bed force g cos^2(theta) grad b of spec §1 each law gives its
// classical along-bed steady state in H and |U|. Coulomb's normal stress is rho g_n h (1 - B gamma)
// per horizontal area (g_n = g cos^2(theta) times the curvature factor), and the Froude number is
// Fr = |U| / sqrt(g cos(theta) H) = s |u| / sqrt(g_n h).
#ifndef TALUS_BASAL_RHEOLOGY_CL
#define TALUS_BASAL_RHEOLOGY_CL
#include "flow/debris_closures.cl"
#include "flow/manning.cl"  // MANNING_ALONG_BED

#define RHEOLOGY_COULOMB 0
#define RHEOLOGY_VOELLMY 1
#define RHEOLOGY_MU_I 2
#define RHEOLOGY_HERSCHEL_BULKLEY 3  // Bingham: flow index 1

/// The column a basal law acts on (all per unit horizontal area).
typedef struct {
  real h_st;     // thickness of the stage's own state: the weight in the Coulomb normal stress [m]
  real h;        // thickness the momentum belongs to [m]
  real n_g;      // (1 - B gamma) g_n: Coulomb normal stress per unit thickness and density [m/s^2]
  real g_n;      // g cos^2(theta) times the curvature factor [m/s^2]
  real cos_t;    // cos(theta) of the bed
  real stretch;  // s = |U| / |u| in the direction of motion
  real rho;      // density of the solids [kg/m^3]
  real tan_delta;  // tan of the cell's bed friction angle (Coulomb)
} BasalColumn;

/// Coulomb: tau = tan(delta) sigma_n (Savage & Hutter 1989; OpenLISEM P.39). Returns the factor
/// q / q* in [0, 1].
INLINE real coulomb_factor(BasalColumn c, real qs, real ds) {
  const real fric = ds * c.tan_delta * c.n_g * c.h_st;
  return qs <= fric ? (real)0 : (real)1 - fric / qs;
}

/// Voellmy (1955), in the form of Salm (1993) and com1DFA: tau = mu sigma_n + rho g |U|^2 / xi.
/// The turbulent part, horizontal and per unit density, is (g / xi) |U|^2 / (s cos(theta)) = c q^2
/// with c = (g / xi) s / (h^2 cos(theta)); with r = q* - ds mu n_g h_st the implicit step
/// q + ds c q^2 = r has the root q = 2 r / (1 + sqrt(1 + 4 ds c r)) (no cancellation). The steady
/// uniform state on a plane is |U|^2 = xi H (sin(theta) - mu cos(theta)). rheo = {mu, g / xi} (g / xi dimensionless).
INLINE real voellmy_factor(__constant const DebrisParams* dp, BasalColumn c, real qs, real ds) {
  const real r = qs - ds * dp->rheo[0] * c.n_g * c.h_st;
  if (r <= (real)0) return (real)0;
  const real cq = ds * dp->rheo[1] * c.stretch / (c.h * c.h * c.cos_t);
  const real q = (real)2 * r / ((real)1 + sqrt((real)1 + (real)4 * cq * r));
  return q / qs;
}

/// Pouliquen & Forterre (2002, J. Fluid Mech. 453, eqs. 2.9-2.12 without the start/stop hysteresis):
/// mu(H, Fr) = tan z1 + (tan z2 - tan z1) / (1 + beta H / (L Fr)) for Fr >= beta, and
/// mu_stop(H) = tan z1 + (tan z2 - tan z1) / (1 + H / L) below (the two agree at Fr = beta); mu
/// rises with the speed, so the implicit step has one root. With K = ds n_g h_st, Fr = f q (f = s /
/// (h sqrt(g_n h))), A = beta H / L and R = q* - K tan z1, the Fr >= beta branch
/// q + K (tan z1 + D f q / (f q + A)) = q* is the quadratic f q^2 + (A - R f + K D f) q - R A = 0.
/// rheo = {tan z1, tan z2, beta, L}. The steady uniform states: tan(theta) = mu, i.e. h_stop(theta) =
/// L (tan z2 - tan theta) / (tan theta - tan z1) and Fr = beta H / h_stop(theta) above it.
INLINE real mu_i_factor(__constant const DebrisParams* dp, BasalColumn c, real qs, real ds) {
  const real t1 = dp->rheo[0], dt12 = dp->rheo[1] - dp->rheo[0], beta = dp->rheo[2], L = dp->rheo[3];
  const real K = ds * c.n_g * c.h_st;
  const real H = c.h * c.cos_t;
  const real mu_stop = t1 + dt12 / ((real)1 + H / L);
  const real f = c.stretch / (c.h * sqrt(c.g_n * c.h));
  // At Fr = beta: if q* cannot reach it, the solution lies in the Fr < beta branch (mu = mu_stop).
  if (beta / f + K * mu_stop >= qs) {
    const real q = qs - K * mu_stop;
    return q <= (real)0 ? (real)0 : q / qs;
  }
  const real A = beta * H / L, R = qs - K * t1;
  const real bq = A - R * f + K * dt12 * f;
  const real disc = sqrt(bq * bq + (real)4 * f * R * A);
  const real q = bq >= (real)0 ? (real)2 * R * A / (bq + disc) : (disc - bq) / ((real)2 * f);
  return fmin(q / qs, (real)1);
}

/// The depth-averaged along-bed speed of a Herschel-Bulkley layer of thickness H under the bed shear tau
/// (tau_y yield stress, K consistency, n flow index; Bingham: n = 1, K = mu_B): the shear rate
/// ((tau(z) - tau_y) / K)^(1/n) with tau(z) = tau (1 - z/H) below a plug integrates (Huang & Garcia
/// 1998, eq. 9 for n = 1) to U = n/(n+1) (tau/K)^(1/n) H (1-r)^(1+1/n) (1 - n/(2n+1) (1-r)), r =
/// tau_y / tau; for n = 1, 2 tau^3 - (3 tau_y + 6 mu_B U / H) tau^2 + tau_y^3 = 0. Also returns
/// dU/dtau in *dU.
INLINE real hb_speed(real tau, real ty, real K, real n, real H, real* dU) {
  const real r = ty / tau, w = (real)1 - r;
  if (!(w > (real)0)) {
    *dU = (real)0;
    return (real)0;
  }
  const real a = (real)1 + (real)1 / n, bb = n / ((real)2 * n + (real)1);
  const real core = (real)1 - bb * w;
  const real U = n / (n + (real)1) * pow(tau / K, (real)1 / n) * H * pow(w, a) * core;
  *dU = U / tau * ((real)1 / n + a * r / w - bb * r / core);
  return U;
}

/// Herschel-Bulkley / Bingham plastic: the bed shear tau >= tau_y of hb_speed. With m = ds / (rho
/// cos(theta) s) the step q = q* - m tau needs F(tau) = h U(tau) / s + m tau - q* = 0, F increasing
/// from F(tau_y) < 0 to F(q*/m) >= 0: Newton's method kept inside that bracket (bisection where a
/// step leaves it). Held while q* <= m tau_y. rheo = {tau_y, K, n}. The steady uniform state on a
/// plane is tau = rho g H sin(theta), U = U(tau); a layer with rho g H sin(theta) <= tau_y rests.
INLINE real herschel_bulkley_factor(__constant const DebrisParams* dp, BasalColumn c, real qs, real ds) {
  const real ty = dp->rheo[0], K = dp->rheo[1], n = dp->rheo[2];
  const real m = ds / (c.rho * c.cos_t * c.stretch);
  if (qs <= m * ty) return (real)0;
  const real H = c.h * c.cos_t, hs = c.h / c.stretch;
  real lo = ty, hi = qs / m, tau = hi;
  for (int it = 0; it < 80; ++it) {
    real dU;
    const real F = hs * hb_speed(tau, ty, K, n, H, &dU) + m * tau - qs;
    if (F > (real)0) hi = tau; else lo = tau;
    const real dF = hs * dU + m;
    real next = tau - F / dF;
    if (!(next > lo && next < hi)) next = (real)0.5 * (lo + hi);
    const real change = fabs(next - tau);
    tau = next;
    if (!(change > (real)4 * REAL_EPS * tau) || hi - lo <= (real)4 * REAL_EPS * hi) break;
  }
  return fmax(qs - m * tau, (real)0) / qs;
}

/// The law: fixed at build time in the solver's kernels (-DRHEOLOGY=<id>, FlowSolverDebris.cpp), so a
/// Coulomb run carries none of the other laws' terms (the column's slope factors are then dead code);
/// the test kernel (basal_rheology_test.cl) reads it from the parameters.
#ifdef RHEOLOGY
#define BASAL_LAW(dp) RHEOLOGY
#else
#define BASAL_LAW(dp) ((dp)->rheology)
#endif

/// The factor q / q* of the cell's law (q* > 0).
INLINE real basal_factor(__constant const DebrisParams* dp, BasalColumn c, real qs, real ds) {
  switch (BASAL_LAW(dp)) {
    case RHEOLOGY_VOELLMY: return voellmy_factor(dp, c, qs, ds);
    case RHEOLOGY_MU_I: return mu_i_factor(dp, c, qs, ds);
    case RHEOLOGY_HERSCHEL_BULKLEY: return herschel_bulkley_factor(dp, c, qs, ds);
    default: return coulomb_factor(c, qs, ds);
  }
}

/// The bed stress a column at rest can hold, horizontal, per unit area and solid density [m^2/s^2]:
/// the largest q* / ds that the cell's law still holds (basal_factor returns 0), i.e. each law's
/// yield threshold at zero speed: Coulomb tan(delta) n_g h, Voellmy mu n_g h, mu(I) mu_stop(H) n_g h
/// (the Fr < beta branch), Herschel-Bulkley tau_y / (rho cos(theta) s).
INLINE real basal_strength(__constant const DebrisParams* dp, BasalColumn c) {
  switch (BASAL_LAW(dp)) {
    case RHEOLOGY_VOELLMY: return dp->rheo[0] * c.n_g * c.h_st;
    case RHEOLOGY_MU_I: {
      const real mu_stop = dp->rheo[0] + (dp->rheo[1] - dp->rheo[0]) / ((real)1 + c.h * c.cos_t / dp->rheo[3]);
      return mu_stop * c.n_g * c.h_st;
    }
    case RHEOLOGY_HERSCHEL_BULKLEY: return dp->rheo[0] / (c.rho * c.cos_t * c.stretch);
    default: return c.tan_delta * c.n_g * c.h_st;
  }
}

/// s = sqrt(1 + (e.grad b)^2) of motion along (rx, ry) over the bed gradient (bx, by); 1 with the
/// horizontal form of the slope terms (MANNING_ALONG_BED=0, slope correction off).
INLINE real along_bed_stretch(real rx, real ry, real bx, real by) {
#if MANNING_ALONG_BED
  const real qn = sqrt(rx * rx + ry * ry);
  if (!(qn > (real)0)) return (real)1;
  const real w = (rx * bx + ry * by) / qn;
  return sqrt((real)1 + w * w);
#else
  return (real)1;
#endif
}

#endif
