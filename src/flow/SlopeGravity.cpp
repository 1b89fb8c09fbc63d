#include "flow/SlopeGravity.hpp"

#include "core/Constants.hpp"

namespace talus::flow {
namespace {

/// d b / d(index) along one axis: centred where both neighbours are inside, one-sided otherwise.
double gradient(const Grid& g, const std::vector<double>& bed, const std::vector<uint8_t>& mask, int i, int j,
                int di, int dj) {
  auto inside = [&](int a, int b) { return a >= 0 && b >= 0 && a < g.nx && b < g.ny && mask[g.index(a, b)]; };
  const bool m = inside(i - di, j - dj), p = inside(i + di, j + dj);
  const double c = bed[g.index(i, j)];
  if (m && p) return 0.5 * (bed[g.index(i + di, j + dj)] - bed[g.index(i - di, j - dj)]) / g.dx;
  if (p) return (bed[g.index(i + di, j + dj)] - c) / g.dx;
  if (m) return (c - bed[g.index(i - di, j - dj)]) / g.dx;
  return 0.0;
}

}  // namespace

SlopeGravity computeSlopeGravity(const Grid& grid, const std::vector<double>& bed, const std::vector<uint8_t>& mask,
                                 const FlowSettings& settings) {
  SlopeGravity s;
  s.gn.assign(grid.cells(), kGravity);
  s.gp.assign(grid.cells(), kGravity);
  if (!settings.slopeCorrection) return s;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      if (!mask[k]) continue;
      const double bx = gradient(grid, bed, mask, i, j, 1, 0), by = gradient(grid, bed, mask, i, j, 0, 1);
      const double cos2 = 1.0 / (1.0 + bx * bx + by * by);
      s.gn[k] = kGravity * cos2;
      s.gp[k] = settings.depthPressure == DepthPressure::Cos4 ? kGravity * cos2 * cos2 : s.gn[k];
    }
  return s;
}

}  // namespace talus::flow
