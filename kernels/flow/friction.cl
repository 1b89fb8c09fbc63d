// Basal Manning friction, applied after the flux step with a semi-implicit (linearised) update in
// its slope-consistent form (flow/manning.cl): q_new = q / (1 + dt g n^2 |U| / h_n^(4/3)), which can
// slow a flow to rest but never reverses it.
#include "flow/flow_common.cl"
#include "flow/manning.cl"

__kernel void flow_friction(__constant const FlowParams* p, __global const uchar* mask, __global const int* tile_list,
                            __global const real* manning, __global const real* gn, __global const real* slope,
                            __global const real* h, __global real* qx, __global real* qy, const real dt) {
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  if (i >= p->nx || j >= p->ny || !cell_inside(p, mask, i, j)) return;
  const int k = cell_index(p, i, j);
  const real hk = h[k], n = manning[k];
  if (hk <= p->h_dry || n <= (real)0) return;
  const int cells = p->nx * p->ny;
  const real u = velocity(hk, qx[k], p->h_dry), v = velocity(hk, qy[k], p->h_dry);
  const real factor = manning_factor(n, hk, u, v, slope[k], slope[cells + k], gn[k] / (real)GRAVITY, dt);
  qx[k] /= factor;
  qy[k] /= factor;
}
