// Particles that lose their neighbours (kernels/particles/particle_stress.cl, point 1: the damped
// inverse of the kernel-gradient correction), double:
//  - ParticleFragments.APairFlyingApartThinsNoMoreThanItsSeparationGrows: two particles moving
//    apart are a segment of material being stretched; the continuity equation then lets each
//    particle's area grow at most as the segment's length, A/A0 <= r/r0, and a lone particle keeps
//    its area and thickness once the other has left its support;
//  - ParticleFragments.ANeighbourThatStandsForALargeAreaKeepsTheGradientFiniteInFloat: the damped
//    inverse stays finite in float for a nearly rank-1 correction matrix of large size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/Constants.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"
#include "support/TestDevice.hpp"

using namespace talus;
using namespace talus::particles;

// Two particles 0.6 m apart (h = dx = 1 m, support 2 m) on a flat, frictionless bed, cohesionless
// (c = 0, so the tension cut leaves them stress free) and without lateral pressure (K = 0), moving
// apart at 1 m/s each along x. They interact through the velocity gradient alone until their
// distance passes 2h. Each particle's strain rate is that of the segment between them, at most
// (relative speed) / distance, so its area grows at most as the distance (dA/dt = A div v): the
// thickness H = V/A may fall to H0 r0/r, not below (tolerance 1 %: the first-order area update over
// sub-steps of 0.2 h / (c + |v|)); after the pair has separated it must stay constant. Until
// 2026-12 a particle whose correction matrix was singular took the uncorrected gradient, which
// scales with the neighbour's area: the two areas then fed each other's growth (1e34 m^2 within
// seconds in the paper's fragmenting setup 1 C, where float overflowed).
TEST(ParticleFragments, APairFlyingApartThinsNoMoreThanItsSeparationGrows) {
  const Grid grid = Grid::make(20, 10, 1.0);
  ParticleTerrain terrain;
  terrain.mask.assign(grid.cells(), 1);
  terrain.bed.assign(grid.cells(), 0.0);
  const double rho = 2000.0, A0 = 0.25, V0 = 0.5, r0 = 0.6;
  SeededParticles seeded;
  seeded.x = {10.0 - r0 / 2, 10.0 + r0 / 2};
  seeded.y = {5.0, 5.0};
  seeded.area = {A0, A0};
  seeded.volume = {V0, V0};
  seeded.mass = {rho * V0, rho * V0};
  seeded.cell = {static_cast<uint32_t>(grid.index(9, 5)), static_cast<uint32_t>(grid.index(10, 5))};
  seeded.particleVolume = V0;
  ParticleMaterial material;
  material.density = {rho};
  material.phi = {30 * 3.14159265358979323846 / 180.0};
  material.delta = {0.0};
  material.cohesion = {0.0};
  ParticleSettings ps;
  ps.youngModulus = 1e5;
  ps.earthPressure = ParticleEarthPressure::Constant;
  ps.kConst = 0.0;
  ParticleSolver solver(test::testContext(compute::Precision::Double), grid, terrain, ps);
  solver.setParticles(seeded, material);
  solver.setVelocities({-1.0, 1.0}, {0.0, 0.0});
  solver.computeDerivedFields();
  const double H0 = solver.state().H[0];
  double worst = 0, Hseparated = -1;
  for (int k = 0; k < 30; ++k) {
    solver.step(0.1);
    const ParticleState s = solver.state();
    ASSERT_EQ(s.size(), 2u);
    const double r = std::fabs(s.x[1] - s.x[0]);
    for (int q = 0; q < 2; ++q) {
      ASSERT_TRUE(std::isfinite(s.H[q]) && s.H[q] > 0) << "step " << k;
      worst = std::max(worst, (H0 * r0 / r) / s.H[q]);  // <= 1: thinned no more than the segment stretched
    }
    if (r > 2.0 * solver.smoothingLength()) {
      if (Hseparated < 0) Hseparated = s.H[0];
      EXPECT_EQ(s.H[0], Hseparated) << "a lone particle keeps its thickness (step " << k << ")";
    }
  }
  const ParticleState s = solver.state();
  std::printf("pair flying apart: H %.6g -> %.6g m (%.6g once apart), distance %.3g m; worst (H0 r0/r)/H %.4f\n", H0,
              s.H[0], Hseparated, std::fabs(s.x[1] - s.x[0]), worst);
  EXPECT_GT(Hseparated, 0.0) << "the pair must separate within the run";
  EXPECT_LE(worst, 1.01);
}

// The damped inverse in float for a nearly rank-1 M of large size: a particle beside one neighbour
// that stands for a large area (a stretched particle: 2e5 m^2; particles reached 8e4 m^2 on the avaKot
// path) has M ~ 750 along their line and ~0 across it. Written as det(M^2 + d^2 I) expanded, the
// float arithmetic cancels terms of 750^4 and leaves that determinant <= 0: C becomes infinite and the
// particle's stress NaN. The kernel forms it from det M and the squares of M's entries instead.
// Asserted: after one step (float) both particles' thickness and velocity are finite; the former
// formula gives NaN velocities here.
TEST(ParticleFragments, ANeighbourThatStandsForALargeAreaKeepsTheGradientFiniteInFloat) {
  const Grid grid = Grid::make(40, 40, 5.0);
  ParticleTerrain terrain;
  terrain.mask.assign(grid.cells(), 1);
  terrain.bed.assign(grid.cells(), 0.0);
  SeededParticles seeded;
  seeded.x = {100.0, 108.0};
  seeded.y = {100.0, 100.5};
  seeded.area = {2e5, 5.0};
  seeded.volume = {16.0, 16.0};
  seeded.mass = {3.2e4, 3.2e4};
  seeded.cell = {static_cast<uint32_t>(grid.index(20, 20)), static_cast<uint32_t>(grid.index(21, 20))};
  seeded.particleVolume = 16.0;
  ParticleMaterial material;
  material.density = {2000.0};
  material.phi = {25 * 3.14159265358979323846 / 180.0};
  material.delta = {0.0};
  material.cohesion = {0.0};
  ParticleSettings ps;
  ParticleSolver solver(test::testContext(compute::Precision::Float), grid, terrain, ps);
  solver.setParticles(seeded, material);
  solver.setVelocities({-2.0, 2.0}, {0.0, 0.0});
  solver.step(0.05);
  const ParticleState s = solver.state();
  ASSERT_EQ(s.size(), 2u);
  for (std::size_t q = 0; q < 2; ++q) {
    std::printf("particle %zu: H %.6g m, v (%.6g, %.6g) m/s\n", q, s.H[q], s.vx[q], s.vy[q]);
    EXPECT_TRUE(std::isfinite(s.H[q]) && std::isfinite(s.vx[q]) && std::isfinite(s.vy[q])) << "particle " << q;
  }
}
