// The SPH kernel of the particle mode (kernels/particles/sph.cl, spec §5 P.74-P.77), evaluated on the
// device (double) and checked analytically:
//  - normalisation: the integral of W over the plane, 2 pi int_0^2h r W dr, is 1 (composite
//    Simpson on 4000 intervals: error below 1e-10 for this piecewise cubic; measured ~1e-15);
//  - derivative: dW/dr equals the central difference (W(r + e) - W(r - e)) / 2e on both branches
//    (e = 1e-6 h: truncation e^2 W''' / 6 ~ 1e-12, round-off 1e-16 / e ~ 1e-10, relative to max|dW/dr|);
//  - continuity of W and dW/dr at q = 1 and q = 2 (both branches agree to round-off), and dW/dr
//    = 0 at r = 0 and W = 0 beyond 2h.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Kernel.hpp"
#include "compute/Program.hpp"
#include "support/TestDevice.hpp"

using namespace talus;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Probe {
  std::vector<double> w, dw;
};

Probe probe(const std::vector<double>& r, double h) {
  compute::Context& ctx = test::testContext(compute::Precision::Double);
  compute::RealBuffer rb(ctx, r.size()), wb(ctx, r.size()), db(ctx, r.size());
  rb.upload(r);
  compute::Kernel k(ctx.program("particles/sph_probe.cl"), "sph_probe");
  k.bind(rb, compute::RealArg{h}, static_cast<int>(r.size()), wb, db);
  k.launch(compute::Range{r.size()});
  return {wb.download(), db.download()};
}

}  // namespace

TEST(SphKernel, IntegratesToOneOverThePlane) {
  for (double h : {0.37, 1.0, 10.0}) {
    const int n = 4000;
    std::vector<double> r(n + 1);
    for (int i = 0; i <= n; ++i) r[i] = 2 * h * i / n;
    const Probe p = probe(r, h);
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
      const double f = 2 * kPi * r[i] * p.w[i];
      sum += f * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
    }
    sum *= (2 * h / n) / 3;
    EXPECT_NEAR(sum, 1.0, 1e-10) << "h " << h;
  }
}

TEST(SphKernel, DerivativeMatchesFiniteDifferencesOnBothBranches) {
  const double h = 0.8, e = 1e-6 * h;
  std::vector<double> r;
  for (double q = 0.05; q < 1.999; q += 0.0371) r.push_back(q * h);
  std::vector<double> plus(r), minus(r);
  for (std::size_t i = 0; i < r.size(); ++i) plus[i] += e, minus[i] -= e;
  const Probe p = probe(r, h), pp = probe(plus, h), pm = probe(minus, h);
  double maxDw = 0;
  for (double d : p.dw) maxDw = std::max(maxDw, std::fabs(d));
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (std::fabs(r[i] / h - 1) < 2e-6) continue;  // the difference straddles the branch point
    const double fd = (pp.w[i] - pm.w[i]) / (2 * e);
    EXPECT_NEAR(p.dw[i], fd, 1e-8 * maxDw) << "q " << r[i] / h;
  }
}

TEST(SphKernel, ContinuousAtTheBranchPointsAndZeroOutside) {
  const double h = 1.3, t = 1e-12;
  const Probe p = probe({h * (1 - t), h * (1 + t), h * (2 - t), 2 * h, 2.5 * h, 0.0}, h);
  EXPECT_NEAR(p.w[0], p.w[1], 1e-10);
  EXPECT_NEAR(p.dw[0], p.dw[1], 1e-10);
  EXPECT_NEAR(p.dw[0], -0.75 * 10 / (7 * kPi * h * h * h), 1e-10);  // both branches give -3/4 s/h^3
  EXPECT_NEAR(p.w[2], 0.0, 1e-10);
  EXPECT_NEAR(p.dw[2], 0.0, 1e-10);
  EXPECT_EQ(p.w[3], 0.0);
  EXPECT_EQ(p.w[4], 0.0);
  EXPECT_EQ(p.dw[4], 0.0);
  EXPECT_NEAR(p.w[5], 10 / (7 * kPi * h * h), 1e-14);
  EXPECT_EQ(p.dw[5], 0.0);
}
