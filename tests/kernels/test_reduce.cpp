// Tests of the device reductions (src/compute/Reducer, kernels/common/reduce.cl): sum, min and max
// against host references on random data of awkward sizes, in float and double, NaN propagation,
// the empty-input identities, prefixes of a larger buffer, and reduceRows against per-row reduce.
//
// Tolerance of sums. The device adds in a tree: each of T = 128 * G work-items (G = min(64,
// ceil(n / 128)) groups, the Reducer's launch geometry) first adds ceil(n / T) elements in
// sequence, then two 128-wide tree passes of 7 levels each combine the partials. Every element
// therefore passes through at most d = ceil(n / T) + 14 roundings, and the classic bound for any
// summation tree of depth d (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed.,
// sec. 4.2) gives |sum_device - sum_exact| <= gamma_d * sum |x_i| with gamma_d = d u / (1 - d u),
// u = eps / 2; we allow d * eps * sum|x_i| (>= gamma_d whenever d u < 1/2). For n = 1e6 in float
// that is 137 eps sum|x| ~ 1.6e-5 sum|x|, far from the n eps of a naive bound and from being
// flaky, while a lost or doubled element (an error of at least min |x| ~ 1e-3 sum|x| / n) would
// still show for all but the largest sizes. The exact sum is taken in long double of the values
// the device actually holds. Min and max involve no rounding and must match exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Reducer.hpp"
#include "core/Error.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus::compute;

const std::size_t kSizes[] = {0, 1, 2, 127, 128, 129, 1000, 65537, 1000000};

double epsOf(Precision p) {
  return p == Precision::Double ? std::numeric_limits<double>::epsilon()
                                : static_cast<double>(std::numeric_limits<float>::epsilon());
}

/// Random values of mixed sign and magnitude (2^-8 .. 2^8), representable in the precision.
std::vector<double> randomData(std::size_t n, Precision p, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-8, 8);
  std::vector<double> v(n);
  for (double& x : v) {
    x = std::ldexp(uni(rng), exponent(rng));
    if (p == Precision::Float) x = static_cast<double>(static_cast<float>(x));
  }
  return v;
}

/// The rounding depth d of a device sum of n elements (see the file header).
double sumDepth(std::size_t n, std::size_t threads) { return std::ceil(double(n) / double(threads)) + 14.0; }

double sumTolerance(const std::vector<double>& v, std::size_t n, Precision p, std::size_t threads) {
  long double abs = 0;
  for (std::size_t k = 0; k < n; ++k) abs += std::fabs(v[k]);
  return sumDepth(n, threads) * epsOf(p) * static_cast<double>(abs);
}

std::size_t reduceThreads(std::size_t n) {
  const std::size_t groups = std::max<std::size_t>(1, std::min<std::size_t>(64, (n + 127) / 128));
  return 128 * groups;
}

class Reduce : public ::testing::TestWithParam<Precision> {};

TEST_P(Reduce, SumMinMaxMatchHostOnRandomData) {
  const Precision p = GetParam();
  Context& ctx = talus::test::testContext(p);
  Reducer reducer(ctx);
  unsigned seed = 100;
  for (std::size_t n : kSizes) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const std::vector<double> v = randomData(n, p, ++seed);
    RealBuffer buf(ctx, n);
    buf.upload(v);
    const long double exact = std::accumulate(v.begin(), v.end(), 0.0L);
    EXPECT_NEAR(reducer.sum(buf, n), static_cast<double>(exact), sumTolerance(v, n, p, reduceThreads(n)));
    if (n == 0) {
      // The identities: 0, +max and -max of the precision.
      const double big = p == Precision::Double ? std::numeric_limits<double>::max()
                                                : static_cast<double>(std::numeric_limits<float>::max());
      EXPECT_EQ(reducer.sum(buf, 0), 0.0);
      EXPECT_EQ(reducer.min(buf, 0), big);
      EXPECT_EQ(reducer.max(buf, 0), -big);
      continue;
    }
    EXPECT_EQ(reducer.min(buf, n), *std::min_element(v.begin(), v.end()));
    EXPECT_EQ(reducer.max(buf, n), *std::max_element(v.begin(), v.end()));
  }
}

TEST_P(Reduce, ReducesOnlyThePrefix) {
  // n smaller than the buffer: the NaN tail must never be read.
  const Precision p = GetParam();
  Context& ctx = talus::test::testContext(p);
  Reducer reducer(ctx);
  for (std::size_t n : {std::size_t(1), std::size_t(129), std::size_t(20000)}) {
    std::vector<double> v = randomData(n, p, 7 + static_cast<unsigned>(n));
    const long double exact = std::accumulate(v.begin(), v.end(), 0.0L);
    const double lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
    const double tol = sumTolerance(v, n, p, reduceThreads(n));
    v.resize(n + 300, std::numeric_limits<double>::quiet_NaN());
    RealBuffer buf(ctx, v.size());
    buf.upload(v);
    EXPECT_NEAR(reducer.sum(buf, n), static_cast<double>(exact), tol) << n;
    EXPECT_EQ(reducer.min(buf, n), lo) << n;
    EXPECT_EQ(reducer.max(buf, n), hi) << n;
  }
}

TEST_P(Reduce, NaNPropagatesThroughEveryOperation) {
  const Precision p = GetParam();
  Context& ctx = talus::test::testContext(p);
  Reducer reducer(ctx);
  for (std::size_t n : {std::size_t(1), std::size_t(1000), std::size_t(65537)}) {
    for (std::size_t at : {std::size_t(0), n / 2, n - 1}) {
      std::vector<double> v = randomData(n, p, 3);
      v[at] = std::numeric_limits<double>::quiet_NaN();
      RealBuffer buf(ctx, n);
      buf.upload(v);
      EXPECT_TRUE(std::isnan(reducer.sum(buf, n))) << "n " << n << " NaN at " << at;
      EXPECT_TRUE(std::isnan(reducer.min(buf, n))) << "n " << n << " NaN at " << at;
      EXPECT_TRUE(std::isnan(reducer.max(buf, n))) << "n " << n << " NaN at " << at;
    }
  }
}

TEST_P(Reduce, RowsEqualPerRowReduce) {
  const Precision p = GetParam();
  Context& ctx = talus::test::testContext(p);
  Reducer reducer(ctx);
  const std::vector<ReduceOp> pattern = {ReduceOp::Max, ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Min};
  for (std::size_t n : {std::size_t(1), std::size_t(127), std::size_t(130), std::size_t(4097)}) {
    for (std::size_t rows : {std::size_t(1), std::size_t(5), std::size_t(16)}) {
      SCOPED_TRACE("n = " + std::to_string(n) + ", rows = " + std::to_string(rows));
      std::vector<ReduceOp> ops(rows);
      for (std::size_t r = 0; r < rows; ++r) ops[r] = pattern[r % pattern.size()];
      const std::vector<double> all = randomData(n * rows, p, 31 + static_cast<unsigned>(n * rows));
      RealBuffer buf(ctx, all.size());
      buf.upload(all);
      const std::vector<double> got = reducer.reduceRows(buf, n, ops);
      ASSERT_EQ(got.size(), rows);
      for (std::size_t r = 0; r < rows; ++r) {
        const std::vector<double> row(all.begin() + r * n, all.begin() + (r + 1) * n);
        RealBuffer one(ctx, n);
        one.upload(row);
        const double single = reducer.reduce(one, n, ops[r]);
        if (ops[r] == ReduceOp::Sum) {
          // Different trees (one 128-wide group per row vs up to 64 groups): both within their
          // bounds of the exact sum, hence within the sum of the bounds of each other.
          const double exact = static_cast<double>(std::accumulate(row.begin(), row.end(), 0.0L));
          const double tolRows = sumTolerance(row, n, p, 128), tolOne = sumTolerance(row, n, p, reduceThreads(n));
          EXPECT_NEAR(got[r], exact, tolRows) << "row " << r;
          EXPECT_NEAR(got[r], single, tolRows + tolOne) << "row " << r;
        } else {
          EXPECT_EQ(got[r], single) << "row " << r;  // min/max: exact
        }
      }
    }
  }
}

TEST_P(Reduce, RowsKeepNaNInItsRow) {
  const Precision p = GetParam();
  Context& ctx = talus::test::testContext(p);
  Reducer reducer(ctx);
  const std::size_t n = 500;
  std::vector<double> all = randomData(3 * n, p, 5);
  all[n + 123] = std::numeric_limits<double>::quiet_NaN();  // in row 1 only
  RealBuffer buf(ctx, all.size());
  buf.upload(all);
  for (ReduceOp op : {ReduceOp::Sum, ReduceOp::Min, ReduceOp::Max}) {
    const std::vector<double> got = reducer.reduceRows(buf, n, {op, op, op});
    EXPECT_FALSE(std::isnan(got[0]));
    EXPECT_TRUE(std::isnan(got[1]));
    EXPECT_FALSE(std::isnan(got[2]));
  }
}

TEST_P(Reduce, RowsRejectBadShapes) {
  Context& ctx = talus::test::testContext(GetParam());
  Reducer reducer(ctx);
  RealBuffer buf(ctx, 100);
  EXPECT_THROW(reducer.reduceRows(buf, 10, {}), talus::ComputeError);
  EXPECT_THROW(reducer.reduceRows(buf, 1, std::vector<ReduceOp>(17, ReduceOp::Sum)), talus::ComputeError);
  EXPECT_THROW(reducer.reduceRows(buf, 51, {ReduceOp::Sum, ReduceOp::Sum}), talus::ComputeError);
}

INSTANTIATE_TEST_SUITE_P(, Reduce, ::testing::Values(Precision::Float, Precision::Double),
                         [](const ::testing::TestParamInfo<Precision>& info) {
                           return std::string(precisionName(info.param));
                         });

}  // namespace
