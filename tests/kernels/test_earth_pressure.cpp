// The Savage-Hutter earth-pressure coefficient and its active-passive ramp (kernels/common/
// earth_pressure.cl), which the grid's solids and the particles share, against:
//  - the host formula of Savage & Hutter (1989, eq. 3.5), K = 2 (1 -+ sqrt(1 - cos^2 phi / cos^2 delta))
//    / cos^2 phi - 1, blended linearly from active to passive over the contraction rates
//    0 .. 0.1 sqrt(g_n / H), written here independently, on random cases;
//  - Rankine's coefficients, which it reduces to on a frictionless bed (delta = 0):
//    K_act = (1 - sin phi) / (1 + sin phi), K_pass = 1 / K_act;
//  - continuity: no jump at the onset of contraction (the particles used to switch K there).
// Tolerances: 1e-12 relative in double (a few operations of round-off on O(1) values, the cosines
// of the device and the host may differ in the last bit), 1e-5 in float.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "support/TestDevice.hpp"

using talus::compute::Precision;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct Case {
  double phi, delta, rate, gn, H;
};

double hostK(const Case& c) {
  const double r = 1.0 - std::pow(std::cos(c.phi), 2) / std::pow(std::cos(c.delta), 2);
  const double root = r > 0 ? std::sqrt(r) : 0.0;
  const double kAct = 2.0 * (1.0 - root) / std::pow(std::cos(c.phi), 2) - 1.0;
  const double kPass = 2.0 * (1.0 + root) / std::pow(std::cos(c.phi), 2) - 1.0;
  const double share = std::clamp(c.rate / (0.1 * std::sqrt(c.gn / c.H)), 0.0, 1.0);
  return kAct + share * (kPass - kAct);
}

std::vector<double> deviceK(Precision precision, const std::vector<Case>& cases) {
  talus::compute::Context& ctx = talus::test::testContext(precision);
  std::vector<double> in;
  for (const Case& c : cases)
    for (double v : {c.phi, c.delta, c.rate, c.gn, c.H}) in.push_back(v);
  talus::compute::RealBuffer inBuf(ctx, in.size(), "earth pressure in"), out(ctx, cases.size(), "earth pressure out");
  inBuf.upload(in);
  talus::compute::Kernel k(ctx.program("common/earth_pressure_test.cl"), "earth_pressure_test");
  k.bind(inBuf, out, static_cast<int>(cases.size()));
  k.launch(talus::compute::Range{cases.size()});
  return out.download();
}

class EarthPressure : public ::testing::TestWithParam<Precision> {
 protected:
  double tol() const { return GetParam() == Precision::Double ? 1e-12 : 1e-5; }
};

}  // namespace

TEST_P(EarthPressure, RampMatchesSavageHutterOnRandomCases) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<Case> cases(4000);
  for (Case& c : cases) {
    c.phi = (15.0 + 30.0 * uni(rng)) * kDeg;
    c.delta = (5.0 + 45.0 * uni(rng)) * kDeg;  // also beyond phi: the root clipped at zero
    c.gn = 4.0 + 5.8 * uni(rng);
    c.H = 0.01 * std::pow(1000.0, uni(rng));
    c.rate = (3.0 * uni(rng) - 1.0) * 0.1 * std::sqrt(c.gn / c.H);  // extending, ramping, saturated
  }
  const std::vector<double> k = deviceK(GetParam(), cases);
  double worst = 0;
  for (std::size_t q = 0; q < cases.size(); ++q) worst = std::max(worst, std::fabs(k[q] - hostK(cases[q])) / hostK(cases[q]));
  std::printf("earth pressure: worst relative difference to the host formula %.2e over %zu cases\n", worst, cases.size());
  EXPECT_LE(worst, tol());
}

TEST_P(EarthPressure, FrictionlessBedGivesRankine) {
  std::vector<Case> cases;
  for (double phiDeg : {20.0, 30.0, 40.0}) {
    cases.push_back({phiDeg * kDeg, 0.0, -1.0, 9.81, 1.0});  // extending: active
    cases.push_back({phiDeg * kDeg, 0.0, 10.0, 9.81, 1.0});  // contracting fast: passive
  }
  const std::vector<double> k = deviceK(GetParam(), cases);
  for (std::size_t q = 0; q < cases.size(); q += 2) {
    const double s = std::sin(cases[q].phi), kAct = (1 - s) / (1 + s);
    EXPECT_NEAR(k[q], kAct, tol() * 10 * kAct) << cases[q].phi / kDeg;
    EXPECT_NEAR(k[q + 1], 1 / kAct, tol() * 10 / kAct) << cases[q].phi / kDeg;
  }
}

TEST_P(EarthPressure, NoJumpAtTheOnsetOfContraction) {
  // phi 35, delta 25: K_act 0.70, K_pass 3.25 (a switch would jump by 2.55 between the two rates).
  const double scale = 0.1 * std::sqrt(9.81 / 1.0);
  const std::vector<Case> cases = {{35 * kDeg, 25 * kDeg, -1e-9 * scale, 9.81, 1.0},
                                   {35 * kDeg, 25 * kDeg, 1e-9 * scale, 9.81, 1.0}};
  const std::vector<double> k = deviceK(GetParam(), cases);
  EXPECT_GT(hostK({35 * kDeg, 25 * kDeg, 10.0, 9.81, 1.0}) - k[0], 2.5);  // the gap a switch would jump
  EXPECT_NEAR(k[1], k[0], 1e-8 * 2.55 + tol() * k[0]);                   // the ramp: 1e-9 of the gap
}

INSTANTIATE_TEST_SUITE_P(Precisions, EarthPressure, ::testing::Values(Precision::Double, Precision::Float),
                         [](const ::testing::TestParamInfo<Precision>& i) {
                           return i.param == Precision::Double ? std::string("Double") : std::string("Float");
                         });
