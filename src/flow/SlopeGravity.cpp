#include "flow/SlopeGravity.hpp"

#include <algorithm>
#include <cmath>

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
  s.slopeSpeed.assign(grid.cells(), 0.0);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      if (!mask[k]) continue;
      const double bx = gradient(grid, bed, mask, i, j, 1, 0), by = gradient(grid, bed, mask, i, j, 0, 1);
      // The steeper of the centred and the two one-sided differences bounds the local slope.
      double steepest = std::hypot(bx, by);
      for (int d = 0; d < 2; ++d)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          const int a = i + (d == 0 ? sgn : 0), b = j + (d == 1 ? sgn : 0);
          if (a >= 0 && b >= 0 && a < grid.nx && b < grid.ny && mask[grid.index(a, b)])
            steepest = std::max(steepest, std::fabs(bed[grid.index(a, b)] - bed[k]) / grid.dx);
        }
      s.slopeSpeed[k] = std::sqrt(kGravity * steepest * grid.dx);
      if (!settings.slopeCorrection) continue;
      const double cos2 = 1.0 / (1.0 + (bx * bx + by * by));  // grouped: x<->y symmetric bitwise
      s.gn[k] = kGravity * cos2;
      s.gp[k] = settings.depthPressure == DepthPressure::Cos4 ? kGravity * cos2 * cos2 : s.gn[k];
    }
  return s;
}

}  // namespace talus::flow
