#include "particles/ParticleSeeding.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/Error.hpp"

namespace talus::particles {

void r2Point(uint64_t n, double s, double& u, double& v) {
  constexpr double a1 = 1.0 / kPlasticNumber, a2 = 1.0 / (kPlasticNumber * kPlasticNumber);
  // n a in double: below n = 2^32 the fraction keeps 20 or more bits (a millionth of a cell).
  const double nd = static_cast<double>(n);
  u = s + nd * a1;
  v = s + nd * a2;
  u -= std::floor(u);
  v -= std::floor(v);
}

namespace {

[[noreturn]] void tooMany(double volume, std::size_t maxParticles) {
  char text[160];
  std::snprintf(text, sizeof text, "particle seeding: a particle volume of %.3g m^3 gives more than %zu particles",
                volume, maxParticles);
  throw InputError(text);
}

}  // namespace

SeededParticles seedParticles(const Grid& grid, const SeedInput& in, const SeedSpacing& spacing,
                              std::size_t maxParticles) {
  const std::size_t n = grid.cells();
  if (in.mask.size() != n || in.bed.size() != n || in.thickness.size() != n || in.density.size() != n)
    throw InputError("particle seeding: the mask, bed, thickness and density maps must have " +
                     std::to_string(n) + " cells");
  const double area = grid.dx * grid.dx;
  double hMax = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!in.mask[k]) continue;
    const double h = in.thickness[k];
    if (!(h >= 0) || !std::isfinite(h))
      throw InputError("particle seeding: structured thickness " + std::to_string(h) + " m at cell " +
                       std::to_string(k % grid.nx) + ", " + std::to_string(k / grid.nx) + " is not a finite value >= 0");
    if (h > 0 && !(in.density[k] > 0 && std::isfinite(in.density[k])))
      throw InputError("particle seeding: density " + std::to_string(in.density[k]) + " kg/m^3 at cell " +
                       std::to_string(k % grid.nx) + ", " + std::to_string(k / grid.nx) + " must be positive");
    hMax = std::max(hMax, h);
  }
  SeededParticles out;
  if (hMax <= 0) return out;
  double vi = spacing.volume;
  if (!(vi > 0)) {
    if (!(spacing.perCell >= 1) || !std::isfinite(spacing.perCell))
      throw InputError("particle seeding: particles per cell must be at least 1 (got " +
                       std::to_string(spacing.perCell) + ")");
    vi = hMax * area / spacing.perCell;
  }
  out.particleVolume = vi;
  // Count first, so an absurd setting fails before allocating.
  std::size_t total = 0;
  std::vector<std::size_t> count(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (!in.mask[k] || !(in.thickness[k] > 0)) continue;
    const double want = std::round(in.thickness[k] * area / vi);
    if (want > static_cast<double>(maxParticles)) tooMany(vi, maxParticles);
    count[k] = std::max<std::size_t>(1, static_cast<std::size_t>(want));
    total += count[k];
    if (total > maxParticles) tooMany(vi, maxParticles);
  }
  out.x.reserve(total);
  out.y.reserve(total);
  out.mass.reserve(total);
  out.volume.reserve(total);
  out.area.reserve(total);
  out.cell.reserve(total);
  uint64_t index = 0;  // runs on across cells
  const double offset = 0.5;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      if (count[k] == 0) continue;
      const double cellVolume = in.thickness[k] * area;
      const double m = in.density[k] * cellVolume / static_cast<double>(count[k]);
      const double v = cellVolume / static_cast<double>(count[k]);
      for (std::size_t p = 0; p < count[k]; ++p, ++index) {
        double u, w;
        r2Point(index, offset, u, w);
        out.x.push_back((i + u) * grid.dx);
        out.y.push_back((j + w) * grid.dx);
        out.mass.push_back(m);
        out.volume.push_back(v);
        out.area.push_back(area / static_cast<double>(count[k]));
        out.cell.push_back(static_cast<uint32_t>(k));
      }
    }
  return out;
}

}  // namespace talus::particles
