// Test probe of the SPH kernel functions (sph.cl): W(r, h) and dW/dr(r, h) at given radii.
#include "particles/sph.cl"

__kernel void sph_probe(__global const real* r, const real h, const int n, __global real* w, __global real* dw) {
  const int i = get_global_id(0);
  if (i >= n) return;
  w[i] = sph_w(r[i], h);
  dw[i] = sph_dwdr(r[i], h);
}
