// Thickness and areal density of the particles (spec §5, P.74-P.75). Each particle stands for a
// horizontal area A (set at seeding to dx^2 / particles per cell, then carried by the continuity
// equation dA/dt = A div v in particle_integrate) and a confined volume V (constant). The thickness
// is the Shepard-normalised kernel estimate
//   H_i = sum_j V_j W_ij / sum_j A_j W_ij   (j over the particles within 2h, i itself included),
// and the areal density rhoA_i = rho_i H_i. For a layer of uniform thickness it is exact, at free
// edges too. The plain sum rhoA_i = sum_j m_j W_ij of the spec is what this normalises: on the R2
// layouts with h = 2 dp it scatters by +-15 % from particle to particle and sags at every edge, which
// made an elastic bar ring 5 % slow and would drive spurious lateral pressure in a block at rest.
#include "particles/particle_common.cl"

__kernel void particle_density(__constant const ParticleParams* p, __constant const NeighbourGridParams* ng,
                               __global const uint* cell_start, __global const uint* cell_end,
                               __global const real* x, __global const real* y, __global const real* V,
                               __global const real* A, __global const real* rho, __global real* rhoA,
                               __global real* H) {
  const int i = get_global_id(0);
  if (i >= p->count) return;
  const real xi = x[i], yi = y[i], h = p->h, r2max = (real)4 * h * h;
  real vol = 0, area = 0;
  FOR_EACH_NEARBY_PARTICLE(ng, cell_start, cell_end, xi, yi, j) {
    const real dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
    if (r2 >= r2max) continue;
    const real w = sph_w(sqrt(r2), h);
    vol += V[j] * w;
    area += A[j] * w;
  }
  H[i] = vol / area;
  rhoA[i] = rho[i] * H[i];
}
