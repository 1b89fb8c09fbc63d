// Device reductions of a `real` array: sum, min and max, in two passes (work-group partials, then
// one work-group over the partials). Work-group size must be a power of two.
#include "common/real.cl"

#define REDUCE_SUM 0
#define REDUCE_MIN 1
#define REDUCE_MAX 2

INLINE real reduce_identity(int op) {
  return op == REDUCE_SUM ? (real)0 : (op == REDUCE_MIN ? REAL_MAX : -REAL_MAX);
}

// NaN propagates through every operation, so a NaN anywhere is visible in the result.
INLINE real reduce_combine(int op, real a, real b) {
  if (isnan(a) || isnan(b)) return a + b;
  return op == REDUCE_SUM ? a + b : (op == REDUCE_MIN ? min(a, b) : max(a, b));
}

/// Reduces in[0..n) into out[group] per work-group (grid-stride loop, then a tree in local memory).
__kernel void reduce_stage(__global const real* in, const uint n, const int op, __global real* out,
                           __local real* scratch) {
  const uint lid = get_local_id(0);
  real acc = reduce_identity(op);
  for (uint i = get_global_id(0); i < n; i += get_global_size(0)) acc = reduce_combine(op, acc, in[i]);
  scratch[lid] = acc;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint s = get_local_size(0) / 2; s > 0; s >>= 1) {
    if (lid < s) scratch[lid] = reduce_combine(op, scratch[lid], scratch[lid + s]);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) out[get_group_id(0)] = scratch[0];
}

/// Reduces the first n entries of rows that start every `stride` entries of `in`, one work-group
/// per row; the operation of row r is bits 2r..2r+1 of `ops`. out[r] receives the result.
__kernel void reduce_rows(__global const real* in, const uint n, const uint stride, const uint ops,
                          __global real* out, __local real* scratch) {
  const uint lid = get_local_id(0), row = get_group_id(0);
  const int op = (int)((ops >> (2 * row)) & 3u);
  __global const real* r = in + (size_t)row * stride;
  real acc = reduce_identity(op);
  for (uint i = lid; i < n; i += get_local_size(0)) acc = reduce_combine(op, acc, r[i]);
  scratch[lid] = acc;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint s = get_local_size(0) / 2; s > 0; s >>= 1) {
    if (lid < s) scratch[lid] = reduce_combine(op, scratch[lid], scratch[lid + s]);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) out[row] = scratch[0];
}
