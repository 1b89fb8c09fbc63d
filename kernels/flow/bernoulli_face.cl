// The state that water moving towards a cell face brings to the face bed z* of the hydrostatic
// reconstruction (riemann.cl, hydrostatic_face) when z* lies above its own face bed: the rise is
// climbed with the energy of the approach, as a resolved rise would be, instead of being cut off at
// the still-water level.
//
// Audusse et al. (2004) re-measure the side's column from z* at rest: h* = e - z*, velocity kept.
// That is exact for a lake at rest but not for moving water: a supercritical sheet of depth h
// meeting a cell-scale rise of height dz passes only (h - dz) u of its discharge h u and is stopped
// altogether by a rise higher than its depth, although its head h + u^2 / (2 g) carries it over;
// the water piles up in front of every step of a coarse DEM (data/kot_dambreak at 5 m inundated
// 6 % less than at 1.25 m, docs/numerics.md). Here a side that arrives supercritically (its speed
// towards the face w > sqrt(g h)) keeps its discharge q = h u and its total head across the rise
// (Bernoulli: steady frictionless flow over a step, the energy-conserving reconstruction of the
// moving-water well-balanced schemes of Noelle, Xing & Shu 2007, J. Comput. Phys. 226, sec. 3):
// the depth h' at z* is the supercritical root of
//   h' + q^2 / (2 g h'^2) = E = h + w^2 / (2 g) - (z* - z),
// between h and h_c = (q^2 / g)^(1/3) (a supercritical sheet gets deeper and slower as it climbs),
// and u' = q / h'. Where E is below the critical energy 3/2 h_c the rise chokes the flow: the face
// takes the critical state h' = 2/3 E, u' = sqrt(g h') (the largest discharge the head can pass),
// and E <= 0 blocks the face. Its head H = e + w^2 / (2 g) also replaces the surface in the cap of
// the face bed (riemann.cl, hydrostatic_face), so a sheet can climb a rise above its own surface.
//
// Water at rest, subcritical water and water moving away from the face are re-measured as Audusse's,
// so a lake at rest is kept bit for bit. The split at Froude 1 is the physics of the two branches:
// supercritical water receives nothing from downstream and arrives with its head, while in
// subcritical water the rise is felt upstream and the hydrostatic coupling is what its linear waves
// need: with the discharge kept at every Froude number (the Bernoulli subcritical root) the face
// passes the full h u of the cell's round-off velocity through the thin layer above a shoreline
// rise while the pressure still acts on h*, the coupling is no longer energy-neutral, and a lake at
// rest over a rough bed grew round-off into 6e-7 m/s in 200 steps. With the kinetic head of water
// moving away from the face as well, a thin fast film was pushed off the rise behind it and the
// stress suite's energy bound failed. At Froude 1 the two treatments differ by O(dz^2) where the
// water passes, and by up to h_c / 2 in the height a choked sheet can climb.
#ifndef TALUS_FLOW_BERNOULLI_FACE_CL
#define TALUS_FLOW_BERNOULLI_FACE_CL
#include "flow/flow_common.cl"
// 1: the water stage; 0: Audusse's reconstruction everywhere (the two-phase stage, debris_stage.cl).
#ifndef SUPERCRITICAL_FACES
#define SUPERCRITICAL_FACES 1
#endif

/// How a side approaches the face: its normal speed towards it when it arrives supercritically
/// (w^2 > g h), else 0, and its head, the free surface plus the kinetic head of that approach,
/// e + w^2 / (2 g). Computed once per side and face (hydrostatic_face) and passed on.
typedef struct {
  real w, head;
} Approach;

/// `towards` is +1 for the minus side, -1 for the plus side.
INLINE Approach side_approach(real h, real e, real un, real towards, real g) {
  Approach a;
  const real v = fmax((real)0, towards * un);
  a.w = SUPERCRITICAL_FACES && v * v > g * h ? v : (real)0;
  a.head = e + a.w * a.w / ((real)2 * g);
  return a;
}

/// The state (h', u') that steady frictionless flow of depth h and normal velocity un reaches where
/// its specific energy is `es` (h' + q^2 / (2 g h'^2) = es, q = h un), on the supercritical branch:
/// es <= 0 blocks it (0, 0); below the critical energy 3/2 h_c, h_c = (q^2 / g)^(1/3), the critical
/// state h' = 2/3 es, u' = sqrt(g h') (the largest discharge the energy passes); otherwise the root
/// between h and h_c. `g` is the gravity of the pressure g h^2 / 2 (the water's g, or the solids'
/// pressure gravity G of solid_bed.cl). Shared by the water's and the solids' faces.
INLINE real2 supercritical_state(real h, real un, real es, real g) {
  if (!(es > (real)0)) return (real2)((real)0, (real)0);
  const real q2 = h * h * un * un;
  const real hc = cbrt(q2 / g);
  if (es <= (real)1.5 * hc) {  // choked: the critical depth that the head supports
    const real hs = es * (real)(2.0 / 3.0);
    return (real2)(hs, copysign(fmin(fabs(un), sqrt(g * hs)), un));
  }
  // Newton from the side's own depth (the supercritical root of the same equation with the energy
  // before the rise): f(x) = x + q^2 / (2 g x^2) - es is convex and decreasing below h_c, so the
  // iterates rise monotonically to the root, which lies between h and h_c.
  real x = h;
  for (int it = 0; it < 24; ++it) {
    const real slope = (real)1 - q2 / (g * x * x * x);
    if (!(slope < (real)0)) break;
    const real next = x - (x + q2 / ((real)2 * g * x * x) - es) / slope;
    const real kept = fmin(next, hc);
    const int done = fabs(kept - x) <= (real)4 * REAL_EPS * x;
    x = kept;
    if (done) break;
  }
  return (real2)(x, h * un / x);
}

/// (h', u') at the face bed zs >= z = e - h for a side (h, e, un) arriving supercritically (a.w > 0,
/// see above); otherwise Audusse's (e - zs, un).
INLINE real2 bernoulli_state(real h, real e, real un, Approach a, real g, real zs) {
  if (!(a.w > (real)0) || !(h > (real)0))
    return (real2)(fmax((real)0, e - zs), un);
  // Specific energy left at z*, from the side's own thickness and the rise zs - (e - h): not from
  // the absolute surface and face bed, whose difference carries the rounding of the elevation
  // (1e-4 m in float at 2000 m), which the root amplifies by 1 / (Fr^2 - 1) near Froude 1. Where
  // z* is the side's own face bed the rise is 0 bit for bit (z* is one of the values it is the
  // min/max of); where it is the side's own head (the cap) nothing is left, exactly.
  const real es = zs == a.head ? (real)0 : h + a.w * a.w / ((real)2 * g) - (zs - (e - h));
  return supercritical_state(h, un, es, g);
}

/// Bed-jump momentum term of a side re-measured from z*, without the factor g: the difference of its
/// normal-momentum flux (pressure and advection) and that of its face state, so that the flux at z*
/// plus this term is the side's own flux (a steady flow over the step stays steady). At rest, and
/// for water moving away from the face (w = 0), Audusse's (h^2 - h'^2) / 2.
INLINE real bernoulli_jump_term(real h, real un, real2 face, real w, real g) {
  real c = (real)0.5 * (h * h - face.x * face.x);
  if (w > (real)0) c += (h * un * un - face.x * face.y * face.y) / g;
  return c;
}

#endif
