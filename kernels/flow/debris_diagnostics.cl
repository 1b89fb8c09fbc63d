// Diagnostics and running maxima of the two-phase model (spec §8), one work-group per active tile:
// CFL speed max over cells of max(|u_s| + |v_s|, |u_f| + |v_f|) + 2 (sqrt(g H max(1, K_passive)) + w),
// w the bed-slope speed of diagnostics.cl (plus the viscous speed bound of debris_viscous.cl when on),
// volumes and outflow of each phase, kinetic energy (J, both phases), the work of the step's stiff
// sources (debris_stage.cl, out_step row 2), smallest thickness; and per
// cell the maxima of each phase's thickness and speed, of the total thickness, the solid fraction
// and the impact pressure rho_m |u_m|^2 of the mixture, and the arrival time of the mixture.
#ifndef DEBRIS_OBSTACLE
#define DEBRIS_OBSTACLE 0
#endif
#include "flow/diagnostics.cl"
#include "flow/debris_closures.cl"
#ifndef DEBRIS_VISCOUS
#define DEBRIS_VISCOUS 0
#endif
#if DEBRIS_VISCOUS
#include "flow/debris_viscous.cl"
#endif

__kernel __attribute__((reqd_work_group_size(TILE, TILE, 1)))
void debris_tile_diagnostics(__constant const FlowParams* p, __constant const DebrisParams* dp,
                             __global const uchar* mask, __global const int* tile_list, __global const real* S,
                             __global const real* hf, __global const real* qfx, __global const real* qfy,
                             __global const real* slope_speed, __global const real* delta,
                             __global const real* pbed, __global const real* bed, __global const real* slope,
                             __global const real* out_step,
                             __global real* partial, __global int* tile_wet) {
  __local real s[DIAG_MAX_ROWS * TILE_CELLS];
  __local int s_wet[TILE_CELLS];
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  const int lid = get_local_id(1) * TILE + get_local_id(0);
  const int n = p->nx * p->ny;
  real speed = 0, volf = 0, outf = 0, ke = 0, hmin = REAL_MAX, vols = 0, outs = 0, pe = 0, kev = 0, flow = 0,
       wave_wet = 0, work = 0;
  int wet = 0;
  if (i < p->nx && j < p->ny && cell_inside(p, mask, i, j)) {
    const int k = cell_index(p, i, j);
    const real hs = S[k], h = hf[k], H = fmax(hs, (real)0) + fmax(h, (real)0);
    const real us = solid_velocity(hs, S[n + k], p->h_dry, dp->film_h), vs = solid_velocity(hs, S[2 * n + k], p->h_dry, dp->film_h);
    const real uf = velocity(h, qfx[k], p->h_dry), vf = velocity(h, qfy[k], p->h_dry);
    const real rho_s = hs > p->h_dry ? S[4 * n + k] / hs : dp->rho_s_default;
    const real phi = hs > p->h_dry ? S[3 * n + k] / hs : dp->phi_default;
    const real K = dp->earth_pressure == EARTH_CONSTANT ? dp->k_const
                                                        : earth_pressure(phi, dp->delta_from_phi ? phi : delta[k], (real)1);
    const real area = p->dx * p->dx;
    real w = slope_speed[k];
#if DEBRIS_OBSTACLE
    // Hybrid mode: the particle bed's steps accelerate the flow as the DEM's slope does; its slope
    // speed sqrt(g |dH_c|) from the largest step to a neighbour (the bed moves with the particles,
    // so this is re-evaluated each step, after the bed of the next step was written).
    real step = 0;
    for (int q = 0; q < 4; ++q) {
      const int a = i + (q == 0) - (q == 1), b2 = j + (q == 2) - (q == 3);
      if (cell_inside(p, mask, a, b2)) step = fmax(step, fabs(pbed[cell_index(p, a, b2)] - pbed[k]));
    }
    w += sqrt(GRAVITY * step);
#endif
    speed = H > (real)0 ? fmax(fabs(us) + fabs(vs), fabs(uf) + fabs(vf)) + (real)2 * (sqrt(GRAVITY * H * fmax((real)1, K)) + w)
                        : (real)0;
    // The CFL check of the health check judges the hyperbolic wave speed of layers above the dry
    // threshold; the viscous rate below belongs to the time step (explicit diffusion) but says
    // nothing about a wave outrunning the step, and it jumps as a film thins (1 / h_f).
    if (hs > p->h_dry || h > p->h_dry) wave_wet = speed;
#if DEBRIS_VISCOUS
    speed += visc_speed(p, dp, mask, S, hf, qfx, qfy, i, j);
#endif
    volf = h * area;
    vols = hs * area;
    outf = out_step[k];
    outs = out_step[n + k];
    work = out_step[2 * n + k];
    ke = (real)0.5 * (rho_s * hs * (us * us + vs * vs) + dp->rho_f * h * (uf * uf + vf * vf)) * area;
    // Energy accounting: the centroid height of each phase's column (solids on the DEM, fluid on
    // top of them) and the vertical velocity u.grad b of material that follows the bed (the slope of
    // the reconstructed bed, flow/SlopeGravity.hpp); with the horizontal kinetic energy these make
    // the mechanical energy that the terrain-following gravity conserves (solid_bed.cl).
    const real hs0 = fmax(hs, (real)0), hf0 = fmax(h, (real)0);
    pe = GRAVITY * (rho_s * hs0 * (bed[k] + (real)0.5 * hs0) + dp->rho_f * hf0 * (bed[k] + hs0 + (real)0.5 * hf0)) * area;
    const real ws = us * slope[k] + vs * slope[n + k], wf = uf * slope[k] + vf * slope[n + k];
    kev = (real)0.5 * (rho_s * hs * ws * ws + dp->rho_f * h * wf * wf) * area;
    hmin = fmin(hs, h);
    // Health check: the material speed of either phase, over phases thicker than the dry
    // threshold (films below it carry no velocity).
    if (hs > p->h_dry) flow = sqrt(us * us + vs * vs);
    if (h > p->h_dry) flow = fmax(flow, sqrt(uf * uf + vf * vf));
    wet = H > (real)0 || isnan(H);
    if (isnan(H) || isnan(S[n + k]) || isnan(S[2 * n + k]) || isnan(qfx[k]) || isnan(qfy[k]))
      speed = flow = wave_wet = NAN;
  }
  s[DIAG_SPEED * TILE_CELLS + lid] = speed;
  s[DIAG_VOLUME * TILE_CELLS + lid] = volf;
  s[DIAG_OUTFLOW * TILE_CELLS + lid] = outf;
  s[DIAG_KINETIC * TILE_CELLS + lid] = ke;
  s[DIAG_MIN_H * TILE_CELLS + lid] = hmin;
  s[DIAG_FLOW_SPEED * TILE_CELLS + lid] = flow;
  s[DIAG_WAVE_WET * TILE_CELLS + lid] = wave_wet;
  s[DIAG_VOLUME_S * TILE_CELLS + lid] = vols;
  s[DIAG_OUTFLOW_S * TILE_CELLS + lid] = outs;
  s[DIAG_POTENTIAL * TILE_CELLS + lid] = pe;
  s[DIAG_KINETIC_V * TILE_CELLS + lid] = kev;
  s[DIAG_WORK * TILE_CELLS + lid] = work;
  s_wet[lid] = wet;
  reduce_tile(s, s_wet, DIAG_MAX_ROWS, lid, get_group_id(0), p->tiles_x * p->tiles_y, partial, tile_wet,
              tile_list[get_group_id(0)]);
}

/// Running maxima, components of `maxima` (each n cells): 0 h_f, 1 v_f, 2 h_s, 3 v_s, 4 H,
/// 5 solid fraction, 6 impact pressure [Pa]; arrival: first time H exceeds the threshold.
__kernel void debris_track_maxima(__constant const FlowParams* p, __constant const DebrisParams* dp,
                                  __global const uchar* mask, __global const int* tile_list, __global const real* S,
                                  __global const real* hf, __global const real* qfx, __global const real* qfy,
                                  __global real* maxima, __global real* arrival, const real t) {
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  if (i >= p->nx || j >= p->ny || !cell_inside(p, mask, i, j)) return;
  const int n = p->nx * p->ny;
  const int k = cell_index(p, i, j);
  const real hs = S[k], h = hf[k], H = hs + h;
  const real us = solid_velocity(hs, S[n + k], p->h_dry, dp->film_h), vs = solid_velocity(hs, S[2 * n + k], p->h_dry, dp->film_h);
  const real uf = velocity(h, qfx[k], p->h_dry), vf = velocity(h, qfy[k], p->h_dry);
  const real rho_s = hs > p->h_dry ? S[4 * n + k] / hs : dp->rho_s_default;
  const real ms = rho_s * hs, mf = dp->rho_f * h;
  real impact = 0, frac = 0;
  if (H > p->h_dry) {
    // Mixture density and momentum-weighted mixture velocity.
    const real umx = (ms * us + mf * uf) / (ms + mf), umy = (ms * vs + mf * vf) / (ms + mf);
    impact = (ms + mf) / H * (umx * umx + umy * umy);
    frac = hs / H;
  }
  // Speeds and impact pressure count where the phase (mixture) is thicker than the arrival threshold,
  // as flow maps usually do: films thinner than that carry no meaningful velocity.
  const real thick = p->arrival_h;
  const real vals[7] = {h, h > thick ? sqrt(uf * uf + vf * vf) : (real)0, hs, hs > thick ? sqrt(us * us + vs * vs) : (real)0,
                        H, frac, H > thick ? impact : (real)0};
  for (int q = 0; q < 7; ++q) maxima[q * n + k] = fmax(maxima[q * n + k], vals[q]);
  if (arrival[k] < (real)0 && H > p->arrival_h) arrival[k] = t;
}
