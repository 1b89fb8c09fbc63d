// Test entry of common/earth_pressure.cl for tests/kernels/test_earth_pressure.cpp: one case per
// work-item, in[5 k ...] = {phi, delta, contraction rate, g_n, H}, out[k] = K of the ramp.
#include "common/earth_pressure.cl"

__kernel void earth_pressure_test(__global const real* in, __global real* out, const int n) {
  const int k = get_global_id(0);
  if (k >= n) return;
  __global const real* v = in + 5 * k;
  out[k] = earth_pressure(v[0], v[1], passive_share_of_rate(v[2], v[3], v[4]));
}
