// The bed as the solids of the two-phase grid model feel it (debris_stage.cl): terrain-following
// gravity with the curvature of the bed, the reconstructed bed, and the solid flux through a face
// whose two sides stand on different beds.
//
// 1. Terrain-following gravity. In horizontal coordinates a mass point that follows the bed
//    z = b(x, y) with horizontal velocity u has the vertical velocity w = u.grad b and the vertical
//    acceleration kappa = u.grad(u.grad b), so the bed's normal reaction per unit mass is
//    lambda = (g + kappa) / (1 + |grad b|^2) and its horizontal acceleration -lambda grad b
//    (Denlinger & Iverson 2004, J. Geophys. Res. 109, F01014, eq. 9-10, in horizontal coordinates;
//    the bead on a surface, exact for K = 0). The plane part g_n = g cos^2(theta) acts as the bed
//    force of the reconstructed bed (point 2) and its faces (point 3). The curvature part is taken
//    along the path the material actually takes (debris_stage.cl, `Curvature Acceleration`): over a
//    step the solids that flow into a cell through a face (mass F dt / dx per unit area) arrive moving
//    along their own cell's bed, with vertical velocity u_o.grad b_o, and the bed turns them onto this
//    cell's tangent plane, u_o.grad b_k. That normal impulse, (dt/dx) sum_in F u_o.(grad b_k - grad b_o)
//    along the bed normal (horizontal part -grad b_k / (1 + |grad b_k|^2) per unit of vertical
//    velocity), is the projection of the arriving 3-D velocity onto the tangent plane: kappa to first
//    order on a smooth bed, and never a gain of kinetic energy on a rough one. (The centred Hessian
//    u^T H u of each cell's own velocity, the form before, rectified a real DEM's noise: no normal
//    force on convex spots, a multiple of g on concave ones, and thin layers at 230 m/s on avaKot.)
//    The impulse is signed: material that a convex edge would throw off is held on the bed (its
//    energy kept as vertical kinetic energy). The basal normal stress, and with it the basal friction,
//    carries the turn where it presses (centripetal normal stress at concave bends, Savage & Hutter
//    1991, Acta Mech. 86, eq. 3.9), never below zero. The lateral pressure keeps g_n: the turn is
//    an impulse on the arriving material, not a lasting load of the column (with it, thin margin
//    cells that the flow crosses each step pushed their neighbours at tens of g).
// 2. The reconstructed bed. Per axis the bed is linear in each cell with the minmod slope of its two
//    one-sided differences (next to outside cells the one-sided difference limited by the next one
//    inward, bed_rise), whatever the solids in and around the cell: a plane is exact, and a DEM
//    step, a pit rim or a kink is a jump of the reconstructed bed at a face.
// 2a. The reconstructed thickness (reconstruct2, debris_stage.cl). Material that carries lateral
//    pressure (Pi > 0 at its own thickness, above the dry threshold) is reconstructed as the water
//    is (reconstruct_surface, flow_common.cl): its surface w = b + h with the run's limiter over the
//    minmod bed of point 2, the thickness slope bounded by the maximum principle or by the slope the
//    surface and the bed give when both are limited alike, and the bed flattened where only that
//    keeps the faces positive (a shoreline inside the cell, or the foot of a ramp steeper than the
//    column is deep): the part of the bed's change the cell no longer carries is a jump at its face,
//    which point 3 handles. A layer of uniform thickness still follows its bed (s_w = L(b)), and a
//    level deposit has level face surfaces, so no face pushes it: with K = 1 a level surface is the
//    model's rest state without friction, and it stays at rest over any bed
//    (SolidSteps.LevelDepositOverARoughFloorStaysAtRest). Material without lateral pressure (cohesion
//    above its overburden) has no surface to balance: its thickness is limited on its own, first
//    order at its fronts and next to outside cells, over the bed of point 2, which carries a rigid
//    block and a sheet exactly (Granular.RigidBlockSlidesWithExactAcceleration,
//    CohesionTransport.*). Before (until 2026-12-07) every solid was reconstructed that way. Then a
//    column at the foot of a ramp steeper than it was deep stood at its face as a layer following
//    the ramp: a 50 m column at the foot of a 97 m rise had its face surface 48 m above its level
//    surface, and its pressure drove it up the ramp as a dam break (two-phase soak seed
//    1355826582887882713). Inside a deposit, MC's thickness slope, twice minmod's bed slope, tilted
//    a level surface at a pit's floor (2306745511091219079), and a level deposit over a rough floor
//    slid at up to 2.9 m/s. In hybrid runs (particles) the solids keep the thickness
//    reconstruction: the particles' share of the bed force is the difference from the DEM's own
//    linear bed.
// 3. A face between two reconstructed beds (hydrostatic reconstruction with a subcell bed, after
//    Chen & Noelle 2017, SIAM J. Numer. Anal. 55, eq. 3.4-3.9): the face bed is
//      z* = min(max(z_L, z_R), min(w_L, w_R))          (w = z + h, the solid surface at the face),
//    the thickness that reaches the face from each side h*_s = clamp(w_s - z*, 0, h_s), and the flux is
//    the HLL flux of the two h* states. Between its own face bed z_s and z* each side meets a jump of
//    the bed, on which it takes a force (added to its face momentum flux as a correction):
//     - a rise (z* > z_s): the column below z* meets a step and pushes it with the material's own
//       lateral pressure p(h_s) - p(h*_s) (p = h Pi(h), Pi the earth pressure of debris_stage.cl);
//     - a drop (z* < z_s: the neighbour's surface lies below our face bed, a thin layer on a steep
//       staircase or at a cliff edge): the bed force g_eff h_s (z_s - z*) of the fall the material makes
//       to the neighbour's surface, so a thin front on a slope is driven by its true slope.
//    So with any K a layer with a level surface beside a step is held exactly as by the domain wall.
//    3a. Flow over a rise (solid_face_state). h*_s = w_s - z* is the state of material at rest; moving
//    material that arrives supercritically (faster than its waves, u^2 > G h) climbs a rise with
//    its energy, as over a resolved ramp, and keeps its discharge: its face state is the Bernoulli
//    state of the depth-averaged solids at z* (the granular form of the water's faces,
//    bernoulli_face.cl; Noelle, Xing & Shu 2007, J. Comput. Phys. 226, sec. 3), z* is capped by its
//    head instead of its surface, and its jump force includes the momentum the climb costs, so a
//    steady flow over a step is an exact discrete steady state (test_solid_flow_over_step.cpp).
//    With h*, a sheet thinner than a cell-scale rise of the reconstructed bed passed nothing and
//    one thicker passed only (h - dz) u: on a DEM rough at the scale of the cell fronts were held at
//    every such rise, and the runout and area grew with refinement (docs/terrain_comparison.md).
//    Material at rest, subcritical or moving away keeps h* (a deposit beside a step stays exact).
// 4. A column that meets a wall cannot move into it. The part of each side's column that a rise
//    stops (fraction d_b / h: what its kinetic energy cannot lift over the rise, blocked_fraction;
//    all of it at the domain wall) takes the normal reaction of the wall: after the stage its
//    momentum into the face is removed (an inelastic, unilateral contact, applied implicitly like
//    friction: the speed that decides d_b is the one after the stage; moving away is free). This is the force
//    that holds material pressed against a wall or a step by the slope, and that stops material
//    flowing into an obstacle, which then piles up until it overtops the step.
// 5. The bed only pushes (the curvature term's contact, debris_stage.cl). Over a stage the bed must
//    give the solids the vertical velocity g ds + turn / h (gravity, and the turn of point 1) for them
//    to follow it; at a convex edge fast enough material needs a negative share, a pull. The bed
//    cannot pull: the material lifts off, and the speed at which it moves away from the bed, w >= 0,
//    is carried with it (the fifth passive scalar h_s w). Gravity and the next concave turns use w up
//    before the bed presses again, so the landing's normal impulse is the net turn of the whole
//    flight, not the concave half of it: the contact impulse is max(0, need - w) and w becomes
//    max(0, w - need). Over a bed whose roughness is shorter than the flights, the mean normal
//    impulse is then gravity's (momentum balance normal to the mean bed), and the friction on it the
//    plane's; clamping each cell's load at zero instead (the form before) added the concave halves'
//    friction without the convex halves' relief, a friction that grew with u^2 times the DEM's noise
//    (test_terrain_roughness.cpp). The kinematics stay on the bed (the depth-averaged
//    model has no flight path): only the friction's normal stress knows the flight.
// 6. Static contacts. Between two cells whose solids are at rest (or empty) no mass crosses, and the
//    force the columns exert on each other is statically indeterminate: any value that both
//    columns' basal strength can hold keeps them at rest. The HLL pressure of the two face states is
//    the flowing value; at rest the face transmits it only as far as each side can push back: the
//    pressure of its whole face column, p(h) (p(h*) on the face and, where the face bed rises, p(h) -
//    p(h*) on the step, point 3), plus `hold`, the share of its basal strength one face may use:
//      P = min(P_HLL, p_m(h_m) + hold_m, p_p(h_p) + hold_p),
//    hold = half the law's strength at rest over the cell's area, per unit width (basal_strength,
//    basal_rheology.cl). Half, because a column's strength is shared by its contacts: with each face
//    bounded by half, the two faces that can push a column the same way (one per axis; opposite
//    faces of an axis push against each other) load it with at most 1/sqrt(2) of its strength,
//    and the rest is left for its own loads, its bed slope and the imbalance of its own pressure.
//    So a film or a thin layer beside a pile at rest is pushed at most with part of its own
//    friction (the HLL share of the pile's pressure drove a 0.1 mm film beside a 0.5 m pile to
//    180 m/s in one step, data/kot_debrisflow), the pile carries the rest with its own friction or
//    starts to move, and between static columns whose HLL pressure both can hold nothing changes
//    (the submerged mixture at rest keeps its exact balance). It is a local form of the contact
//    problem over the static region, not its implicit solution: a column whose own loads already
//    take more than half its strength can be pushed past it and start to move. It replaces a rule
//    that switched to min(p_m, p_p) below a thickness ratio of 1/10 (test_solid_steps.cpp,
//    `SolidSteps.GranularStepBelowReposeStaysAtRest`).
// 7. Submerged solids. The solids' momentum has -(1 - gamma) g_n h_s grad b (their weight, less the
//    fluid's share of it) and the buoyancy -gamma h_s (g_n grad b + g_p grad H), the fluid-pressure
//    gradient acting on the solids (spec section 4, after Pudasaini 2012; H = h_s + h_f), which is
//    -gamma h_s (g_p grad eta + (g_n - g_p) grad b) with eta = b + H the fluid's surface. In a lake
//    the weight and the bed part of the buoyancy are two large terms that cancel to the submerged
//    weight, so they are taken together: the bed machinery of points 2-4 acts with the submerged
//    weight g_eff = (1 - gamma_eff) g_n (drops, rises, run-up heights), as the lateral pressure
//    already does, and the buoyancy is the gradient of the fluid's surface, centred, zero in a lake
//    at rest over any bed (debris_stage.cl; a neighbour without fluid is seen as a wall, its top but
//    not above our surface). Before, the buoyancy was -gamma g_p h_s grad H from centred thicknesses
//    while the bed force took the full weight over the faces: at a cliff below water the fall took
//    the full weight over one face and the buoyancy half the jump, and a submerged layer at the edge
//    gained up to 2.4 times the energy the mixture released (two-phase soak seed
//    7226485060292652449). (Taking the buoyancy as the solids' share gamma_eff h_s / h_f of the
//    fluid's discrete pressure force, exact in the hydrostatic limit, was tried: at a dam-break face
//    the Riemann pressure on a thin fluid film over solids is far above h_f g grad eta, and the solids
//    under it were thrown off, soak seed 9962061747903623964.) One term more is the fall itself:
//    material that drops into the other side's fluid from a column with less fluid of its own (a dry
//    bank into a pool) meets the pool's buoyancy on the part of the fall below the pool's surface,
//    g_sub = (gamma_sat - gamma_eff) g_n (gamma_sat = rho_f / rho_s); without it a dry layer at the
//    shore fell into the pool with its full weight, and the pool's water, lifted by what arrived,
//    was paid by nobody.
#ifndef TALUS_FLOW_SOLID_BED_CL
#define TALUS_FLOW_SOLID_BED_CL
#include "flow/riemann.cl"
// 1: supercritical solids climb rises with their energy (point 3a); 0: Audusse's h* everywhere.
#ifndef SOLID_SUPERCRITICAL_FACES
#define SOLID_SUPERCRITICAL_FACES 1
#endif

/// One side of a solid face: face thickness h, face bed z, normal and tangential
/// velocity, the lateral pressure Pi(h') = max(0, a (h' + hf) - c0) for any thickness h' of the side,
/// g_eff = (1 - gamma_eff) g_n of its cell, the weight of its material in its own fluid (for the
/// drop force and the run-up height; point 7), g_sub = (gamma_sat - gamma_eff) g_n, the buoyancy it
/// meets beyond that where it falls into the other side's fluid (point 7), and, where the face is a
/// static contact, the push its column can hold beyond its own pressure (point 6) [m^3/s^2].
typedef struct {
  real h, z, un, ut;
  real a, c0, hf;
  real geff, gsub;
  real hold;
} SolidSide;

INLINE real side_pi(SolidSide s, real h) { return fmax((real)0, s.a * (h + s.hf) - s.c0); }
INLINE real side_pressure(SolidSide s, real h) { return h * side_pi(s, h); }

/// The part of one side's column that a bed jump can stop (point 4): the column below the face bed,
/// d = h - h* of the side's face thickness h, at a rise dz, with g_eff of its cell; at the domain
/// wall the whole column. Which part of it is stopped depends on the speed at which the material
/// meets the step, and that is decided after the stage (blocked_fraction), like friction.
typedef struct {
  real dz, d, h, geff;
  int wall;
} Block;

/// Fraction of the column stopped by the jump of `b` for material whose velocity towards the face
/// after the stage is u_in: what its kinetic energy cannot lift over the rise, d_b = clamp(dz -
/// u_in^2 / (2 g_eff), 0, d) (the run-up height u^2 / 2g of material meeting an obstacle), over h.
/// Material pressed against a step at rest is stopped whole; fast flow over the small rises that
/// the reconstruction leaves in a smooth bend is not (removing a share rise/h of its momentum at
/// every face of a bend cost 95 % of the run-up in the valley of test_terrain_forcing.cpp). The
/// speed is the one after the stage, not before it: a film at rest in front of a rise that the
/// stage fills with fast material is not a wall to it (decided on the film's speed before the
/// stage, it stopped every flow that ran into it until the flow was deeper than the rise).
INLINE real blocked_fraction(Block b, real u_in) {
  if (b.wall) return (real)1;
  if (!(b.d > (real)0) || !(b.h > (real)0)) return (real)0;
  const real u = fmax(u_in, (real)0);
  const real lift = b.geff > (real)0 ? u * u / ((real)2 * b.geff) : b.dz;
  return clamp(b.dz - lift, (real)0, b.d) / b.h;
}

/// Force of a bed rise dz >= 0 at a face on the side s whose column (thickness h, h* above the face
/// bed z*) meets it (points 3, 4): the column meets the rise over d = h - h* and pushes it with the
/// material's own pressure, p(h) - p(h*) (independent of the motion, so a layer at rest beside a
/// step is held exactly, for any K). `blk` gets that part of the column (blocked_fraction).
INLINE real rise_force(SolidSide s, real hstar, real dz, Block* blk) {
  const real d = s.h - hstar;
  blk->dz = dz;
  blk->d = fmax(d, (real)0);
  blk->h = s.h;
  blk->geff = s.geff;
  blk->wall = 0;
  if (!(d > (real)0)) return (real)0;
  return side_pressure(s, s.h) - side_pressure(s, hstar);
}

/// How a solid side approaches a face (the solids' form of bernoulli_face.cl, point 3a): its
/// pressure gravity G = (dp/dh) / h of its lateral pressure p(h) = h Pi(h) (G h is the square of the
/// wave speed; 2a for a cohesionless dry layer, K g_n: the water's g for K = 1), its speed towards
/// the face w where it arrives supercritically (w^2 > G h, else 0), and the height its column
/// reaches: its surface z + h, or for a supercritical arrival the head z + (w^2 / 2 + G h) / g_eff
/// where that lies higher.
typedef struct {
  real w, G, head;
} SolidApproach;

/// `towards` is +1 for the minus side, -1 for the plus side.
INLINE SolidApproach solid_approach(SolidSide s, real towards) {
  SolidApproach a;
  const real pi = side_pi(s, s.h);
  a.G = pi > (real)0 && s.h > (real)0 ? (pi + s.a * s.h) / s.h : (real)0;
  const real v = fmax((real)0, towards * s.un);
  a.w = SOLID_SUPERCRITICAL_FACES && s.h > (real)0 && v * v > a.G * s.h && s.geff > (real)0 ? v : (real)0;
  a.head = s.z + s.h;
  if (a.w > (real)0) a.head = fmax(a.head, s.z + ((real)0.5 * a.w * a.w + a.G * s.h) / s.geff);
  return a;
}

/// Thickness and normal velocity at the face bed zs > s.z of side s arriving supercritically
/// (a.w > 0; solid_approach). It keeps its discharge q = h u and its energy per unit mass across the rise (steady,
/// frictionless flow of the depth-averaged solids over a step: u^2 / 2 + G h + g_eff z constant,
/// the momentum balance u u' + G h' + g_eff z' = 0 integrated with G frozen at the side's value,
/// exact for a cohesionless dry layer): h' is the supercritical root of
///   q^2 / (2 h'^2) + G h' = e = w^2 / 2 + G h - g_eff (zs - z),
/// between h and the critical thickness h_c = (q^2 / G)^(1/3); below the critical energy 3/2 G h_c
/// the rise chokes the flow (critical state h' = 2 e / (3 G), u' = sqrt(G h')), e <= 0 stops it, and
/// without lateral pressure (G = 0) h' = q / sqrt(2 e).
INLINE real2 solid_bernoulli_state(SolidSide s, SolidApproach a, real zs) {
  // The energy left at zs, from the side's own thickness and the rise (exactly the approach's where
  // zs is the side's own face bed, exactly 0 where it is the side's head), as in bernoulli_state.
  const real e = zs == a.head ? (real)0 : (real)0.5 * a.w * a.w + a.G * s.h - s.geff * (zs - s.z);
  if (!(e > (real)0)) return (real2)((real)0, (real)0);
  if (!(a.G > (real)0)) return (real2)(s.h * a.w / sqrt((real)2 * e), copysign(sqrt((real)2 * e), s.un));
  // The water's relation with g = G: h' + q^2 / (2 G h'^2) = e / G (bernoulli_face.cl).
  return supercritical_state(s.h, s.un, e / a.G, a.G);
}

/// The face state of side s at zs: its own where zs is its face bed; the Bernoulli state of a
/// supercritical arrival (solid_bernoulli_state) where that passes at least the discharge of the
/// part of its column above the rise, h* u; otherwise h* = h - (zs - z) with the velocity kept, and
/// a->w is set to 0 (the side is then treated as at rest by solid_jump). The part of a column that
/// stands above a rise passes it whatever its energy: a slow arrival whose energy cannot lift the
/// whole column (choked, or e <= 0; for material without lateral pressure, K = 0, every arrival
/// counts as supercritical) still passes that part, as a resolved ramp it could not climb would let
/// the top of a deep column flow on while its base stops.
INLINE real2 solid_face_state(SolidSide s, SolidApproach* a, real zs) {
  if (zs == s.z) return (real2)(s.h, s.un);  // no rise: the side's own state, bit for bit
  const real2 hyd = (real2)(clamp(s.h - (zs - s.z), (real)0, s.h), s.un);
  if (!(a->w > (real)0)) return hyd;
  const real2 ber = solid_bernoulli_state(s, *a, zs);
  if (ber.x * fabs(ber.y) >= hyd.x * fabs(hyd.y)) return ber;
  a->w = (real)0;
  return hyd;
}

/// Lateral pressure Pi' of the face state h' of side s: the law's, Pi(h'), except for a
/// supercritical arrival (a.w > 0), whose Bernoulli state solid_bernoulli_state built with the
/// pressure gravity G frozen at the side's value: its pressure is the one that momentum balance
/// integrates to, p' = p(h) + G (h'^2 - h^2) / 2, and Pi' = p' / h' (the law's own value for a
/// cohesionless dry layer, p = a h^2). With the law's value instead, material without lateral
/// pressure at its own thickness (cohesion above its overburden: G = 0) that met a rise of the
/// height of its kinetic head got a thick, slow face state (h' = q / sqrt(2 e), e -> 0) that the law
/// did press: the face saw a wave speed its cell never had, and its HLL flux drained several times
/// the cell's content in one step (two-phase soak seeds 4445931888577538981, 5853659436162393912,
/// 1481104073426978450: solids created where the emptied cell was clipped at zero; in float a rise
/// of one rounding unit of the bed was enough).
INLINE real face_pi(SolidSide s, SolidApproach a, real h) {
  if (!(a.w > (real)0) || h == s.h) return side_pi(s, h);
  if (!(h > (real)0)) return (real)0;
  return fmax((real)0, side_pressure(s, s.h) + (real)0.5 * a.G * (h * h - s.h * s.h)) / h;
}

/// Bed-jump force of side s at a rise to zs, with its face state `st` (solid_face_state): the
/// material's pressure on the step, p(h) - p(h') (p(h') = h' face_pi), and for a supercritical
/// arrival the momentum its flow loses climbing it, h u^2 - h' u'^2, so that the face flux of the
/// state at zs plus this term is the side's own flux (a steady flow over the step stays steady).
/// `blk` as in rise_force; of a supercritical arrival nothing is blocked where it passes (or
/// chokes), its whole column where its energy cannot lift it over the rise.
INLINE real solid_jump(SolidSide s, SolidApproach a, real2 st, real zs, Block* blk) {
  if (!(a.w > (real)0)) return rise_force(s, st.x, zs - s.z, blk);
  rise_force(s, st.x > (real)0 ? s.h : (real)0, zs - s.z, blk);
  return side_pressure(s, s.h) - st.x * face_pi(s, a, st.x) + s.h * s.un * s.un - st.x * st.y * st.y;
}

/// Force (as a face-flux correction, < 0 along the fall) of the drop from side s's face bed to z* <
/// s.z (point 3), with the buoyancy of point 7: the fall in its own weight g_eff, less g_sub on the
/// part of it below the other side's mixture surface.
INLINE real drop_force(SolidSide s, SolidSide other, real zs) {
  const real fall = s.z - zs;
  const real under = clamp(other.z + other.h + other.hf - zs, (real)0, fall);
  return -s.h * (s.geff * fall - s.gsub * under);
}

typedef struct {
  real fh, fqn, fqt, p;  // mass, normal momentum (no pressure), tangential momentum, pressure flux
  real corr_m, corr_p;   // bed-jump corrections of the minus / plus side (added to their face flux)
  real wall_m, wall_p;   // the part of each side's correction that the neighbour's bed takes (rises)
  Block blk_m, blk_p;    // the part of each side's column that its bed jump can stop (point 4)
} SolidFace;

/// The solid face between side m (minus) and side p (plus); conventions of face_between
/// (riemann.cl) for outside sides (ghosts). `locked`: both cells static or empty, so no mass crosses
/// and the sides touch at rest (point 6).
INLINE SolidFace solid_face(int m_in, SolidSide m, int p_in, SolidSide p, int kind, int locked) {
  SolidFace f;
  f.fh = f.fqn = f.fqt = f.p = f.corr_m = f.corr_p = f.wall_m = f.wall_p = (real)0;
  const Block none = {0, 0, 0, 0, 0};
  f.blk_m = f.blk_p = none;
  if (!m_in && !p_in) return f;
  int wall = 0;
  if (!m_in) {
    wall = kind == BOUNDARY_WALL || p.un > (real)0;
    m = p;
    m.un = wall ? -p.un : p.un;
  } else if (!p_in) {
    wall = kind == BOUNDARY_WALL || m.un < (real)0;
    p = m;
    p.un = wall ? -m.un : m.un;
  }
  // z* capped by the height each column reaches (its surface, or its head where it arrives
  // supercritically, point 3a); a side whose face bed is z* keeps its thickness bitwise. Only the
  // lower side can meet a rise: the higher one's head lies above its own face bed, which is then
  // z*, so its approach is not needed (nor evaluated: `still`, a side at rest, gives the same z*
  // and the same face, bit for bit).
  const real zm = m.z, zp = p.z;
  const SolidApproach still = {0, 0, INFINITY};
  const SolidApproach am = zm < zp ? solid_approach(m, (real)1) : still;
  const SolidApproach ap = zp < zm ? solid_approach(p, (real)-1) : still;
  const real zs = fmin(fmax(zm, zp), fmin(am.head, ap.head));
  SolidApproach am_f = am, ap_f = ap;
  const real2 sm = zs >= zm ? solid_face_state(m, &am_f, zs) : (real2)(m.h, m.un);
  const real2 sp = zs >= zp ? solid_face_state(p, &ap_f, zs) : (real2)(p.h, p.un);
  const real hm = sm.x, hp = sp.x;
  if (hm > (real)0 || hp > (real)0) {
    const real pim = face_pi(m, am_f, hm), pip = face_pi(p, ap_f, hp);
    const real2 s = wave_speeds(hm, sm.y, sqrt((real)2 * pim), hp, sp.y, sqrt((real)2 * pip));
    const FaceFlux r = hll_core(hm, sm.y, m.ut, hm * pim, hp, sp.y, p.ut, hp * pip, s);
    const int closed = wall || locked;
    f.fh = closed ? (real)0 : r.fh;
    f.fqn = r.fqn;
    f.fqt = closed ? (real)0 : r.fqt;
    // A static contact transmits no more than either column can hold (point 6).
    f.p = locked ? fmin(r.p, fmin(side_pressure(m, m.h) + m.hold, side_pressure(p, p.h) + p.hold)) : r.p;
  }
  // Bed jumps of each side (point 3): a drop is the fall, a rise takes the material's pressure
  // (and, arriving supercritically, the momentum the climb costs).
  if (zs >= zm) {
    f.corr_m = f.wall_m = solid_jump(m, am_f, sm, zs, &f.blk_m);
  } else {
    f.corr_m = drop_force(m, p, zs);
  }
  if (zs >= zp) {
    f.corr_p = f.wall_p = solid_jump(p, ap_f, sp, zs, &f.blk_p);
  } else {
    f.corr_p = drop_force(p, m, zs);
  }
  if (wall) f.blk_m.wall = f.blk_p.wall = 1;
  return f;
}

/// The wall reaction of point 4 on the normal momentum q of a cell of thickness h (both after the
/// stage) whose minus face can block `lo` and whose plus face `hi`: the momentum into a face, less
/// the share of the column that face stops at the cell's new speed.
INLINE real wall_reaction(real q, real h, Block lo, Block hi) {
  const real u = h > (real)0 ? fabs(q) / h : (real)0;
  if (q > (real)0) return q * ((real)1 - blocked_fraction(hi, u));
  if (q < (real)0) return q * ((real)1 - blocked_fraction(lo, u));
  return q;
}

#endif
