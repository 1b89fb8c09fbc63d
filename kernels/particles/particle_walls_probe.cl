// Test probe of the particles' bed surface (particle_walls.cl, walled_bed_gradient; particle_common.cl,
// bed_gradient): both gradients and walled_bed_offset at given points for given columns (rows of 5).
#include "particles/particle_walls.cl"

__kernel void particle_walls_probe(__constant const ParticleParams* p, __global const real* patch,
                                   __global const uchar* mask, __global const real* bed,
                                   __global const real* lslope, __global const real* x, __global const real* y,
                                   __global const real* column, const int n, __global real* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const real2 plain = bed_gradient(p, patch, x[i], y[i]);
  const real2 walled = walled_bed_gradient(p, patch, mask, bed, lslope, x[i], y[i], column[i]);
  out[5 * i] = plain.x;
  out[5 * i + 1] = plain.y;
  out[5 * i + 2] = walled.x;
  out[5 * i + 3] = walled.y;
  out[5 * i + 4] = walled_bed_offset(p, patch, mask, bed, lslope, x[i], y[i], column[i]);
}
