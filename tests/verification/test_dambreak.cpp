// Grid-convergence tests of the shallow-water solver on the 1D dam-break problems with exact
// solutions: Ritter (dry downstream bed) and Stoker (wet downstream bed), SWASHES sections 4.1.1
// and 4.1.2 (Delestre et al. 2013). Domain [0, 100] m, dam at x = 50 m, hL = 1 m, t = 4 s, flat
// frictionless bed, classical SWE (slope correction off, so g_n = g_p = g). The rarefaction head
// reaches x = 50 - 4 sqrt(g) = 37.5 m and the Ritter front x = 50 + 8 sqrt(g) = 75.1 m, so the waves
// stay well inside and the walls at the ends never matter.
//
// One row of cells (ny = 1) with walls on every raster edge: both y faces of each cell are wall
// faces with mirrored ghosts, which pass no mass and give exactly opposite pressure fluxes, so qy
// stays exactly zero and the run is a 1D run.
//
// Errors are L1 norms, sum |h_i - hbar_i| dx [m^2], against the cell averages hbar_i of the exact
// solution (analytic::cellAverage1D), which is what a finite-volume scheme approximates; with
// point values, the cells cut by the kinks and the shock would carry an O(dx) error of the
// comparison itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/Constants.hpp"
#include "support/Analytic.hpp"
#include "support/FlowScene.hpp"
#include "verification/ValidationOut.hpp"

namespace an = talus::analytic;
namespace fl = talus::flow;
using talus::Grid;
using talus::test::FlowRun;

namespace {

constexpr double kLength = 100.0, kDam = 50.0, kHL = 1.0, kT = 4.0;
const int kGrids[] = {100, 200, 400, 800};

struct DamBreakErrors {
  int nx = 0;
  double errH = 0;  ///< L1 of h over the whole domain [m^2]
  double errU = 0;  ///< L1 of u over the wet cells [m^2/s]
  int steps = 0;
  double seconds = 0;
};

/// File-name stem of a run for the validation CSVs (ValidationOut.hpp): ritter / stoker, plus
/// _first for the first-order scheme and _hll for the HLL solver.
std::string caseName(double hR, fl::Limiter limiter, fl::RiemannSolver riemann) {
  std::string name = hR > 0.0 ? "stoker" : "ritter";
  if (limiter == fl::Limiter::None) name += "_first";
  if (riemann == fl::RiemannSolver::HLL) name += "_hll";
  return name;
}

fl::FlowSettings dambreakSettings(fl::Limiter limiter, fl::RiemannSolver riemann,
                                  fl::TimeScheme scheme = fl::TimeScheme::Unsplit, double cfl = 0.5) {
  fl::FlowSettings s;
  s.scheme = scheme;
  s.cfl = cfl;
  s.limiter = limiter;
  s.riemann = riemann;
  s.edge = fl::Boundary::Wall;
  s.slopeCorrection = false;  // the exact solutions are for classical SWE with g
  return s;
}

/// Runs the dam break with downstream depth hR (0: Ritter) on nx cells and measures the errors.
DamBreakErrors runDamBreak(int nx, double hR, fl::Limiter limiter, fl::RiemannSolver riemann,
                           fl::TimeScheme scheme = fl::TimeScheme::Unsplit, double cfl = 0.5) {
  const double dx = kLength / nx;
  const Grid grid = Grid::make(nx, 1, dx);
  const auto input = talus::test::makeInput(
      grid, [](double, double) { return 0.0; }, [&](double x, double) { return x < kDam ? kHL : hR; });
  const fl::FlowSettings settings = dambreakSettings(limiter, riemann, scheme, cfl);
  const FlowRun run = talus::test::runFlow(grid, input, settings, talus::test::RunLimits::until(kT));
  EXPECT_NEAR(run.time, kT, 1e-12);

  const double g = talus::kGravity;
  std::vector<double> hRef(nx), uRef(nx);
  for (int i = 0; i < nx; ++i) {
    const double xc = talus::test::cellX(grid, i);
    hRef[i] = an::cellAverage1D([&](double x) { return an::stoker(x, kT, kDam, kHL, hR, g).h; }, xc, dx);
    // The scheme evolves cell averages of h and hu, so its q/h approximates avg(hu) / avg(h).
    const double qRef = an::cellAverage1D(
        [&](double x) { const an::State1D s = an::stoker(x, kT, kDam, kHL, hR, g); return s.h * s.u; }, xc, dx);
    uRef[i] = hRef[i] > 0.0 ? qRef / hRef[i] : 0.0;
  }
  // The exact discharge through the y walls is zero, so the run must be exactly 1D.
  for (int i = 0; i < nx; ++i) EXPECT_EQ(run.qy[i], 0.0) << "cell " << i;

  DamBreakErrors e;
  e.nx = nx;
  e.errH = an::l1(run.h, hRef, dx);
  const std::vector<double> u = run.velocityX(settings.hDry);
  for (int i = 0; i < nx; ++i)
    if (hRef[i] > 0.0 && run.h[i] > settings.hDry) e.errU += std::fabs(u[i] - uRef[i]) * dx;
  e.steps = run.steps;
  e.seconds = run.wallSeconds;
  if (talus::test::validation::enabled()) {  // the profile against the exact cell averages
    talus::test::validation::Table t({"x_m", "h_m", "h_exact_m", "u_m_s", "u_exact_m_s"});
    for (int i = 0; i < nx; ++i) t.add({talus::test::cellX(grid, i), run.h[i], hRef[i], u[i], uRef[i]});
    t.write(caseName(hR, limiter, riemann) + "_profile_nx" + std::to_string(nx) + ".csv");
  }
  return e;
}

std::vector<DamBreakErrors> convergenceStudy(const char* label, double hR, fl::Limiter limiter,
                                             fl::RiemannSolver riemann, bool printVelocity) {
  std::vector<DamBreakErrors> out;
  for (int nx : kGrids) out.push_back(runDamBreak(nx, hR, limiter, riemann));
  std::printf("[ %s ] hL %.1f m, hR %.1f m, t %.1f s\n", label, kHL, hR, kT);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const auto& e = out[k];
    std::printf("  nx %4d  L1(h) %.4e m^2", e.nx, e.errH);
    if (k > 0) std::printf(" (order %.3f)", an::observedOrder(out[k - 1].errH, e.errH, 2.0));
    if (printVelocity) {
      std::printf("  L1(u) %.4e m^2/s", e.errU);
      if (k > 0) std::printf(" (order %.3f)", an::observedOrder(out[k - 1].errU, e.errU, 2.0));
    }
    std::printf("  %d steps %.2f s\n", e.steps, e.seconds);
  }
  std::fflush(stdout);
  if (talus::test::validation::enabled()) {
    talus::test::validation::Table t({"nx", "dx_m", "l1_h_m2", "order_h", "l1_u_m2_s", "order_u", "steps"});
    for (std::size_t k = 0; k < out.size(); ++k) {
      const auto& e = out[k];
      const double oh = k > 0 ? an::observedOrder(out[k - 1].errH, e.errH, 2.0) : std::nan("");
      const double ou = k > 0 ? an::observedOrder(out[k - 1].errU, e.errU, 2.0) : std::nan("");
      t.add({e.nx, kLength / e.nx, e.errH, oh, e.errU, ou, e.steps});
    }
    t.write(caseName(hR, limiter, riemann) + "_errors.csv");
  }
  return out;
}

/// Expects the error to fall on every refinement.
void expectMonotone(const std::vector<DamBreakErrors>& e, double DamBreakErrors::*err, const char* what) {
  for (std::size_t k = 1; k < e.size(); ++k)
    EXPECT_LT(e[k].*err, e[k - 1].*err) << what << " grew from nx " << e[k - 1].nx << " to " << e[k].nx;
}

/// Observed order between the two finest grids.
double finestOrder(const std::vector<DamBreakErrors>& e, double DamBreakErrors::*err) {
  return an::observedOrder(e[e.size() - 2].*err, e.back().*err, 2.0);
}

/// Least-squares slope of log(error) against log(dx) over all grids.
double fittedOrder(const std::vector<DamBreakErrors>& e, double DamBreakErrors::*err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(e.size());
  for (const auto& r : e) {
    const double x = std::log(kLength / r.nx), y = std::log(r.*err);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Minimum observed L1 order of h between nx = 400 and 800. A MUSCL scheme is second order only
// where the solution is smooth, and the L1 error of these Riemann problems is dominated by O(dx)
// contributions: the Ritter front (h ~ (x_f - x)^2 meets a dry bed, where the limiter drops to
// first order and the front lags by O(dx)), the Stoker shock (an O(1) jump smeared over a fixed
// number of cells), and the start-up error of the centred rarefaction (the fan of the discrete
// solution is centred O(dx) away from the dam, an O(dx) error across the whole fan, measured to
// dominate the Stoker error). The asymptotic L1 order is therefore 1, and 0.8 leaves room for the
// pre-asymptotic mix of rates on these grids (measured: about 1.0 for Ritter, 0.9 for Stoker).
constexpr double kMinOrder = 0.8;

}  // namespace

TEST(DamBreak, RitterConverges) {
  const auto e =
      convergenceStudy("Ritter, van Leer, HLLC", 0.0, fl::Limiter::VanLeer, fl::RiemannSolver::HLLC, false);
  expectMonotone(e, &DamBreakErrors::errH, "L1(h)");
  const double order = finestOrder(e, &DamBreakErrors::errH);
  RecordProperty("ritter_l1_h_nx800", std::to_string(e.back().errH));
  RecordProperty("ritter_order_h", std::to_string(order));
  EXPECT_GE(order, kMinOrder);

  // The first-order scheme (no reconstruction) on the finest grid: the second-order scheme must be
  // clearly better; both have L1 order 1 here, but the first-order scheme's error constant in the
  // rarefaction and at the front is several times larger (measured ratio printed).
  const DamBreakErrors first = runDamBreak(e.back().nx, 0.0, fl::Limiter::None, fl::RiemannSolver::HLLC);
  std::printf("  first order nx %d: L1(h) %.4e m^2, ratio second/first %.3f\n", first.nx, first.errH,
              e.back().errH / first.errH);
  RecordProperty("ritter_l1_h_first_order", std::to_string(first.errH));
  if (talus::test::validation::enabled()) {
    talus::test::validation::Table t({"nx", "l1_h_second_order_m2", "l1_h_first_order_m2", "ratio"});
    t.add({first.nx, e.back().errH, first.errH, e.back().errH / first.errH});
    t.write("ritter_first_order.csv");
  }
  EXPECT_LT(e.back().errH, 0.8 * first.errH);
}

namespace {
/// The sweeps of `scheme` at CFL 0.9 on Ritter's and Stoker's dam breaks (nx 400 and 800) against
/// the unsplit default at 0.5 and nx 800: convergence in h at kMinOrder, both errors within 2.5x of
/// the default's, under 0.6 of its steps; the nx 800 L1(h) recorded as <case>_<tag>_cfl09_l1_h_nx800.
void expectSweepsAtNineTenthsConverge(fl::TimeScheme scheme, const char* label, const std::string& tag) {
  for (const double hR : {0.0, 0.1}) {
    const char* name = hR > 0 ? "Stoker" : "Ritter";
    const DamBreakErrors base = runDamBreak(800, hR, fl::Limiter::VanLeer, fl::RiemannSolver::HLLC);
    std::vector<DamBreakErrors> sw;
    for (const int nx : {400, 800})
      sw.push_back(runDamBreak(nx, hR, fl::Limiter::VanLeer, fl::RiemannSolver::HLLC, scheme, 0.9));
    const double orderH = an::observedOrder(sw[0].errH, sw[1].errH, 2.0);
    const double orderU = an::observedOrder(sw[0].errU, sw[1].errU, 2.0);
    std::printf("[ %s, %s at CFL 0.9 ] nx 400: L1(h) %.4e, L1(u) %.4e; nx 800: L1(h) %.4e, L1(u) %.4e, "
                "%d steps (orders %.2f, %.2f); unsplit CFL 0.5 at nx 800: L1(h) %.4e, L1(u) %.4e, %d steps\n",
                name, label, sw[0].errH, sw[0].errU, sw[1].errH, sw[1].errU, sw[1].steps, orderH, orderU, base.errH,
                base.errU, base.steps);
    EXPECT_GE(orderH, kMinOrder) << name;
    EXPECT_LT(sw[1].errH, 2.5 * base.errH) << name;
    EXPECT_LT(sw[1].errU, 2.5 * base.errU) << name;
    EXPECT_LT(sw[1].steps, 0.6 * base.steps) << name;
    ::testing::Test::RecordProperty(std::string(hR > 0 ? "stoker" : "ritter") + "_" + tag + "_cfl09_l1_h_nx800",
                                    std::to_string(sw[1].errH));
  }
}
}  // namespace

// The split sweeps at a Courant number of 0.9 (GeoClaw's default; above 1/2 the Ritter front cells,
// which empty within a stage, have their outflow limited by the draining time, kernels/flow/stage.cl)
// against the default unsplit scheme at 0.5. In 1D the unsplit CFL speed counts the y direction's c
// as well, so the split step is 0.9 / 0.5 * (|u| + 2c) / (|u| + c) as long: 1.8 where the fastest
// cell is the thin, fast Ritter front (c small), more in the Stoker flow.
// The longer step costs accuracy: measured L1(h) at nx 800, Ritter 0.0452 / 0.0600 / 0.0819 at split
// CFL 0.5 / 0.7 / 0.9 (0.0391 at 0.1), Stoker 0.0392 / 0.0460 / 0.0643 (0.0351); the unsplit default
// 0.0404 and 0.0364. Every one of them halves with dx (the O(dx) terms of kMinOrder dominate; the
// larger Courant number, beyond the 1/2 where SSP-RK2 with these limiters is TVD, scales their
// constant). Asserted: the split run at 0.9 converges in h at the same minimum order (its volume is
// checked in Thacker.SplitSchemeAtCourantNumberNineTenths), takes under 0.6 of the steps (measured
// 0.50 Ritter, 0.38 Stoker), and stays within 2.5x of the default's errors (measured 1.56-2.03x, so
// a change that makes the large step worse is caught).
TEST(DamBreak, SplitSweepsAtCourantNumberNineTenthsConverge) {
  expectSweepsAtNineTenthsConverge(fl::TimeScheme::Split, "split sweeps", "split");
}

TEST(DamBreak, StokerConverges) {
  constexpr double hR = 0.1;
  std::vector<DamBreakErrors> hllcErrors;
  for (const auto riemann : {fl::RiemannSolver::HLLC, fl::RiemannSolver::HLL}) {
    const bool hllc = riemann == fl::RiemannSolver::HLLC;
    const std::string name = hllc ? "hllc" : "hll";
    const auto e = convergenceStudy(hllc ? "Stoker, van Leer, HLLC" : "Stoker, van Leer, HLL", hR,
                                    fl::Limiter::VanLeer, riemann, true);
    expectMonotone(e, &DamBreakErrors::errH, "L1(h)");
    expectMonotone(e, &DamBreakErrors::errU, "L1(u)");
    const double orderH = finestOrder(e, &DamBreakErrors::errH);
    // The velocity error is dominated by the one or two cells inside the smeared shock, whose error
    // depends on where the exact shock falls within its cell at t = 4 s; that phase differs from
    // grid to grid, so pairwise orders of L1(u) scatter (0.6 to 1.3 measured). The least-squares
    // slope over all four grids is the robust estimate of the order.
    const double orderU = fittedOrder(e, &DamBreakErrors::errU);
    std::printf("  order of L1(h), nx 400 -> 800: %.3f; least-squares order of L1(u): %.3f\n", orderH, orderU);
    RecordProperty("stoker_" + name + "_l1_h_nx800", std::to_string(e.back().errH));
    RecordProperty("stoker_" + name + "_order_h", std::to_string(orderH));
    RecordProperty("stoker_" + name + "_l1_u_nx800", std::to_string(e.back().errU));
    RecordProperty("stoker_" + name + "_fitted_order_u", std::to_string(orderU));
    EXPECT_GE(orderH, kMinOrder) << name;
    EXPECT_GE(orderU, kMinOrder) << name;
    if (hllc) {
      hllcErrors = e;
    } else {
      // In 1D the tangential velocity is zero everywhere, and the solver's HLLC differs from HLL
      // only in the tangential momentum flux (kernels/flow/riemann.cl), so the runs coincide.
      bool same = true;
      for (std::size_t k = 0; k < e.size(); ++k) same = same && e[k].errH == hllcErrors[k].errH;
      std::printf("  HLL and HLLC errors %s\n", same ? "identical (expected in 1D)" : "differ");
    }
  }
}

// The one-stage MUSCL-Hancock sweeps (Time Scheme=hancock, kernels/flow/hancock.cl) at CFL 0.9, the
// same checks as the split sweeps above: convergence in h at the minimum order, errors against the
// unsplit default at nx 800, and fewer steps. One stage per sweep is centred in time (van Leer
// 1984), so at equal Courant number it is no less accurate than the two-stage sweeps; its bound is
// the split sweeps' 2.5x of the default's errors.
TEST(DamBreak, MusclHancockSweepsAtCourantNumberNineTenthsConverge) {
  expectSweepsAtNineTenthsConverge(fl::TimeScheme::Hancock, "MUSCL-Hancock sweeps", "hancock");
}
