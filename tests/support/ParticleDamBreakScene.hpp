// The cohesionless particle dam break of the verification suite (test_particle_dambreak.cpp) and of
// the accuracy-against-run-time benchmark (bench/bench_pareto.cpp): a 1 m reservoir of particles
// behind a dam at x0 = 20 m on a 35 degree plane, 50 x 30 cells of 1 m, bed friction 22 degrees,
// phi = 1 degree, c = 0, density 2000 kg/m^3 (spec §10, Mangeney et al. 2000 with K = 1).
#pragma once
#include "core/Grid.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"

namespace talus::test {

struct ParticleDamBreakScene {
  static constexpr double kDeg = 3.14159265358979323846 / 180.0;
  double theta = 35 * kDeg, delta = 22 * kDeg, H0 = 1.0, x0 = 20.0, dx = 1.0, density = 2000.0;
  int nx = 50, ny = 30;
  Grid grid;
  particles::ParticleTerrain terrain;
  particles::SeededParticles seeded;
  particles::ParticleMaterial material;
};

/// The scene seeded with `particlesPerCell` particles per cell.
ParticleDamBreakScene makeParticleDamBreak(double particlesPerCell);

}  // namespace talus::test
