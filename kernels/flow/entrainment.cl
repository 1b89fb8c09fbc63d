// Entrainment of an erodible bed layer by the two-phase flow (docs/entrainment.md), once per step
// after the two RK stages, one cell per work-item over the active tiles.
//
// Rate law: the growth rate of McDougall & Hungr (2005, Can. Geotech. J. 42, eq. 13; Hungr 1995):
// the bulk volume grows in proportion to itself and to the distance it travels, dV/dt = E V |U|,
// i.e. per unit bed area dH/dt = E H |U| (H bed-normal bulk thickness, |U| along-bed speed, E [1/m]
// the growth rate, which a user calibrates as E = ln(V_final / V_release) / path length). r.avaflow's
// entrainment coefficient form q_E = 10^C_E |rho h u| is the same law with E = 10^C_E rho / rho_E.
// Per unit horizontal area (vertical h = H / cos(theta), |U| = s |u|, s as basal_rheology.cl) the
// bed-area rate E H |U| / cos(theta) is dh/dt = E s |h u| = E s |q_s + q_f|: the bulk discharge, which
// the entrained material (at rest) does not change, so over a step the entrained depth is exactly
// dh = E s |q_s + q_f| dt, capped by the erodible depth left.
// Conservation: the entrained depth joins the solids (h_s += dh, transported scalars at the flow's
// values, cohesion included: the erodible layer takes the flow's properties; the defaults
// where there were no solids, no cohesion) with zero momentum, so the momenta of both phases
// are unchanged (the entrained mass enters at rest; the flow slows by mass dilution); the bed drops by
// dh (b -= dh) and the erodible depth and the bed change record it, so h_s + erodible is conserved
// per cell and the surface b + h_s is unchanged (a flow at rest stays at rest; nothing at rest
// entrains). The bed's slope and curvature fields are then recomputed (bed_geometry.cl).
#include "flow/debris_closures.cl"
#include "flow/basal_rheology.cl"

__kernel void debris_entrain(__constant const FlowParams* p, __constant const DebrisParams* dp,
                             __global const uchar* mask, __global const int* tile_list, __global const real* slope,
                             __global const real* qfx, __global const real* qfy, __global real* S, __global real* b,
                             __global real* erodible, __global real* bed_change, __global int* eroded,
                             const real growth, const real dt) {
  const int2 c = tile_cell(p, tile_list);
  const int i = c.x, j = c.y;
  if (i >= p->nx || j >= p->ny || !cell_inside(p, mask, i, j)) return;
  const int n = p->nx * p->ny;
  const int k = cell_index(p, i, j);
  const real e = erodible[k];
  if (!(e > (real)0)) return;
  const real qx = S[n + k] + qfx[k], qy = S[2 * n + k] + qfy[k];
  const real q = sqrt(qx * qx + qy * qy);
  if (!(q > (real)0)) return;
  const real s = along_bed_stretch(qx, qy, slope[k], slope[n + k]);
  const real dh = fmin(e, growth * s * q * dt);
  if (!(dh > (real)0)) return;
  const real hs = S[k], hn = hs + dh;
  // The passive scalars, h_s value (debris_stage.cl); the fifth, the lift-off speed, keeps h_s w: the
  // entrained material lies on the bed (w = 0) and mixes in.
  for (int cc = 0; cc < 4; ++cc) {
    const real value = hs > p->h_dry ? S[(3 + cc) * n + k] / hs : scalar_default(dp, cc);
    S[(3 + cc) * n + k] = hn * value;
  }
  S[k] = hn;
  b[k] -= dh;
  erodible[k] = e - dh;
  bed_change[k] -= dh;
  *eroded = 1;  // every writer stores the same value
}
