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
// faster than the paper's 1.3 m/s the block slid sideways off the obstacle, docs/scenes.md.) A lower
// jump, and any ramp however steep, is climbed on the bed-slope force, which pays the potential
// energy. So whether a step is a wall depends on its height against the material, not on the cell
// size (the former rule, a rise steeper than 60 degrees over one cell, made a 1.7 m step a wall at
// 1 m cells and a 17 m cliff a ramp at 10 m cells).
#include "particles/particle_common.cl"
#ifndef PARTICLE_CURVATURE
#define PARTICLE_CURVATURE 0
#endif

/// Rise of the reconstructed bed at the face from cell `here` to its neighbour (a, b) along one axis
/// (d = +1 or -1): the neighbour's face value minus ours. Where the neighbour is not a domain cell
/// of the raster, infinite if that boundary is a wall (`Boundary Type`, `Nodata Boundary Type`:
/// nothing crosses it), else 0 (the particle crosses and leaves as outflow).
INLINE real face_rise(__constant const ParticleParams* p, __global const uchar* mask, __global const real* bed,
                      __global const real* lslope, int here, int a, int b, int axis, int d) {
  if (a < 0 || b < 0 || a >= p->nx || b >= p->ny) return p->edge_wall ? (real)INFINITY : (real)0;
  if (!mask[b * p->nx + a]) return p->nodata_wall ? (real)INFINITY : (real)0;
  const int n = p->nx * p->ny, nb = b * p->nx + a;
  const real hw = (real)0.5 * p->dx * (real)d;
  const real own = bed[here] + hw * lslope[axis * n + here], other = bed[nb] - hw * lslope[axis * n + nb];
  return other - own;
}

/// The velocity along a wall after a contact that stopped the velocity `into` it: Coulomb friction
/// with the impulse the wall gave, |dv_along| <= mu |into|, mu the bed's friction tan(delta) (reduced
/// by buoyancy as the bed's), never reversing the motion along the wall. A particle pressed against a
/// wall by a force m a meets it every sub-step with |into| = dt |a|, so this is the Coulomb force
/// mu m |a| along the wall, the basal friction's law turned onto the wall.
INLINE real wall_friction(real along, real into, real mu) {
  const real slip = fabs(along), cut = mu * fabs(into);
  return slip > cut ? along * ((real)1 - cut / slip) : (real)0;
}

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
                                 __global real* lift_off, __global real* tally, const real dt) {
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
  // The bed is one continuous surface z = b(x, y), the bilinear interpolant of the cell-centre
  // elevations (particle_common.cl, bed_gradient), and gravity, the metric below and the turn
  // all take its exact gradient at the particle, with g_n = g / (1 + |grad b|^2) of that gradient
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
  const real2 slope = bed_gradient(p, patch, xi, yi);
  const real bx = slope.x, by = slope.y, g = bed_normal_gravity(slope);
#if PARTICLE_CURVATURE
  real u0 = vx[i], v0 = vy[i];
  real gload = g;
  {
    const real xb = xi - dt * u0, yb = yi - dt * v0;
    const real2 back = bed_gradient(p, patch, xb, yb);
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
  const real u0 = vx[i], v0 = vy[i], gload = g;  // (Curvature Acceleration off: compiled out)
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
  // The bed's Coulomb coefficient tan(delta) (1 - B gamma), which the walls take as well (below).
  const real mu = tan(delta[i]) * fmax((real)0, (real)1 - p->pore_b * gamma);
  const real stop = dt * mu * gload;
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
      const real column = V[i] / A[i];
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
  {
    const real wx = (real)0.5 * dt * m[i] * (u0 + ux), wy = (real)0.5 * dt * m[i] * (v0 + uy);
    tally[cap + i] = avx * wx + avy * wy;
    tally[2 * cap + i] = asx * wx + asy * wy;
    // What the basal friction and the wall contacts took: the kinetic energy on the bed (the same
    // metric) before them less after them (both scale or cut the velocity, so this is >= 0).
    tally[3 * cap + i] = kinetic - kinetic_on_bed(m[i], ux, uy, bx, by);
  }
  const int cell = terrain_cell(p, xn, yn);
  if (cell < 0 || !mask[cell]) {
    tally[i] = m[i] + p->rho_f * released[i];
    released[i] = 0;
    m[i] = 0;
    x[i] = y[i] = NAN;
    vx[i] = vy[i] = 0;
    return;
  }
  {
    // The potential released, m g (b(x) - b(x_new)), as the gradient at the midpoint times the step:
    // exact for the bilinear patch (b is quadratic along a straight path in it), and no difference
    // of two elevations of a thousand metres in float.
    const real2 mid = bed_gradient(p, patch, (real)0.5 * (xi + xn), (real)0.5 * (yi + yn));
    tally[4 * cap + i] = -m[i] * (real)GRAVITY * (mid.x * (xn - xi) + mid.y * (yn - yi));
  }
  A[i] = share[i] / numberDensity[i];  // the area anchored to the positions (particle_density.cl)
  vx[i] = ux;
  vy[i] = uy;
  x[i] = xn;
  y[i] = yn;
}

/// Per-particle rows for the diagnostics (rows of `stride` entries): |v|, the kinetic energy on the bed
/// (kinetic_on_bed), m, V_f, released.
__kernel void particle_totals(__constant const ParticleParams* p, __global const real* patch, __global const real* x,
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
  const real2 slope = m[i] > (real)0 ? bed_gradient(p, patch, x[i], y[i]) : (real2)(0, 0);
  rows[i] = sqrt(v2);
  rows[stride + i] = kinetic_on_bed(m[i], vx[i], vy[i], slope.x, slope.y);
  rows[2 * stride + i] = m[i];
  rows[3 * stride + i] = Vf[i];
  rows[4 * stride + i] = released[i];
}
