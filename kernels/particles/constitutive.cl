// The elasto-plastic stress update of one particle of the hybrid (particle) mode: spec §5, the
// paper's P.12-P.26, P.40-P.41, P.69-P.71, P.79-P.82 and its appendix B (P.89-P.94), after
// Bui, Fukagawa, Sako & Ohno (2008), IJNAMG 32:1537-1570 ("Bui" below).
//
// Sign convention: tension positive, compression negative (as Bui and spec §1); p = -I1/3.
// Units: stresses and moduli in Pa, rates in 1/s, dt in s, angles in radians.
//
// State of a particle: the in-plane Cauchy stress (xx, yy, xy). The out-of-plane shears are zero
// (P.40) and the vertical normal stress is not a state variable: it is the overburden of the
// depth-averaged column, sigma_zz = -1/2 rho_c g_n H (P.41), computed by the caller and passed in.
// The invariants of the yield function are those of the full 3D state (xx, yy, zz, xy):
//   I1 = xx + yy + zz (P.18),  J2 = 1/2 s:s (P.19), s = sigma - I1/3 I.
// With p2 = (xx + yy)/2, d = (xx - yy)/2, R = sqrt(d^2 + xy^2) (the in-plane shear radius) this is
//   I1 = 2 p2 + zz,  J2 = R^2 + (p2 - zz)^2 / 3,
// which is the form the return below works in.
//
// One step over dt, given the velocity gradient L^ab = dv^a/dx^b (stress_update):
//  1. Rates (P.79, P.80): strain rate eps' = (L + L^T)/2 (the paper's P.12 and P.70 print a minus
//     sign here by mistake), spin w = (L - L^T)/2, in-plane volumetric rate eps'_v = L_xx + L_yy.
//  2. Jaumann rotation (P.23, P.81): the co-rotational terms sigma w^T + w sigma are integrated
//     exactly: sigma <- Q sigma Q^T with Q = exp(w dt), a rotation by w_xy dt (for the pair (d, xy)
//     a rotation by 2 w_xy dt). To first order in dt this is sigma + dt (sigma w^T + w sigma); unlike
//     that forward-Euler form, which inflates J2 by (1 + (2 w_xy dt)^2) every step, it leaves I1 and
//     J2 unchanged to round-off under any rigid rotation (incremental objectivity, Hughes & Winget
//     1980 do the same with a Cayley rotation).
//  3. Elastic trial (P.13/P.21 without the plastic term), plane stress: G = E/(2(1+nu)),
//     K = E/(3(1-2nu)) (P.14), lambda = K - 2G/3. The layer is thin and its vertical stress is not
//     integrated but prescribed (the overburden), so its vertical strain is free: the in-plane law
//     is Hooke's with sigma_zz unchanged, 2G eps'_ab + lambda* eps'_v delta_ab with
//     lambda* = 2G lambda / (lambda + 2G) = E nu / (1 - nu^2) (the plane-stress condensation of
//     P.13; elastic vertical strain rate -lambda/(lambda + 2G) eps'_v). A bar then rings at
//     sqrt(E/rho). (Until 2026-12 the kernel used Bui's plane-strain law, lambda in place of
//     lambda*: a vertical strain held at zero, which the depth-averaged layer, free at its surface,
//     has no means to hold; its in-plane bulk modulus lambda + G was 35 % stiffer at nu = 0.3.)
//  4. Yield check, Drucker-Prager fitted to Mohr-Coulomb in plane strain (P.16, P.20 = P.71, the
//     fit Bui uses): f = alpha_phi I1 + sqrt(J2) - k_c with
//       alpha_phi = tan(phi) / sqrt(9 + 12 tan^2 phi),  k_c = 3 c / sqrt(9 + 12 tan^2 phi).
//     f* <= 0: the step is elastic and sigma* is the result.
//  5. Plastic corrector (P.21-P.22, P.81-P.82, from Bui's consistency condition, in plane stress)
//     with the non-associated potential
//       g = alpha_psi I1 + sqrt(J2),  n = dg/dsigma = alpha_psi I + s / (2 sqrt(J2)).
//     The plastic strain rate lambda' n has a vertical part; with sigma_zz held, the elastic
//     vertical strain takes it up, so the in-plane stress changes by the plane-stress law of step 3
//     applied to the in-plane part of n:
//       C_ab = G s_ab / sqrt(J2) + kappa delta_ab,  kappa = 2 G alpha_psi + lambda* (2 alpha_psi - r/2),
//     r = s_zz / sqrt(J2) (n_xx + n_yy = 2 alpha_psi - r/2, as s_xx + s_yy = -s_zz). The consistency
//     condition at the trial state, with df/dsigma = alpha_phi I + s / (2 sqrt(J2)) on the in-plane
//     components (s_in : s_in = 2 J2 - s_zz^2), gives dlambda = f* / h with
//       h = G (1 - r^2/2) + lambda* r^2/4 + (G + lambda*) (4 alpha_phi alpha_psi - (alpha_phi + alpha_psi) r).
//     h > 0 for every state: it is concave in r (lambda* < 2G for nu < 1/2), |r| <= 2/sqrt3, and at
//     the ends it is (G + lambda*)(1/sqrt3 -+ 2 alpha_phi)(1/sqrt3 -+ 2 alpha_psi) > 0 since
//     alpha < 1/(2 sqrt3) for angles below 90 degrees. (For 3D Hooke the same steps give Bui's
//     9 alpha_phi alpha_psi K + G; when sigma_n lies on the surface dlambda = lambda' dt + O(dt^2):
//     the backward-Euler form of his explicit rate.) The in-plane components take
//     sigma -= dlambda C; the deviatoric part removed is capped at all of it (a larger dlambda means
//     a return to the apex region, handled by step 6, and must not flip the deviator).
//     Dilatancy coefficient: alpha_psi = tan(psi) / sqrt(9 + 12 tan^2 psi), the same plane-strain
//     fit as alpha_phi. With it a plastic plane-strain flow (zero vertical plastic strain rate)
//     dilates at exactly the Mohr-Coulomb angle psi (sin psi = -(e1 + e3)/(e1 - e3) of the plastic
//     principal rates), psi = 0 gives no plastic volume change and psi = phi associated flow. The
//     terms 9 K sin(psi) of P.21/P.81 and 27 alpha_phi K sin(psi) of P.22/P.82 (after Bui) are the
//     same formulas with alpha_psi = 3 sin(psi), i.e. g = sqrt(J2) + 3 I1 sin(psi) (P.17 prints
//     alpha_phi I1 sin(psi), which matches neither); that coefficient cannot be a plane-strain
//     dilatancy angle (the rate above would be 9 sin(psi) / sqrt(1 - 27 sin^2 psi), undefined
//     beyond 11 deg), so we use the fit. dp_dilatancy_coefficient() is the one place that choice
//     is made.
//  6. Stress remapping (appendix B, P.89-P.94; Bui's tension-cracking and stress-scaling-back
//     treatments): tension cracking, then scaling of the deviator back onto the surface. Bui's
//     versions move sigma_zz; here sigma_zz is the prescribed overburden, so both act on the
//     in-plane components with zz fixed:
//     - the in-plane isotropic states (R = 0) that satisfy f <= 0 are p2 in [p_lo, p_hi], where
//         p_hi = (k_c - alpha zz + zz/sqrt3) / (2 alpha + 1/sqrt3)   (in-plane tension limit),
//         p_lo = (k_c - alpha zz - zz/sqrt3) / (2 alpha - 1/sqrt3)   (in-plane compression limit,
//       the Drucker-Prager counterpart of Rankine's passive state; 2 alpha < 1/sqrt3 for phi < 90);
//     - tension cracking: p2 > p_hi (which includes every state beyond the apex, I1 > k_c/alpha,
//       P.89) moves the in-plane mean back to p_hi with zero deviator, the counterpart of P.90 (the
//       3D apex itself is reachable only when zz = k_c/(3 alpha));
//     - compression cap: p2 < p_lo moves it to p_lo with zero deviator;
//     - scaling: otherwise the in-plane deviator (d, xy) is scaled by r = R_max/R at fixed I1, with
//       R_max^2 = (k_c - alpha I1)^2 - (p2 - zz)^2/3 (P.92-P.94 with zz held: for zz = I1/3 it is
//       exactly Bui's r = (k_c - alpha I1)/sqrt(J2)).
//     After a plastic corrector the scaling is applied in both directions (r may slightly exceed 1
//     when the in-plane part of the corrector over-returned): a plastic step ends on the
//     surface, f = 0, except when the corrector took the whole deviator and left the mean inside
//     [p_lo, p_hi] (an apex-region return that lands inside the cone). Outside a plastic step
//     (dp_remap with snap = 0) the remap only acts when f > 0, e.g. after cohesion dropped.
//     The admissible set is empty when zz > k_c/(3 alpha) (vertical tension beyond the apex, never
//     the case for an overburden zz <= 0); the stress is then set to the isotropic state zz, where
//     f is smallest, and CONS_INADMISSIBLE is raised.
//  After the update f <= a few ulps of the stress scale for every particle.
//
// Fracturing (P.26, spec §5): while a particle yields its cohesion degrades with the volumetric
// strain rate, dc/dt = -c0 |eps'_v| / (2 eps_c) (bond strengths uniform in [0, 2 c0]); c never
// rises and never drops below 0 (cohesion_degrade). The structured and confined fractions follow
// the intact bonds, f_sc = f_sc0 c/c0 and f_fc = f_fc0 c/c0 (P.27-P.28 as made consistent by spec
// §5; bond_fraction, structure_fractions). The caller moves the released fluid to the grid.
//
// A particle step kernel calls, per particle:
//   const DPMaterial mat = dp_material(E, nu, phi, c, psi);     // c: current cohesion
//   PlaneStress s = {sxx[i], syy[i], sxy[i]};
//   const StressUpdate u = stress_update(&s, L, szz, mat, dt);
//   c = cohesion_degrade(c, c0, u.eps_v_rate, eps_c, dt, u.flags != 0);
//   structure_fractions(c, c0, fsc0, ffc0, &fsc, &ffc);
// constitutive_test_steps at the end of this file does exactly that for the tests.
#ifndef TALUS_CONSTITUTIVE_CL
#define TALUS_CONSTITUTIVE_CL
#include "common/real.cl"

/// Flags of a stress update (StressUpdate.flags); 0 means an elastic step.
#define CONS_YIELDED 1          // the trial state was outside the yield surface (plastic step)
#define CONS_SCALED 2           // the in-plane deviator was scaled onto the surface
#define CONS_TENSION_CUT 4      // tension cracking: in-plane mean moved to the tension limit
#define CONS_COMPRESSION_CAP 8  // in-plane mean moved to the compression limit
#define CONS_INADMISSIBLE 16    // sigma_zz > k_c / (3 alpha_phi): no admissible in-plane state

/// Velocity gradient of one particle, L^ab = dv^a / dx^b [1/s] (xy = dv_x/dy, yx = dv_y/dx).
typedef struct {
  real xx, xy, yx, yy;
} VelocityGradient;

/// In-plane Cauchy stress, tension positive [Pa]; sigma_xz = sigma_yz = 0 (P.40).
typedef struct {
  real xx, yy, xy;
} PlaneStress;

/// The constants of the update for one particle's material (dp_material).
typedef struct {
  real G;          // shear modulus [Pa]
  real K2;         // in-plane bulk modulus of plane stress, lambda* + G = E / (2 (1 - nu)) [Pa]
  real alpha_phi;  // friction coefficient of the yield function (P.20) [-]
  real alpha_psi;  // dilatancy coefficient of the plastic potential [-]
  real k_c;        // cohesion term of the yield function (P.20) [Pa]
} DPMaterial;

/// What one stress update did.
typedef struct {
  real dlambda;     // plastic multiplier of the step, lambda' dt (0 for an elastic step) [-]
  real eps_v_rate;  // volumetric strain rate tr(eps') = L_xx + L_yy [1/s]
  int flags;        // CONS_* bits; nonzero exactly when the particle yielded this step
} StressUpdate;

/// 1 / sqrt(9 + 12 tan^2 a), the factor of the plane-strain Drucker-Prager fit (P.20).
INLINE real dp_fit_factor(real angle) {
  const real t = tan(angle);
  return (real)1 / sqrt((real)9 + (real)12 * t * t);
}

/// alpha_phi = tan(phi) / sqrt(9 + 12 tan^2 phi) (P.20, P.71); phi in radians, [0, pi/2).
INLINE real dp_alpha(real phi) { return tan(phi) * dp_fit_factor(phi); }

/// k_c = 3 c / sqrt(9 + 12 tan^2 phi) [Pa] (P.20, P.71); c the current cohesion [Pa].
INLINE real dp_cohesion_term(real c, real phi) { return (real)3 * c * dp_fit_factor(phi); }

/// Dilatancy coefficient alpha_psi of the plastic potential g = alpha_psi I1 + sqrt(J2): the same
/// plane-strain fit as alpha_phi (see the header, step 5, for why not Bui's 3 sin psi).
INLINE real dp_dilatancy_coefficient(real psi) { return tan(psi) * dp_fit_factor(psi); }

/// The update constants from the shear modulus G and the in-plane bulk modulus K2 [Pa] (both
/// positive), friction angle phi, cohesion c [Pa] (the current, possibly degraded, value) and
/// dilatancy angle psi [rad]. The particle kernels get G and K2 from the host, computed in double
/// from E and nu: the in-plane law needs them, and reconstructing nu in float from large moduli
/// (G = 1e14 Pa with E = 1e7 Pa is nu = -1 + 5e-8) is not possible.
INLINE DPMaterial dp_material_of_moduli(real G, real K2, real phi, real c, real psi) {
  DPMaterial m;
  m.G = G;
  m.K2 = K2;
  m.alpha_phi = dp_alpha(phi);
  m.alpha_psi = dp_dilatancy_coefficient(psi);
  m.k_c = dp_cohesion_term(c, phi);
  return m;
}

/// The same from Young's modulus E [Pa] and Poisson's ratio nu [-] (P.14): G = E / (2 (1 + nu)),
/// K2 = E / (2 (1 - nu)).
INLINE DPMaterial dp_material(real E, real nu, real phi, real c, real psi) {
  return dp_material_of_moduli(E / ((real)2 * ((real)1 + nu)), E / ((real)2 * ((real)1 - nu)), phi, c, psi);
}

/// I1 and J2 of the 3D state (xx, yy, szz, xy) with zero out-of-plane shears (P.18, P.19).
INLINE void dp_invariants(PlaneStress s, real szz, real* I1, real* J2) {
  const real p2 = (real)0.5 * (s.xx + s.yy), d = (real)0.5 * (s.xx - s.yy), q = p2 - szz;
  *I1 = (real)2 * p2 + szz;
  *J2 = d * d + s.xy * s.xy + q * q / (real)3;
}

/// The yield function f = alpha_phi I1 + sqrt(J2) - k_c (P.16) of the 3D state; f <= 0 admissible.
INLINE real dp_yield(PlaneStress s, real szz, DPMaterial m) {
  real I1, J2;
  dp_invariants(s, szz, &I1, &J2);
  return m.alpha_phi * I1 + sqrt(J2) - m.k_c;
}

/// The co-rotational (Jaumann) part of one step, integrated exactly: Q s Q^T with Q = exp(w dt),
/// w = spin_xy = (L_xy - L_yx)/2 [1/s]. Leaves the in-plane mean and R unchanged.
INLINE PlaneStress stress_rotate(PlaneStress s, real spin_xy, real dt) {
  const real angle = (real)2 * spin_xy * dt;
  const real cs = cos(angle), sn = sin(angle);
  const real p2 = (real)0.5 * (s.xx + s.yy), d = (real)0.5 * (s.xx - s.yy);
  const real dr = d * cs + s.xy * sn;
  PlaneStress r;
  r.xx = p2 + dr;
  r.yy = p2 - dr;
  r.xy = s.xy * cs - d * sn;
  return r;
}

/// Stress remapping with sigma_zz held (header, step 6; P.89-P.94). With snap = 0 it acts only on
/// states outside the surface (f > 0); with snap = 1 (after a plastic corrector) a state inside is
/// also scaled out onto the surface when it has an in-plane deviator. Adds CONS_* bits to *flags.
INLINE PlaneStress dp_remap(PlaneStress s, real szz, DPMaterial m, int snap, int* flags) {
  const real alpha = m.alpha_phi, kc = m.k_c;
  if (!snap && !(dp_yield(s, szz, m) > (real)0)) return s;
  const real inv_sqrt3 = (real)0.57735026918962576451;
  real p2 = (real)0.5 * (s.xx + s.yy), d = (real)0.5 * (s.xx - s.yy), t = s.xy;
  if ((real)3 * alpha * szz > kc) {
    // Vertical tension beyond the apex: no admissible state; the isotropic state szz is closest.
    *flags |= CONS_INADMISSIBLE;
    p2 = szz, d = (real)0, t = (real)0;
  } else {
    const real p_hi = (kc - alpha * szz + szz * inv_sqrt3) / ((real)2 * alpha + inv_sqrt3);
    const real p_lo = (kc - alpha * szz - szz * inv_sqrt3) / ((real)2 * alpha - inv_sqrt3);
    if (p2 > p_hi) {
      *flags |= CONS_TENSION_CUT;
      p2 = p_hi, d = (real)0, t = (real)0;
    } else if (p2 < p_lo) {
      *flags |= CONS_COMPRESSION_CAP;
      p2 = p_lo, d = (real)0, t = (real)0;
    } else {
      const real R = sqrt(d * d + t * t);
      if (R > (real)0) {
        // R_max^2 = Y^2 - q^2/3 as a product: Y - |q|/sqrt3 = -f(p2, R = 0) >= 0 here.
        const real Y = kc - alpha * ((real)2 * p2 + szz), aq = fabs(p2 - szz) * inv_sqrt3;
        const real Rmax = sqrt(fmax((real)0, (Y - aq) * (Y + aq)));
        if (snap || Rmax < R) {
          const real r = Rmax / R;
          d *= r, t *= r;
          *flags |= CONS_SCALED;
        }
      }
    }
  }
  PlaneStress out;
  out.xx = p2 + d;
  out.yy = p2 - d;
  out.xy = t;
  return out;
}

/// One elasto-plastic step of a particle's stress over dt (header, steps 1-6): *s is the in-plane
/// stress at the start of the step and receives the new one; L the velocity gradient [1/s]; szz
/// the vertical stress -1/2 rho_c g_n H [Pa] (P.41); m from dp_material. Returns the plastic
/// multiplier, the volumetric strain rate and the CONS_* flags (0: elastic).
INLINE StressUpdate stress_update(PlaneStress* s, VelocityGradient L, real szz, DPMaterial m, real dt) {
  StressUpdate u;
  u.dlambda = (real)0;
  u.flags = 0;
  // 1. Rates (P.79, P.80).
  const real exx = L.xx, eyy = L.yy, exy = (real)0.5 * (L.xy + L.yx);
  const real spin = (real)0.5 * (L.xy - L.yx);
  u.eps_v_rate = exx + eyy;
  // 2. Exact Jaumann rotation; 3. elastic trial (plane-stress Hooke, written with the two positive
  // moduli G and K2 = lambda* + G: 2G e + lambda* tr(e) I = G (e_xx - e_yy) (1, -1) + K2 tr(e) (1, 1)).
  PlaneStress tr = stress_rotate(*s, spin, dt);
  const real G = m.G, K2 = m.K2, shear = G * (exx - eyy), bulk = K2 * u.eps_v_rate;
  tr.xx += dt * (bulk + shear);
  tr.yy += dt * (bulk - shear);
  tr.xy += dt * ((real)2 * G * exy);
  // 4. Yield check.
  real I1, J2;
  dp_invariants(tr, szz, &I1, &J2);
  const real sqJ2 = sqrt(J2);
  const real f = m.alpha_phi * I1 + sqJ2 - m.k_c;
  if (!(f > (real)0)) {
    *s = tr;
    return u;
  }
  // 5. Plastic corrector (plane stress: dlambda C with C_ab = G s_ab / sqrt(J2) + kappa delta_ab).
  u.flags = CONS_YIELDED;
  const real mean = I1 / (real)3;
  const real r = sqJ2 > (real)0 ? (szz - mean) / sqJ2 : (real)0;
  const real ap = m.alpha_phi, aq = m.alpha_psi;
  // kappa and h of the header with lambda* = K2 - G (its first two terms are then non-negative).
  const real kappa = (real)2 * aq * K2 - (real)0.5 * (K2 - G) * r;
  const real h = G * ((real)1 - (real)0.75 * r * r) + (real)0.25 * K2 * r * r +
                 K2 * ((real)4 * ap * aq - (ap + aq) * r);
  u.dlambda = f / h;
  const real vol = kappa * u.dlambda;
  const real dev = sqJ2 > (real)0 ? fmin((real)1, G * u.dlambda / sqJ2) : (real)1;
  PlaneStress pc;
  pc.xx = tr.xx - vol - dev * (tr.xx - mean);
  pc.yy = tr.yy - vol - dev * (tr.yy - mean);
  pc.xy = tr.xy - dev * tr.xy;
  // 6. Tension cracking / scaling onto the surface.
  *s = dp_remap(pc, szz, m, 1, &u.flags);
  return u;
}

/// Cohesion after one step (P.26): while the particle yields and c > 0,
/// c <- max(0, c - dt c0 |eps'_v| / (2 eps_c)); otherwise unchanged. Never rises, never below 0
/// (for c >= 0). eps_c > 0 is the critical volumetric strain [-].
INLINE real cohesion_degrade(real c, real c0, real eps_v_rate, real eps_c, real dt, int yielding) {
  if (!yielding || !(c > (real)0)) return c;
  const real drop = dt * c0 * fabs(eps_v_rate) / ((real)2 * eps_c);
  return fmax((real)0, c - drop);
}

/// Fraction of intact bonds c/c0, clipped to [0, 1]; 1 for a material that never had cohesion
/// (c0 <= 0: nothing to break, the fractions keep their initial values).
INLINE real bond_fraction(real c, real c0) {
  if (!(c0 > (real)0)) return (real)1;
  return fmin((real)1, fmax((real)0, c / c0));
}

/// Structured and confined-fluid fractions following the intact bonds (spec §5, P.27-P.28):
/// f_sc = f_sc0 c/c0, f_fc = f_fc0 c/c0.
INLINE void structure_fractions(real c, real c0, real fsc0, real ffc0, real* fsc, real* ffc) {
  const real b = bond_fraction(c, c0);
  *fsc = fsc0 * b;
  *ffc = ffc0 * b;
}

// ---------------------------------------------------------------------------------------------
// Test kernel (tests/kernels/test_constitutive.cpp): `steps` particle steps with a fixed velocity
// gradient, exactly the sequence a particle step kernel runs (material, stress update, cohesion,
// fractions). Per particle, in[CONS_TEST_IN * i + k]:
//   0-3 L (xx, xy, yx, yy), 4-6 stress (xx, yy, xy), 7 szz, 8 E, 9 nu, 10 phi, 11 c, 12 psi,
//   13 c0, 14 eps_c, 15 f_sc0, 16 f_fc0;
// out[CONS_TEST_OUT * i + k]:
//   0-2 stress, 3 dlambda and 4 eps_v_rate and 5 flags of the last step, 6 c, 7 f_sc, 8 f_fc,
//   9 f of the final stress with the cohesion its last update used, 10 number of yielding steps.
#define CONS_TEST_IN 17
#define CONS_TEST_OUT 11

__kernel void constitutive_test_steps(__global const real* in, __global real* out, real dt, int steps, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  __global const real* a = in + (size_t)CONS_TEST_IN * i;
  VelocityGradient L;
  L.xx = a[0], L.xy = a[1], L.yx = a[2], L.yy = a[3];
  PlaneStress s;
  s.xx = a[4], s.yy = a[5], s.xy = a[6];
  const real szz = a[7], E = a[8], nu = a[9], phi = a[10], psi = a[12], c0 = a[13], eps_c = a[14];
  real c = a[11];
  StressUpdate u;
  u.dlambda = (real)0, u.eps_v_rate = (real)0, u.flags = 0;
  DPMaterial mat = dp_material(E, nu, phi, c, psi);
  int yielding_steps = 0;
  for (int k = 0; k < steps; ++k) {
    mat = dp_material(E, nu, phi, c, psi);
    u = stress_update(&s, L, szz, mat, dt);
    yielding_steps += u.flags != 0;
    c = cohesion_degrade(c, c0, u.eps_v_rate, eps_c, dt, u.flags != 0);
  }
  real fsc, ffc;
  structure_fractions(c, c0, a[15], a[16], &fsc, &ffc);
  __global real* o = out + (size_t)CONS_TEST_OUT * i;
  o[0] = s.xx, o[1] = s.yy, o[2] = s.xy;
  o[3] = u.dlambda, o[4] = u.eps_v_rate, o[5] = (real)u.flags;
  o[6] = c, o[7] = fsc, o[8] = ffc;
  o[9] = dp_yield(s, szz, mat);
  o[10] = (real)yielding_steps;
}

#endif
