// Thacker's planar oscillation in a paraboloid (Thacker 1981; SWASHES section 4.2.2, Delestre et
// al. 2013): a tilted planar lake in the bowl b = -h0 (1 - r^2 / a^2) whose wet disk circles the
// vertex at radius eta with period 2 pi a / sqrt(2 g h0), every part of it moving with the same
// velocity. SWASHES parameters: a = 1 m, h0 = 0.1 m, eta = 0.5 m, domain [0, 4]^2 m, vertex at
// (2, 2). The wet disk never comes closer than 0.5 m to the boundary, so walls on the raster edge
// change nothing except making the volume budget closed.
//
// The test runs one full period, after which the exact state equals the initial one, and measures
// the L1 error of h [m^3] against the exact depth at the cell centres (the scene is sampled at cell
// centres too, as in SWASHES), the error of the water's centre of mass, the observed orders and the
// volume balance. Classical SWE: slope correction off, frictionless.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/Analytic.hpp"
#include "support/FlowScene.hpp"
#include "verification/ValidationOut.hpp"

namespace an = talus::analytic;
namespace fl = talus::flow;
using talus::Grid;
using talus::test::cellX;
using talus::test::cellY;

namespace {

constexpr double kDomain = 4.0;

struct ThackerErrors {
  int n = 0;
  double errH = 0;       ///< L1 of h after one period [m^3]
  double errCentre = 0;  ///< distance of the centre of mass from the exact one [m]
  double volumeDrift = 0;  ///< |V(T) - V(0)| / V(0) from the solver's diagnostics
  double hostVolumeDrift = 0;  ///< same, from the downloaded depths
  int steps = 0;
  double seconds = 0;
};

ThackerErrors runThacker(int n, fl::TimeScheme scheme = fl::TimeScheme::Unsplit, double cfl = 0.5) {
  const an::ThackerPlanar th;  // SWASHES parameters
  const double dx = kDomain / n;
  const Grid grid = Grid::make(n, n, dx);
  const double v0 = th.v(0.0), u0 = th.u(0.0);
  const auto input = talus::test::makeInput(
      grid, [&](double x, double y) { return th.bed(x, y); }, [&](double x, double y) { return th.h(x, y, 0.0); },
      [&](double x, double y) { return th.h(x, y, 0.0) * u0; },
      [&](double x, double y) { return th.h(x, y, 0.0) * v0; });
  fl::FlowSettings settings;
  settings.edge = fl::Boundary::Wall;
  settings.slopeCorrection = false;  // the exact solution is for classical SWE with g
  settings.scheme = scheme;
  settings.cfl = cfl;
  const double period = th.period();
  const auto run = talus::test::runFlow(grid, input, settings, talus::test::RunLimits::until(period));
  EXPECT_NEAR(run.time, period, 1e-12 * period);

  ThackerErrors e;
  e.n = n;
  e.steps = run.steps;
  e.seconds = run.wallSeconds;
  double hostV0 = 0, hostV = 0, mx = 0, my = 0;
  std::vector<double> hRef(grid.cells());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::size_t k = grid.index(i, j);
      const double x = cellX(grid, i), y = cellY(grid, j);
      hRef[k] = th.h(x, y, period);
      hostV0 += input.h[k];
      hostV += run.h[k];
      mx += run.h[k] * x;
      my += run.h[k] * y;
    }
  e.errH = an::l1(run.h, hRef, dx * dx);
  // The exact depth is symmetric about the centre of the wet disk, which after one period is back
  // at (xc + eta, yc).
  e.errCentre = std::hypot(mx / hostV - (th.xc + th.eta), my / hostV - th.yc);
  e.volumeDrift = std::fabs(run.volume - run.volume0) / run.volume0;
  e.hostVolumeDrift = std::fabs(hostV - hostV0) / hostV0;
  if (scheme == fl::TimeScheme::Unsplit && talus::test::validation::enabled()) {  // the row through the vertex (y = yc + dx/2)
    talus::test::validation::Table t({"x_m", "y_m", "bed_m", "h_m", "h_exact_m", "h0_m"});
    const int j = n / 2;
    for (int i = 0; i < n; ++i) {
      const std::size_t k = grid.index(i, j);
      t.add({cellX(grid, i), cellY(grid, j), th.bed(cellX(grid, i), cellY(grid, j)), run.h[k], hRef[k], input.h[k]});
    }
    t.write("thacker_profile_n" + std::to_string(n) + ".csv");
  }
  return e;
}

void report(const std::vector<ThackerErrors>& e, const std::string& csv = "thacker_errors.csv") {
  std::printf("[ Thacker planar, one period %.4f s, van Leer, HLLC ]\n", an::ThackerPlanar{}.period());
  for (std::size_t k = 0; k < e.size(); ++k) {
    std::printf("  %4d^2  L1(h) %.4e m^3", e[k].n, e[k].errH);
    if (k > 0) std::printf(" (order %.3f)", an::observedOrder(e[k - 1].errH, e[k].errH, 2.0));
    std::printf("  centre %.4e m", e[k].errCentre);
    if (k > 0) std::printf(" (order %.3f)", an::observedOrder(e[k - 1].errCentre, e[k].errCentre, 2.0));
    std::printf("  dV/V %.1e (host %.1e)  %d steps %.2f s\n", e[k].volumeDrift, e[k].hostVolumeDrift, e[k].steps,
                e[k].seconds);
  }
  std::fflush(stdout);
  if (talus::test::validation::enabled()) {
    talus::test::validation::Table t(
        {"n", "dx_m", "l1_h_m3", "order_h", "centre_error_m", "order_centre", "volume_drift", "steps"});
    for (std::size_t k = 0; k < e.size(); ++k) {
      const bool o = k > 0;
      t.add({e[k].n, kDomain / e[k].n, e[k].errH, o ? an::observedOrder(e[k - 1].errH, e[k].errH, 2.0) : std::nan(""),
             e[k].errCentre, o ? an::observedOrder(e[k - 1].errCentre, e[k].errCentre, 2.0) : std::nan(""),
             e[k].volumeDrift, e[k].steps});
    }
    t.write(csv);
  }
}

}  // namespace

// Minimum observed L1 order of h between 100^2 and 200^2. The depth is smooth inside the wet disk
// but has a kink (slope jump) at the moving shoreline, where the hydrostatic reconstruction and
// the limiter fall back to first order and a band of O(dx) cells is partly wet, so the L1 order is
// bounded by the front, between 1 and 2 (1.5 measured: the front is a kink, not a jump). 0.7 is
// the documented floor for wet/dry fronts and fails only if the front treatment degrades.
constexpr double kMinOrder = 0.7;
// Volume: walls everywhere and no source of mass, so the volume changes only by round-off in the
// flux differences and the reductions; relative 1e-12 is about 5000 eps, far above the 2e-15
// measured after ~1300 steps (the sum of interior flux differences cancels in pairs).
constexpr double kVolumeTol = 1e-12;

TEST(Thacker, PlanarOscillationOnePeriod) {
  // 200^2 takes 17 to 25 s on two PoCL cores (1289 steps), inside the suite's budget.
  std::vector<ThackerErrors> e;
  for (int n : {50, 100, 200}) e.push_back(runThacker(n));
  report(e);
  for (std::size_t k = 1; k < e.size(); ++k) {
    EXPECT_LT(e[k].errH, e[k - 1].errH) << "L1(h) grew from " << e[k - 1].n << "^2 to " << e[k].n << "^2";
    EXPECT_LT(e[k].errCentre, e[k - 1].errCentre) << "centre error grew from " << e[k - 1].n << "^2";
  }
  for (const auto& r : e) {
    EXPECT_LT(r.volumeDrift, kVolumeTol) << r.n << "^2";
    EXPECT_LT(r.hostVolumeDrift, kVolumeTol) << r.n << "^2";
  }
  const double orderH = an::observedOrder(e[1].errH, e[2].errH, 2.0);
  const double orderCentre = an::observedOrder(e[1].errCentre, e[2].errCentre, 2.0);
  RecordProperty("thacker_l1_h_200", std::to_string(e[2].errH));
  RecordProperty("thacker_order_h", std::to_string(orderH));
  RecordProperty("thacker_centre_error_200", std::to_string(e[2].errCentre));
  RecordProperty("thacker_order_centre", std::to_string(orderCentre));
  EXPECT_GE(orderH, kMinOrder);
  EXPECT_GE(orderCentre, kMinOrder);
}

// The dimensionally split scheme (Time Scheme=split) on the same oscillation: the water moves
// diagonally (u and v alike), so its per-direction time step is about twice the unsplit one, and
// the test checks that the accuracy holds at that step. References: the exact solution (errors
// decrease, order above the wet/dry floor kMinOrder) and the volume budget (kVolumeTol), as above;
// and the unsplit scheme's error on the same grid, which the split one may exceed by at most 25 %:
// Lie splitting with alternated order is second order like the SSP-RK2 stages it is made of, and
// both errors are dominated by the first-order shoreline, so they agree to well within that margin
// unless the splitting itself is inconsistent (a sweep of one direction's faces that missed a term
// gives errors of order one). Steps: the split run must take fewer than 0.7 of the unsplit steps
// (dt = cfl dx / max(max(|u|, |v|) + c) against cfl dx / max(|u| + |v| + 2 c): close to a half).
TEST(Thacker, SplitSchemeOnePeriod) {
  std::vector<ThackerErrors> split;
  for (int n : {50, 100}) split.push_back(runThacker(n, fl::TimeScheme::Split));
  const ThackerErrors unsplit = runThacker(100);
  std::printf("[ Thacker planar, split time scheme ]\n");
  report(split, "thacker_split_errors.csv");
  std::printf("  unsplit 100^2: L1(h) %.4e m^3, centre %.4e m, %d steps\n", unsplit.errH, unsplit.errCentre,
              unsplit.steps);
  EXPECT_LT(split[1].errH, split[0].errH);
  EXPECT_LT(split[1].errCentre, split[0].errCentre);
  EXPECT_GE(an::observedOrder(split[0].errH, split[1].errH, 2.0), kMinOrder);
  for (const auto& r : split) {
    EXPECT_LT(r.volumeDrift, kVolumeTol) << r.n << "^2";
    EXPECT_LT(r.hostVolumeDrift, kVolumeTol) << r.n << "^2";
  }
  EXPECT_LT(split[1].errH, 1.25 * unsplit.errH);
  EXPECT_LT(split[1].errCentre, 1.25 * unsplit.errCentre + 1e-4);
  EXPECT_LT(split[1].steps, 0.7 * unsplit.steps);
  RecordProperty("thacker_split_l1_h_100", std::to_string(split[1].errH));
  RecordProperty("thacker_split_steps_100", std::to_string(split[1].steps));
}

namespace {
/// The sweeps of `scheme` at CFL 0.9 against the split sweeps at 0.5 on the 100^2 oscillation:
/// volume to round-off, L1(h) within errFactor of the reference's, the centre within 25 %, in under
/// stepFactor of its steps. Returns the CFL 0.9 run.
ThackerErrors expectSweepsAtNineTenths(fl::TimeScheme scheme, const char* name, double errFactor, double stepFactor) {
  const ThackerErrors half = runThacker(100, fl::TimeScheme::Split);
  const ThackerErrors nine = runThacker(100, scheme, 0.9);
  std::printf("[ Thacker planar, 100^2 ] split CFL 0.5: L1(h) %.4e m^3, centre %.4e m, %d steps; %s CFL 0.9: L1(h) "
              "%.4e m^3, centre %.4e m, %d steps\n",
              half.errH, half.errCentre, half.steps, name, nine.errH, nine.errCentre, nine.steps);
  EXPECT_LT(nine.volumeDrift, kVolumeTol);
  EXPECT_LT(nine.hostVolumeDrift, kVolumeTol);
  EXPECT_LT(nine.errH, errFactor * half.errH);
  EXPECT_LT(nine.errCentre, 1.25 * half.errCentre + 1e-4);
  EXPECT_LT(nine.steps, stepFactor * half.steps);
  return nine;
}
}  // namespace

// The split sweeps at a Courant number of 0.9 (GeoClaw's default), above the 1/2 of their positivity
// proof: the shoreline cells that empty within a stage have their outflow limited by the draining
// time (kernels/flow/stage.cl). Volume is kept to round-off, and the errors stay those of CFL 0.5
// within the same 25 % margin as above (the time error is of higher order than the shoreline's
// first-order space error), in under 0.65 of the steps (dt grows by 0.9/0.5, the step count falls by
// less, as the largest speed of the flow it meets differs from step to step: 0.596 of the steps
// measured).
TEST(Thacker, SplitSchemeAtCourantNumberNineTenths) {
  const ThackerErrors nine = expectSweepsAtNineTenths(fl::TimeScheme::Split, "split", 1.25, 0.65);
  RecordProperty("thacker_split_cfl09_l1_h_100", std::to_string(nine.errH));
  RecordProperty("thacker_split_cfl09_steps_100", std::to_string(nine.steps));
}

// The one-stage MUSCL-Hancock sweeps (Time Scheme=hancock) at CFL 0.9 on the same oscillation, with
// the same references as the split sweeps at 0.9 above: volume to round-off, the errors against the
// split sweeps at 0.5, fewer steps. The margin is wider than the split sweeps' 25 %: the Hancock
// reconstruction treats an empty neighbour whose bed stands above the water's reach as a wall
// (surface difference zero, flow_common.cl), which holds a lake among dry islands at rest but
// gives the shoreline cells of this tilted surface a flat one. Measured: L1(h) 2.47e-3 against
// 1.56e-3 (1.58x; 1.66e-3 without the wall rule, whose lake then drifts to 3e-5 m/s), centre
// 2.49e-3 against 2.45e-3, 282 steps against 417 (0.68). Bounds: 1.75x the error (the shoreline
// rule's measured cost with a margin of 10 %) and 0.75 of the steps.
TEST(Thacker, MusclHancockSweepsAtCourantNumberNineTenths) {
  const ThackerErrors nine = expectSweepsAtNineTenths(fl::TimeScheme::Hancock, "MUSCL-Hancock", 1.75, 0.75);
  RecordProperty("thacker_hancock_cfl09_l1_h_100", std::to_string(nine.errH));
}
