// Host references of the neighbour search (see NeighbourReference.hpp).
#include "support/NeighbourReference.hpp"

#include <algorithm>
#include <cmath>

namespace talus::test {
namespace {

template <class Real>
bool insideBox(const particles::DomainBox& b, Real x, Real y) {
  return x >= static_cast<Real>(b.xMin) && x <= static_cast<Real>(b.xMax) && y >= static_cast<Real>(b.yMin) &&
         y <= static_cast<Real>(b.yMax);
}

template <class Real>
int cellCoord(double v, double lo, double cellSize, int cells) {
  const Real q = (static_cast<Real>(v) - static_cast<Real>(lo)) / static_cast<Real>(cellSize);
  const Real clamped = std::min(std::floor(q), static_cast<Real>(cells - 1));
  return std::min(static_cast<int>(clamped), cells - 1);
}

template <class Real>
std::vector<std::vector<uint32_t>> bruteForce(const std::vector<double>& xd, const std::vector<double>& yd,
                                              const particles::DomainBox& box, double radius) {
  const std::size_t n = xd.size();
  std::vector<Real> x(n), y(n);
  std::vector<char> in(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = static_cast<Real>(xd[i]);
    y[i] = static_cast<Real>(yd[i]);
    in[i] = insideBox<Real>(box, x[i], y[i]);
  }
  const Real r = static_cast<Real>(radius);
  const Real r2 = r * r;
  std::vector<std::vector<uint32_t>> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!in[i]) continue;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || !in[j]) continue;
      // Same operations as the kernel: differences, squares, one sum, then the comparison.
      const Real dx = x[j] - x[i], dy = y[j] - y[i];
      const Real dx2 = dx * dx, dy2 = dy * dy;
      const Real d2 = dx2 + dy2;
      if (d2 <= r2) out[i].push_back(static_cast<uint32_t>(j));
    }
  }
  return out;
}

}  // namespace

ReferenceGrid ReferenceGrid::of(const particles::NeighbourGrid& g) {
  return {g.box().xMin, g.box().yMin, g.box().xMax, g.box().yMax, g.cellSize(), g.cellsX(), g.cellsY()};
}

int referenceCellCoord(double v, double lo, double cellSize, int cells, bool isDouble, bool* nearLine, double tol) {
  if (nearLine) {
    const double q = (v - lo) / cellSize;
    *nearLine = std::fabs(q - std::round(q)) < tol;
  }
  return isDouble ? cellCoord<double>(v, lo, cellSize, cells) : cellCoord<float>(v, lo, cellSize, cells);
}

uint32_t referenceCellKey(const ReferenceGrid& g, double x, double y, bool isDouble, bool* ambiguous) {
  const particles::DomainBox box{g.xMin, g.yMin, g.xMax, g.yMax};
  const bool in = isDouble ? insideBox<double>(box, x, y)
                           : insideBox<float>(box, static_cast<float>(x), static_cast<float>(y));
  if (ambiguous) *ambiguous = false;
  if (!in) return particles::NeighbourGrid::kCellKeyOutside;
  bool nearX = false, nearY = false;
  const int cx = referenceCellCoord(x, g.xMin, g.cellSize, g.cellsX, isDouble, &nearX);
  const int cy = referenceCellCoord(y, g.yMin, g.cellSize, g.cellsY, isDouble, &nearY);
  if (ambiguous) *ambiguous = nearX || nearY;
  return static_cast<uint32_t>(cy) * static_cast<uint32_t>(g.cellsX) + static_cast<uint32_t>(cx);
}

void referenceCellTables(const std::vector<uint32_t>& sortedKeys, std::size_t cells, std::vector<uint32_t>& start,
                         std::vector<uint32_t>& end) {
  start.assign(cells, 0);
  end.assign(cells, 0);
  for (std::size_t r = 0; r < sortedKeys.size(); ++r) {
    const uint32_t k = sortedKeys[r];
    if (k == particles::NeighbourGrid::kCellKeyOutside) continue;
    if (r == 0 || sortedKeys[r - 1] != k) start[k] = static_cast<uint32_t>(r);
    end[k] = static_cast<uint32_t>(r + 1);
  }
}

std::vector<std::vector<uint32_t>> bruteForceNeighbours(const std::vector<double>& x, const std::vector<double>& y,
                                                        const particles::DomainBox& box, double radius,
                                                        bool isDouble) {
  return isDouble ? bruteForce<double>(x, y, box, radius) : bruteForce<float>(x, y, box, radius);
}

}  // namespace talus::test
