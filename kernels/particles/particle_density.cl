// Thickness and areal density of the particles (spec §5, P.74-P.75). Each particle stands for a
// horizontal area A (set at seeding to dx^2 / particles per cell, then carried by the continuity
// equation dA/dt = A div v in particle_integrate) and a confined volume V (constant). The thickness
// is the Shepard-normalised kernel estimate
//   H_i = sum_j V_j W_ij / sum_j A_j W_ij   (j over the particles within 2h, i itself included),
// and the areal density rhoA_i = rho_i H_i. For a layer of uniform thickness it is exact, at free
// edges too. The plain sum rhoA_i = sum_j m_j W_ij of the spec is what this normalises: on the R2
// layouts with h = 2 dp it scatters by +-15 % from particle to particle and sags at every edge, which
// made an elastic bar ring 5 % slow and would drive spurious lateral pressure in a block at rest.
// particle_stress.cl accumulates these sums in its own neighbour loop (one pass over the neighbours
// for the thickness and the strain rate; a separate pass for the thickness alone cost a fifth of the
// particle step), in the loop's fixed visiting order.
#ifndef TALUS_PARTICLE_DENSITY_CL
#define TALUS_PARTICLE_DENSITY_CL
#include "common/real.cl"

/// The sums of H_i over the neighbours j (i itself included): vol += V_j W_ij, area += A_j W_ij.
typedef struct {
  real vol, area;
} ThicknessSums;

inline void thickness_add(ThicknessSums* t, real Vj, real Aj, real w) {
  t->vol += Vj * w;
  t->area += Aj * w;
}

/// H_i = sum V_j W_ij / sum A_j W_ij.
inline real thickness_of(ThicknessSums t) { return t.vol / t.area; }

#endif
