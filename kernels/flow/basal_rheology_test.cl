// Test entry of the basal laws (basal_rheology.cl) for tests/kernels/test_basal_rheology.cpp: one
// column per work-item, in[10 k ...] = {h_st, h, n_g, g_n, cos(theta), stretch, rho, tan(delta), q*,
// ds}, out[k] = q / q* of the law selected in the parameters block; basal_strength_test writes the
// column's strength at rest (basal_strength) instead.
#include "flow/basal_rheology.cl"

#define BASAL_TEST_IN 10

INLINE BasalColumn test_column(__global const real* v) {
  BasalColumn c;
  c.h_st = v[0];
  c.h = v[1];
  c.n_g = v[2];
  c.g_n = v[3];
  c.cos_t = v[4];
  c.stretch = v[5];
  c.rho = v[6];
  c.tan_delta = v[7];
  return c;
}

__kernel void basal_rheology_test(__constant const DebrisParams* dp, __global const real* in, __global real* out,
                                  const int n) {
  const int k = get_global_id(0);
  if (k >= n) return;
  __global const real* v = in + BASAL_TEST_IN * k;
  out[k] = basal_factor(dp, test_column(v), v[8], v[9]);
}

__kernel void basal_strength_test(__constant const DebrisParams* dp, __global const real* in, __global real* out,
                                  const int n) {
  const int k = get_global_id(0);
  if (k >= n) return;
  out[k] = basal_strength(dp, test_column(in + BASAL_TEST_IN * k));
}
