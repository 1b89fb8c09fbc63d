#include "sim/ParticleScene.hpp"

#include <algorithm>

namespace talus::sim {

void splitStructured(const Grid& grid, InitialMaterial& m, ParticleScene& p, std::size_t maxParticles) {
  const std::size_t n = grid.cells();
  particles::SeedInput in;
  in.mask = m.mask;
  in.bed = m.bed;
  in.thickness.assign(n, 0.0);
  in.density.assign(n, 0.0);
  std::vector<double> confinedFluid(n, 0.0);  // f_fc h_f per cell [m]
  for (std::size_t k = 0; k < n; ++k) {
    if (!m.mask[k]) continue;
    const double s = m.structured[k] * m.hs[k], f = m.confined[k] * m.hf[k];
    const double H = s + f;
    if (!(H > 0)) continue;
    in.thickness[k] = H;
    in.density[k] = (s * m.rhoS[k] + f * m.rhoF) / H;
    confinedFluid[k] = f;
    m.hs[k] -= s;
    m.hf[k] -= f;
  }
  p.seeded = particles::seedParticles(grid, in, p.spacing, maxParticles);
  const std::size_t np = p.seeded.size();
  std::vector<double> perCell(n, 0.0);
  for (uint32_t k : p.seeded.cell) perCell[k] += 1;
  p.material.density.resize(np);
  p.material.phi.resize(np);
  p.material.delta.resize(np);
  p.material.cohesion.resize(np);
  p.material.structured.resize(np);
  p.material.confined.resize(np);
  p.material.fluidVolume.resize(np);
  const double area = grid.dx * grid.dx;
  for (std::size_t q = 0; q < np; ++q) {
    const std::size_t k = p.seeded.cell[q];
    p.material.density[q] = in.density[k];
    p.material.phi[q] = m.phi[k];
    p.material.delta[q] = m.delta[k];
    p.material.cohesion[q] = m.cohesion[k];
    p.material.structured[q] = m.structured[k];
    p.material.confined[q] = m.confined[k];
    // The particle's share of its cell's confined fluid (its volume is the same share of H_c dx^2).
    p.material.fluidVolume[q] = std::min(confinedFluid[k] * area / perCell[k], p.seeded.volume[q]);
  }
  if (!m.grain.empty() && np > 0) {  // the particles' mean grain size, weighted by their volume
    double sum = 0, weight = 0;
    for (std::size_t q = 0; q < np; ++q) {
      sum += p.seeded.volume[q] * m.grain[p.seeded.cell[q]];
      weight += p.seeded.volume[q];
    }
    p.grain = sum / weight;
  }
  p.terrain.mask = m.mask;
  p.terrain.bed = m.bed;
}

}  // namespace talus::sim
