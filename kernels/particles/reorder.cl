// Reordering of particle arrays (structure of arrays) into the sorted order of the neighbour grid:
// dst[r] = src[order[r]], where order[r] is the index, before sorting, of the particle at sorted
// position r. One kernel per element type; every particle field is a `real`, uint or uchar array.
#include "common/real.cl"

__kernel void particles_gather_real(__global const real* src, __global const uint* order, const uint n,
                                    __global real* dst) {
  const uint r = get_global_id(0);
  if (r < n) dst[r] = src[order[r]];
}

__kernel void particles_gather_uint(__global const uint* src, __global const uint* order, const uint n,
                                    __global uint* dst) {
  const uint r = get_global_id(0);
  if (r < n) dst[r] = src[order[r]];
}

__kernel void particles_gather_uchar(__global const uchar* src, __global const uint* order, const uint n,
                                     __global uchar* dst) {
  const uint r = get_global_id(0);
  if (r < n) dst[r] = src[order[r]];
}
