// The bed's slope fields recomputed on the device after the bed changed (entrainment.cl), over the
// active tiles (bed changes happen in wet cells; the active tiles cover two cells around them).
// The same formulas as the host's computeSlopeGravity (src/flow/SlopeGravity.cpp, its CPU reference
// in tests/kernels/test_bed_geometry.cpp): per axis the limited bed slope of bed_rise (flow_common.cl),
// the slope speed sqrt(g s_max dx) from the steepest one-sided difference, g_n = g cos^2(theta) and
// g_p = g_n or g cos^4(theta) (-DDEPTH_COS4=1). Built with -DSLOPE_CORRECTION=0 the gravities stay g,
// as on the host.
#include "flow/flow_common.cl"

#ifndef SLOPE_CORRECTION
#define SLOPE_CORRECTION 1
#endif
#ifndef DEPTH_COS4
#define DEPTH_COS4 0
#endif

/// Limited slope of `f` at (i, j) along (di, dj), per unit length (SlopeGravity.cpp, limitedBedSlope).
INLINE real bed_limited_slope(__constant const FlowParams* p, __global const uchar* mask, __global const real* f, int i,
                          int j, int di, int dj) {
  const int m = cell_inside(p, mask, i - di, j - dj), q = cell_inside(p, mask, i + di, j + dj);
  const int mm = m && cell_inside(p, mask, i - 2 * di, j - 2 * dj), qq = q && cell_inside(p, mask, i + 2 * di, j + 2 * dj);
  const real fm = m ? f[cell_index(p, i - di, j - dj)] : (real)0, fq = q ? f[cell_index(p, i + di, j + dj)] : (real)0;
  const real fmm = mm ? f[cell_index(p, i - 2 * di, j - 2 * dj)] : (real)0, fqq = qq ? f[cell_index(p, i + 2 * di, j + 2 * dj)] : (real)0;
  return bed_rise(fmm, mm, fm, m, f[cell_index(p, i, j)], fq, q, fqq, qq) / p->dx;
}

__kernel void bed_slope_fields(__constant const FlowParams* p, __global const uchar* mask, __global const int* tile_list,
                               __global const real* b, __global real* gn, __global real* gp, __global real* slope_speed,
                               __global real* slope) {
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  if (i >= p->nx || j >= p->ny || !cell_inside(p, mask, i, j)) return;
  const int n = p->nx * p->ny;
  const int k = cell_index(p, i, j);
  const real bx = bed_limited_slope(p, mask, b, i, j, 1, 0), by = bed_limited_slope(p, mask, b, i, j, 0, 1);
  slope[k] = bx;
  slope[n + k] = by;
  real steepest = hypot(bx, by);
  for (int d = 0; d < 2; ++d)
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      const int a = i + (d == 0 ? sgn : 0), e = j + (d == 1 ? sgn : 0);
      if (cell_inside(p, mask, a, e)) steepest = fmax(steepest, fabs(b[cell_index(p, a, e)] - b[k]) / p->dx);
    }
  slope_speed[k] = sqrt(GRAVITY * steepest * p->dx);
#if SLOPE_CORRECTION
  const real cos2 = (real)1 / ((real)1 + (bx * bx + by * by));
  gn[k] = GRAVITY * cos2;
  gp[k] = DEPTH_COS4 ? GRAVITY * cos2 * cos2 : GRAVITY * cos2;
#endif
}
