// Tests of the particle neighbour grid (src/particles/NeighbourGrid, kernels/particles/*.cl) against
// the host references of tests/support/NeighbourReference, in float and double:
// - cell keys, the sort permutation, the cell start/end tables and the inside count of a build;
// - neighbour lists from the 3 x 3 cells around each particle equal a brute-force O(n^2) search,
//   for uniform and clustered clouds, lattices whose spacing equals the radius (pairs exactly at the
//   radius, particles on cell lines and on the box edge), particles exactly on the grid's cell lines,
//   pairs placed at the radius across a large float domain (the cell-size margin), and particles
//   outside the box or at NaN;
// - rebuilds after moving, removing and adding particles leave no stale table entries;
// - reordered real, uint and uchar arrays equal the host permutation bitwise;
// - the edge cases n = 0 and n = 1, all particles outside, and invalid arguments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "core/Error.hpp"
#include "particles/NeighbourGrid.hpp"
#include "support/NeighbourReference.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus;
using compute::Buffer;
using compute::Precision;
using particles::DomainBox;
using particles::NeighbourGrid;

struct Cloud {
  std::vector<double> x, y;
  void add(double px, double py) {
    x.push_back(px);
    y.push_back(py);
  }
  std::size_t size() const { return x.size(); }
};

class NeighbourGridTest : public ::testing::TestWithParam<Precision> {
 protected:
  bool isDouble() const { return GetParam() == Precision::Double; }
  compute::Context& ctx() const { return test::testContext(GetParam()); }

  /// Uploads a cloud (as the device's real) and builds `grid` from it.
  void build(NeighbourGrid& grid, const Cloud& c, compute::RealBuffer& x, compute::RealBuffer& y) {
    x = compute::RealBuffer(ctx(), c.size(), "x");
    y = compute::RealBuffer(ctx(), c.size(), "y");
    x.upload(c.x);
    y.upload(c.y);
    grid.build(x, y, c.size());
  }

  /// Checks keys, permutation, tables and inside count of the last build of `grid` from `c`.
  void expectTablesMatchHost(NeighbourGrid& grid, const Cloud& c) {
    const std::size_t n = c.size();
    const test::ReferenceGrid ref = test::ReferenceGrid::of(grid);
    const std::vector<uint32_t> keys = grid.sortedKeys().read(), order = grid.order().read();
    ASSERT_GE(keys.size(), n);
    // order is a permutation, and every particle has its own cell's key (a position within 1e-4
    // cells of a cell line may take either cell on a device without correctly rounded division).
    std::vector<char> seen(n, 0);
    std::vector<uint32_t> deviceKey(n);
    std::size_t wrongKeys = 0, insideHost = 0;
    for (std::size_t r = 0; r < n; ++r) {
      ASSERT_LT(order[r], n) << "rank " << r;
      ASSERT_FALSE(seen[order[r]]) << "index " << order[r] << " appears twice";
      seen[order[r]] = 1;
      const uint32_t i = order[r];
      bool ambiguous = false;
      const uint32_t expect = test::referenceCellKey(ref, test::toDeviceReal(c.x[i], isDouble()),
                                                     test::toDeviceReal(c.y[i], isDouble()), isDouble(), &ambiguous);
      deviceKey[i] = keys[r];
      if (keys[r] != expect && !ambiguous) ++wrongKeys;
      insideHost += expect != NeighbourGrid::kCellKeyOutside;
    }
    EXPECT_EQ(wrongKeys, 0u);
    // The pairs are exactly std::sort of (device key, index).
    std::vector<std::pair<uint32_t, uint32_t>> pairs(n);
    for (std::size_t i = 0; i < n; ++i) pairs[i] = {deviceKey[i], static_cast<uint32_t>(i)};
    std::sort(pairs.begin(), pairs.end());
    for (std::size_t r = 0; r < n; ++r) {
      ASSERT_EQ(keys[r], pairs[r].first) << "rank " << r;
      ASSERT_EQ(order[r], pairs[r].second) << "rank " << r;
    }
    // Tables over all cells (stale entries of a previous build would show here).
    std::vector<uint32_t> start, end;
    test::referenceCellTables(std::vector<uint32_t>(keys.begin(), keys.begin() + n), grid.cells(), start, end);
    EXPECT_TRUE(grid.cellStart().read() == start) << "cell start table differs";
    EXPECT_TRUE(grid.cellEnd().read() == end) << "cell end table differs";
    EXPECT_EQ(grid.readInsideCount(), insideHost);
  }

  /// Neighbour lists of the grid (through reordered positions) against brute force.
  void expectNeighboursMatchBruteForce(NeighbourGrid& grid, const Cloud& c, double radius) {
    const std::size_t n = c.size();
    compute::RealBuffer x, y;
    build(grid, c, x, y);
    expectTablesMatchHost(grid, c);
    const auto expect = test::bruteForceNeighbours(c.x, c.y, grid.box(), radius, isDouble());
    std::size_t capacity = 1, pairs = 0;
    for (const auto& l : expect) capacity = std::max(capacity, l.size()), pairs += l.size();
    compute::RealBuffer xs(ctx(), n, "x sorted"), ys(ctx(), n, "y sorted");
    grid.gather(x, xs);
    grid.gather(y, ys);
    Buffer<cl_uint> count(ctx(), n), list(ctx(), n * capacity);
    grid.listNeighbours(xs, ys, radius, capacity, count, list);
    const std::vector<uint32_t> cnt = count.read(), lst = list.read(), order = grid.order().read();
    std::size_t wrong = 0, found = 0;
    std::string firstWrong;
    for (std::size_t r = 0; r < n; ++r) {
      const uint32_t i = order[r];
      std::vector<uint32_t> got;
      for (std::size_t m = 0; m < std::min<std::size_t>(cnt[r], capacity); ++m)
        got.push_back(order[lst[r * capacity + m]]);
      std::sort(got.begin(), got.end());
      found += cnt[r];
      if (cnt[r] != expect[i].size() || got != expect[i]) {
        if (wrong++ == 0)
          firstWrong = "particle " + std::to_string(i) + " at (" + std::to_string(c.x[i]) + ", " +
                       std::to_string(c.y[i]) + "): " + std::to_string(cnt[r]) + " neighbours, brute force " +
                       std::to_string(expect[i].size());
      }
    }
    EXPECT_EQ(wrong, 0u) << firstWrong;
    EXPECT_EQ(found, pairs);
    EXPECT_GT(pairs, 0u) << "the cloud should have neighbours at all";
  }
};

/// v moved by `ulps` units in the last place of the device's real (float or double).
double stepUlps(double v, int ulps, bool isDouble) {
  for (; ulps > 0; --ulps) v = isDouble ? std::nextafter(v, 1e300) : double(std::nextafter(float(v), 1e30f));
  for (; ulps < 0; ++ulps) v = isDouble ? std::nextafter(v, -1e300) : double(std::nextafter(float(v), -1e30f));
  return v;
}

Cloud uniformCloud(const DomainBox& b, std::size_t n, double outsideShare, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(b.xMin, b.xMax), uy(b.yMin, b.yMax), u01(0.0, 1.0);
  const double w = b.xMax - b.xMin, h = b.yMax - b.yMin;
  std::uniform_real_distribution<double> ox(b.xMin - 0.2 * w, b.xMax + 0.2 * w), oy(b.yMin - 0.2 * h, b.yMax + 0.2 * h);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    if (u01(rng) < outsideShare) c.add(ox(rng), oy(rng));  // mostly outside, some inside
    else c.add(ux(rng), uy(rng));
  }
  return c;
}

TEST_P(NeighbourGridTest, UniformCloudWithOutsideAndNanParticles) {
  const DomainBox box{-3.0, 1.5, 7.0, 7.5};
  const double radius = 0.37;
  NeighbourGrid grid(ctx(), box, radius);
  Cloud c = uniformCloud(box, 3000, 0.05, 11);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  c.add(nan, 2.0);
  c.add(0.0, nan);
  c.add(box.xMax, box.yMax);  // the corner belongs to the last cell
  c.add(box.xMin, box.yMin);
  expectNeighboursMatchBruteForce(grid, c, radius);
  EXPECT_EQ(grid.cellsX(), static_cast<int>(std::ceil(10.0 / grid.cellSize())));
}

TEST_P(NeighbourGridTest, ClusteredCloudWithManyParticlesPerCell) {
  const DomainBox box{0.0, 0.0, 8.0, 8.0};
  const double radius = 0.3;
  NeighbourGrid grid(ctx(), box, radius);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 0.15);
  const double centres[][2] = {{1, 1}, {4, 4.2}, {6.5, 2}, {2, 7.9}, {7.95, 7.95}};
  Cloud c;
  for (int k = 0; k < 2000; ++k) {
    const auto& ctr = centres[k % 5];
    c.add(ctr[0] + g(rng), ctr[1] + g(rng));
  }
  expectNeighboursMatchBruteForce(grid, c, radius);
}

TEST_P(NeighbourGridTest, LatticesWithSpacingEqualToTheRadius) {
  // Spacing 0.25 (exact in binary: pairs exactly at the radius, points on the box edge) and 0.1 (not
  // exact: distances of neighbours round to either side of the radius, cell coordinates round near
  // integers), with the box origin away from zero.
  for (double spacing : {0.25, 0.1}) {
    SCOPED_TRACE("spacing " + std::to_string(spacing));
    const DomainBox box{-1.3, 2.0, -1.3 + 30 * spacing, 2.0 + 20 * spacing};
    NeighbourGrid grid(ctx(), box, spacing);
    Cloud c;
    for (int j = 0; j <= 20; ++j)
      for (int i = 0; i <= 30; ++i) c.add(box.xMin + i * spacing, box.yMin + j * spacing);
    expectNeighboursMatchBruteForce(grid, c, spacing);
  }
}

TEST_P(NeighbourGridTest, ParticlesExactlyOnCellLines) {
  const DomainBox box{0.0, 0.0, 5.0, 3.0};
  const double radius = 0.5;
  NeighbourGrid grid(ctx(), box, radius);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Cloud c;
  for (int k = 0; k < 1500; ++k) {
    const int line = static_cast<int>(u01(rng) * grid.cellsX());
    double x = box.xMin + line * grid.cellSize();
    // Exactly on the line, or one unit of rounding to either side of it.
    const double fx = test::toDeviceReal(x, isDouble());
    const int side = k % 3 - 1;
    const double next = isDouble() ? std::nextafter(fx, side * 1e9)
                                   : static_cast<double>(std::nextafter(static_cast<float>(fx), side * 1e9f));
    x = side == 0 ? fx : next;
    if (k % 2) c.add(std::min(x, box.xMax), u01(rng) * 3.0);
    else c.add(u01(rng) * 5.0, std::min(box.yMin + (line % grid.cellsY()) * grid.cellSize(), box.yMax));
  }
  expectNeighboursMatchBruteForce(grid, c, radius);
}

TEST_P(NeighbourGridTest, PairsAtTheRadiusAcrossALargeDomain) {
  // 2000 x 1000 m at radius 0.7 m with an origin that is not representable: in float, coordinates
  // near 2000 carry 1.2e-4 m of rounding, and the cell coordinate (x - xMin) / cellSize rounds too.
  // Pairs placed at the radius (in the device's arithmetic) with one particle a few units of
  // rounding off a cell line must still be found: this is what the cell-size margin of
  // NeighbourGrid::cellSizeFor guarantees (with cellSize = radius this test fails in float).
  const DomainBox box{-123.4, 56.7, -123.4 + 2000.0, 56.7 + 1000.0};
  const double radius = 0.7;
  NeighbourGrid grid(ctx(), box, radius);
  std::mt19937_64 rng(23);
  std::uniform_int_distribution<int> lineX(1, grid.cellsX() - 3), jitter(-3, 3);
  std::uniform_real_distribution<double> uy(box.yMin + 1.0, box.yMax - 1.0), angle(-0.3, 0.3);
  auto real = [&](double v) { return test::toDeviceReal(v, isDouble()); };
  Cloud c;
  for (int k = 0; k < 4000; ++k) {
    // Anchor on or a few ulps next to a cell line, partner one radius away (to the right, or at a
    // small angle), both as the device holds them.
    const double ax = stepUlps(real(box.xMin + lineX(rng) * grid.cellSize()), jitter(rng), isDouble());
    const double ay = real(uy(rng));
    c.add(ax, ay);
    if (k % 2) {
      c.add(real(ax + radius), ay);
    } else {
      const double a = angle(rng);
      c.add(real(ax + radius * std::cos(a)), real(ay + radius * std::sin(a)));
    }
  }
  expectNeighboursMatchBruteForce(grid, c, radius);
}

// The thickness sums of an expanded particle look as far as 2 h_i <= 6 h = 3 times the grid's radius
// (kernels/particles/particle_density.cl), over the cells neighbour_cells_within() gives: the same
// pairs as brute force at radii from just below the grid's to three times it, on a uniform cloud and
// for pairs placed at the radius next to cell lines of a large domain (float rounding of the cell
// coordinate, as in PairsAtTheRadiusAcrossALargeDomain).
TEST_P(NeighbourGridTest, WiderRadiiFindThePairsOfABruteForceSearch) {
  const DomainBox box{-5.0, -3.0, 25.0, 17.0};
  const double radius = 0.8;
  NeighbourGrid grid(ctx(), box, radius);
  const Cloud c = uniformCloud(box, 3000, 0.05, 41);
  for (double f : {0.999, 1.0, 1.5, 2.0, 2.7, 3.0}) {
    SCOPED_TRACE("radius " + std::to_string(f) + " times the grid's");
    expectNeighboursMatchBruteForce(grid, c, f * radius);
  }
  const DomainBox large{-123.4, 56.7, -123.4 + 2000.0, 56.7 + 1000.0};
  NeighbourGrid wide(ctx(), large, 0.7);
  std::mt19937_64 rng(29);
  std::uniform_int_distribution<int> lineX(4, wide.cellsX() - 5), jitter(-3, 3);
  std::uniform_real_distribution<double> uy(large.yMin + 4.0, large.yMax - 4.0);
  auto real = [&](double v) { return test::toDeviceReal(v, isDouble()); };
  for (double f : {2.0, 3.0}) {
    SCOPED_TRACE("large domain, radius " + std::to_string(f) + " times the grid's");
    const double r = f * 0.7;
    Cloud p;
    for (int k = 0; k < 2000; ++k) {
      const double ax = stepUlps(real(large.xMin + lineX(rng) * wide.cellSize()), jitter(rng), isDouble());
      const double ay = real(uy(rng));
      p.add(ax, ay);
      p.add(real(k % 2 ? ax + r : ax - r), ay);
    }
    expectNeighboursMatchBruteForce(wide, p, r);
  }
}

TEST_P(NeighbourGridTest, RebuildsAfterMovingRemovingAndAddingParticles) {
  const DomainBox box{0.0, 0.0, 4.0, 4.0};
  NeighbourGrid grid(ctx(), box, 0.2, 100);
  compute::RealBuffer x, y;
  for (std::size_t n : {2500u, 1200u, 1200u, 6000u, 0u, 1u, 300u}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const Cloud c = uniformCloud(box, n, 0.1, 1000 + static_cast<unsigned>(n) + static_cast<unsigned>(grid.count()));
    build(grid, c, x, y);
    EXPECT_EQ(grid.count(), n);
    expectTablesMatchHost(grid, c);
  }
}

TEST_P(NeighbourGridTest, ReorderedArraysEqualTheHostPermutationBitwise) {
  const DomainBox box{0.0, 0.0, 3.0, 3.0};
  NeighbourGrid grid(ctx(), box, 0.15);
  const std::size_t n = 4097;
  const Cloud c = uniformCloud(box, n, 0.02, 31);
  compute::RealBuffer x, y;
  build(grid, c, x, y);
  const std::vector<uint32_t> order = grid.order().read();

  std::mt19937_64 rng(3);
  std::vector<double> field(n);
  std::vector<uint32_t> ids(n);
  std::vector<unsigned char> flags(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double mantissa = static_cast<double>(rng() % 100000) - 5e4;
    field[i] = test::toDeviceReal(std::ldexp(mantissa, -static_cast<int>(rng() % 40)), isDouble());
    ids[i] = static_cast<uint32_t>(rng());
    flags[i] = static_cast<unsigned char>(rng());
  }
  compute::RealBuffer f(ctx(), n), fs(ctx(), n);
  f.upload(field);
  Buffer<cl_uint> id(ctx(), n), ids2(ctx(), n);
  id.write(ids);
  Buffer<cl_uchar> fl(ctx(), n), fl2(ctx(), n);
  fl.write(flags);
  grid.gather(f, fs);
  grid.gather(id, ids2);
  grid.gather(fl, fl2);
  const std::vector<double> gotField = fs.download();
  const std::vector<uint32_t> gotIds = ids2.read();
  const std::vector<unsigned char> gotFlags = fl2.read();
  std::size_t bad = 0;
  for (std::size_t r = 0; r < n; ++r) {
    bad += std::memcmp(&gotField[r], &field[order[r]], sizeof(double)) != 0;
    bad += gotIds[r] != ids[order[r]];
    bad += gotFlags[r] != flags[order[r]];
  }
  EXPECT_EQ(bad, 0u);
  // In place, through the grid's scratch buffer.
  grid.reorder(f);
  const std::vector<double> inPlace = f.download();
  EXPECT_EQ(std::memcmp(inPlace.data(), gotField.data(), n * sizeof(double)), 0);
  // Reordered positions have ascending cell keys.
  compute::RealBuffer xs(ctx(), n);
  grid.gather(x, xs);
  const std::vector<double> xsHost = xs.download();
  const std::vector<uint32_t> keys = grid.sortedKeys().read();
  for (std::size_t r = 0; r < n; ++r) ASSERT_EQ(xsHost[r], test::toDeviceReal(c.x[order[r]], isDouble()));
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
}

TEST_P(NeighbourGridTest, EmptySingleAndAllOutside) {
  const DomainBox box{0.0, 0.0, 1.0, 1.0};
  NeighbourGrid grid(ctx(), box, 0.1);
  compute::RealBuffer x, y;
  Cloud none;
  build(grid, none, x, y);
  EXPECT_EQ(grid.readInsideCount(), 0u);
  expectTablesMatchHost(grid, none);

  Cloud one;
  one.add(0.55, 0.55);
  build(grid, one, x, y);
  expectTablesMatchHost(grid, one);
  EXPECT_EQ(grid.readInsideCount(), 1u);

  Cloud outside;
  for (int k = 0; k < 50; ++k) outside.add(-1.0 - k, 0.5);
  build(grid, outside, x, y);
  expectTablesMatchHost(grid, outside);
  EXPECT_EQ(grid.readInsideCount(), 0u);
  const std::vector<uint32_t> keys = grid.sortedKeys().read();
  for (std::size_t r = 0; r < 50; ++r) EXPECT_EQ(keys[r], NeighbourGrid::kCellKeyOutside);
}

TEST_P(NeighbourGridTest, RejectsInvalidArguments) {
  EXPECT_THROW(NeighbourGrid(ctx(), DomainBox{0, 0, 1, 1}, 0.0), InputError);
  EXPECT_THROW(NeighbourGrid(ctx(), DomainBox{0, 0, 1, 1}, std::nan("")), InputError);
  EXPECT_THROW(NeighbourGrid(ctx(), DomainBox{1, 0, 0, 1}, 0.1), InputError);
  EXPECT_THROW(NeighbourGrid(ctx(), DomainBox{0, 0, std::numeric_limits<double>::infinity(), 1}, 0.1), InputError);
  EXPECT_THROW(NeighbourGrid(ctx(), DomainBox{0, 0, 1e6, 1e6}, 1e-2), InputError);  // 10^16 cells

  NeighbourGrid grid(ctx(), DomainBox{0, 0, 1, 1}, 0.1);
  compute::RealBuffer x(ctx(), 10), y(ctx(), 10);
  x.fill(0.5);
  y.fill(0.5);
  EXPECT_THROW(grid.build(x, y, 11), ComputeError);
  grid.build(x, y, 10);
  Buffer<cl_uint> count(ctx(), 10), list(ctx(), 100);
  EXPECT_THROW(grid.listNeighbours(x, y, 0.0, 10, count, list), InputError);
  EXPECT_THROW(grid.listNeighbours(x, y, std::nan(""), 10, count, list), InputError);
  EXPECT_THROW(grid.gather(x, x), ComputeError);
  compute::RealBuffer small(ctx(), 5);
  EXPECT_THROW(grid.gather(x, small), ComputeError);
  // Drain the queue: PoCL compiles kernels lazily on its worker threads, and a launch still pending
  // when the process exits gets compiled after LLVM's static destructors ran (a crash under ASan).
  ctx().finish();
}

TEST(NeighbourGridCellSize, MarginCoversRoundingAndIsSmall) {
  const DomainBox box{0, 0, 2000, 1000};
  const double f = NeighbourGrid::cellSizeFor(1.0, box, Precision::Float);
  const double d = NeighbourGrid::cellSizeFor(1.0, box, Precision::Double);
  EXPECT_GT(f, 1.0 + 4 * 2000 * 6e-8);
  EXPECT_LT(f, 1.001);
  EXPECT_GT(d, 1.0);
  EXPECT_LT(d, 1.0 + 1e-11);
}

INSTANTIATE_TEST_SUITE_P(Precisions, NeighbourGridTest, ::testing::Values(Precision::Float, Precision::Double),
                         [](const auto& info) { return info.param == Precision::Double ? "Double" : "Float"; });

}  // namespace
