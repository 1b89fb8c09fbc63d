// The material update of one particle over dt (spec §5): the adapter between the particle kernels
// and the constitutive model of constitutive.cl. Stresses are tension positive.
// The stress the yield surface sees is the total in-plane stress sigma + sigma_lat I: the elastic
// history sigma (which starts at zero: a block at rest is in equilibrium, spec §5) plus the
// Bell-Rankine lateral stress sigma_lat = -max(0, K p_zz - 2 c sqrt(K)) (OpenLISEM Hazard P.43,
// spec §4), with the overburden sigma_zz = -p_zz = -rho g_n H / 2 (P.41). A cohesionless particle
// with K = 1 therefore starts hydrostatic (inside the cone), not at zero in-plane stress under a
// vertical load (which would be far outside it). The update (Jaumann rotation, elastic trial,
// Drucker-Prager return with the in-plane tension cut and scaling) acts on that total; the elastic
// part is what remains after taking sigma_lat I off again. While the particle yields, its cohesion
// degrades (P.26); the returned lateral stress is the one the update used, so the depth-integrated
// stress N = H (sigma + sigma_lat I) is the returned, admissible one.
#ifndef TALUS_PARTICLE_MATERIAL_CL
#define TALUS_PARTICLE_MATERIAL_CL
#include "particles/constitutive.cl"
#include "particles/particle_common.cl"

typedef struct {
  real sxx, syy, sxy;  // in-plane elastic stress [Pa]
  real c;              // current cohesion [Pa]
  real plastic;        // accumulated plastic multiplier [-]
} MaterialState;

/// Bell-Rankine lateral stress (tension positive, never tensile): -max(0, K p_zz - 2 c sqrt(K)).
INLINE real bell_rankine(real K, real pzz, real c) {
  return -fmax((real)0, K * pzz - (real)2 * c * sqrt(K));
}

/// Advances the particle's stress and cohesion by dt; returns the lateral stress sigma_lat.
INLINE real particle_material_update(__constant const ParticleParams* p, MaterialState* s, real L00, real L01,
                                     real L10, real L11, real pzz, real K, real phi, real c0, real dt) {
  const real lat = bell_rankine(K, pzz, s->c);
  PlaneStress total = {s->sxx + lat, s->syy + lat, s->sxy};
  const VelocityGradient L = {L00, L01, L10, L11};
  const DPMaterial m = dp_material_of_moduli(p->shear_modulus, p->plane_bulk_modulus, phi, s->c, p->dilatancy);
  const StressUpdate u = stress_update(&total, L, -pzz, m, dt);
  s->sxx = total.xx - lat;
  s->syy = total.yy - lat;
  s->sxy = total.xy;
  s->plastic += u.dlambda;
  s->c = cohesion_degrade(s->c, c0, u.eps_v_rate, p->eps_crit, dt, u.flags != 0);
  return lat;
}

#endif
