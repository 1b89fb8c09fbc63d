#include "core/Grid.hpp"

#include <cmath>

namespace talus {

bool sameGrid(const Grid& a, const Grid& b) {
  if (a.nx != b.nx || a.ny != b.ny) return false;
  const double tol = 1e-9 * std::max(std::fabs(a.dx), 1e-300);
  for (int k = 0; k < 6; ++k) {
    // Origins may be large (projected coordinates): compare relative to the cell size and magnitude.
    const double scale = std::max(1.0, std::fabs(a.geoTransform[k]));
    if (std::fabs(a.geoTransform[k] - b.geoTransform[k]) > tol * scale) return false;
  }
  return true;
}

}  // namespace talus
