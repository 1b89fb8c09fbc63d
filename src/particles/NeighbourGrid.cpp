#include "particles/LaunchSize.hpp"
#include "particles/NeighbourGrid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "compute/ClError.hpp"
#include "compute/Context.hpp"
#include "compute/Program.hpp"
#include "core/Error.hpp"
#include "particles/NeighbourGridParams.hpp"

namespace talus::particles {
namespace {

constexpr const char* kTableFile = "particles/cell_table.cl";
constexpr const char* kReorderFile = "particles/reorder.cl";
constexpr const char* kListFile = "particles/neighbour_lists.cl";
constexpr double kMaxCells = 2147483648.0;  // 2^31: keys stay below kCellKeyOutside

template <class Real>
void writeParams(compute::RawBuffer& buf, const DomainBox& box, double cellSize, int cellsX, int cellsY) {
  NeighbourGridParamsT<Real> p{};
  p.cellsX = cellsX;
  p.cellsY = cellsY;
  p.xMin = static_cast<Real>(box.xMin);
  p.yMin = static_cast<Real>(box.yMin);
  p.xMax = static_cast<Real>(box.xMax);
  p.yMax = static_cast<Real>(box.yMax);
  p.cellSize = static_cast<Real>(cellSize);
  buf.writeBytes(&p, sizeof p);
}

int cellCount(double extent, double cellSize) {
  return std::max(1, static_cast<int>(std::ceil(extent / cellSize)));
}

}  // namespace

double NeighbourGrid::cellSizeFor(double radius, const DomainBox& box, compute::Precision precision) {
  const double eps = precision == compute::Precision::Double
                         ? std::numeric_limits<double>::epsilon()
                         : static_cast<double>(std::numeric_limits<float>::epsilon());
  const double u = eps / 2;  // unit round-off of `real`
  const double m =
      std::max({1.0, std::ceil((box.xMax - box.xMin) / radius), std::ceil((box.yMax - box.yMin) / radius)});
  return radius * (1.0 + 8.0 * u * (m + 2.0));
}

NeighbourGrid::NeighbourGrid(compute::Context& ctx, const DomainBox& box, double radius, std::size_t capacity)
    : ctx_(ctx), box_(box), radius_(radius), sort_(ctx) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw InputError("neighbour grid: the search radius must be positive, got " + std::to_string(radius));
  const bool finite = std::isfinite(box.xMin) && std::isfinite(box.xMax) && std::isfinite(box.yMin) &&
                      std::isfinite(box.yMax);
  if (!finite || box.xMax < box.xMin || box.yMax < box.yMin)
    throw InputError("neighbour grid: the domain box must be finite with xMax >= xMin and yMax >= yMin");
  cellSize_ = cellSizeFor(radius, box, ctx.precision());
  const double cx = std::ceil((box.xMax - box.xMin) / cellSize_), cy = std::ceil((box.yMax - box.yMin) / cellSize_);
  if (std::max(cx, 1.0) * std::max(cy, 1.0) >= kMaxCells)
    throw InputError("neighbour grid: " + std::to_string(cx) + " x " + std::to_string(cy) +
                     " cells exceed the limit of 2^31 (radius too small for the domain)");
  cellsX_ = cellCount(box.xMax - box.xMin, cellSize_);
  cellsY_ = cellCount(box.yMax - box.yMin, cellSize_);

  params_ = compute::RawBuffer(ctx, sizeof(NeighbourGridParamsT<double>), "neighbour grid parameters");
  if (ctx.precision() == compute::Precision::Double)
    writeParams<double>(params_, box, cellSize_, cellsX_, cellsY_);
  else
    writeParams<float>(params_, box, cellSize_, cellsX_, cellsY_);
  cellStart_ = compute::Buffer<cl_uint>(ctx, cells(), "cell start");
  cellEnd_ = compute::Buffer<cl_uint>(ctx, cells(), "cell end");
  inside_ = compute::Buffer<cl_uint>(ctx, 1, "particles inside");
  inside_.fill(0);
  reserve(capacity);

  compute::Program& table = ctx.program(kTableFile);
  cellKeys_ = compute::Kernel(table, "particles_cell_keys");
  clearCells_ = compute::Kernel(table, "particles_clear_cells");
  cellRanges_ = compute::Kernel(table, "particles_cell_ranges");
  compute::Program& reorder = ctx.program(kReorderFile);
  gatherReal_ = compute::Kernel(reorder, "particles_gather_real");
  gatherUint_ = compute::Kernel(reorder, "particles_gather_uint");
  gatherUchar_ = compute::Kernel(reorder, "particles_gather_uchar");
}

void NeighbourGrid::reserve(std::size_t n) {
  if (n <= capacity_ && !keys_.raw().empty()) return;
  // Grow by half again, so a slowly growing particle count reallocates rarely.
  const std::size_t size = std::max(n, capacity_ + capacity_ / 2);
  keys_ = compute::Buffer<cl_uint>(ctx_, size, "cell keys");
  sortedKeys_ = compute::Buffer<cl_uint>(ctx_, size, "sorted cell keys");
  order_ = compute::Buffer<cl_uint>(ctx_, size, "sort order");
  scratch_ = compute::RealBuffer(ctx_, size, "reorder scratch");
  capacity_ = size;
  clearAll_ = true;  // the previous sorted keys are gone
}

void NeighbourGrid::build(const compute::RealBuffer& x, const compute::RealBuffer& y, std::size_t n) {
  if (x.size() < n || y.size() < n)
    throw ComputeError("neighbour grid: position buffers hold fewer than " + std::to_string(n) + " particles");
  if (n >= kMaxCells) throw ComputeError("neighbour grid: more than 2^31 particles");
  const cl_uint un = static_cast<cl_uint>(n);
  // Clear the cells the previous build filled, while its sorted keys still exist.
  if (!clearAll_ && count_ > 0) {
    clearCells_.bind(sortedKeys_, static_cast<cl_uint>(count_), cellStart_, cellEnd_);
    clearCells_.launch({count_}, kParticleGroup);
  }
  reserve(n);
  if (clearAll_) {
    cellStart_.fill(0);
    cellEnd_.fill(0);
    clearAll_ = false;
  }
  inside_.fill(0);
  count_ = n;
  if (n == 0) return;
  cellKeys_.bind(params_, x, y, un, keys_);
  cellKeys_.launch({n}, kParticleGroup);
  sort_.sortWithIndex(keys_, n, sortedKeys_, order_);
  cellRanges_.bind(sortedKeys_, un, cellStart_, cellEnd_, inside_);
  cellRanges_.launch({n}, kParticleGroup);
}

void NeighbourGrid::checkGather(const compute::RawBuffer& src, std::size_t srcSize, const compute::RawBuffer& dst,
                                std::size_t dstSize) const {
  if (srcSize < count_ || dstSize < count_)
    throw ComputeError("neighbour grid: gather of " + std::to_string(count_) + " particles into or from a buffer of " +
                       std::to_string(std::min(srcSize, dstSize)));
  if (src.mem() == dst.mem() && count_ > 0)
    throw ComputeError("neighbour grid: gather source and target are one buffer");
}

void NeighbourGrid::gather(const compute::RealBuffer& src, compute::RealBuffer& dst) {
  checkGather(src.raw(), src.size(), dst.raw(), dst.size());
  gatherReal_.bind(src, order_, static_cast<cl_uint>(count_), dst);
  gatherReal_.launch({count_}, kParticleGroup);
}

void NeighbourGrid::gather(const compute::Buffer<cl_uint>& src, compute::Buffer<cl_uint>& dst) {
  checkGather(src.raw(), src.size(), dst.raw(), dst.size());
  gatherUint_.bind(src, order_, static_cast<cl_uint>(count_), dst);
  gatherUint_.launch({count_}, kParticleGroup);
}

void NeighbourGrid::gather(const compute::Buffer<cl_uchar>& src, compute::Buffer<cl_uchar>& dst) {
  checkGather(src.raw(), src.size(), dst.raw(), dst.size());
  gatherUchar_.bind(src, order_, static_cast<cl_uint>(count_), dst);
  gatherUchar_.launch({count_}, kParticleGroup);
}

void NeighbourGrid::reorder(compute::RealBuffer& field) {
  if (count_ == 0) return;
  gather(field, scratch_);
  const std::size_t bytes = count_ * compute::realSize(ctx_.precision());
  compute::clCheck(clEnqueueCopyBuffer(ctx_.queue(), scratch_.mem(), field.mem(), 0, 0, bytes, 0, nullptr, nullptr),
                   "copying a reordered particle array back");
}

void NeighbourGrid::listNeighbours(const compute::RealBuffer& xSorted, const compute::RealBuffer& ySorted,
                                   double radius, std::size_t capacity, compute::Buffer<cl_uint>& count,
                                   compute::Buffer<cl_uint>& list) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw InputError("neighbour grid: list radius " + std::to_string(radius) + " m is not a positive number");
  if (xSorted.size() < count_ || ySorted.size() < count_ || count.size() < count_ || list.size() < count_ * capacity)
    throw ComputeError("neighbour grid: neighbour-list buffers are too small for " + std::to_string(count_) +
                       " particles");
  if (count_ == 0) return;
  if (lists_.name().empty()) lists_ = compute::Kernel(ctx_.program(kListFile), "particles_neighbour_lists");
  lists_.bind(params_, cellStart_, cellEnd_, xSorted, ySorted, static_cast<cl_uint>(count_), compute::RealArg{radius},
              static_cast<cl_uint>(capacity), count, list);
  lists_.launch({count_}, kParticleGroup);
}

std::size_t NeighbourGrid::readInsideCount() const { return inside_.read()[0]; }

}  // namespace talus::particles
