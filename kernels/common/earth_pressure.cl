// The Savage & Hutter (1989) earth-pressure coefficient with its active-passive ramp, shared by the
// grid's solids (kernels/flow/debris_stage.cl) and the particles (kernels/particles/particle_stress.cl),
// so both see the same lateral pressure law.
#ifndef TALUS_COMMON_EARTH_PRESSURE_CL
#define TALUS_COMMON_EARTH_PRESSURE_CL
#include "common/real.cl"

/// Savage & Hutter (1989) earth-pressure coefficient: K = 2/cos^2(phi) (1 -+ sqrt(1 - cos^2(phi) /
/// cos^2(delta))) - 1, active (-, the flow extends) or passive (+, it contracts); the root's argument
/// is clipped at zero when delta > phi. `passive` in [0, 1] blends linearly from K_act (0) to K_pass (1).
/// The two parts of K that depend on the material only (a = 2 / cos^2(phi) and the root), so a
/// kernel that needs K of one material at several rates evaluates the trigonometry once
/// (debris_stage.cl); earth_pressure_at then gives bitwise the value of earth_pressure.
typedef struct {
  real a, root;
} EarthPressureTerms;

INLINE EarthPressureTerms earth_pressure_terms(real phi, real delta) {
  const real cp = cos(phi), cd = cos(delta);
  EarthPressureTerms t;
  t.root = sqrt(fmax((real)0, (real)1 - cp * cp / (cd * cd)));
  t.a = (real)2 / (cp * cp);
  return t;
}

INLINE real earth_pressure_at(EarthPressureTerms t, real passive) {
  return t.a * ((real)1 + ((real)2 * passive - (real)1) * t.root) - (real)1;
}

INLINE real earth_pressure(real phi, real delta, real passive) {
  return earth_pressure_at(earth_pressure_terms(phi, delta), passive);
}

/// Passive share of K for material contracting at the strain rate `rate` [1/s] (> 0 contracting):
/// 0 while it extends or stays, rising linearly to 1 at rate = 0.1 sqrt(g_n / H) (H the thickness).
/// A sign switch instead flips K between K_act and K_pass on the velocity noise of a settling
/// deposit, a pressure jump friction cannot hold: on fine grids such a deposit never came to rest
/// (found by the column-collapse series, tests/verification/test_column_collapse.cpp: with the
/// switch, a = 1 at 80 cells per column length still moved at 2.8 s; with this ramp it is at rest at
/// 0.37 s, and the runouts of the series are unchanged to the cell. A ramp 10 times steeper (0.01)
/// still sloshed).
INLINE real passive_share_of_rate(real rate, real gn, real H) {
  if (!(rate > (real)0)) return (real)0;
  return fmin(rate / ((real)0.1 * sqrt(gn / fmax(H, (real)1e-6))), (real)1);
}

#endif
