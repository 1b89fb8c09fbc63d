// The stiff exchange of the two-phase grid model (debris_stage.cl) over a stage's source step ds:
// the drag between the phases (with virtual mass) and the basal stress of the solids, solved
// together, so that flowing water can set a deposit moving that friction alone would hold, and a
// held deposit passes the drag it takes from the water on to the bed.
//
// Per unit area, with m_s = rho_s h_s, m_f = rho_f h_f, M = m_s + m_f and w = u_f - u_s: the basal
// impulse P (against the solids' motion over ds) enters as the other forces on the solids do,
// before the drag's relaxation, whose exact factor for the free phases is F (w -> F w:
// exp(-lambda ds) linear, 1 / (1 + lambda |w| ds) quadratic; lambda = rho_s H C inv / (1 + m_vm inv),
// inv = 1/m_s + 1/m_f, virtual mass m_vm = C_vm rho_f h_s; OpenLISEM Hazard P.31-P.35, Pudasaini
// 2012 eq. 11-15). The relaxation keeps m_s u_s + m_f u_f, so with the state (u_s*, w*) of the
// explicit terms the end state is
//   w   = F (w* + P / m_s),
//   u_s = A - c P,    A = (m_s u_s* + m_f (u_s* + w*) - m_f F w*) / M,    c = (m_s + m_f F) / (M m_s),
// A the solid velocity of the drag alone (P = 0). P is parallel to A (the laws are isotropic), so
// u_s + c P(u_s) = A is the basal law's own implicit step q + ds' T(q) = q_A (basal_rheology.cl) with
// the shorter step ds' = c m_s ds: the water the drag couples to the solids shares the basal
// impulse. Limits: no drag (F = 1) gives c = 1/m_s, the law alone; infinite drag (F = 0) c = 1/M,
// the law on the whole mixture. P = (A - u_s) / c, then the fluid. A held deposit (u_s = 0) takes
// P = A / c from the bed: the explicit forces on it are cancelled (a lake over a held layer stays
// at rest), and the water relaxes towards rest with the rate lambda m_s / M (the fixed-bed rate
// without virtual mass; with it, the rate has 1 + m_vm inv in place of 1 + m_vm / m_f). The drag of
// the free phases (P = 0: a frictionless bed) is the relaxation alone, bitwise.
#ifndef TALUS_FLOW_PHASE_EXCHANGE_CL
#define TALUS_FLOW_PHASE_EXCHANGE_CL
#include "flow/basal_rheology.cl"
#include "flow/debris_closures.cl"

/// The drag of the free phases over ds (P = 0 above) for solids (hs, qs) and fluid (hf, qf).
typedef struct {
  real ax, ay;   // solid velocity after the drag alone [m/s]
  real wx, wy;   // relative velocity before the exchange, w* [m/s]
  real F;        // relaxation factor of w
  real ms, mf;   // areal masses [kg/m^2]
} DragStep;

INLINE DragStep drag_step(__constant const DebrisParams* dp, real rho_s, real grain, real hs, real hf, const real* qs,
                          const real* qf, real ds) {
  DragStep d;
  d.ms = rho_s * hs;
  d.mf = dp->rho_f * hf;
  const real usx = qs[0] / hs, usy = qs[1] / hs;
  d.wx = qf[0] / hf - usx;
  d.wy = qf[1] / hf - usy;
  const real H = hs + hf, as = hs / H;
  const real inv = (real)1 / d.ms + (real)1 / d.mf;
  const real mvm = dp->virtual_mass ? (real)0.5 * ((real)1 + (real)2 * as) / (hf / H) * dp->rho_f * hs : (real)0;
  const real C = drag_coefficient(dp, as, rho_s, grain);
  const real lambda = rho_s * H * C * inv / ((real)1 + mvm * inv);
  const real w = sqrt(d.wx * d.wx + d.wy * d.wy);
  d.F = dp->drag_law == DRAG_QUADRATIC ? (real)1 / ((real)1 + lambda * w * ds) : exp(-lambda * ds);
  const real Px = d.ms * usx + d.mf * (usx + d.wx), Py = d.ms * usy + d.mf * (usy + d.wy);
  d.ax = (Px - d.mf * d.wx * d.F) / (d.ms + d.mf);
  d.ay = (Py - d.mf * d.wy * d.F) / (d.ms + d.mf);
  return d;
}

/// The exchange of the header on solids (hs, qs) over a bed moving at (ucx, ucy) (the particles in
/// hybrid mode, else 0) and fluid (hf, qf). `coupled`: both phases present and the drag on; else the
/// basal law acts on the solids alone and the fluid is left as it is. `col` is the basal column of
/// the solids (basal_rheology.cl). Writes the new momenta and the basal impulse (px, py)
/// [kg/(m s)] the bed takes; returns 1 where the basal law holds the solids (factor 0).
INLINE int phase_exchange(__constant const DebrisParams* dp, real rho_s, real grain, BasalColumn col, real hs, real hf,
                          real* qs, real* qf, real ucx, real ucy, real ds, int coupled, real* px, real* py) {
  // (qax, qay) = h_s A, the solids' momentum after the drag alone: the momentum itself where there
  // is no drag, so that the law alone is evaluated on the momenta as they are (q -> u_c h + f (q -
  // u_c h)), with no division and multiplication by h_s to change their round-off.
  real qax = qs[0], qay = qs[1], ds_law = ds, share = (real)1;
  DragStep d;
  if (coupled) {
    d = drag_step(dp, rho_s, grain, hs, hf, qs, qf, ds);
    qax = hs * d.ax;
    qay = hs * d.ay;
    // c m_s = (m_s + m_f F) / M: the part of the basal impulse the solids keep
    share = (d.ms + d.mf * d.F) / (d.ms + d.mf);
    ds_law = share * ds;
  }
  // The basal law on the momentum relative to the bed, with the shared step c m_s ds.
  const real rx = qax - hs * ucx, ry = qay - hs * ucy;
  const real qn = sqrt(rx * rx + ry * ry);
  const real f = qn > (real)0 ? basal_factor(dp, col, qn, ds_law) : (real)0;
  qs[0] = hs * ucx + f * rx;
  qs[1] = hs * ucy + f * ry;
  // P = (A - u_s) / c = m_s (A - u_s) / (c m_s)
  *px = rho_s * (qax - qs[0]) / share;
  *py = rho_s * (qay - qs[1]) / share;
  if (coupled) {
    // w = F (w* + P / m_s); with P = 0 the drag's own end state, bitwise.
    const real wx = *px == (real)0 ? d.wx * d.F : d.F * (d.wx + *px / d.ms);
    const real wy = *py == (real)0 ? d.wy * d.F : d.F * (d.wy + *py / d.ms);
    // the solid velocity u_c + f (A - u_c), = A itself where the bed does not act
    qf[0] = hf * (ucx + f * (d.ax - ucx) + wx);
    qf[1] = hf * (ucy + f * (d.ay - ucy) + wy);
  }
  return f == (real)0;
}

#endif
