// The particle part of a scene (hybrid mode, spec §3 and §5): which share of the initial material is
// structured and becomes particles, seeded and with its material, and what stays on the grid.
#pragma once
#include <cstdint>
#include <vector>

#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSettings.hpp"
#include "particles/ParticleSolver.hpp"

namespace talus::sim {

struct ParticleScene {
  bool enabled = false;                  ///< `Use Material Point Method`
  particles::ParticleSettings settings;
  particles::SeedSpacing spacing;
  particles::ParticleTerrain terrain;
  particles::SeededParticles seeded;
  particles::ParticleMaterial material;  ///< one value per seeded particle
  flow::DebrisSettings fluid;            ///< drag closure and its parameters for the fluid coupling
  double grain = 0.01;                   ///< grain size of the confined phase for the drag [m]
};

/// Per-cell initial maps the split needs (row-major on the DEM's grid; mask 0 = outside).
struct InitialMaterial {
  std::vector<uint8_t> mask;
  std::vector<double> bed;
  std::vector<double> hs, hf;        ///< solid and fluid thickness [m]
  std::vector<double> rhoS;          ///< [kg/m^3]
  double rhoF = 1000;                ///< [kg/m^3]
  std::vector<double> phi, delta;    ///< [rad]
  std::vector<double> cohesion;      ///< [Pa]
  std::vector<double> structured;    ///< f_sc: share of the solids that is structured [0, 1]
  std::vector<double> confined;      ///< f_fc: share of the fluid held in the structured solids [0, 1]
  std::vector<double> grain;         ///< grain size [m] (empty: the scene keeps its default)
};

/// Seeds the particles of the structured part: per cell the confined phase H_c = f_sc h_s + f_fc h_f
/// with density rho_c = (f_sc h_s rho_s + f_fc h_f rho_f) / H_c (OpenLISEM Hazard's confined phase:
/// structured solids with the fluid they hold), and removes it from `hs` and `hf`, which keep the
/// unstructured solids and the free fluid for the grid. Each particle takes the friction angles
/// and cohesion of its seeding cell.
void splitStructured(const Grid& grid, InitialMaterial& m, ParticleScene& p, std::size_t maxParticles);

}  // namespace talus::sim
