// The neighbour search of the particle mode (spec §5): particles keyed by their cell of a uniform
// grid over the domain, (key, index) pairs sorted on the device, per-cell start/end tables, and the
// reordering of particle arrays into the sorted order.
#pragma once
#include <CL/cl.h>

#include <cstddef>

#include "compute/Buffer.hpp"
#include "compute/Kernel.hpp"
#include "particles/ParticleSort.hpp"

namespace talus::particles {

/// The rectangle the neighbour grid covers [m]. Particles outside it have no cell and no neighbours.
struct DomainBox {
  double xMin = 0, yMin = 0, xMax = 0, yMax = 0;
};

/// A uniform grid of square cells over a DomainBox, rebuilt from the particle positions by build().
///
/// Cells are numbered row-major from the lower-left corner, key = cy * cellsX() + cx; a particle
/// outside the box gets the key kCellKeyOutside (and sorts last). The cell edge is the search radius
/// enlarged by a few units of rounding (cellSizeFor), so that a pair whose computed distance is within
/// the radius always lies in the same or in adjacent cells, even with float positions: the 3 x 3
/// cells around a particle hold all of its neighbours, exactly as a brute-force search finds them.
///
/// After build(x, y, n), with r the sorted position:
///   sortedKeys()[r]  key of the particle at sorted position r (ascending; ties by original index),
///   order()[r]       its index before sorting (apply with gather() to every particle array),
///   cellStart()[c], cellEnd()[c]  the sorted positions [start, end) of the particles in cell c
///                    (0, 0 for an empty cell),
///   params()         the NeighbourGridParams block for kernels (kernels/particles/neighbours.cl),
///   readInsideCount() the number of particles inside the box: they are sorted positions [0, inside).
/// The tables refer to the sorted order: kernels that iterate neighbours must read particle arrays
/// that were reordered by gather() after the same build().
class NeighbourGrid {
 public:
  /// Key of a particle outside the box.
  static constexpr cl_uint kCellKeyOutside = 0xFFFFFFFFu;

  /// A grid over `box` for neighbours within `radius` [m] (> 0), with room for `capacity`
  /// particles (more are allocated when build() needs them). Throws InputError for a box that is
  /// not finite or has xMax < xMin or yMax < yMin, a radius that is not positive, or more than
  /// 2^31 cells.
  NeighbourGrid(compute::Context& ctx, const DomainBox& box, double radius, std::size_t capacity = 0);

  /// Keys particles 0..n-1 by the cell of (x[i], y[i]), sorts them and rebuilds the cell tables.
  /// Costs O(n log^2 n) for the sort and O(n) for the tables (the previous build's cells are
  /// cleared one by one, not the whole table).
  void build(const compute::RealBuffer& x, const compute::RealBuffer& y, std::size_t n);

  /// dst[r] = src[order()[r]] for the n particles of the last build (src and dst distinct).
  void gather(const compute::RealBuffer& src, compute::RealBuffer& dst);
  void gather(const compute::Buffer<cl_uint>& src, compute::Buffer<cl_uint>& dst);
  void gather(const compute::Buffer<cl_uchar>& src, compute::Buffer<cl_uchar>& dst);
  /// Reorders `field` in place (gather into a scratch buffer, then a device copy back).
  void reorder(compute::RealBuffer& field);

  /// Explicit neighbour lists (kernels/particles/neighbour_lists.cl) for checks and statistics:
  /// for each sorted particle i, count[i] = the number of j != i with |p_j - p_i| <= radius
  /// (computed as dx^2 + dy^2 <= radius^2 in the kernels' precision), list[i * capacity + m] the
  /// first `capacity` of them. xSorted, ySorted: positions reordered by gather(). radius > 0 and
  /// finite; beyond radius() the search visits as many cells as the radius reaches.
  void listNeighbours(const compute::RealBuffer& xSorted, const compute::RealBuffer& ySorted, double radius,
                      std::size_t capacity, compute::Buffer<cl_uint>& count, compute::Buffer<cl_uint>& list);

  /// Reads back the number of particles of the last build inside the box.
  std::size_t readInsideCount() const;

  const compute::Buffer<cl_uint>& sortedKeys() const { return sortedKeys_; }
  const compute::Buffer<cl_uint>& order() const { return order_; }
  const compute::Buffer<cl_uint>& cellStart() const { return cellStart_; }
  const compute::Buffer<cl_uint>& cellEnd() const { return cellEnd_; }
  /// The NeighbourGridParams block (bind as `__constant const NeighbourGridParams*`).
  const compute::RawBuffer& params() const { return params_; }
  /// Particles of the last build.
  std::size_t count() const { return count_; }
  int cellsX() const { return cellsX_; }
  int cellsY() const { return cellsY_; }
  std::size_t cells() const { return static_cast<std::size_t>(cellsX_) * static_cast<std::size_t>(cellsY_); }
  double cellSize() const { return cellSize_; }
  double radius() const { return radius_; }
  const DomainBox& box() const { return box_; }

  /// The cell edge used for `radius` on `box` in the given precision: radius * (1 + 8 u (m + 2)),
  /// u the unit round-off and m the larger cell count of a side. Positions inside the box carry a
  /// relative rounding of about 2u in the computed cell coordinate (x - xMin) / cellSize, that is
  /// at most 4u m cells between two particles; the margin keeps the cell coordinates of two particles
  /// whose computed distance is <= radius less than one cell apart, so their cells are adjacent.
  static double cellSizeFor(double radius, const DomainBox& box, compute::Precision precision);

 private:
  void reserve(std::size_t n);
  void checkGather(const compute::RawBuffer& src, std::size_t srcSize, const compute::RawBuffer& dst,
                   std::size_t dstSize) const;

  compute::Context& ctx_;
  DomainBox box_;
  double radius_ = 0, cellSize_ = 0;
  int cellsX_ = 0, cellsY_ = 0;
  std::size_t capacity_ = 0, count_ = 0;
  bool clearAll_ = true;  ///< the next build clears the whole table (first build, or after growth)
  ParticleSort sort_;
  compute::RawBuffer params_;
  compute::Buffer<cl_uint> keys_, sortedKeys_, order_;
  compute::Buffer<cl_uint> cellStart_, cellEnd_, inside_;
  compute::RealBuffer scratch_;
  compute::Kernel cellKeys_, clearCells_, cellRanges_, gatherReal_, gatherUint_, gatherUchar_, lists_;
};

}  // namespace talus::particles
