// The Gray-Monaghan artificial stress of a particle (spec §5, P.85; Gray, Monaghan & Swift 2001):
// in the principal frame of S = N / rhoA^2 (N the depth-integrated in-plane stress, tension
// positive), each tensile principal value s > 0 gives -eps s, compressive ones 0; rotated back.
// particle_stress evaluates it once per particle and sub-step, particle_forces applies it to the
// pairs (R_i + R_j) f_ij^n; it is zero for a particle without tension, and the pair term then
// vanishes unless the neighbour has one.
#ifndef TALUS_ARTIFICIAL_STRESS_CL
#define TALUS_ARTIFICIAL_STRESS_CL
#include "common/real.cl"

/// The artificial-stress tensor R (xx, yy, xy) of a particle from its S = N / rhoA^2.
INLINE real4 artificial_stress(real eps, real sxx, real syy, real sxy) {
  const real c = (real)0.5 * (sxx + syy), d = (real)0.5 * (sxx - syy);
  const real rad = sqrt(d * d + sxy * sxy);
  const real s1 = c + rad, s2 = c - rad;
  const real r1 = s1 > (real)0 ? -eps * s1 : (real)0, r2 = s2 > (real)0 ? -eps * s2 : (real)0;
  // Principal direction of s1: angle theta with cos 2 theta = d / rad, sin 2 theta = sxy / rad.
  const real c2 = rad > (real)0 ? d / rad : (real)1, s2t = rad > (real)0 ? sxy / rad : (real)0;
  const real mean = (real)0.5 * (r1 + r2), dev = (real)0.5 * (r1 - r2);
  return (real4)(mean + dev * c2, mean - dev * c2, dev * s2t, 0);
}

#endif
