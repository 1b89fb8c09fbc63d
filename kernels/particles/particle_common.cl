// Parameter block and terrain sampling shared by the particle kernels of the hybrid mode (spec §5;
// mirrored by src/particles/ParticleParams.hpp). Particles live in the terrain grid's frame: cell
// (i, j) spans [i dx, (i + 1) dx) x [j dx, (j + 1) dx), its centre at ((i + 1/2) dx, (j + 1/2) dx).
#ifndef TALUS_PARTICLE_COMMON_CL
#define TALUS_PARTICLE_COMMON_CL
#include "common/real.cl"
#include "particles/neighbours.cl"
#include "particles/sph.cl"

#define PARTICLE_EARTH_SAVAGE_HUTTER 0
#define PARTICLE_EARTH_CONSTANT 1

typedef struct {
  int nx, ny;             // terrain grid
  int count;              // particles in the arrays (alive ones first after each sort)
  int earth_pressure;     // PARTICLE_EARTH_*
  int edge_wall;          // 1: the raster edge is a wall, 0: open (particles leave as outflow)
  int nodata_wall;        // the same for the faces to nodata cells
  real dx;                // terrain cell [m]
  real h;                 // SPH smoothing length [m] (support 2h)
  real shear_modulus;     // G [Pa]
  real plane_bulk_modulus;  // in-plane bulk modulus of plane stress, E / (2 (1 - nu)) [Pa]
  real sound_speed;       // c of the artificial viscosity [m/s]
  real alpha_pi, beta_pi; // Monaghan artificial viscosity constants (P.83-P.84)
  real eps_art;           // Gray-Monaghan artificial stress epsilon_0 (P.85-P.86)
  real n_art;             // its exponent n
  real w_spacing;         // W(mean particle spacing, h), the reference of f_ij = W_ij / W(dp)
  real dilatancy;         // psi [rad]
  real eps_crit;          // critical strain epsilon_c of the cohesion degradation (P.26)
  real k_const;           // constant earth-pressure coefficient
  real pore_b;            // basal pore-pressure factor B (P.39)
  real rho_f;             // density of the fluid released from broken bonds [kg/m^3]
  real seed_area;         // A_0, the mean seeded area per particle [m^2] (particle_density.cl)
  real h_max;             // the largest smoothing length of the thickness sums [m] (particle_density.cl)
  real pad1;
} ParticleParams;

/// The gradient of the bed surface the particles move on, z = b(x, y): the bilinear interpolant of
/// the cell-centre elevations (each dual cell, between four cell centres, is one bilinear patch;
/// over the raster's outer half cells the edge patches continue linearly). One continuous surface, so
/// the gravity force -g_n grad b it gives is the gradient of the potential g b along any path.
/// `patch` holds, per patch (indexed by its lower-left centre's cell, rows of nx * ny), the slopes
/// of its two edges from that centre and its twist, e_x = (b10 - b00) / dx, e_y = (b01 - b00) / dx,
/// t = (b11 - b10 - b01 + b00) / dx, computed by the host in double (ParticleSolver): a plane then
/// has the same gradient to the last bit everywhere, and no difference of two large elevations is
/// taken in float. In the patch, grad b = (e_x + t v, e_y + t u) at the fractional position (u, v).
INLINE real2 bed_gradient(__constant const ParticleParams* p, __global const real* patch, real x, real y) {
  const real fx = x / p->dx - (real)0.5, fy = y / p->dx - (real)0.5;
  const int i0 = clamp((int)floor(fx), 0, max(p->nx - 2, 0)), j0 = clamp((int)floor(fy), 0, max(p->ny - 2, 0));
  const int k = j0 * p->nx + i0, n = p->nx * p->ny;
  const real u = fx - (real)i0, v = fy - (real)j0, t = patch[2 * n + k];
  return (real2)(patch[k] + t * v, patch[n + k] + t * u);
}

#ifndef PARTICLE_METRIC
#define PARTICLE_METRIC 1
#endif

/// The gravity normal to the bed of gradient `slope`, g_n = g / (1 + |grad b|^2) = g cos^2(theta)
/// (spec §1); g itself with `Slope Correction=0` (PARTICLE_METRIC 0, the flat-bed equations).
INLINE real bed_normal_gravity(real2 slope) {
#if PARTICLE_METRIC
  return (real)GRAVITY / ((real)1 + slope.x * slope.x + slope.y * slope.y);
#else
  return (real)GRAVITY;
#endif
}

/// Index of the terrain cell holding (x, y), or -1 outside the raster.
INLINE int terrain_cell(__constant const ParticleParams* p, real x, real y) {
  if (!(x >= (real)0 && y >= (real)0)) return -1;
  const real fx = floor(x / p->dx), fy = floor(y / p->dx);
  if (fx >= (real)p->nx || fy >= (real)p->ny) return -1;
  return (int)fy * p->nx + (int)fx;
}

#endif
