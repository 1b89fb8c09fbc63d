// Seeding of the particles of the hybrid mode from the initial rasters (spec §5, OpenLISEM Hazard
// P.88): every cell with structured (confined) material gets round(H_c dx^2 / V_I) particles, at least
// one, placed by the R2 quasi-random sequence, with masses that make each cell's seeded mass exactly
// its initial mass.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Grid.hpp"

namespace talus::particles {

/// Per-cell inputs of the seeding (row-major on the grid; mask 0 cells are never seeded).
struct SeedInput {
  std::vector<uint8_t> mask;
  std::vector<double> bed;        ///< b [m] (the particles' initial base)
  std::vector<double> thickness;  ///< confined-phase thickness H_c [m] (vertical)
  std::vector<double> density;    ///< confined-phase density rho_c [kg/m^3]
};

/// How many particles: a fixed particle volume V_I [m^3] (OpenLISEM Hazard's setting), or, when
/// volume <= 0, the volume that gives `perCell` particles in the thickest cell.
struct SeedSpacing {
  double volume = 0;
  double perCell = 4;
};

/// The seeded particles, structure of arrays in world coordinates of the grid's frame (x = (i + u) dx,
/// y = (j + v) dx for cell (i, j), u, v in [0, 1)), in row-major cell order.
struct SeededParticles {
  std::vector<double> x, y;
  std::vector<double> mass;    ///< [kg]
  std::vector<double> volume;  ///< [m^3], mass / rho_c of the cell
  std::vector<double> area;    ///< horizontal area the particle stands for [m^2]: dx^2 / particles in its cell
  std::vector<uint32_t> cell;  ///< row-major index of the seeding cell
  double particleVolume = 0;   ///< V_I used [m^3]
  std::size_t size() const { return x.size(); }
};

/// The plastic number p (real root of p^3 = p + 1), whose powers 1/p, 1/p^2 give the R2 sequence
/// (Roberts 2018) of low-discrepancy points in the unit square.
constexpr double kPlasticNumber = 1.32471795724474602596;

/// Point n of the R2 sequence with offset s: (frac(s + n / p), frac(s + n / p^2)).
void r2Point(uint64_t n, double s, double& u, double& v);

/// Seeds particles. The R2 index runs on across cells (cell after cell, row-major), so neighbouring
/// cells do not share one pattern. Throws InputError for inconsistent sizes, a non-finite or negative
/// thickness, a non-positive density where there is material, or more than `maxParticles`.
SeededParticles seedParticles(const Grid& grid, const SeedInput& in, const SeedSpacing& spacing,
                              std::size_t maxParticles = std::size_t(1) << 28);

}  // namespace talus::particles
