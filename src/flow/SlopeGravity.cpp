#include "flow/SlopeGravity.hpp"

#include <algorithm>
#include <cmath>

#include "core/Constants.hpp"

namespace talus::flow {
namespace {

bool insideCell(const Grid& g, const std::vector<uint8_t>& mask, int a, int b) {
  return a >= 0 && b >= 0 && a < g.nx && b < g.ny && mask[g.index(a, b)];
}

double minmod(double a, double b) {
  if (a * b <= 0) return 0.0;
  return std::fabs(a) < std::fabs(b) ? a : b;
}

}  // namespace

double limitedBedSlope(const Grid& g, const std::vector<double>& field, const std::vector<uint8_t>& mask, int i, int j,
                       int di, int dj) {
  const bool m = insideCell(g, mask, i - di, j - dj), p = insideCell(g, mask, i + di, j + dj);
  const double c = field[g.index(i, j)];
  if (m && p) return minmod(c - field[g.index(i - di, j - dj)], field[g.index(i + di, j + dj)] - c) / g.dx;
  if (p) {
    const double d = field[g.index(i + di, j + dj)] - c;
    if (!insideCell(g, mask, i + 2 * di, j + 2 * dj)) return d / g.dx;
    return minmod(d, field[g.index(i + 2 * di, j + 2 * dj)] - field[g.index(i + di, j + dj)]) / g.dx;
  }
  if (m) {
    const double d = c - field[g.index(i - di, j - dj)];
    if (!insideCell(g, mask, i - 2 * di, j - 2 * dj)) return d / g.dx;
    return minmod(d, field[g.index(i - di, j - dj)] - field[g.index(i - 2 * di, j - 2 * dj)]) / g.dx;
  }
  return 0.0;
}

SlopeGravity computeSlopeGravity(const Grid& grid, const std::vector<double>& bed, const std::vector<uint8_t>& mask,
                                 const FlowSettings& settings) {
  const std::size_t n = grid.cells();
  SlopeGravity s;
  s.gn.assign(n, kGravity);
  s.gp.assign(n, kGravity);
  s.slopeSpeed.assign(n, 0.0);
  s.slopeX.assign(n, 0.0);
  s.slopeY.assign(n, 0.0);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      if (!mask[k]) continue;
      s.slopeX[k] = limitedBedSlope(grid, bed, mask, i, j, 1, 0);
      s.slopeY[k] = limitedBedSlope(grid, bed, mask, i, j, 0, 1);
      // The steepest one-sided difference bounds the speed a film gains over one cell.
      double steepest = std::hypot(s.slopeX[k], s.slopeY[k]);
      for (int d = 0; d < 2; ++d)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          const int a = i + (d == 0 ? sgn : 0), b = j + (d == 1 ? sgn : 0);
          if (insideCell(grid, mask, a, b)) steepest = std::max(steepest, std::fabs(bed[grid.index(a, b)] - bed[k]) / grid.dx);
        }
      s.slopeSpeed[k] = std::sqrt(kGravity * steepest * grid.dx);
      if (!settings.slopeCorrection) continue;
      const double bx = s.slopeX[k], by = s.slopeY[k];
      const double cos2 = 1.0 / (1.0 + (bx * bx + by * by));  // grouped: x<->y symmetric bitwise
      s.gn[k] = kGravity * cos2;
      s.gp[k] = settings.depthPressure == DepthPressure::Cos4 ? kGravity * cos2 * cos2 : s.gn[k];
    }
  return s;
}

}  // namespace talus::flow
