// Closures of the two-phase debris-flow model (spec §4; Pudasaini 2012, JGR 117 F03010): the
// Savage-Hutter earth-pressure coefficient, the O'Brien-Julien viscosity, the settling velocity and
// the generalised drag coefficient, and the parameter block of the two-phase kernels (mirrored by
// src/flow/DebrisParams.hpp).
#ifndef TALUS_DEBRIS_CLOSURES_CL
#define TALUS_DEBRIS_CLOSURES_CL
#include "flow/flow_common.cl"
#include "common/earth_pressure.cl"

#define EARTH_SAVAGE_HUTTER 0
#define EARTH_CONSTANT 1
#define DRAG_OFF 0
#define DRAG_LINEAR 1
#define DRAG_QUADRATIC 2

typedef struct {
  int earth_pressure;  // EARTH_SAVAGE_HUTTER or EARTH_CONSTANT
  int drag_law;        // DRAG_OFF, DRAG_LINEAR (j = 1), DRAG_QUADRATIC (j = 2)
  int virtual_mass;    // 1: virtual mass in the phase exchange
  int delta_from_phi;  // 1: bed friction angle = internal friction angle of the cell
  int rheology;        // basal law of the solids: RHEOLOGY_* of basal_rheology.cl
  int pad_int;
  real k_const;        // constant earth-pressure coefficient
  real rho_f;          // fluid density [kg/m^3]
  real pore_b;         // basal pore-pressure factor B (scales buoyancy in the basal normal stress)
  real drag_mult;      // multiplier of the drag coefficient
  real drag_m;         // P = alpha_s^m
  real drag_M;         // G = alpha_f^(M - 1)
  real drag_kappa;     // K in the smoothing function S_p [m/s]
  real visc_a;         // O'Brien-Julien eta = a exp(b alpha_s) [Pa s]
  real visc_b;         // [-]
  real phi_default;    // internal friction angle where no solids are [rad]
  real rho_s_default;  // solid density where no solids are [kg/m^3]
  real d_default;      // grain size where no solids are [m]
  real film_h;         // solid layers thinner than this have desingularised velocities [m]
  real inv_nr;         // 1 / N_R, Reynolds number of the fluid's Newtonian stress (0: off)
  real inv_nra;        // 1 / N_RA, interfacial Reynolds number of the non-Newtonian stress (0: off)
  real chi;            // vertical shear factor of the fluid velocity (basal viscous term)
  real xi;             // vertical solid-fraction profile factor (basal interfacial term)
  real rheo[4];        // parameters of the basal law (src/flow/Rheology.cpp)
  real packing;        // solid volume fraction phi_p of the saturated skeleton (submergence)
} DebrisParams;

/// Value of the solids' passive scalar `c` (0 phi, 1 rho_s, 2 d, 3 cohesion) where there are none
/// (debris_stage.cl, entrainment.cl).
INLINE real scalar_default(__constant const DebrisParams* dp, int c) {
  return c == 0 ? dp->phi_default : c == 1 ? dp->rho_s_default : c == 2 ? dp->d_default : (real)0;
}

/// Buoyancy ratio gamma_eff = (rho_f / rho_s) chi of solids h_s under fluid h_f: the skeleton of
/// packing phi_p holds the pore volume h_s (1 - phi_p) / phi_p, which the fluid fills from the bed
/// up, so the submerged share of the solids is chi = min(1, h_f phi_p / (h_s (1 - phi_p))) and the
/// fluid's buoyancy (rho_f g per submerged solid volume, Archimedes) grows continuously from zero
/// with the fluid, reaching the saturated value of the mixture model (Pudasaini 2012) once the
/// pores are full. It scales the basal normal stress (1 - B gamma_eff), the lateral pressure
/// (1 - gamma_eff) and the buoyancy force gamma_eff g_p h_s grad(H) (debris_stage.cl): a partly
/// saturated layer interpolates linearly in chi between dry and saturated.
INLINE real submerged_gamma(__constant const DebrisParams* dp, real rho_s, real hs, real hf) {
  if (!(hf > (real)0)) return (real)0;
  const real gamma = dp->rho_f / rho_s;
  const real pores = hs * ((real)1 - dp->packing);
  const real wet = hf * dp->packing;
  return wet >= pores ? gamma : gamma * wet / pores;
}

/// Solid velocity desingularised in films (Kurganov & Petrova 2007, eq. 2.21, with eps = max(h_dry,
/// film_h)): u = sqrt(2) h q / sqrt(h^4 + max(h^4, eps^4)). In a solid film of a fraction of a
/// millimetre q/h is ill-conditioned and would drive spurious speeds (and tiny time steps) at thin
/// fronts. Above eps it is exactly q/h. The stage rewrites q = h u.
INLINE real solid_velocity(real h, real q, real h_dry, real film_h) {
  if (h <= h_dry) return (real)0;
  const real eps = fmax(h_dry, film_h);
  if (h >= eps) return q / h;
  const real h4 = h * h * h * h, e4 = eps * eps * eps * eps;
  return M_SQRT2 * h * q / sqrt(h4 + fmax(h4, e4));
}

/// Passive share of the Savage-Hutter K (common/earth_pressure.cl) of a cell whose solids' velocity
/// changes by du across it (face hi minus face lo, along the direction): the strain rate -du/dx.
INLINE real passive_share(real du, real dx, real gn, real H) { return passive_share_of_rate(-du / dx, gn, H); }

/// O'Brien & Julien (1985) dynamic viscosity of the fluid phase carrying solids (OpenLISEM P.72).
INLINE real obrien_julien(__constant const DebrisParams* dp, real alpha_s) {
  return dp->visc_a * exp(dp->visc_b * alpha_s);
}

/// Settling velocity of a grain of size d (OpenLISEM Hazard P.73): Stokes below 100 um, Zanke
/// (1977) above 1 mm, U = 10 nu/d (sqrt(1 + 0.01 (rho_s - rho_f)/rho_f g d^3 / nu^2) - 1), and a
/// linear blend in between.
INLINE real settling_velocity(real d, real rho_s, real rho_f, real eta) {
  const real dd = fmax(d, (real)1e-7);
  const real nu = eta / rho_f;
  const real rel = fmax(rho_s - rho_f, (real)0) / rho_f;
  const real stokes = rel * GRAVITY * dd * dd / ((real)18 * nu);
  const real zanke = (real)10 * nu / dd * (sqrt((real)1 + (real)0.01 * rel * GRAVITY * dd * dd * dd / (nu * nu)) - (real)1);
  if (dd <= (real)1e-4) return stokes;
  if (dd >= (real)1e-3) return zanke;
  const real w = (dd - (real)1e-4) / (real)9e-4;
  return ((real)1 - w) * stokes + w * zanke;
}

/// Drag coefficient C of Pudasaini (2012, eqs. 11-15; OpenLISEM Hazard P.31-P.34) in
/// dq_s/dt = H C (u_f - u_s) |u_f - u_s|^(j-1) [1/s for j = 1, 1/m for j = 2]:
/// C = alpha_s alpha_f (1 - gamma) g / [U_T (P F + (1 - P) G) + S_p]^j,
/// F = gamma/180 (alpha_f/alpha_s)^3 Re_p, G = alpha_f^(M-1), P = alpha_s^m, Re_p = rho_f d U_T / eta,
/// S_p = (P/alpha_s + (1 - P)/alpha_f) K.
INLINE real drag_coefficient(__constant const DebrisParams* dp, real alpha_s, real rho_s, real d) {
  const real as = clamp(alpha_s, (real)1e-6, (real)1 - (real)1e-6), af = (real)1 - as;
  const real gamma = dp->rho_f / rho_s;
  const real eta = obrien_julien(dp, as);
  const real ut = settling_velocity(d, rho_s, dp->rho_f, eta);
  const real rep = dp->rho_f * d * ut / eta;
  const real ratio = af / as;
  const real F = gamma / (real)180 * ratio * ratio * ratio * rep;
  const real G = pow(af, dp->drag_M - (real)1);
  const real P = pow(as, dp->drag_m);
  const real sp = (P / as + ((real)1 - P) / af) * dp->drag_kappa;
  real denom = ut * (P * F + ((real)1 - P) * G) + sp;
  if (dp->drag_law == DRAG_QUADRATIC) denom *= denom;
  return dp->drag_mult * as * af * ((real)1 - gamma) * GRAVITY / denom;
}

#endif
