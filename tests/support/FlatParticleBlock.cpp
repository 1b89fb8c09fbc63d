#include "support/FlatParticleBlock.hpp"

namespace talus::test {

FlatParticleBlock flatParticleBlock(int n, double dx, int lo, int hi, double rho, double particlesPerCell) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  FlatParticleBlock s;
  s.grid = Grid::make(n, n, dx);
  s.terrain.mask.assign(s.grid.cells(), 1);
  s.terrain.bed.assign(s.grid.cells(), 0.0);
  particles::SeedInput in;
  in.mask = s.terrain.mask;
  in.bed = s.terrain.bed;
  in.thickness.assign(s.grid.cells(), 0.0);
  in.density.assign(s.grid.cells(), rho);
  for (int j = lo; j < hi; ++j)
    for (int i = lo; i < hi; ++i) in.thickness[s.grid.index(i, j)] = 1.0;
  s.seeded = particles::seedParticles(s.grid, in, particles::SeedSpacing{0, particlesPerCell});
  s.material.density = {rho};
  s.material.phi = {30 * kDeg};
  s.material.delta = {0.0};     // frictionless
  s.material.cohesion = {1e9};  // elastic throughout
  return s;
}

double setRadialVelocity(particles::ParticleSolver& solver, const particles::SeededParticles& seeded, double rate,
                         double xc) {
  std::vector<double> vx(seeded.size()), vy(seeded.size());
  double e = 0;
  for (std::size_t q = 0; q < seeded.size(); ++q) {
    vx[q] = rate * (seeded.x[q] - xc), vy[q] = rate * (seeded.y[q] - xc);
    e += 0.5 * seeded.mass[q] * (vx[q] * vx[q] + vy[q] * vy[q]);
  }
  solver.setVelocities(vx, vy);
  return e;
}

}  // namespace talus::test
