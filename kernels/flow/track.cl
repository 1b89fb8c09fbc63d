// Running maxima and arrival time for the output maps (spec §8): maximum thickness, maximum speed,
// first time the thickness exceeds the arrival threshold (-1 until then).
#include "flow/flow_common.cl"

__kernel void flow_track_maxima(__constant const FlowParams* p, __global const uchar* mask,
                                __global const int* tile_list, __global const real* h, __global const real* qx,
                                __global const real* qy, __global real* h_max, __global real* v_max,
                                __global real* arrival, const real t) {
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  if (i >= p->nx || j >= p->ny || !cell_inside(p, mask, i, j)) return;
  const int k = cell_index(p, i, j);
  const real hk = h[k];
  const real u = velocity(hk, qx[k], p->h_dry), v = velocity(hk, qy[k], p->h_dry);
  h_max[k] = fmax(h_max[k], hk);
  v_max[k] = fmax(v_max[k], sqrt(u * u + v * v));
  if (arrival[k] < (real)0 && hk > p->arrival_h) arrival[k] = t;
}
