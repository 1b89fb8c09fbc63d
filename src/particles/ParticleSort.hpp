// Device sort of (uint key, uint value) pairs by a bitonic network (kernels/particles/bitonic_sort.cl).
#pragma once
#include <CL/cl.h>

#include <cstddef>

#include "compute/Buffer.hpp"
#include "compute/Kernel.hpp"

namespace talus::particles {

/// Sorts n (key, value) pairs on the device, for any n (0 and 1 included): by key, ties by value,
/// so the result is unique and equals std::sort of the pairs. The pairs are padded to the next
/// power of two; strides below a work-group's tile run in local memory, the larger strides in
/// global passes of two strides each (see the kernel file). Owns its scratch, which grows to the
/// largest n seen. All work is enqueued on the context's queue; nothing is read back.
class ParticleSort {
 public:
  /// `localSize`: work-items per work-group (a power of two; each group sorts 4 * localSize pairs in
  /// local memory); 0 picks min(256, the device's limits).
  explicit ParticleSort(compute::Context& ctx, std::size_t localSize = 0);

  /// Sorts the pairs (keys[i], i), i < n: sortedKeys[r] and order[r] (the original index of the pair
  /// at rank r) for r < n. Output buffers may be the input buffer. Throws ComputeError when a buffer
  /// holds fewer than n entries or n >= 2^31.
  void sortWithIndex(const compute::Buffer<cl_uint>& keys, std::size_t n, compute::Buffer<cl_uint>& sortedKeys,
                     compute::Buffer<cl_uint>& order);

  /// Sorts the pairs (keys[i], values[i]), i < n, into sortedKeys and sortedValues (which may be the
  /// input buffers). Same limits as sortWithIndex.
  void sortPairs(const compute::Buffer<cl_uint>& keys, const compute::Buffer<cl_uint>& values, std::size_t n,
                 compute::Buffer<cl_uint>& sortedKeys, compute::Buffer<cl_uint>& sortedValues);

  /// Work-items per work-group of the local-memory passes.
  std::size_t localSize() const { return localSize_; }
  /// The padded length of the network for n pairs: the next power of two (1 for n <= 1).
  static std::size_t paddedSize(std::size_t n);

 private:
  void reserve(std::size_t padded);
  void sortPacked(std::size_t padded);
  void unpack(std::size_t n, compute::Buffer<cl_uint>& sortedKeys, compute::Buffer<cl_uint>& sortedValues);

  compute::Context& ctx_;
  std::size_t localSize_ = 0;
  compute::Kernel packIndex_, packPairs_, unpack_, sortLocal_, mergeLocal_, mergeGlobal_, mergeGlobal2_;
  compute::Buffer<cl_ulong> packed_;  ///< (key << 32 | value) words, padded to a power of two
};

}  // namespace talus::particles
