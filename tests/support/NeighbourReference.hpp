// Plain C++ references of the particle neighbour search (src/particles/NeighbourGrid), for tests:
// the cell of a position, the cell start/end tables of sorted keys, and a brute-force O(n^2) search.
// Arithmetic is done in `Real` (float or double, the kernels' precision) with the same operations
// as kernels/particles/neighbours.cl, so decisions on the radius agree bitwise with the device.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "particles/NeighbourGrid.hpp"

namespace talus::test {

/// The geometry of a NeighbourGrid as the reference needs it.
struct ReferenceGrid {
  double xMin, yMin, xMax, yMax, cellSize;
  int cellsX, cellsY;
  static ReferenceGrid of(const particles::NeighbourGrid& g);
};

/// Cell coordinate (floor((v - lo) / cellSize), clamped to [0, cells - 1]) in Real arithmetic, and in
/// `nearLine` whether the exact quotient lies within `tol` cells of a cell line (where a device
/// whose division is not correctly rounded may pick the other cell).
int referenceCellCoord(double v, double lo, double cellSize, int cells, bool isDouble, bool* nearLine = nullptr,
                       double tol = 1e-4);

/// Key of (x, y) as the device computes it (kCellKeyOutside outside the box or for NaN); x, y are
/// the values the device holds (already rounded to Real). `ambiguous` is set when the position lies
/// within 1e-4 cells of a cell line.
uint32_t referenceCellKey(const ReferenceGrid& g, double x, double y, bool isDouble, bool* ambiguous = nullptr);

/// cellStart/cellEnd of ascending sorted keys (0, 0 for empty cells; outside keys ignored).
void referenceCellTables(const std::vector<uint32_t>& sortedKeys, std::size_t cells, std::vector<uint32_t>& start,
                         std::vector<uint32_t>& end);

/// For every particle i, the ascending indices j != i with (x_j - x_i)^2 + (y_j - y_i)^2 <= radius^2
/// (in Real arithmetic, as the device computes it), both inside the box [xMin, xMax] x [yMin, yMax]
/// (compared in Real). Particles outside have no neighbours. O(n^2).
std::vector<std::vector<uint32_t>> bruteForceNeighbours(const std::vector<double>& x, const std::vector<double>& y,
                                                        const particles::DomainBox& box, double radius,
                                                        bool isDouble);

/// Rounds v to float when !isDouble (the value a float RealBuffer holds).
inline double toDeviceReal(double v, bool isDouble) {
  return isDouble ? v : static_cast<double>(static_cast<float>(v));
}

}  // namespace talus::test
