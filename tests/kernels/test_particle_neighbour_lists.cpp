// The particles' neighbour lists (kernels/particles/particle_stress.cl writes them, particle_forces.cl
// reads them): particle_stress lists the pairs within the support in the neighbour grid's visiting
// order, with each pair's kernel-gradient factor, and particle_forces sums over the list instead of
// walking the grid again. A particle with more neighbours than the list holds walks the grid in
// particle_forces. Both paths must give the same sums to the last bit: the list holds exactly the
// grid walk's pairs, in its order, with the factor the walk computes (sph.cl). Reference: the grid
// walk itself, forced for every particle by a list of 8 entries (every particle of the block has at
// least 28 neighbours), and for the interior particles only by a list of 100 entries (about 113
// neighbours there at 9 particles per cell, h = dx; fewer at the edges and corners).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"
#include "support/TestDevice.hpp"

using namespace talus;
using namespace talus::particles;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// A cohesive 8 m x 8 m block on a 20-degree plane with the velocity field v = U (-(x - xc), y - yc) / 4:
/// it converges along x (the artificial viscosity acts) and is pulled apart along y (tension: the
/// artificial stress acts); stiff enough that its stress matters. 10 steps of 0.02 s.
ParticleState runBlock(compute::Precision precision, unsigned listEntries) {
  const int n = 24;
  const double dx = 1.0, rho = 2000.0, U = 1.0, c = 12.0;
  const Grid grid = Grid::make(n, n, dx);
  ParticleTerrain terrain;
  terrain.mask.assign(grid.cells(), 1);
  terrain.bed.assign(grid.cells(), 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) terrain.bed[grid.index(i, j)] = -std::tan(20 * kDeg) * (i + 0.5) * dx;
  SeedInput in;
  in.mask = terrain.mask;
  in.bed = terrain.bed;
  in.thickness.assign(grid.cells(), 0.0);
  in.density.assign(grid.cells(), rho);
  for (int j = 8; j < 16; ++j)
    for (int i = 8; i < 16; ++i) in.thickness[grid.index(i, j)] = 1.0;
  const SeededParticles seeded = seedParticles(grid, in, SeedSpacing{0, 9});
  ParticleMaterial material;
  material.density = {rho};
  material.phi = {30 * kDeg};
  material.delta = {25 * kDeg};
  material.cohesion = {2e4};
  ParticleSettings ps;
  ps.youngModulus = 1e6;
  ps.neighbourListEntries = listEntries;
  ParticleSolver solver(test::testContext(precision), grid, terrain, ps);
  solver.setParticles(seeded, material);
  std::vector<double> vx(seeded.size()), vy(seeded.size());
  for (std::size_t q = 0; q < seeded.size(); ++q) {
    vx[q] = -U * (seeded.x[q] - c) / 4.0;
    vy[q] = U * (seeded.y[q] - c) / 4.0;
  }
  solver.setVelocities(vx, vy);
  for (int k = 0; k < 10; ++k) solver.step(0.02);
  return solver.state();
}

void expectSameState(const ParticleState& a, const ParticleState& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  std::size_t differ = 0;
  for (std::size_t q = 0; q < a.size(); ++q)
    if (a.x[q] != b.x[q] || a.y[q] != b.y[q] || a.vx[q] != b.vx[q] || a.vy[q] != b.vy[q] ||
        a.cohesion[q] != b.cohesion[q])
      ++differ;
  EXPECT_EQ(differ, 0u) << what << ": particles whose state differs";
}

}  // namespace

TEST(ParticleNeighbourLists, ForcesFromTheListEqualTheGridWalkToTheBit) {
  for (const auto precision : {compute::Precision::Float, compute::Precision::Double}) {
    const ParticleState automatic = runBlock(precision, 0);
    const ParticleState walk = runBlock(precision, 8);
    const ParticleState mixed = runBlock(precision, 100);
    // The block moved, and its bonds yielded where it was pulled apart (where the artificial stress
    // acts): a comparison of states that never changed would prove nothing.
    double moved = 0;
    std::size_t weakened = 0;
    for (std::size_t q = 0; q < automatic.size(); ++q) {
      moved = std::max(moved, std::fabs(automatic.vx[q]));
      weakened += automatic.cohesion[q] < automatic.cohesion0[q];
    }
    std::printf("%s: max |vx| %.3f m/s, %zu of %zu particles weakened\n", compute::precisionName(precision), moved,
                weakened, automatic.size());
    EXPECT_GT(moved, 0.1);
    EXPECT_GT(weakened, 0u);
    expectSameState(automatic, walk, compute::precisionName(precision));
    expectSameState(automatic, mixed, compute::precisionName(precision));
  }
}
