// Per-tile diagnostics in one pass over the wet tiles, one work-group per TILE x TILE tile:
// the CFL wave speed max over cells of (|u| + c) + (|v| + c) with c = sqrt(g_p h), the volume,
// the outflow of the last step, the kinetic energy per unit density, the smallest thickness and
// whether the tile holds any water. The host reduces the partials with the generic reduction.
// Then flow_activate_tiles marks every tile within one tile of a wet tile as active for the next
// step: with CFL <= 1 water moves at most two cells per step, far less than a tile.
#include "flow/flow_common.cl"

#define DIAG_SPEED 0
#define DIAG_VOLUME 1
#define DIAG_OUTFLOW 2
#define DIAG_KINETIC 3
#define DIAG_MIN_H 4
#define DIAG_COUNT 5

__kernel __attribute__((reqd_work_group_size(TILE, TILE, 1)))
void flow_tile_diagnostics(__constant const FlowParams* p, __global const uchar* mask, __global const int* tile_active,
                           __global const real* h, __global const real* qx, __global const real* qy,
                           __global const real* gp, __global const real* out_step, __global real* partial,
                           __global int* tile_wet) {
  __local real s_speed[TILE * TILE], s_vol[TILE * TILE], s_out[TILE * TILE], s_ke[TILE * TILE], s_min[TILE * TILE];
  __local int s_wet[TILE * TILE];
  const int i = get_global_id(0), j = get_global_id(1);
  const int lid = get_local_id(1) * TILE + get_local_id(0);
  const int tile = get_group_id(1) * p->tiles_x + get_group_id(0);
  const int ntiles = p->tiles_x * p->tiles_y;
  real speed = 0, vol = 0, out = 0, ke = 0, hmin = REAL_MAX;
  int wet = 0;
  if (i < p->nx && j < p->ny && tile_active[tile] && cell_inside(p, mask, i, j)) {
    const int k = cell_index(p, i, j);
    const real hk = h[k];
    const real u = velocity(hk, qx[k], p->h_dry), v = velocity(hk, qy[k], p->h_dry);
    const real c = sqrt(gp[k] * fmax(hk, (real)0));
    const real area = p->dx * p->dx;
    speed = hk > (real)0 ? fabs(u) + fabs(v) + (real)2 * c : (real)0;
    vol = hk * area;
    out = out_step[k];
    ke = (real)0.5 * hk * (u * u + v * v) * area;
    hmin = hk;
    wet = hk > (real)0 || isnan(hk);
    if (isnan(hk) || isnan(qx[k]) || isnan(qy[k])) speed = NAN;
  }
  s_speed[lid] = speed; s_vol[lid] = vol; s_out[lid] = out; s_ke[lid] = ke; s_min[lid] = hmin; s_wet[lid] = wet;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int s = TILE * TILE / 2; s > 0; s >>= 1) {
    if (lid < s) {
      const real a = s_speed[lid], c = s_speed[lid + s];
      s_speed[lid] = (isnan(a) || isnan(c)) ? NAN : fmax(a, c);
      s_vol[lid] += s_vol[lid + s];
      s_out[lid] += s_out[lid + s];
      s_ke[lid] += s_ke[lid + s];
      s_min[lid] = fmin(s_min[lid], s_min[lid + s]);
      s_wet[lid] |= s_wet[lid + s];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) {
    partial[DIAG_SPEED * ntiles + tile] = s_speed[0];
    partial[DIAG_VOLUME * ntiles + tile] = s_vol[0];
    partial[DIAG_OUTFLOW * ntiles + tile] = s_out[0];
    partial[DIAG_KINETIC * ntiles + tile] = s_ke[0];
    partial[DIAG_MIN_H * ntiles + tile] = s_min[0];
    tile_wet[tile] = s_wet[0];
  }
}

__kernel void flow_activate_tiles(__constant const FlowParams* p, __global const int* tile_wet,
                                  __global int* tile_active) {
  const int ti = get_global_id(0), tj = get_global_id(1);
  if (ti >= p->tiles_x || tj >= p->tiles_y) return;
  int active = !p->skip_dry_tiles;
  for (int dj = -1; dj <= 1 && !active; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int a = ti + di, c = tj + dj;
      if (a >= 0 && c >= 0 && a < p->tiles_x && c < p->tiles_y && tile_wet[c * p->tiles_x + a]) active = 1;
    }
  tile_active[tj * p->tiles_x + ti] = active;
}
