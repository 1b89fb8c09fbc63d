// Peak maps of the particle (confined) phase over a run: after each grid step, the P2G of the
// particles (particle_grid.cl, particles_to_grid: per cell the thickness H_c, the mass M_c and the
// momentum P_c) raises each cell's maximum thickness and maximum speed |P_c| / M_c (the mass-weighted
// mean velocity of the particles that weigh on the cell). Written as `hcmax` and `vcmax`.
#include "common/real.cl"

__kernel void particle_track_maxima(const int cells, __global const real* Hc, __global const real* Mc,
                                    __global const real* Px, __global const real* Py, __global real* hmax,
                                    __global real* vmax) {
  const int k = get_global_id(0);
  if (k >= cells) return;
  hmax[k] = fmax(hmax[k], Hc[k]);
  if (Mc[k] > (real)0) vmax[k] = fmax(vmax[k], sqrt(Px[k] * Px[k] + Py[k] * Py[k]) / Mc[k]);
}
