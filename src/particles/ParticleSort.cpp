#include "particles/LaunchSize.hpp"
#include "particles/ParticleSort.hpp"

#include <algorithm>
#include <string>

#include "compute/ClError.hpp"
#include "compute/Context.hpp"
#include "compute/Program.hpp"
#include "core/Error.hpp"

namespace talus::particles {
namespace {

constexpr const char* kSortFile = "particles/bitonic_sort.cl";
constexpr std::size_t kDefaultLocal = 256;
constexpr std::size_t kMaxPairs = std::size_t(1) << 31;  // indices and padded sizes stay in uint

std::size_t floorPowerOfTwo(std::size_t v) {
  std::size_t p = 1;
  while (p * 2 <= v) p *= 2;
  return p;
}

/// The largest work-group size (a power of two, at most `wanted`) the device allows for a tile of
/// 4 * size ulongs in local memory.
std::size_t chooseLocalSize(const compute::DeviceInfo& device, std::size_t wanted) {
  cl_ulong localBytes = 0;
  compute::clCheck(clGetDeviceInfo(device.id, CL_DEVICE_LOCAL_MEM_SIZE, sizeof localBytes, &localBytes, nullptr),
                   "querying the local memory size of " + device.name);
  std::size_t size = std::min(wanted, device.maxWorkGroupSize == 0 ? wanted : device.maxWorkGroupSize);
  size = std::min<std::size_t>(size, static_cast<std::size_t>(localBytes / (4 * sizeof(cl_ulong))));
  return floorPowerOfTwo(std::max<std::size_t>(size, 1));
}

void requireSize(const compute::Buffer<cl_uint>& b, std::size_t n, const char* what) {
  if (b.size() < n)
    throw ComputeError(std::string("sort: ") + what + " holds " + std::to_string(b.size()) + " entries, " +
                       std::to_string(n) + " are sorted");
}

}  // namespace

ParticleSort::ParticleSort(compute::Context& ctx, std::size_t localSize) : ctx_(ctx) {
  if (localSize != 0 && (localSize & (localSize - 1)) != 0)
    throw ComputeError("sort: work-group size " + std::to_string(localSize) + " is not a power of two");
  localSize_ = chooseLocalSize(ctx.device(), localSize == 0 ? kDefaultLocal : localSize);
  compute::Program& program = ctx.program(kSortFile);
  packIndex_ = compute::Kernel(program, "sort_pack_with_index");
  packPairs_ = compute::Kernel(program, "sort_pack_pairs");
  unpack_ = compute::Kernel(program, "sort_unpack");
  sortLocal_ = compute::Kernel(program, "bitonic_sort_local");
  mergeLocal_ = compute::Kernel(program, "bitonic_merge_local");
  mergeGlobal_ = compute::Kernel(program, "bitonic_merge_global");
  mergeGlobal2_ = compute::Kernel(program, "bitonic_merge_global_2");
}

std::size_t ParticleSort::paddedSize(std::size_t n) {
  std::size_t p = 1;
  while (p < n) p *= 2;
  return p;
}

void ParticleSort::reserve(std::size_t padded) {
  if (packed_.size() < padded) packed_ = compute::Buffer<cl_ulong>(ctx_, padded, "sort pairs");
}

void ParticleSort::sortWithIndex(const compute::Buffer<cl_uint>& keys, std::size_t n,
                                 compute::Buffer<cl_uint>& sortedKeys, compute::Buffer<cl_uint>& order) {
  if (n >= kMaxPairs) throw ComputeError("sort: " + std::to_string(n) + " pairs exceed the limit of 2^31");
  requireSize(keys, n, "the key buffer");
  requireSize(sortedKeys, n, "the sorted-key buffer");
  requireSize(order, n, "the order buffer");
  if (n == 0) return;
  const std::size_t padded = paddedSize(n);
  reserve(padded);
  packIndex_.bind(keys, static_cast<cl_uint>(n), static_cast<cl_uint>(padded), packed_);
  packIndex_.launch({padded}, {0, 0}, "sort_pack");
  sortPacked(padded);
  unpack(n, sortedKeys, order);
}

void ParticleSort::sortPairs(const compute::Buffer<cl_uint>& keys, const compute::Buffer<cl_uint>& values,
                             std::size_t n, compute::Buffer<cl_uint>& sortedKeys,
                             compute::Buffer<cl_uint>& sortedValues) {
  if (n >= kMaxPairs) throw ComputeError("sort: " + std::to_string(n) + " pairs exceed the limit of 2^31");
  requireSize(keys, n, "the key buffer");
  requireSize(values, n, "the value buffer");
  requireSize(sortedKeys, n, "the sorted-key buffer");
  requireSize(sortedValues, n, "the sorted-value buffer");
  if (n == 0) return;
  const std::size_t padded = paddedSize(n);
  reserve(padded);
  packPairs_.bind(keys, values, static_cast<cl_uint>(n), static_cast<cl_uint>(padded), packed_);
  packPairs_.launch({padded}, {0, 0}, "sort_pack");
  sortPacked(padded);
  unpack(n, sortedKeys, sortedValues);
}

void ParticleSort::sortPacked(std::size_t padded) {
  if (padded < 2) return;
  const std::size_t pairs = padded / 2;
  if (padded == 2) {  // smaller than any tile: the single compare-exchange
    mergeGlobal_.bind(packed_, cl_uint{2}, cl_uint{1}, static_cast<cl_uint>(pairs));
    mergeGlobal_.launch({pairs}, {0, 0}, "bitonic_merge_global");
    return;
  }
  // A work-group of `local` work-items owns a tile of 4 * local elements; the tile never exceeds
  // the array.
  const std::size_t local = std::min(localSize_, padded / 4);
  const std::size_t tile = 4 * local;
  const std::size_t groups = padded / tile;
  const std::size_t tileBytes = tile * sizeof(cl_ulong);
  sortLocal_.bind(packed_).setLocal(1, tileBytes);
  sortLocal_.launch({groups * local}, {local}, "bitonic_sort_local");
  for (std::size_t k = 2 * tile; k <= padded; k *= 2) {
    // Global strides k/2 .. tile, two per pass while two are left.
    std::size_t j = k / 2;
    for (; j >= 2 * tile; j /= 4) {
      mergeGlobal2_.bind(packed_, static_cast<cl_uint>(k), static_cast<cl_uint>(j), static_cast<cl_uint>(pairs / 2));
      mergeGlobal2_.launch({pairs / 2}, {0, 0}, "bitonic_merge_global");
    }
    if (j == tile) {
      mergeGlobal_.bind(packed_, static_cast<cl_uint>(k), static_cast<cl_uint>(j), static_cast<cl_uint>(pairs));
      mergeGlobal_.launch({pairs}, {0, 0}, "bitonic_merge_global");
    }
    mergeLocal_.bind(packed_, static_cast<cl_uint>(k)).setLocal(2, tileBytes);
    mergeLocal_.launch({groups * local}, {local}, "bitonic_merge_local");
  }
}

void ParticleSort::unpack(std::size_t n, compute::Buffer<cl_uint>& sortedKeys,
                          compute::Buffer<cl_uint>& sortedValues) {
  unpack_.bind(packed_, static_cast<cl_uint>(n), sortedKeys, sortedValues);
  unpack_.launch({n}, kParticleGroup, "sort_unpack");
}

}  // namespace talus::particles
