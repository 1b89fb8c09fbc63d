// Per-tile diagnostics in one pass over the active tiles, one work-group per tile: the CFL wave
// speed max over wet cells of (|u| + c + w) + (|v| + c + w) (with -DSPLIT=1, for the dimensionally
// split scheme, max(|u|, |v|) + c + w) with c = sqrt(g h) (g >= g_p of any face)
// and w = sqrt(g |grad b| dx), the speed the bed slope gives water over one cell (without it a thin
// film at rest on a slope, whose c is tiny, would get a step in which gravity accelerates it far
// past the CFL limit); the volume, the outflow of the
// last step, the kinetic energy per unit density, the smallest thickness and whether the tile holds
// any water. Partials are stored at the tile's position in the active list (rows of length ntiles),
// so the host reduces the first `count` entries of each row; the list is in ascending tile order,
// which makes every sum deterministic.
//
// flow_compact_tiles then marks every tile within one tile of a wet tile as active for the next step
// (with CFL <= 1 water moves at most two cells per step, far less than a tile) and writes the
// ascending list of active tiles and its length, in one work-group (a prefix sum over tile chunks).
#include "flow/flow_common.cl"

#define DIAG_SPEED 0
#define DIAG_VOLUME 1
#define DIAG_OUTFLOW 2
#define DIAG_KINETIC 3
#define DIAG_MIN_H 4
#define DIAG_FLOW_SPEED 5  // max material speed |u| of cells thicker than Minimum Flow Height [m/s]
#define DIAG_WAVE_WET 6    // the CFL wave speed over cells thicker than Minimum Flow Height [m/s]
#define DIAG_SINGLE_ROWS 7
#define DIAG_VOLUME_S 7    // two-phase only: solid volume
#define DIAG_OUTFLOW_S 8   // two-phase only: solid outflow
#define DIAG_POTENTIAL 9   // two-phase only: potential energy g sum m (centroid height) [J]
#define DIAG_KINETIC_V 10  // two-phase only: kinetic energy of the vertical motion m (u.grad b)^2 / 2 [J]
#define DIAG_WORK 11       // two-phase only: kinetic energy the step's basal law, drag and viscous terms took [J]
#define DIAG_MAX_ROWS 12
#define DIAG_IS_MAX(r) ((r) == DIAG_SPEED || (r) == DIAG_FLOW_SPEED || (r) == DIAG_WAVE_WET)
#define TILE_CELLS (TILE * TILE)

/// Reduces `rows` values per work-item (row r in s[r * TILE_CELLS + lid]; the speed rows by max with
/// NaN propagation, DIAG_MIN_H by min, the others by sum) and the wet flags, then work-item 0 writes
/// the tile's partials at its slot in the active list and its wet flag.
INLINE void reduce_tile(__local real* s, __local int* s_wet, int rows, int lid, int slot, int ntiles,
                        __global real* partial, __global int* tile_wet, int tile) {
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int step = TILE_CELLS / 2; step > 0; step >>= 1) {
    if (lid < step) {
      for (int r = 0; r < rows; ++r) {
        const real x = s[r * TILE_CELLS + lid], y = s[r * TILE_CELLS + lid + step];
        real v;
        if (DIAG_IS_MAX(r)) v = (isnan(x) || isnan(y)) ? NAN : fmax(x, y);
        else if (r == DIAG_MIN_H) v = fmin(x, y);
        else v = x + y;
        s[r * TILE_CELLS + lid] = v;
      }
      s_wet[lid] |= s_wet[lid + step];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) {
    for (int r = 0; r < rows; ++r) partial[r * ntiles + slot] = s[r * TILE_CELLS];
    tile_wet[tile] = s_wet[0];
  }
}

__kernel __attribute__((reqd_work_group_size(TILE, TILE, 1)))
void flow_tile_diagnostics(__constant const FlowParams* p, __global const uchar* mask, __global const int* tile_list,
                           __global const real* h, __global const real* qx, __global const real* qy,
                           __global const real* slope_speed, __global const real* out_step, __global real* partial,
                           __global int* tile_wet) {
  __local real s[DIAG_SINGLE_ROWS * TILE_CELLS];
  __local int s_wet[TILE_CELLS];
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  const int lid = get_local_id(1) * TILE + get_local_id(0);
  real speed = 0, vol = 0, out = 0, ke = 0, hmin = REAL_MAX, flow = 0, wave_wet = 0;
  int wet = 0;
  if (i < p->nx && j < p->ny && cell_inside(p, mask, i, j)) {
    const int k = cell_index(p, i, j);
    const real hk = h[k];
    const real u = velocity(hk, qx[k], p->h_dry), v = velocity(hk, qy[k], p->h_dry);
    // Wave speed with the largest g a face can use, plus the speed the bed slope adds (see header).
    const real cw = sqrt(GRAVITY * fmax(hk, (real)0));
    const real area = p->dx * p->dx;
#if SPLIT
    // Dimensionally split scheme: each sweep's Courant number is along its own direction, with the
    // same slope speed w per direction as the unsplit sum. A smaller weight (the speed a film gains
    // within the step, (a + sqrt(a^2 + 4 cfl w^2)) / 2) kept a lake at rest between walls still but
    // let a lake against an open edge drain at m/s within 150 s: the zero-gradient open edge leaves
    // such a lake only neutrally at rest and it drains by itself over a rough bed, faster with
    // longer steps (docs/numerics.md; level edges keep it at rest). w keeps its full weight.
    speed = hk > (real)0 ? fmax(fabs(u), fabs(v)) + cw + slope_speed[k] : (real)0;
#else
    speed = hk > (real)0 ? fabs(u) + fabs(v) + (real)2 * (cw + slope_speed[k]) : (real)0;
#endif
    vol = hk * area;
    out = out_step[k];
    ke = (real)0.5 * hk * (u * u + v * v) * area;
    hmin = hk;
    // The health check's quantities: films at or below the dry threshold carry no velocity, so
    // neither their speed nor their wave speed says anything about the flow's energy or stability.
    if (hk > p->h_dry) {
      flow = sqrt(u * u + v * v);
      wave_wet = speed;
    }
    wet = hk > (real)0 || isnan(hk);
    if (isnan(hk) || isnan(qx[k]) || isnan(qy[k])) speed = flow = wave_wet = NAN;
  }
  s[DIAG_SPEED * TILE_CELLS + lid] = speed;
  s[DIAG_VOLUME * TILE_CELLS + lid] = vol;
  s[DIAG_OUTFLOW * TILE_CELLS + lid] = out;
  s[DIAG_KINETIC * TILE_CELLS + lid] = ke;
  s[DIAG_MIN_H * TILE_CELLS + lid] = hmin;
  s[DIAG_FLOW_SPEED * TILE_CELLS + lid] = flow;
  s[DIAG_WAVE_WET * TILE_CELLS + lid] = wave_wet;
  s_wet[lid] = wet;
  reduce_tile(s, s_wet, DIAG_SINGLE_ROWS, lid, get_group_id(0), p->tiles_x * p->tiles_y, partial, tile_wet,
              tile_list[get_group_id(0)]);
}

#define COMPACT_GROUP 256

INLINE int tile_should_run(__constant const FlowParams* p, __global const int* tile_wet, int t) {
  if (!p->skip_dry_tiles) return 1;
  const int ti = t % p->tiles_x, tj = t / p->tiles_x;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int a = ti + di, c = tj + dj;
      if (a >= 0 && c >= 0 && a < p->tiles_x && c < p->tiles_y && tile_wet[c * p->tiles_x + a]) return 1;
    }
  return 0;
}

/// One work-group of COMPACT_GROUP items; item k handles a contiguous chunk of tiles.
__kernel __attribute__((reqd_work_group_size(COMPACT_GROUP, 1, 1)))
void flow_compact_tiles(__constant const FlowParams* p, __global const int* tile_wet, __global int* tile_active,
                        __global int* tile_list, __global int* tile_count) {
  __local int s_sum[COMPACT_GROUP];
  const int lid = get_local_id(0);
  const int ntiles = p->tiles_x * p->tiles_y;
  const int chunk = (ntiles + COMPACT_GROUP - 1) / COMPACT_GROUP;
  const int t0 = lid * chunk, t1 = min(ntiles, t0 + chunk);
  int n = 0;
  for (int t = t0; t < t1; ++t) {
    const int a = tile_should_run(p, tile_wet, t);
    tile_active[t] = a;
    n += a;
  }
  s_sum[lid] = n;
  barrier(CLK_LOCAL_MEM_FENCE);
  // Inclusive Hillis-Steele scan of the chunk counts.
  for (int off = 1; off < COMPACT_GROUP; off <<= 1) {
    const int add = lid >= off ? s_sum[lid - off] : 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    s_sum[lid] += add;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  int pos = s_sum[lid] - n;
  for (int t = t0; t < t1; ++t)
    if (tile_active[t]) tile_list[pos++] = t;
  if (lid == COMPACT_GROUP - 1) tile_count[0] = s_sum[lid];
}
