// Rainfall and infiltration as sources and sinks of the water (kernels/flow/water_sources.cl,
// docs/sources.md), in double precision:
//   - the source kernel against its per-cell formula (S1)-(S3), bitwise, on random states;
//   - rain on a flat closed basin: the volume grows by i A t to round-off, the depth stays uniform
//     and the water at rest (also over a rough bed fully under water: well-balanced);
//   - infiltration on a flat plate: the depth falls linearly at the capacity until dry, never below
//     zero, and the removed volume is tallied to round-off;
//   - rain on a tilted plane: the outflow hydrograph at the open lower edge against the analytic
//     kinematic-wave solution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "flow/FlowSolver.hpp"
#include "support/FlowScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;

namespace {

constexpr double kMmPerHour = 1.0 / (3600.0 * 1000.0);  // mm/h -> m/s

fl::FlowInput flatInput(const Grid& g, double h0, double manning) {
  fl::FlowInput in;
  in.mask.assign(g.cells(), 1);
  in.bed.assign(g.cells(), 0.0);
  in.manning.assign(g.cells(), manning);
  in.h.assign(g.cells(), h0);
  return in;
}

fl::FlowSettings closedBasin() {
  fl::FlowSettings s;
  s.edge = fl::Boundary::Wall;
  return s;
}

}  // namespace

// (S1)-(S3) on random depths (some dry, some below Minimum Flow Height), discharges, capacities and
// a random mask, compared bitwise with the same formula evaluated on the host in double.
TEST(WaterSources, KernelMatchesCpuReference) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const Grid g = Grid::make(37, 29, 1.5, 0.0, 0.0);
  std::mt19937 rng(77u);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  fl::FlowInput in = flatInput(g, 0.0, 0.0);
  std::vector<double> f(g.cells());
  in.qx.resize(g.cells());
  in.qy.resize(g.cells());
  for (std::size_t k = 0; k < g.cells(); ++k) {
    in.mask[k] = U(rng) < 0.9 ? 1 : 0;
    const double r = U(rng);
    in.h[k] = r < 0.2 ? 0.0 : r < 0.3 ? 5e-7 : 0.05 * U(rng);
    in.qx[k] = 0.02 * (U(rng) - 0.5);
    in.qy[k] = 0.02 * (U(rng) - 0.5);
    f[k] = 1e-4 * U(rng);
  }
  fl::FlowSettings settings;
  fl::FlowSolver solver(ctx, g, settings);
  solver.setInput(in);
  solver.setInfiltration(f);
  const std::vector<double> h0 = solver.h(), qx0 = solver.qx(), qy0 = solver.qy();
  const double dt = 7.0, rain = 3e-4;
  solver.applySources(dt, rain);
  const std::vector<double> h = solver.h(), qx = solver.qx(), qy = solver.qy();
  double removed = 0;
  int mismatches = 0;
  for (std::size_t k = 0; k < g.cells(); ++k) {
    double eh = h0[k], ex = qx0[k], ey = qy0[k];
    if (in.mask[k]) {
      const double wet = h0[k] + rain;
      const double loss = std::fmin(wet, f[k] * dt);
      eh = wet - loss;
      removed += loss;
      if (eh <= settings.hDry) {
        ex = ey = 0.0;
      } else if (loss > 0) {
        ex *= eh / wet;
        ey *= eh / wet;
      }
    }
    mismatches += (h[k] != eh) + (qx[k] != ex) + (qy[k] != ey);
  }
  EXPECT_EQ(mismatches, 0);
  int inside = 0;
  for (uint8_t m : in.mask) inside += m;
  EXPECT_DOUBLE_EQ(solver.diagnostics().rain, rain * inside * g.dx * g.dx);
  // The device sums the sink in another order than the host loop: round-off of ~n ulps.
  EXPECT_NEAR(solver.diagnostics().infiltrated, removed * g.dx * g.dx, 1e-12 * removed * g.dx * g.dx);
  for (double v : h) EXPECT_GE(v, 0.0);
}

// Rain of 36 mm/h on a dry flat basin closed by walls: after t the depth is i t in every cell, the
// volume i A t, and nothing moves (uniform depth on a flat bed has no pressure gradient). In float
// the depth is a sum of 400 rounded increments (relative error up to ~400 x 6e-8) and the volume a
// float reduction; the discharge stays exactly zero in both precisions.
static void rainOnFlatClosedBasin(Precision precision, double depthTol, double volumeTol) {
  auto& ctx = talus::test::testContext(precision);
  const Grid g = Grid::make(40, 24, 2.0, 0.0, 0.0);  // several 16 x 16 tiles, all dry at the start
  fl::FlowSolver solver(ctx, g, closedBasin());
  solver.setInput(flatInput(g, 0.0, 0.03));
  const double intensity = 36.0 * kMmPerHour;
  double t = 0, rain = 0;
  for (int n = 0; n < 400; ++n) {
    const double dt = std::min(solver.stableDt(), 2.0);
    solver.step(dt, intensity * dt);
    t += dt;
    rain += solver.diagnostics().rain;
  }
  const double area = g.cells() * g.dx * g.dx;
  EXPECT_NEAR(rain, intensity * t * area, 1e-12 * intensity * t * area);
  EXPECT_NEAR(solver.diagnostics().volume, intensity * t * area, volumeTol * intensity * t * area);
  EXPECT_EQ(solver.activeTiles(), solver.tileCount());
  const std::vector<double> h = solver.h(), qx = solver.qx(), qy = solver.qy();
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  std::printf("rain on a flat basin (%s): depth error %.2e, volume error %.2e (relative)\n",
              precision == Precision::Double ? "double" : "float", std::fabs(*lo / (intensity * t) - 1),
              std::fabs(solver.diagnostics().volume / (intensity * t * area) - 1));
  EXPECT_NEAR(*lo, intensity * t, depthTol * intensity * t);
  EXPECT_EQ(*hi, *lo);
  // The maxima follow the rain on tiles that were dry: the deepest so far is the depth now.
  const std::vector<double> hMax = solver.hMax();
  for (std::size_t k = 0; k < g.cells(); ++k) {
    EXPECT_EQ(qx[k], 0.0);
    EXPECT_EQ(qy[k], 0.0);
    EXPECT_EQ(hMax[k], h[k]);
  }
}

TEST(WaterSources, RainOnFlatClosedBasin) { rainOnFlatClosedBasin(Precision::Double, 1e-12, 1e-11); }
TEST(WaterSources, RainOnFlatClosedBasinFloat) { rainOnFlatClosedBasin(Precision::Float, 3e-5, 3e-5); }

// Well-balanced: uniform rain on a lake at rest over a rough bed that is everywhere under water
// raises the surface uniformly and creates no motion beyond round-off.
TEST(WaterSources, RainOnLakeAtRestStaysAtRest) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const Grid g = Grid::make(48, 40, 2.0, 0.0, 0.0);
  const std::vector<double> bed = talus::test::roughDem(g, 4242u, 0.3);
  const double top = *std::max_element(bed.begin(), bed.end());
  const double eta0 = top + 0.2;  // the highest cell under 20 cm of water: no dry islands
  fl::FlowInput in = flatInput(g, 0.0, 0.0);
  in.bed = bed;
  for (std::size_t k = 0; k < g.cells(); ++k) in.h[k] = eta0 - bed[k];
  fl::FlowSolver solver(ctx, g, closedBasin());
  solver.setInput(in);
  const double intensity = 100.0 * kMmPerHour;
  double t = 0;
  for (int n = 0; n < 300; ++n) {
    const double dt = solver.stableDt();
    solver.step(dt, intensity * dt);
    t += dt;
  }
  const std::vector<double> h = solver.h(), qx = solver.qx(), qy = solver.qy();
  double surface = 0, speed = 0;
  for (std::size_t k = 0; k < g.cells(); ++k) {
    surface = std::max(surface, std::fabs(h[k] + bed[k] - (eta0 + intensity * t)));
    speed = std::max({speed, std::fabs(qx[k] / h[k]), std::fabs(qy[k] / h[k])});
  }
  std::printf("rain on a lake at rest: t = %.1f s, max |eta - eta_exact| = %.2e m, max |u| = %.2e m/s\n", t,
              surface, speed);
  // Round-off of eta ~ 2 m in double (4e-16) accumulated over 300 steps.
  EXPECT_LT(surface, 1e-12);
  EXPECT_LT(speed, 1e-12);
}

// Constant-rate infiltration on a flat plate: h(t) = max(0, h0 - f t) in every cell (step by step
// the kernel removes min(h, f dt)); the depth stays uniform, so nothing moves, and the last step
// removes only what is left (never below zero).
TEST(WaterSources, InfiltrationOnFlatPlate) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const Grid g = Grid::make(32, 20, 5.0, 0.0, 0.0);
  const double h0 = 0.01, f = 60.0 * kMmPerHour;  // 60 mm/h: dry after 600 s
  fl::FlowSolver solver(ctx, g, closedBasin());
  solver.setInput(flatInput(g, h0, 0.03));
  solver.setInfiltration(std::vector<double>(g.cells(), f));
  const double volume0 = h0 * g.cells() * g.dx * g.dx;
  double t = 0, removed = 0;
  const double dt = 7.0;  // 600 s is not a multiple of it: the last wet step removes less than f dt
  while (t < 800.0) {
    solver.step(dt);
    t += dt;
    removed += solver.diagnostics().infiltrated;
    const std::vector<double> h = solver.h();
    const double expect = std::max(0.0, h0 - f * t);
    const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
    // h0 - f t accumulated over ~100 subtractions of f dt: a few ulps of 0.01.
    ASSERT_NEAR(*lo, expect, 1e-16) << "t = " << t << " s";
    ASSERT_EQ(*lo, *hi) << "t = " << t << " s";
    ASSERT_GE(*lo, 0.0);
    ASSERT_NEAR(solver.diagnostics().volume + removed, volume0, 1e-13 * volume0) << "t = " << t << " s";
  }
  EXPECT_NEAR(removed, volume0, 1e-13 * volume0);
  EXPECT_EQ(solver.diagnostics().volume, 0.0);
}

// Rain and infiltration act on the fluid phase of the two-phase model: a uniform 1 m layer of solids
// at rest on a flat closed basin under 72 mm/h of rain and 18 mm/h of infiltration capacity. The
// solid volume is unchanged to the bit, the fluid volume is the rain minus what infiltrated (the
// capacity, once water stands), every cell holds the same fluid depth and nothing moves: a uniform
// mixture on a flat bed has no gradient to drive it. Tolerances: round-off of 200 steps (double).
TEST(WaterSources, RainFallsIntoTheFluidPhaseOfTheTwoPhaseModel) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const Grid g = Grid::make(40, 24, 2.0, 0.0, 0.0);
  fl::FlowSettings s = closedBasin();
  s.twoPhase = true;
  fl::FlowSolver solver(ctx, g, s);
  fl::FlowInput in = flatInput(g, 0.0, 0.0);
  in.hs.assign(g.cells(), 1.0);
  solver.setInput(in);
  solver.setInfiltration(std::vector<double>(g.cells(), 18.0 * kMmPerHour));
  const double solid0 = solver.diagnostics().volumeSolid;
  const double intensity = 72.0 * kMmPerHour;
  double rain = 0, infiltrated = 0;
  for (int n = 0; n < 200; ++n) {
    const double dt = std::min(solver.stableDt(), 0.5);
    solver.step(dt, intensity * dt);
    rain += solver.diagnostics().rain;
    infiltrated += solver.diagnostics().infiltrated;
  }
  const fl::FlowDiagnostics& d = solver.diagnostics();
  EXPECT_EQ(d.volumeSolid, solid0);
  EXPECT_GT(infiltrated, 0.0);
  EXPECT_NEAR(d.volume, rain - infiltrated, 1e-12 * rain);
  const std::vector<double> h = solver.h(), qsx = solver.qsx(), qx = solver.qx();
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  EXPECT_NEAR(*hi - *lo, 0.0, 1e-15);
  EXPECT_NEAR(*lo * g.cells() * g.dx * g.dx, rain - infiltrated, 1e-12 * rain);
  for (std::size_t k = 0; k < g.cells(); ++k) {
    EXPECT_EQ(qsx[k], 0.0) << k;
    EXPECT_EQ(qx[k], 0.0) << k;
  }
}
