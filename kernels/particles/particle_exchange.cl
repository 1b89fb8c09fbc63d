// Drag between the particles' confined phase and the grid's free fluid (spec §6; Pudasaini 2012 drag
// with virtual mass, OpenLISEM Hazard P.31-P.35), one work-item per terrain cell, after the particles
// were transferred to the grid (P2G: thickness H_c, mass M_c, momentum P_c of the cell).
// In a cell with both, the relative velocity w = u_f - u_c relaxes exactly over dt (linear law:
// w e^{-lambda dt}; quadratic: w / (1 + lambda |w| dt)) at the rate of the grid model's drag
// (kernels/flow/phase_exchange.cl, drag_step) with the confined phase in the solids' place:
// lambda = rho_c H C (1/m_c + 1/m_f) / (1 + m_vm (1/m_c + 1/m_f)), m_c = M_c / dx^2, m_f = rho_f h_f,
// H = H_c + h_f, C the drag coefficient of alpha_c = H_c / H, rho_c = m_c / H_c and grain size d.
// The total momentum m_c u_c + m_f u_f of the cell is kept; the fluid's new discharge is written
// back and the confined phase's velocity change (du, dv) goes to the particles by G2P with the same
// B-spline weights, so the particles gain exactly what the fluid loses.
#include "flow/debris_closures.cl"

__kernel void particle_fluid_drag(__constant const DebrisParams* dp, const int n, const real dx, const real h_dry,
                                  const real grain, __global const real* Hc, __global const real* Mc,
                                  __global const real* Px, __global const real* Py, __global const real* hf,
                                  __global real* qx, __global real* qy, __global real* du, __global real* dv,
                                  const real dt) {
  const int k = get_global_id(0);
  if (k >= n) return;
  du[k] = dv[k] = 0;
  const real h = hf[k], H_c = Hc[k];
  if (!(h > h_dry) || !(H_c > h_dry) || !(Mc[k] > (real)0) || dp->drag_law == DRAG_OFF) return;
  const real area = dx * dx;
  const real mc = Mc[k] / area, mf = dp->rho_f * h;
  const real rho_c = mc / H_c, H = H_c + h, as = H_c / H, af = h / H;
  const real inv = (real)1 / mc + (real)1 / mf;
  const real mvm = dp->virtual_mass ? (real)0.5 * ((real)1 + (real)2 * as) / af * dp->rho_f * H_c : (real)0;
  const real lambda = rho_c * H * drag_coefficient(dp, as, rho_c, grain) * inv / ((real)1 + mvm * inv);
  const real ucx = Px[k] / Mc[k], ucy = Py[k] / Mc[k];
  const real wx = qx[k] / h - ucx, wy = qy[k] / h - ucy, w = sqrt(wx * wx + wy * wy);
  const real f = dp->drag_law == DRAG_QUADRATIC ? (real)1 / ((real)1 + lambda * w * dt) : exp(-lambda * dt);
  // Common motion: (m_c u_c + m_f u_f - m_f w f) / (m_c + m_f).
  const real nx = (mc * ucx + mf * (ucx + wx) - mf * wx * f) / (mc + mf);
  const real ny = (mc * ucy + mf * (ucy + wy) - mf * wy * f) / (mc + mf);
  du[k] = nx - ucx;
  dv[k] = ny - ucy;
  qx[k] = h * (nx + wx * f);
  qy[k] = h * (ny + wy * f);
}
