// Memory-bandwidth probe for the benchmarks (bench/bench_bandwidth.cpp): the STREAM triad
// a[i] = b[i] + s c[i] (McCalpin 1995), 3 reals moved per element, one element per work-item.
#include "common/real.cl"

__kernel void stream_triad(const int n, __global real* a, __global const real* b, __global const real* c,
                           const real s) {
  const int i = get_global_id(0);
  if (i < n) a[i] = b[i] + s * c[i];
}
