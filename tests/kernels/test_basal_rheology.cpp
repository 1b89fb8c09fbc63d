// The solids' basal laws (kernels/flow/basal_rheology.cl, through its test kernel
// basal_rheology_test) against the independent host reference support/BasalRheologyReference, in
// double and float: random columns (thickness 1 mm to 10 m, slopes up to 60 degrees, buoyancy,
// curvature-scaled normal gravity, snow to rock densities, source steps 1e-4 to 0.1 s) and random
// parameters of each law, with momenta from far below the held threshold to far above it.
//
// Tolerances, on the factor q / q* (in [0, 1], so relative to q*). The reference solves the same
// implicit step by bisection to round-off in double (Herschel-Bulkley: its speed by Simpson
// quadrature of the velocity profile, accurate to ~1e-10 for flow indices n <= 1, measured against
// the closed form; for n = 2 to ~1e-5, see the last test). The device uses closed forms (Coulomb,
// Voellmy, mu(I)) or a bracketed Newton iteration (Herschel-Bulkley): each a chain of ~20 operations
// on values of scale q*, hence a few ulps of q*: we allow 1e-9 in double and 2e-5 in float (inputs
// rounded to float first, so the reference sees the same values). A wrong term or factor changes
// the result by the size of the stress term itself, ds T / q* ~ 1e-3 to 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "core/Constants.hpp"
#include "flow/DebrisParams.hpp"
#include "flow/Rheology.hpp"
#include "support/BasalRheologyReference.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus;
using compute::Precision;
using flow::Rheology;
using test::BasalColumnRef;

constexpr double kDeg = M_PI / 180.0;
constexpr int kIn = 10;  // BASAL_TEST_IN

struct Case {
  BasalColumnRef c;
  double qStar = 0, ds = 0;
};

class BasalRheologyTest : public ::testing::TestWithParam<Precision> {
 protected:
  bool isDouble() const { return GetParam() == Precision::Double; }
  compute::Context& ctx() const { return test::testContext(GetParam()); }
  double dev(double x) const { return isDouble() ? x : static_cast<double>(static_cast<float>(x)); }
  double tol() const { return isDouble() ? 1e-9 : 2e-5; }

  /// Rounds the inputs to the device's precision.
  Case rounded(Case k) const {
    BasalColumnRef& c = k.c;
    for (double* v : {&c.hSt, &c.h, &c.nG, &c.gN, &c.cosT, &c.stretch, &c.rho, &c.tanDelta, &k.qStar, &k.ds}) *v = dev(*v);
    return k;
  }
  std::array<double, 4> rounded(std::array<double, 4> p) const {
    for (double& v : p) v = dev(v);
    return p;
  }

  /// q / q* of every case on the device (or, with `entry` basal_strength_test, each column's strength at rest).
  std::vector<double> runDevice(Rheology law, const std::array<double, 4>& rheo, const std::vector<Case>& cases,
                                const char* entry = "basal_rheology_test") const {
    flow::DebrisSettings d;
    d.rheology = law;
    d.rheologyParams = rheo;
    compute::RawBuffer params(ctx(), sizeof(flow::DebrisParamsT<double>), "debris parameters");
    flow::writeDebrisParams(params, d, GetParam());
    std::vector<double> in;
    for (const Case& k : cases) {
      const BasalColumnRef& c = k.c;
      for (double v : {c.hSt, c.h, c.nG, c.gN, c.cosT, c.stretch, c.rho, c.tanDelta, k.qStar, k.ds}) in.push_back(v);
    }
    compute::RealBuffer inBuf(ctx(), in.size(), "basal in"), outBuf(ctx(), cases.size(), "basal out");
    inBuf.upload(in);
    compute::Kernel k(ctx().program("flow/basal_rheology_test.cl"), entry);
    k.bind(params, inBuf, outBuf, static_cast<int>(cases.size()));
    k.launch(compute::Range{cases.size()});
    return outBuf.download();
  }

  /// Random columns whose momentum spans 0.1 to 1e4 times `threshold(column, ds)` (the momentum
  /// the law holds at rest, or a stress scale).
  std::vector<Case> randomCases(unsigned seed, std::size_t n, double (*threshold)(const Case&, const std::array<double, 4>&),
                                const std::array<double, 4>& rheo) const {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, uni(rng)); };
    std::vector<Case> cases(n);
    for (Case& k : cases) {
      BasalColumnRef& c = k.c;
      const double theta = 60.0 * kDeg * uni(rng);
      c.cosT = std::cos(theta);
      c.stretch = 1.0 + (1.0 / c.cosT - 1.0) * 1.2 * uni(rng);  // up to beyond the plane's 1/cos
      c.gN = kGravity * c.cosT * c.cosT * (0.8 + 0.4 * uni(rng));
      c.nG = c.gN * (0.3 + 0.7 * uni(rng));
      c.h = logUniform(1e-3, 10.0);
      c.hSt = c.h * (0.5 + uni(rng));
      c.rho = 200.0 + 2800.0 * uni(rng);
      c.tanDelta = 0.1 + 0.9 * uni(rng);
      k.ds = logUniform(1e-4, 0.1);
      k.qStar = threshold(k, rheo) * logUniform(0.1, 1e4);
      k = rounded(k);
    }
    return cases;
  }

  /// Compares device and reference over the cases; returns the largest difference.
  double compare(Rheology law, const std::array<double, 4>& rheoIn, const std::vector<Case>& cases, double tolerance,
                 bool canHold = true) const {
    const std::array<double, 4> rheo = rounded(rheoIn);
    const std::vector<double> got = runDevice(law, rheo, cases);
    double worst = 0;
    int held = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const double ref = test::basalFactorRef(law, rheo, cases[i].c, cases[i].qStar, cases[i].ds);
      EXPECT_GE(got[i], 0.0) << "case " << i;
      EXPECT_LE(got[i], 1.0) << "case " << i;
      EXPECT_NEAR(got[i], ref, tolerance) << "case " << i << " q* " << cases[i].qStar << " h " << cases[i].c.h;
      worst = std::max(worst, std::fabs(got[i] - ref));
      held += ref == 0.0;
    }
    // The cases must exercise both held and moving columns (a law without a yield never holds).
    if (canHold)
      EXPECT_GT(held, 0) << "no held case";
    else
      EXPECT_EQ(held, 0) << "held without a yield stress";
    EXPECT_LT(held, static_cast<int>(cases.size()) * 9 / 10) << "too few moving cases";
    if (std::getenv("TALUS_TEST_VERBOSE"))
      std::printf("law %d: worst |device - reference| %.3g (%d of %zu held)\n", static_cast<int>(law), worst, held, cases.size());
    return worst;
  }
};

double coulombThreshold(const Case& k, const std::array<double, 4>&) { return k.ds * k.c.tanDelta * k.c.nG * k.c.hSt; }
double voellmyThreshold(const Case& k, const std::array<double, 4>& p) { return k.ds * p[0] * k.c.nG * k.c.hSt; }
double muIThreshold(const Case& k, const std::array<double, 4>& p) { return k.ds * p[1] * k.c.nG * k.c.hSt; }
double hbThreshold(const Case& k, const std::array<double, 4>& p) {
  return k.ds * std::max(p[0], 100.0) / (k.c.rho * k.c.cosT * k.c.stretch);
}

TEST_P(BasalRheologyTest, CoulombMatchesReference) {
  compare(Rheology::Coulomb, {0, 0, 0, 0}, randomCases(1, 400, coulombThreshold, {}), tol());
}

TEST_P(BasalRheologyTest, VoellmyMatchesReference) {
  for (unsigned s = 0; s < 4; ++s) {
    const double mu = 0.05 + 0.15 * s, xi = 100.0 * std::pow(10.0, s * 0.7);
    const std::array<double, 4> p = {mu, kGravity / xi, 0, 0};
    compare(Rheology::Voellmy, p, randomCases(10 + s, 300, voellmyThreshold, p), tol());
  }
}

TEST_P(BasalRheologyTest, MuIMatchesReference) {
  for (unsigned s = 0; s < 4; ++s) {
    const double z1 = (15.0 + 3.0 * s) * kDeg, z2 = z1 + (5.0 + 3.0 * s) * kDeg;
    const double beta = 0.05 + 0.15 * s, L = 1e-4 * std::pow(10.0, s * 1.2);
    const std::array<double, 4> p = {std::tan(z1), std::tan(z2), beta, L};
    compare(Rheology::MuI, p, randomCases(20 + s, 300, muIThreshold, p), tol());
  }
}

TEST_P(BasalRheologyTest, HerschelBulkleyMatchesReference) {
  // Bingham (n = 1) and shear-thinning muds, with and without a yield stress.
  const double n[] = {1.0, 0.33, 0.5, 0.2, 1.0};
  const double ty[] = {1000.0, 200.0, 0.0, 3000.0, 0.0};
  for (unsigned s = 0; s < 5; ++s) {
    const std::array<double, 4> p = {ty[s], 10.0 * std::pow(10.0, s * 0.5), n[s], 0};
    compare(Rheology::HerschelBulkley, p, randomCases(30 + s, 200, hbThreshold, p), tol(), ty[s] > 0);
  }
}

TEST_P(BasalRheologyTest, ShearThickeningHerschelBulkley) {
  // n = 2: the reference's quadrature of the profile (rate ~ sqrt(distance to the plug)) is good to
  // ~1e-5 of the speed (measured 5e-6 against the closed form at r = 0.9), which bounds the factor
  // difference at that level; 5e-5 allows it.
  const std::array<double, 4> p = {500.0, 50.0, 2.0, 0};
  compare(Rheology::HerschelBulkley, p, randomCases(40, 200, hbThreshold, p), std::max(tol(), 5e-5));
}

TEST_P(BasalRheologyTest, HeldColumnsAreExactlyAtRest) {
  // Well below each law's threshold the factor is exactly zero: the cell is "locked" (debris_stage).
  std::vector<Case> cases(1);
  cases[0].c = BasalColumnRef{};
  cases[0].ds = 0.01;
  cases[0].c.tanDelta = 0.6;
  const double coulomb = coulombThreshold(cases[0], {});
  cases[0].qStar = dev(0.5 * coulomb);
  EXPECT_EQ(runDevice(Rheology::Coulomb, {0, 0, 0, 0}, cases)[0], 0.0);
  EXPECT_EQ(runDevice(Rheology::Voellmy, {0.6, kGravity / 1000.0, 0, 0}, cases)[0], 0.0);
  // mu(I): below mu_stop(H) = 0.5 + 0.3 / (1 + 1/0.1) ~ 0.527 > 0.3 (q* / (ds n_g h)).
  EXPECT_EQ(runDevice(Rheology::MuI, rounded(std::array<double, 4>{0.5, 0.8, 0.136, 0.1}), cases)[0], 0.0);
  // Herschel-Bulkley: q* = 0.5 coulomb ~ 0.0294 m^2/s <= ds tau_y / rho = 0.05.
  EXPECT_EQ(runDevice(Rheology::HerschelBulkley, {10000.0, 10.0, 1.0, 0}, cases)[0], 0.0);
}

// The strength at rest (basal_strength) that the static contact of debris_stage bounds a face's
// push with (solid_bed.cl, point 6) is each law's yield threshold: it equals the independent
// formula (Coulomb tan(delta) n_g h, Voellmy mu n_g h, mu(I) mu_stop(H) n_g h with mu_stop of
// Pouliquen & Forterre 2002, Herschel-Bulkley tau_y / (rho cos(theta) s)) to round-off, and the law
// holds a column pushed with ds times it less one part in 1e6 (1e-4 in float, whose q* rounds at
// 6e-8) and moves one pushed with one part more (5 parts in 100 for Herschel-Bulkley, whose speed
// starts as (tau - tau_y)^(1 + 1/n): just above the yield its q is below the round-off of q* - m tau).
TEST_P(BasalRheologyTest, StrengthAtRestIsEachLawsYieldThreshold) {
  const double rel = isDouble() ? 1e-6 : 1e-4;
  struct Law {
    Rheology law;
    std::array<double, 4> rheo;
    double (*formula)(const BasalColumnRef&, const std::array<double, 4>&);
  };
  const Law laws[] = {
      {Rheology::Coulomb, {0, 0, 0, 0}, [](const BasalColumnRef& c, const std::array<double, 4>&) { return c.tanDelta * c.nG * c.hSt; }},
      {Rheology::Voellmy, {0.35, kGravity / 2000.0, 0, 0},
       [](const BasalColumnRef& c, const std::array<double, 4>& p) { return p[0] * c.nG * c.hSt; }},
      {Rheology::MuI, {0.38, 0.64, 0.136, 0.00065},
       [](const BasalColumnRef& c, const std::array<double, 4>& p) {
         return (p[0] + (p[1] - p[0]) / (1.0 + c.h * c.cosT / p[3])) * c.nG * c.hSt;
       }},
      {Rheology::HerschelBulkley, {800.0, 40.0, 0.5, 0},
       [](const BasalColumnRef& c, const std::array<double, 4>& p) { return p[0] / (c.rho * c.cosT * c.stretch); }},
  };
  for (const Law& l : laws) {
    const std::array<double, 4> rheo = rounded(l.rheo);
    std::vector<Case> cases = randomCases(41u, 300, coulombThreshold, rheo);
    const std::vector<double> strength = runDevice(l.law, rheo, cases, "basal_strength_test");
    std::vector<Case> below = cases, above = cases;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const double ref = l.formula(cases[i].c, rheo);
      EXPECT_NEAR(strength[i], ref, (isDouble() ? 1e-13 : 1e-6) * ref) << "law " << static_cast<int>(l.law) << " case " << i;
      below[i].qStar = dev(cases[i].ds * strength[i] * (1.0 - rel));
      above[i].qStar = dev(cases[i].ds * strength[i] * (1.0 + (l.law == Rheology::HerschelBulkley ? 5e-2 : rel)));
    }
    const std::vector<double> held = runDevice(l.law, rheo, below), moving = runDevice(l.law, rheo, above);
    for (std::size_t i = 0; i < cases.size(); ++i) {
      EXPECT_EQ(held[i], 0.0) << "law " << static_cast<int>(l.law) << " case " << i << ": pushed just below its strength";
      EXPECT_GT(moving[i], 0.0) << "law " << static_cast<int>(l.law) << " case " << i << ": pushed just above its strength";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, BasalRheologyTest, ::testing::Values(Precision::Double, Precision::Float),
                         [](const ::testing::TestParamInfo<Precision>& i) {
                           return std::string(i.param == Precision::Double ? "Double" : "Float");
                         });

}  // namespace
