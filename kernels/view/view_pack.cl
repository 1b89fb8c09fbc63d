// Packing of solver fields into what the viewer's shaders read: one float per cell (or particle)
// from up to six `real` inputs, and float x, y, z triples for particle positions. Used on both
// interop paths (src/sim/ViewFields): on the shared path the output is (or is copied into) an
// OpenGL buffer, on the copy path it is read back to the host once. The arithmetic mirrors the
// host computation of sim::ViewFields::snapshot, in the run's precision, then rounds to float.
#include "common/real.cl"

// Modes of view_pack_values (host mirror: sim::PackMode in src/sim/ViewFields.hpp).
#define PACK_COPY 0       // a
#define PACK_SUM 1        // a + b
#define PACK_SPEED 2      // |(b, c)| / a where a > hDry, else 0 (a thickness, b c discharge)
#define PACK_SPEED_SUM 3  // |(b + e, c + f)| / (a + d) where a + d > hDry, else 0 (two phases)
#define PACK_FRACTION 4   // b / (a + b) where a + b > hDry, else 0
#define PACK_MAX2 5       // max(a, b)
#define PACK_ARRIVAL 6    // a, NaN where a < 0 (not arrived)
#define PACK_NORM 7       // |(a, b)|

/// |q| / h where h exceeds the dry threshold, else 0 (the host's speed()).
INLINE real pack_speed(real qx, real qy, real h, real hDry) { return h > hDry ? hypot(qx, qy) / h : (real)0; }

/// out[k] = mode(a..f)[k] as float for k < n; `noValue` where `valid` (when given, useMask != 0)
/// is 0 and where the result is not finite (NaN for snapshots, the shaders' no-data value when the
/// output is an OpenGL buffer). Inputs a mode does not read may be any buffer.
__kernel void view_pack_values(const int n, const int mode, const real hDry, __global const real* a,
                               __global const real* b, __global const real* c, __global const real* d,
                               __global const real* e, __global const real* f, __global const uchar* valid,
                               const int useMask, const float noValue, __global float* out) {
  const int k = get_global_id(0);
  if (k >= n) return;
  if (useMask && !valid[k]) {
    out[k] = noValue;
    return;
  }
  real v = 0;
  switch (mode) {
    case PACK_COPY: v = a[k]; break;
    case PACK_SUM: v = a[k] + b[k]; break;
    case PACK_SPEED: v = pack_speed(b[k], c[k], a[k], hDry); break;
    case PACK_SPEED_SUM: v = pack_speed(b[k] + e[k], c[k] + f[k], a[k] + d[k], hDry); break;
    case PACK_FRACTION: {
      const real ht = a[k] + b[k];
      v = ht > hDry ? b[k] / ht : (real)0;
      break;
    }
    case PACK_MAX2: v = fmax(a[k], b[k]); break;
    case PACK_ARRIVAL: v = a[k] < 0 ? (real)NAN : a[k]; break;
    case PACK_NORM: v = hypot(a[k], b[k]); break;
    default: v = NAN;
  }
  const float packed = convert_float(v);
  out[k] = isfinite(packed) ? packed : noValue;
}

/// Particle positions for drawing: world x, y from the grid coordinates x, y [m from the raster's
/// corner] through the geotransform t0..t5, z = bed elevation of the particle's cell + H. Removed
/// particles (non-finite x) get NaN triples. out holds 3 n floats.
__kernel void view_pack_positions(const int n, __global const real* x, __global const real* y,
                                  __global const real* H, __global const real* bed, const int nx, const int ny,
                                  const real dx, const real t0, const real t1, const real t2, const real t3,
                                  const real t4, const real t5, __global float* out) {
  const int q = get_global_id(0);
  if (q >= n) return;
  if (!isfinite(x[q])) {
    out[3 * q] = out[3 * q + 1] = out[3 * q + 2] = NAN;
    return;
  }
  const real u = x[q] / dx, v = y[q] / dx;  // column, row coordinates
  const int i = clamp((int)u, 0, nx - 1), j = clamp((int)v, 0, ny - 1);
  out[3 * q] = convert_float(t0 + u * t1 + v * t2);
  out[3 * q + 1] = convert_float(t3 + u * t4 + v * t5);
  out[3 * q + 2] = convert_float(bed[j * nx + i] + H[q]);
}
