// Walls for the particles (hybrid mode, spec §5): where a particle meets a DEM step higher than its own
// column, the raster edge or a nodata cell that is a wall, and the bed surface it stands on there.
//   face_rise:           the jump of the reconstructed bed at a face (kernels/flow/solid_bed.cl, point
//                        2: per axis linear in each cell with the minmod slope `lslope`); a jump up
//                        above the particle's column is a vertical wall to it (particle_integrate.cl).
//   wall_friction:       the Coulomb friction such a wall exerts on the motion along it.
//   walled_bed_gradient: the gradient of the bed surface a particle moves on, with the walls it cannot
//                        cross taken out of it (below).
// The particles' bed is the bilinear interpolant of the cell-centre elevations (particle_common.cl,
// bed_gradient): continuous, so its gravity is the gradient of a potential. Next to a wall that
// surface ramps the wall's height over the half cell in front of it: a particle standing against a
// building or an obstacle stood on a slope of (rise / dx) rising into the wall, which pushed it off
// the wall at rest, and a particle pressed into the wall slid up and down that ramp, a bed the DEM
// does not have (a particle squeezed along it at the foot of the paper flume's obstacle left at 12 m/s,
// docs/scenes.md). The particle's bed is the ground it can reach: in the bilinear patch it stands in,
// each corner cell behind a wall (for this particle) takes the elevation the particle's own cell
// reconstruction gives there, its centre plus its limited slope times the distance (a ghost cell, as
// the reflecting boundary of a finite-volume scheme; on flat ground the ground continues flat to the
// wall, on a ramp the ramp continues). A wall's top is then no part of the particle's bed, and a
// particle at rest against a wall on flat ground feels no force (test
// ParticleWall.BlockAtRestAgainstAStepStaysAtRest). Where no corner is behind a wall the surface is the
// bilinear one to the last bit. Jumps up lower than the column, and jumps down seen from above, stay
// part of the continuous surface: a particle climbs them on the bed-slope force, which pays their
// potential energy, or runs down them. Which corners are behind a wall is judged from the cell the
// particle stands in, so where it crosses into another cell the two views can differ: crossing a
// wall's face from its top it falls by the rest of the step, and elsewhere the views differ by the
// terrain's curvature over a cell. particle_integrate.cl takes a fall as a landing (released and
// lost) and makes a particle pay a lift from its kinetic energy, so the bed never does unpaid work.
#ifndef TALUS_PARTICLE_WALLS_CL
#define TALUS_PARTICLE_WALLS_CL
#include "particles/particle_common.cl"

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

/// Where the bed a particle with column `column` (particle_integrate.cl, its wall column) moves on
/// differs from bed_gradient's bilinear surface at (x, y): the patch holding (x, y), the fractional
/// position (u, v) in it, and the change of each corner's elevation (d[a + 2 b] for the corner
/// (i0 + a, j0 + b)) where the corner lies behind a wall for this particle and takes the ghost
/// elevation of the particle's own cell (file comment). The own cell is the corner holding (x, y);
/// the corner across x (y) is behind a wall when the face to it rises above the column; the diagonal
/// corner when it is reached only across a wall. Corner values are taken relative to the patch's
/// lower-left one, from the host's double-precision patch coefficients (no difference of large
/// elevations is formed for the surface); a ghost is the own corner's value plus the own cell's
/// limited slope times dx. `walls` is 0 where no corner is behind a wall (all d = 0).
typedef struct {
  real u, v;
  real d[4];
  int walls;
} WalledPatch;

INLINE WalledPatch walled_patch(__constant const ParticleParams* p, __global const real* patch,
                                __global const uchar* mask, __global const real* bed, __global const real* lslope,
                                real x, real y, real column) {
  WalledPatch w;
  w.u = w.v = 0;
  w.d[0] = w.d[1] = w.d[2] = w.d[3] = 0;
  w.walls = 0;
  if (p->nx < 2 || p->ny < 2) return w;
  const real fx = x / p->dx - (real)0.5, fy = y / p->dx - (real)0.5;
  const int i0 = clamp((int)floor(fx), 0, p->nx - 2), j0 = clamp((int)floor(fy), 0, p->ny - 2);
  w.u = fx - (real)i0;
  w.v = fy - (real)j0;
  const int ci = clamp((int)floor(x / p->dx), i0, i0 + 1), cj = clamp((int)floor(y / p->dx), j0, j0 + 1);
  const int oi = ci == i0 ? i0 + 1 : i0, oj = cj == j0 ? j0 + 1 : j0;  // the corners across x and y
  const int sx = oi - ci, sy = oj - cj, n = p->nx * p->ny;
  const int own = cj * p->nx + ci, acrossX = cj * p->nx + oi, acrossY = oj * p->nx + ci;
  const int wallX = face_rise(p, mask, bed, lslope, own, oi, cj, 0, sx) > column;
  const int wallY = face_rise(p, mask, bed, lslope, own, ci, oj, 1, sy) > column;
  const int wallD = !wallX && !wallY &&
                    ((mask[acrossX] && face_rise(p, mask, bed, lslope, acrossX, oi, oj, 1, sy) > column) ||
                     (mask[acrossY] && face_rise(p, mask, bed, lslope, acrossY, oi, oj, 0, sx) > column));
  w.walls = wallX || wallY || wallD;
  if (!w.walls) return w;
  const int k = j0 * p->nx + i0;
  const real ex = patch[k] * p->dx, ey = patch[n + k] * p->dx, tw = patch[2 * n + k] * p->dx;
  const real c[4] = {0, ex, ey, ex + ey + tw};
  const int a = ci - i0, b = cj - j0;
  const int kOwn = a + 2 * b, kX = (1 - a) + 2 * b, kY = a + 2 * (1 - b), kD = (1 - a) + 2 * (1 - b);
  const real gx = (real)sx * p->dx * lslope[own], gy = (real)sy * p->dx * lslope[n + own];  // own cell's rise
  const real nX = wallX ? c[kOwn] + gx : c[kX], nY = wallY ? c[kOwn] + gy : c[kY];
  const real nD = wallX && wallY ? c[kOwn] + gx + gy
                  : wallX        ? c[kY] + gx
                  : wallY        ? c[kX] + gy
                                 : c[kX] + c[kY] - c[kOwn];
  w.d[kX] = nX - c[kX];
  w.d[kY] = nY - c[kY];
  w.d[kD] = nD - c[kD];
  return w;
}

/// The gradient of that bed at the point of `w`, from the bilinear surface's gradient `plain` there.
INLINE real2 walled_gradient_of(__constant const ParticleParams* p, real2 plain, WalledPatch w) {
  if (!w.walls) return plain;
  return plain + (real2)(((w.d[1] - w.d[0]) * ((real)1 - w.v) + (w.d[3] - w.d[2]) * w.v) / p->dx,
                         ((w.d[2] - w.d[0]) * ((real)1 - w.u) + (w.d[3] - w.d[1]) * w.u) / p->dx);
}

/// The elevation of that bed at the point of `w`, less the bilinear surface's [m] (0 without walls).
INLINE real walled_offset_of(WalledPatch w) {
  const real u = w.u, v = w.v;
  return w.d[0] * ((real)1 - u) * ((real)1 - v) + w.d[1] * u * ((real)1 - v) + w.d[2] * ((real)1 - u) * v +
         w.d[3] * u * v;
}

/// The gradient at (x, y) of the bed a particle with column `column` moves on (walled_patch): the
/// bilinear surface's, bit for bit, where no corner is behind a wall.
INLINE real2 walled_bed_gradient(__constant const ParticleParams* p, __global const real* patch,
                                 __global const uchar* mask, __global const real* bed, __global const real* lslope,
                                 real x, real y, real column) {
  return walled_gradient_of(p, bed_gradient(p, patch, x, y), walled_patch(p, patch, mask, bed, lslope, x, y, column));
}

/// The elevation at (x, y) of the bed a particle with column `column` moves on, less the bilinear
/// surface's [m] (0 where no corner is behind a wall).
INLINE real walled_bed_offset(__constant const ParticleParams* p, __global const real* patch,
                              __global const uchar* mask, __global const real* bed, __global const real* lslope,
                              real x, real y, real column) {
  return walled_offset_of(walled_patch(p, patch, mask, bed, lslope, x, y, column));
}

#endif
