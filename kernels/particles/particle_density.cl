// Thickness and areal density of the particles (spec §5, P.74-P.75). Each particle stands for a
// horizontal area A and a confined volume V (constant). The thickness is the Shepard-normalised
// kernel estimate
//   H_i = sum_j V_j W_ij / sum_j A_j W_ij   (j over the particles within 2h, i itself included),
// and the areal density rhoA_i = rho_i H_i. For a layer of uniform thickness it is exact, at free
// edges too. The plain sum rhoA_i = sum_j m_j W_ij of the spec is what this normalises: on the R2
// layouts with h = 2 dp it scatters by +-15 % from particle to particle and sags at every edge, which
// made an elastic bar ring 5 % slow and would drive spurious lateral pressure in a block at rest.
//
// The area follows the positions through the number density S_i = sum_j W_ij (i included):
//   A_i = a_i / S_i,   a_i = A_i S_i at the first stress pass (A_i the seeded area), then constant.
// This is the continuity equation dA/dt = A div v with the divergence in SPH's summation form,
// div v_i = -(1/S_i) sum_j (v_i - v_j) . grad_i W_ij = -d(ln S_i)/dt (Monaghan 1992, Annu. Rev.
// Astron. Astrophys. 30, section 2: SPH's continuity equation in this form is the time derivative of
// the summation density), integrated exactly, so an area is a function of where the
// particles are and cannot drift from its neighbours'. The anchor a_i takes away the kernel's
// deficiency at free edges at the start (an edge particle's S is about half an interior one's, and
// its a_i about twice): the seeded layer starts with its seeded areas, as before.
// Until 2026-12-05 each particle integrated dA/dt = A div v with its own corrected strain rate
// (particle_stress, L). That is exact for a resolved, smooth deformation, but each particle's errors
// add up along its path and nothing pulls neighbours' areas back together: on real terrain (avaKot
// at 5 m, docs/terrain_comparison.md) areas of 8e4 m^2 stood beside 0.014 m^2 (columns of 1 mm beside
// 1 km) after 30 s, speeds reached 175 m/s and the run stopped with NaN. The summation form cannot
// do that: a lone particle's area is at most a_i / W(0).
//
// The smoothing length of these sums follows the spacing (issue 18, item 2). With a fixed h a
// particle alone in its support has S_i = W(0, h), so A_i can never exceed a_i / W(0, h) and H_i never
// falls below V_i W(0, h) / a_i: about 11 % of the seeded thickness at 4 particles per cell, whatever
// the distance to the neighbours (a thin front carried its particles 1.6-3.8 times as thick as the
// volume-exact grid did). The sums of particle i are therefore taken with
//   h_i = h sqrt(A_i / A_0), clamped to [h, h_max],
// A_i its area (the last sub-step's), A_0 the mean seeded area: the ratio h_i / sqrt(A_i) stays the
// seeding's h / dp, the classical adaptive smoothing length of SPH (h proportional to the particle
// spacing; Monaghan 2005, Rep. Prog. Phys. 68, section 2.5; with A_i from the last sub-step the
// sequence A = a_i / S_i(h_i(A)) converges to the fixed point h_i^2 S_i(h_i) = (h / dp)^2 a_i of
// Springel & Hernquist 2002, MNRAS 333, eq. 6, in 2D: the kernel holds a fixed weight of
// neighbours). A layer that keeps its seeded spacing or is compressed keeps h_i = h (the forces
// and the strain rate always use h: the smoothing length only sets how far the thickness looks);
// h_max bounds the search (src/particles/ParticleSolver.cpp says how far) and sets the floor of
// a particle left alone, W(0, h_max) = (h / h_max)^2 W(0, h). The first sub-step takes h_i from the
// seeded area, so the anchor a_i is the seeded area times S_i(h_i) and a layer at rest keeps its
// areas exactly.
// particle_stress.cl accumulates these sums in its own neighbour loop (one pass over the neighbours
// for the thickness, the number density and the strain rate; a separate pass for the thickness alone
// cost a fifth of the particle step), in the loop's fixed visiting order; particle_integrate sets the
// area for the next sub-step from this sub-step's S.
#ifndef TALUS_PARTICLE_DENSITY_CL
#define TALUS_PARTICLE_DENSITY_CL
#include "common/real.cl"

/// The sums of H_i over the neighbours j (i itself included): vol += V_j W_ij, area += A_j W_ij.
typedef struct {
  real vol, area;
} ThicknessSums;

INLINE void thickness_add(ThicknessSums* t, real Vj, real Aj, real w) {
  t->vol += Vj * w;
  t->area += Aj * w;
}

/// H_i = sum V_j W_ij / sum A_j W_ij.
INLINE real thickness_of(ThicknessSums t) { return t.vol / t.area; }

/// The smoothing length h_i of the thickness sums of a particle of area A_i (header): h sqrt(A_i / A_0)
/// clamped to [h, h_max]; exactly h for A_i <= A_0.
INLINE real thickness_smoothing_length(real h, real h_max, real A0, real Ai) {
  const real ratio = Ai / A0;
  return ratio > (real)1 ? min(h * sqrt(ratio), h_max) : h;
}

#endif
