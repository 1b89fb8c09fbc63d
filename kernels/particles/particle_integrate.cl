// Terrain forces and the symplectic update of the particles (spec §5): bed-slope gravity -g_n grad b
// (horizontal projection, as the grid model, with the curvature of the particle's path in g_n as there),
// the internal forces taken with the bed's metric (below), basal Coulomb friction tan(delta) (1 - B gamma) g_n
// applied implicitly (it stops a particle but never reverses it; gamma = rho_f / rho_c where the
// grid's free fluid stands at the particle (`fluid_depth`, from G2P), 0 for dry particles: buoyancy
// and pore pressure reduce the effective normal stress, P.39), then
// v <- v + dt a, x <- x + dt v (symplectic Euler), and the particle's area A <- a_i / S_i from the
// number density of this sub-step's positions (particle_density.cl). A particle that crosses an open boundary (the raster
// edge with `Boundary Type=open`, a nodata cell with `Nodata Boundary Type=open`; walls hold it, see
// Walls below) is removed: its mass goes to row 0 of `tally` (tallied by the host as outflow), its
// position becomes NaN (it sorts behind every live particle at the next neighbour build) and its
// mass zero.
// Work of the artificial terms: particle_forces leaves the viscous and the artificial-stress
// accelerations in rows 1-2 and 3-4 of `tally` (rows of p->count entries); their work over the
// sub-step, dt m a . (v_start + v_end) / 2, replaces them in rows 1 and 2 (row 0 is the outflow
// mass). With the midpoint velocity the work is exact for the update: on a flat frictionless bed the
// kinetic energy changes by exactly the work of the internal forces. On a slope it is the work in the
// bed's metric (the kinetic energy there is m v^T G v / 2, and the applied acceleration G^-1 a has
// the power m a . v). The artificial viscosity's work is never positive for a pair; its sum over the
// particles and sub-steps is the energy it dissipated (ParticleSolver's diagnostics). Row 3 gets the
// kinetic energy the basal friction and the wall contacts took in the sub-step (measured in the same
// metric before and after them), so that KE + D_visc - W_art + W_friction is the potential energy
// released; row 4 gets that, m g (b(x) - b(x_new)) on the bed surface (particle_common.cl), for the
// particles that stay (test ParticleRealTerrain.*).
// Water release (OpenLISEM Hazard P.27-P.28): the confined fluid follows the intact bonds,
// V_f = V_f0 c / c0; what the particle loses, dV = V_f - V_f0 c / c0 >= 0 (c never rises), leaves
// its volume and mass (rho_f dV) and is added to `released`, which the host moves to the grid's free
// fluid (with the particle's momentum) at the end of the grid step. A removed particle takes its
// pending released fluid out with it (counted in its outflow mass).
// Walls: the particles see the DEM reconstructed as the grid's solids do (kernels/flow/solid_bed.cl,
// point 2: per axis linear in each cell with the minmod slope, `lslope`), in which a resolved ramp is
// continuous and a DEM step, a flume wall or an obstacle is a jump at a face. A jump up that rises
// above the particle's own column (its thickness V/A) is a vertical face to it: a particle about to
// cross it keeps its position along that axis and loses its velocity into it (an inelastic,
// unilateral contact; the grid's columns meet the same walls), and the wall's Coulomb friction
// (wall_friction: the bed's friction angle delta, with the wall's impulse as the normal force) takes
// velocity along it. (Until 2026-12-07 the walls were frictionless: in the paper's flume struck
// faster than the paper's 1.3 m/s the block slid sideways off the obstacle, docs/scenes.md.) A lower jump, and any ramp however
// steep, is climbed on the bed-slope force, which pays the potential energy. So whether a step is a
// wall depends on its height against the material, not on the cell size (the former rule, a rise
// steeper than 60 degrees over one cell, made a 1.7 m step a wall at 1 m cells and a 17 m cliff a ramp
// at 10 m cells). The bed the particle moves on is the same one: a wall's top is no part of it
// (particle_walls.cl, walled_bed_gradient: in front of a wall the ground continues to the wall
// instead of ramping up it), so a particle at rest against a wall feels no force and one pressed into
// it does not ride up and down a ramp the DEM does not have. The thickness a step is measured
// against is the particle's wall column (below), which also decides that bed.
#include "particles/particle_common.cl"
#include "particles/particle_walls.cl"
#ifndef PARTICLE_CURVATURE
#define PARTICLE_CURVATURE 0
#endif

/// Kinetic energy of a particle of mass m moving with horizontal velocity (u, v) on a bed of gradient
/// (bx, by): m (|v|^2 + (v . grad b)^2) / 2 (the metric G of the internal forces, below; with
/// `Slope Correction=0` the flat bed's m |v|^2 / 2).
INLINE real kinetic_on_bed(real m, real u, real v, real bx, real by) {
#if PARTICLE_METRIC
  const real w = u * bx + v * by;
#else
  const real w = 0;
#endif
  return (real)0.5 * m * (u * u + v * v + w * w);
}

__kernel void particle_integrate(__constant const ParticleParams* p, __global const uchar* mask,
                                 __global const real* bed, __global const real* patch, __global const real* lslope,
                                 __global real* x, __global real* y, __global real* vx, __global real* vy,
                                 __global real* m, __global const real* delta, __global const real* ax,
                                 __global const real* ay, __global real* A, __global const real* share,
                                 __global const real* numberDensity,
                                 __global real* V, __global real* rho, __global real* Vf,
                                 __global const real* Vf0, __global const real* coh, __global const real* coh0,
                                 __global real* released, __global const real* fluid_depth,
                                 __global real* lift_off, __global real* wall_column, __global real* tally,
                                 const real dt) {
  const int i = get_global_id(0);
  if (i >= p->count) return;
  const int cap = p->count;
  const real avx = tally[cap + i], avy = tally[2 * cap + i], asx = tally[3 * cap + i], asy = tally[4 * cap + i];
  tally[i] = 0;  // outflow mass
  tally[cap + i] = 0;
  tally[2 * cap + i] = 0;
  tally[3 * cap + i] = 0;
  tally[4 * cap + i] = 0;
  if (!(m[i] > (real)0)) return;
  if (coh0[i] > (real)0 && Vf[i] > (real)0) {
    const real dV = fmax((real)0, Vf[i] - Vf0[i] * coh[i] / coh0[i]);
    if (dV > (real)0) {
      Vf[i] -= dV;
      V[i] -= dV;
      m[i] -= p->rho_f * dV;
      rho[i] = m[i] / V[i];
      released[i] += dV;
    }
  }
  const real xi = x[i], yi = y[i];
  // The wall column: the thickness against which a step is a wall to this particle, both for its
  // contacts (below) and for the bed it moves on (particle_walls.cl: the corners behind a wall are
  // replaced by its own cell's ghost elevation). It follows the particle's own column V / A, but that
  // changes the bed under a particle standing in front of a step whose height the column crosses:
  // the ramp up the step comes back (a thickening column) or goes (a thinning one). A bed that drops
  // under the particle releases m g |lift|, lost as in a landing (tallied as released and
  // dissipated); a bed that rises lifts it, and the lift is paid from its kinetic energy on the bed.
  // A particle that cannot pay keeps its former wall column, and with it the wall, until it can or
  // until it leaves the wall's patch. So the bed does no work it was not paid for, and no energy is
  // made by a column that swells and shrinks in front of a step (test ParticleRealTerrain.*).
  real vxi = vx[i], vyi = vy[i], column = wall_column[i], liftReleased = 0, liftLost = 0;
  WalledPatch start;  // the bed under the particle at the start, for its wall column
  {
    const real2 plain = bed_gradient(p, patch, xi, yi);
    const real own = V[i] / A[i];
    const WalledPatch was = walled_patch(p, patch, mask, bed, lslope, xi, yi, column);
    const WalledPatch now = walled_patch(p, patch, mask, bed, lslope, xi, yi, own);
    start = was;
    if (!was.walls && !now.walls) {
      column = own;
      start = now;
    } else {
      const real lift = walled_offset_of(now) - walled_offset_of(was);
      const real2 s0 = walled_gradient_of(p, plain, was), s1 = walled_gradient_of(p, plain, now);
      const real k0 = kinetic_on_bed(m[i], vxi, vyi, s0.x, s0.y), k1 = kinetic_on_bed(m[i], vxi, vyi, s1.x, s1.y);
      const real target = k0 - m[i] * (real)GRAVITY * fmax(lift, (real)0);
      if (target >= (real)0) {
        const real scale = k1 > (real)0 ? sqrt(target / k1) : (real)0;
        vxi *= scale;
        vyi *= scale;
        column = own;
        start = now;
        liftReleased = -m[i] * (real)GRAVITY * lift;
        liftLost = fmax(liftReleased, (real)0);
      }
    }
    wall_column[i] = column;
  }
  // The bed is the surface z = b(x, y) of particle_walls.cl: the bilinear interpolant of the
  // cell-centre elevations (particle_common.cl, bed_gradient), with the walls (for the wall column)
  // taken out of it, and gravity, the metric below and the turn all take its exact gradient at the
  // particle, with g_n = g / (1 + |grad b|^2) of that gradient
  // (cos^2 of its slope). The force -g_n grad b is then the Lagrangian one of a particle held on that
  // surface, and its work along any path is the drop of g b: a block sliding over a noisy DEM gains
  // no energy. (Until 2026-12-05 the force sampled a bilinear blend of the cells' centred differences
  // and g_n of the cells' limited slopes; that field is not the gradient of any surface, and on a
  // 40 deg plane with 0.1 / 0.5 m of noise a frictionless block's centre of mass ran 3 / 12 % faster
  // than the free fall from its own drop: test ParticleBlockOnANoisyPlaneStaysBelowFreeFall.)
  // Terrain-following gravity (kernels/flow/solid_bed.cl, point 1; Denlinger & Iverson 2004): the
  // particle moved along the tangent plane where it was, x - dt v, and the bed turns it onto the
  // tangent plane where it now is: its 3-D velocity (v, v . grad b(x - dt v)) is rotated into the new
  // plane with its speed kept, as the grid's arriving solids are (debris_stage.cl, arrival_turn; the
  // centred Hessian v^T H v sampled at the particle turned a rough DEM's noise into speed). The
  // turn's normal force, v . (grad b(x) - grad b(x - dt v)) / dt, adds to the weight in the basal
  // friction (centripetal normal stress at concave bends); where it would pull, the particle lifts
  // off and lands later (its lift-off speed carried in lift_off, as the grid's solids carry theirs).
  const real2 slope = walled_bed_gradient(p, patch, mask, bed, lslope, xi, yi, column);
  const real bx = slope.x, by = slope.y, g = bed_normal_gravity(slope);
#if PARTICLE_CURVATURE
  real u0 = vxi, v0 = vyi;
  real gload = g;
  {
    const real xb = xi - dt * u0, yb = yi - dt * v0;
    const real2 back = walled_bed_gradient(p, patch, mask, bed, lslope, xb, yb, column);
    const real bxb = back.x, byb = back.y;
    const real d = u0 * (bx - bxb) + v0 * (by - byb);
    const real c2 = g / (real)GRAVITY;
    const real up = u0 - d * c2 * bx, vp = v0 - d * c2 * by;
    const real wo = u0 * bxb + v0 * byb, wp = up * bx + vp * by;
    const real m2 = (u0 * u0 + v0 * v0) + wo * wo, p2 = (up * up + vp * vp) + wp * wp;
    const real scale = p2 > (real)0 ? sqrt(m2 / p2) : (real)1;
    u0 = scale * up;
    v0 = scale * vp;
    if (dt > (real)0) {
      // The bed only pushes (solid_bed.cl, point 5): of the vertical velocity g dt + d that following
      // it asks, the particle's lift-off speed w is used up first; a pull lifts it off (w grows).
      const real need = (real)GRAVITY * dt + d, w = lift_off[i];
      gload = g * fmax((real)0, need - w) / (dt * (real)GRAVITY);
      lift_off[i] = fmax((real)0, w - need);
    }
  }
#else
  const real u0 = vxi, v0 = vyi, gload = g;  // (Curvature Acceleration off: compiled out)
#endif
  // The internal forces (stress, artificial terms of particle_forces) are horizontal; on the bed a
  // particle's inertia is its 3-D kinetic energy m (|v|^2 + (v . grad b)^2) / 2, whose metric is
  // G = I + grad b grad b^T, so its horizontal acceleration is G^-1 a = a - grad b (grad b . a) /
  // (1 + |grad b|^2) (Lagrange's equations of a particle constrained to z = b(x, y); the gravity term
  // g_n grad b is the same projection of g grad b). Along the fall line this is cos^2(theta) a,
  // across it a. Without it the bonds exchanged horizontal energy while the turn keeps the 3-D speed:
  // on a noisy bed a bonded block gained speed (1.86 of free fall at A = 0.5 m).
  // (`Slope Correction=0`, the classical flat-bed equations: compiled out, as g_n = g there.)
  const real aix = ax[i], aiy = ay[i];
#if PARTICLE_METRIC
  const real ka = (aix * bx + aiy * by) / ((real)1 + bx * bx + by * by);
#else
  const real ka = 0;
#endif
  real ux = u0 + dt * (aix - ka * bx - g * bx), uy = v0 + dt * (aiy - ka * by - g * by);
  const real speed = sqrt(ux * ux + uy * uy);
  const real kinetic = kinetic_on_bed(m[i], ux, uy, bx, by);  // before friction and walls
  const real gamma = fluid_depth[i] > (real)1e-6 ? p->rho_f / rho[i] : (real)0;
  const real stop = dt * tan(delta[i]) * gload * fmax((real)0, (real)1 - p->pore_b * gamma);
  if (speed <= stop) {
    ux = uy = 0;
  } else {
    const real f = (real)1 - stop / speed;
    ux *= f;
    uy *= f;
  }
  if (!(isfinite(ux) && isfinite(uy))) {
    // A non-finite velocity is an instability, not outflow: it stays on the particle, where the
    // run's health check finds it and stops the run with that diagnosis (it used to be taken for
    // a particle leaving the domain and tallied as outflow).
    vx[i] = ux;
    vy[i] = uy;
    return;
  }
  real xn = xi + dt * ux, yn = yi + dt * uy;
  {
    // Walls, axis by axis (a corner is two walls): a jump of the reconstructed bed above the
    // particle's column.
    const int here = terrain_cell(p, xi, yi);
    if (here >= 0) {
      const int ci = here % p->nx, cj = here / p->nx;
      const real mu = tan(delta[i]) * fmax((real)0, (real)1 - p->pore_b * gamma);  // as the bed's
      const int ni = (int)floor(xn / p->dx), nj = (int)floor(yn / p->dx);
      if (ni != ci && face_rise(p, mask, bed, lslope, here, ni, cj, 0, ni > ci ? 1 : -1) > column) {
        xn = xi;
        uy = wall_friction(uy, ux, mu);
        ux = 0;
      }
      const int ai = (int)floor(xn / p->dx);
      const int moved = ai != ci && ai >= 0 && ai < p->nx && mask[cj * p->nx + ai];
      if (nj != cj && (face_rise(p, mask, bed, lslope, here, ci, nj, 1, nj > cj ? 1 : -1) > column ||
                       (moved && face_rise(p, mask, bed, lslope, cj * p->nx + ai, ai, nj, 1, nj > cj ? 1 : -1) > column))) {
        yn = yi;
        ux = wall_friction(ux, uy, mu);
        uy = 0;
      }
    }
  }
  // The bed a particle moves on is continuous inside the part of a patch seen from one cell, but the
  // corners behind a wall are seen from the cell the particle stands in (particle_walls.cl): where it
  // crosses into another cell the two views can differ. Across a face that is a wall from the lower
  // side, seen from the upper side, the particle falls by the step (it lands: the fall is released
  // and lost, as a landing's vertical speed); elsewhere the views differ by the terrain's curvature
  // over a cell and may lift it a little, which it pays from its kinetic energy (or, unable to, stays
  // where it was, as at a wall). `rise` is the change of the bed's elevation over the sub-step that
  // the force, the gradient at the midpoint, did not see: exact zero (to round-off) inside one view.
  const int cell = terrain_cell(p, xn, yn);
  const int stays = cell >= 0 && mask[cell];
  real potential = 0, landing = 0, paid = 0;
  if (stays) {
    const real mx = (real)0.5 * (xi + xn), my = (real)0.5 * (yi + yn);
    const real2 midPlain = bed_gradient(p, patch, mx, my);
    const real2 mid = walled_gradient_of(p, midPlain, walled_patch(p, patch, mask, bed, lslope, mx, my, column));
    const real offStart = walled_offset_of(start);
    const real offEnd = walled_bed_offset(p, patch, mask, bed, lslope, xn, yn, column);
    const real dX = xn - xi, dY = yn - yi;
    const real rise = (offEnd - offStart) - ((mid.x - midPlain.x) * dX + (mid.y - midPlain.y) * dY);
    const real weight = m[i] * (real)GRAVITY;
    if (rise > (real)0) {
      const real k = kinetic_on_bed(m[i], ux, uy, bx, by);
      if (k >= weight * rise) {
        const real f = sqrt((k - weight * rise) / k);
        ux *= f;
        uy *= f;
        paid = weight * rise;
        potential = -weight * (midPlain.x * dX + midPlain.y * dY + offEnd - offStart);
      } else {
        xn = xi;  // (its kinetic energy goes to the contact tally below)
        yn = yi;
        ux = uy = 0;
      }
    } else {
      landing = -weight * rise;
      // The potential released, m g (b(x) - b(x_new)): the bilinear part as the gradient at the
      // midpoint times the step (exact inside a bilinear patch: b is quadratic along a straight path
      // in it; no difference of two elevations of a thousand metres in float), the walls' part as the
      // difference of the offsets.
      potential = -weight * (midPlain.x * dX + midPlain.y * dY + offEnd - offStart);
    }
  }
  {
    const real wx = (real)0.5 * dt * m[i] * (u0 + ux), wy = (real)0.5 * dt * m[i] * (v0 + uy);
    tally[cap + i] = avx * wx + avy * wy;
    tally[2 * cap + i] = asx * wx + asy * wy;
    // What the basal friction, the wall contacts and the landings took: the kinetic energy on the bed
    // (the same metric) before them less after them (all scale or cut the velocity, so this is >= 0),
    // less what was paid for a lift (it went into potential energy), plus the falls.
    tally[3 * cap + i] = kinetic - kinetic_on_bed(m[i], ux, uy, bx, by) - paid + liftLost + landing;
  }
  if (!stays) {
    tally[i] = m[i] + p->rho_f * released[i];
    released[i] = 0;
    m[i] = 0;
    x[i] = y[i] = NAN;
    vx[i] = vy[i] = 0;
    return;
  }
  tally[4 * cap + i] = potential + liftReleased;
  A[i] = share[i] / numberDensity[i];  // the area anchored to the positions (particle_density.cl)
  vx[i] = ux;
  vy[i] = uy;
  x[i] = xn;
  y[i] = yn;
}

/// Per-particle rows for the diagnostics (rows of `stride` entries): |v|, the kinetic energy on the bed
/// (kinetic_on_bed), m, V_f, released.
__kernel void particle_totals(__constant const ParticleParams* p, __global const uchar* mask,
                              __global const real* bed, __global const real* patch, __global const real* lslope,
                              __global const real* wall_column, __global const real* x,
                              __global const real* y, __global const real* vx, __global const real* vy,
                              __global const real* m, __global const real* Vf, __global const real* released,
                              __global real* rows, const int stride) {
  const int i = get_global_id(0);
  if (i >= p->count) return;
  const real v2 = vx[i] * vx[i] + vy[i] * vy[i];
  // A particle removed at an open boundary (mass 0, position NaN until the next neighbour build
  // drops it) has no bed slope: 0 x the slope at a NaN position made the kinetic energy NaN, and the
  // run stopped as "unstable" whenever a particle left in a step's last sub-step (setup 1 B of the
  // regime study at h = 1.5 dx, 37 s). A live particle with a non-finite velocity still gives NaN.
  const real2 slope =
      m[i] > (real)0 ? walled_bed_gradient(p, patch, mask, bed, lslope, x[i], y[i], wall_column[i]) : (real2)(0, 0);
  rows[i] = sqrt(v2);
  rows[stride + i] = kinetic_on_bed(m[i], vx[i], vy[i], slope.x, slope.y);
  rows[2 * stride + i] = m[i];
  rows[3 * stride + i] = Vf[i];
  rows[4 * stride + i] = released[i];
}
