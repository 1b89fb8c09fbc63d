#include "support/ParticleDamBreakScene.hpp"

#include <cmath>

namespace talus::test {

ParticleDamBreakScene makeParticleDamBreak(double particlesPerCell) {
  ParticleDamBreakScene s;
  s.grid = Grid::make(s.nx, s.ny, s.dx);
  const Grid& g = s.grid;
  s.terrain.mask.assign(g.cells(), 1);
  s.terrain.bed.assign(g.cells(), 0.0);
  particles::SeedInput in;
  in.mask = s.terrain.mask;
  in.thickness.assign(g.cells(), 0.0);
  in.density.assign(g.cells(), s.density);
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      s.terrain.bed[g.index(i, j)] = -std::tan(s.theta) * (i + 0.5) * s.dx;
      if ((i + 1) * s.dx <= s.x0) in.thickness[g.index(i, j)] = s.H0;
    }
  in.bed = s.terrain.bed;
  s.seeded = particles::seedParticles(g, in, particles::SeedSpacing{0, particlesPerCell});
  s.material.density = {s.density};
  s.material.phi = {1 * ParticleDamBreakScene::kDeg};
  s.material.delta = {s.delta};
  s.material.cohesion = {0.0};
  return s;
}

}  // namespace talus::test
