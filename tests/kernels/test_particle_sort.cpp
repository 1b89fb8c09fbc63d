// Tests of the device bitonic sort (src/particles/ParticleSort, kernels/particles/bitonic_sort.cl):
// the sorted (key, index) and (key, value) pairs must equal std::sort of the same pairs exactly, for
// sizes that are not powers of two (0, 1, 2, 3, 17, 1000, 4097, 100003), for random keys over the
// full range, keys with many duplicates, all-equal keys, already sorted and reversed input, keys
// equal to the padding value 0xFFFFFFFF, and for several work-group sizes (so that both the
// local-memory and the global passes run at small sizes too).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "core/Error.hpp"
#include "particles/ParticleSort.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus;
using compute::Buffer;
using Pair = std::pair<uint32_t, uint32_t>;

const std::size_t kSizes[] = {0, 1, 2, 3, 17, 1000, 4097, 100003};

enum class Pattern { Random, FewDistinct, AllEqual, Sorted, Reversed, WithMaxKey };

const char* patternName(Pattern p) {
  switch (p) {
    case Pattern::Random: return "random";
    case Pattern::FewDistinct: return "few distinct";
    case Pattern::AllEqual: return "all equal";
    case Pattern::Sorted: return "sorted";
    case Pattern::Reversed: return "reversed";
    case Pattern::WithMaxKey: return "with 0xFFFFFFFF keys";
  }
  return "?";
}

std::vector<uint32_t> makeKeys(std::size_t n, Pattern p, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> k(n);
  switch (p) {
    case Pattern::Random:
      for (auto& v : k) v = rng();
      break;
    case Pattern::FewDistinct:
      for (auto& v : k) v = rng() % 7;
      break;
    case Pattern::AllEqual:
      std::fill(k.begin(), k.end(), 42u);
      break;
    case Pattern::Sorted:
      for (std::size_t i = 0; i < n; ++i) k[i] = static_cast<uint32_t>(i / 3);
      break;
    case Pattern::Reversed:
      for (std::size_t i = 0; i < n; ++i) k[i] = static_cast<uint32_t>(n - i);
      break;
    case Pattern::WithMaxKey:
      for (auto& v : k) v = (rng() % 4 == 0) ? 0xFFFFFFFFu : rng() % 1000;
      break;
  }
  return k;
}

/// Uploads `v` into a new buffer of exactly v.size() entries (at least one, as OpenCL needs).
Buffer<cl_uint> upload(compute::Context& ctx, const std::vector<uint32_t>& v) {
  Buffer<cl_uint> b(ctx, v.size());
  b.write(v);
  return b;
}

std::vector<Pair> hostSorted(const std::vector<uint32_t>& keys, const std::vector<uint32_t>& values) {
  std::vector<Pair> p(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) p[i] = {keys[i], values[i]};
  std::sort(p.begin(), p.end());
  return p;
}

std::vector<uint32_t> iota(std::size_t n) {
  std::vector<uint32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<uint32_t>(i);
  return v;
}

/// Sorts (keys[i], i) on the device and expects exactly the pairs of std::sort.
void expectSortWithIndex(compute::Context& ctx, particles::ParticleSort& sorter, const std::vector<uint32_t>& keys) {
  const std::size_t n = keys.size();
  Buffer<cl_uint> in = upload(ctx, keys), sortedKeys(ctx, n), order(ctx, n);
  sorter.sortWithIndex(in, n, sortedKeys, order);
  const std::vector<uint32_t> k = sortedKeys.read(), o = order.read();
  const std::vector<Pair> expect = hostSorted(keys, iota(n));
  std::size_t bad = 0, first = n;
  for (std::size_t r = 0; r < n; ++r)
    if (k[r] != expect[r].first || o[r] != expect[r].second) {
      if (bad++ == 0) first = r;
    }
  EXPECT_EQ(bad, 0u) << "first mismatch at rank " << first << ": device (" << (first < n ? k[first] : 0) << ", "
                     << (first < n ? o[first] : 0) << "), std::sort (" << (first < n ? expect[first].first : 0)
                     << ", " << (first < n ? expect[first].second : 0) << ")";
}

TEST(ParticleSort, PaddedSizeIsNextPowerOfTwo) {
  EXPECT_EQ(particles::ParticleSort::paddedSize(0), 1u);
  EXPECT_EQ(particles::ParticleSort::paddedSize(1), 1u);
  EXPECT_EQ(particles::ParticleSort::paddedSize(2), 2u);
  EXPECT_EQ(particles::ParticleSort::paddedSize(3), 4u);
  EXPECT_EQ(particles::ParticleSort::paddedSize(4097), 8192u);
  EXPECT_EQ(particles::ParticleSort::paddedSize(100003), 131072u);
}

TEST(ParticleSort, KeyIndexPairsEqualStdSortForAllSizesAndPatterns) {
  compute::Context& ctx = test::testContext(compute::Precision::Float);
  particles::ParticleSort sorter(ctx);
  unsigned seed = 1;
  for (Pattern p : {Pattern::Random, Pattern::FewDistinct, Pattern::AllEqual, Pattern::Sorted, Pattern::Reversed,
                    Pattern::WithMaxKey})
    for (std::size_t n : kSizes) {
      SCOPED_TRACE(std::string(patternName(p)) + ", n = " + std::to_string(n));
      expectSortWithIndex(ctx, sorter, makeKeys(n, p, ++seed));
    }
}

TEST(ParticleSort, SmallWorkGroupsExerciseTheGlobalPasses) {
  // With L work-items per group only strides below 2L run in local memory; L = 1 makes every
  // stride above 1 a global pass, L = 4 and 64 mix both kinds.
  compute::Context& ctx = test::testContext(compute::Precision::Float);
  for (std::size_t local : {1u, 4u, 64u}) {
    particles::ParticleSort sorter(ctx, local);
    EXPECT_EQ(sorter.localSize(), local);
    unsigned seed = 100;
    for (Pattern p : {Pattern::Random, Pattern::FewDistinct, Pattern::Reversed})
      for (std::size_t n : {2u, 3u, 17u, 1000u, 4097u}) {
        SCOPED_TRACE("local " + std::to_string(local) + ", " + patternName(p) + ", n = " + std::to_string(n));
        expectSortWithIndex(ctx, sorter, makeKeys(n, p, ++seed));
      }
  }
}

TEST(ParticleSort, KeyValuePairsSortByKeyThenValue) {
  compute::Context& ctx = test::testContext(compute::Precision::Float);
  particles::ParticleSort sorter(ctx);
  std::mt19937 rng(7);
  for (std::size_t n : kSizes) {
    SCOPED_TRACE("n = " + std::to_string(n));
    // Few distinct keys and values (repeated pairs too), including the all-ones value.
    std::vector<uint32_t> keys(n), values(n);
    for (std::size_t i = 0; i < n; ++i) {
      keys[i] = rng() % 13;
      values[i] = rng() % 5 == 0 ? 0xFFFFFFFFu : rng() % 50;
    }
    Buffer<cl_uint> k = upload(ctx, keys), v = upload(ctx, values);
    // In place: outputs are the input buffers.
    sorter.sortPairs(k, v, n, k, v);
    const std::vector<uint32_t> sk = k.read(), sv = v.read();
    const std::vector<Pair> expect = hostSorted(keys, values);
    std::size_t bad = 0;
    for (std::size_t r = 0; r < n; ++r) bad += sk[r] != expect[r].first || sv[r] != expect[r].second;
    EXPECT_EQ(bad, 0u);
  }
}

TEST(ParticleSort, SortsAPrefixOfALargerBufferAndReusesScratch) {
  compute::Context& ctx = test::testContext(compute::Precision::Float);
  particles::ParticleSort sorter(ctx);
  const std::vector<uint32_t> keys = makeKeys(5000, Pattern::Random, 99);
  Buffer<cl_uint> in = upload(ctx, keys), sortedKeys(ctx, 5000), order(ctx, 5000);
  // A large sort first (scratch grows), then a smaller prefix (scratch reused, padding rewritten).
  sorter.sortWithIndex(in, 5000, sortedKeys, order);
  sorter.sortWithIndex(in, 333, sortedKeys, order);
  const std::vector<uint32_t> k = sortedKeys.read(), o = order.read();
  const std::vector<Pair> expect =
      hostSorted(std::vector<uint32_t>(keys.begin(), keys.begin() + 333), iota(333));
  for (std::size_t r = 0; r < 333; ++r) {
    ASSERT_EQ(k[r], expect[r].first) << "rank " << r;
    ASSERT_EQ(o[r], expect[r].second) << "rank " << r;
  }
}

TEST(ParticleSort, RejectsBuffersShorterThanTheCountAndBadWorkGroups) {
  compute::Context& ctx = test::testContext(compute::Precision::Float);
  particles::ParticleSort sorter(ctx);
  Buffer<cl_uint> small(ctx, 10), big(ctx, 100);
  EXPECT_THROW(sorter.sortWithIndex(small, 11, big, big), ComputeError);
  EXPECT_THROW(sorter.sortWithIndex(big, 11, small, big), ComputeError);
  EXPECT_THROW(sorter.sortPairs(big, small, 11, big, big), ComputeError);
  EXPECT_THROW(particles::ParticleSort(ctx, 3), ComputeError);
}

}  // namespace
