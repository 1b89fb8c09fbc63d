#include "view/TerrainSlope.hpp"

#include <cmath>

namespace talus::gui {

namespace {
/// Derivative along one axis at cell c of the values at c - 1, c, c + 1 (NaN: no neighbour).
double derivative(double before, double here, double after, double step) {
  const bool b = std::isfinite(before), a = std::isfinite(after);
  if (b && a) return (after - before) / (2 * step);
  if (a) return (after - here) / step;
  if (b) return (here - before) / step;
  return 0;
}
}  // namespace

double slopeDegrees(const Grid& g, const std::vector<float>& z, int i, int j) {
  auto at = [&](int ii, int jj) {
    return ii < 0 || jj < 0 || ii >= g.nx || jj >= g.ny ? NAN : static_cast<double>(z[g.index(ii, jj)]);
  };
  const double here = at(i, j);
  if (!std::isfinite(here)) return NAN;
  const double p = derivative(at(i - 1, j), here, at(i + 1, j), std::abs(g.geoTransform[1]));
  const double q = derivative(at(i, j - 1), here, at(i, j + 1), std::abs(g.geoTransform[5]));
  return std::atan(std::sqrt(p * p + q * q)) * 180.0 / M_PI;
}

}  // namespace talus::gui
