// Steady flow of the depth-averaged solids over a cell-scale rise of the bed (kernels/flow/solid_bed.cl,
// point 3a): the granular form of test_flow_over_step.cpp. A dry, cohesionless layer with a constant
// earth-pressure coefficient K on a frictionless bed has the lateral pressure p = K g h^2 / 2 (wave
// speed sqrt(K g h)), so steady frictionless flow keeps its discharge q = h u and its energy per unit
// mass u^2 / 2 + K g h + g z across a step (the momentum balance u u' + K g h' + g z' = 0 integrated
// along the flow). The exact steady solution is two uniform states joined at the step; the thickness
// behind it is the root of q^2 / (2 h^2) + K g h = e - g dz on the approaching flow's (supercritical)
// branch. With the faces of material at rest (h* = h - dz) the scheme passes only the part of the
// column above the step, so the steady state becomes a transient: the sheet piles up into a bore
// that runs upstream, and a sheet thinner than the rise is stopped although its energy carries it
// over.
//
// Scenes: one row of 250 cells of 1 m, the bed 0 up to x = 150 m and dz beyond, bed friction 0, no
// fluid, walls nowhere (open edges: the upstream one acts as a wall for the incoming flow, whose
// rarefaction enters at u + c <= 11.2 m/s and stays behind x = 100 m within 8 s; supercritical
// outflow cannot act upstream), started on the exact steady solution, 8 s, double precision.
//   K = 1: h = 1 m, u = 8 m/s, dz = 0.5 m (Froude 2.55, the water case's numbers);
//   K = 1: a sheet of 0.3 m at 6 m/s over a rise of 0.6 m, twice its thickness;
//   K = 0.5: h = 1 m, u = 8 m/s, dz = 1.2 m (a rise above the layer's surface).
// Tolerance: the face flux of the state at z* plus the bed-jump term returns each cell its own flux,
// so the state is an exact discrete steady state; 1e-9 covers double rounding (measured 0 and 1e-16).
// With h* everywhere (the faces before point 3a, SOLID_SUPERCRITICAL_FACES 0) the errors in
// discharge / thickness are 0.43 / 0.65, 0.98 / 4.6 and 0.97 / 1.4: each sheet piles up into a bore
// that runs upstream.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/Constants.hpp"
#include "flow/FlowSolver.hpp"
#include "support/Analytic.hpp"
#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

using namespace talus;
namespace fl = talus::flow;

namespace {

constexpr double kStepAt = 150.0, kLength = 250.0, kDx = 1.0, kEnd = 8.0;
constexpr double kWindow0 = 100.0, kWindow1 = 240.0;

/// Thickness behind a rise dz of a dry layer (h, u) with pressure gravity K g (Bernoulli, on the
/// supercritical branch; the support library's bisection, independent of the kernels' Newton).
double thicknessBehindRise(double h, double u, double dz, double k) {
  return analytic::supercriticalThicknessBehindRise(h, u, dz, k * kGravity, kGravity);
}

struct StepError {
  double discharge = 0;  ///< max |q / q0 - 1| over the window
  double thickness = 0;  ///< max |h / h_exact - 1| over the window
};

StepError runStep(double h1, double u1, double dz, double k) {
  const Grid grid = Grid::make(static_cast<int>(kLength / kDx), 1, kDx);
  const double h2 = thicknessBehindRise(h1, u1, dz, k), q = h1 * u1;
  test::SolidMaterial mat;
  mat.delta = 0.0;  // frictionless bed
  fl::FlowInput in = test::debrisInput(grid, mat);
  for (int i = 0; i < grid.nx; ++i) {
    const bool behind = test::cellX(grid, i) > kStepAt;
    in.bed[i] = behind ? dz : 0.0;
    in.hs[i] = behind ? h2 : h1;
    in.qsx[i] = q;
  }
  fl::FlowSettings s = test::granularBetweenWalls(k);
  s.edge = fl::Boundary::Open;
  fl::FlowSolver solver(test::testContext(compute::Precision::Double), grid, s);
  solver.setInput(in);
  test::advance(solver, test::RunLimits::until(kEnd));
  const auto st = test::readState(solver);
  StepError e;
  for (int i = 0; i < grid.nx; ++i) {
    const double x = test::cellX(grid, i);
    if (x < kWindow0 || x > kWindow1) continue;
    e.discharge = std::max(e.discharge, std::fabs(st.qsx[i] / q - 1.0));
    e.thickness = std::max(e.thickness, std::fabs(st.hs[i] / (x > kStepAt ? h2 : h1) - 1.0));
  }
  return e;
}

void expectSteady(const char* name, double h1, double u1, double dz, double k) {
  const StepError e = runStep(h1, u1, dz, k);
  std::printf("  %-24s thickness behind the step %.4f m: max discharge error %.2e, thickness error %.2e\n", name,
              thicknessBehindRise(h1, u1, dz, k), e.discharge, e.thickness);
  EXPECT_LT(e.discharge, 1e-9) << name;
  EXPECT_LT(e.thickness, 1e-9) << name;
}

}  // namespace

TEST(SolidFlowOverStep, SupercriticalLayerClimbsACellScaleRiseWithItsEnergy) {
  expectSteady("K = 1", 1.0, 8.0, 0.5, 1.0);
}

TEST(SolidFlowOverStep, SheetClimbsARiseTwiceItsThickness) {
  expectSteady("K = 1, sheet over 2x", 0.3, 6.0, 0.6, 1.0);
}

TEST(SolidFlowOverStep, LowLateralPressureLayerClimbsARiseAboveItsSurface) {
  expectSteady("K = 0.5, rise 1.2 m", 1.0, 8.0, 1.2, 0.5);
}

// A cohesive sheet whose cohesion takes all its lateral pressure at its own thickness (Bell's
// reduction: Pi = max(0, K g h / 2 - 2 c sqrt(K) / rho_s) = 0 below h0 = 1 m) runs at 0.5 m/s into a
// rise of 0.99 of its kinetic head u^2 / 2g. Without lateral pressure it arrives supercritically
// and its Bernoulli face state keeps its discharge at the speed the climb leaves it,
// u' = sqrt(u^2 - 2 g dz) = 0.05 m/s: h' = q / u' = 5 m, above h0, where the law would press. The
// face takes the pressure the state was built with (none: face_pi, kernels/flow/solid_bed.cl);
// with the law's pressure at h' its wave speed (6 m/s) drained three times the front cell's
// content in one step and the clipped cell created solids (two-phase soak seeds
// 4445931888577538981, 5853659436162393912, 1481104073426978450). Reference: conservation of the
// solids between walls, every step (1e-12 relative covers double rounding of 60 cells over the
// run; measured 2e-16, and 6.7e-2 with the law's pressure at the face).
TEST(SolidFlowOverStep, PressureFreeSheetAtItsKineticHeadKeepsItsVolume) {
  const Grid grid = Grid::make(60, 1, 1.0);
  const double h = 0.5, u = 0.5, k = 1.0;
  const double dz = 0.99 * u * u / (2 * kGravity);
  test::SolidMaterial mat;
  mat.delta = 0.0;
  mat.rhoS = 2000.0;
  mat.cohesion = 0.5 * k * kGravity * 1.0 * mat.rhoS / (2 * std::sqrt(k));  // h0 = c0 / a = 1 m
  fl::FlowInput in = test::debrisInput(grid, mat);
  for (int i = 0; i < grid.nx; ++i) {
    in.bed[i] = i >= 30 ? dz : 0.0;
    if (i >= 10 && i < 30) in.hs[i] = h, in.qsx[i] = h * u;
  }
  fl::FlowSettings s = test::granularBetweenWalls(k);
  fl::FlowSolver solver(test::testContext(compute::Precision::Double), grid, s);
  solver.setInput(in);
  const double v0 = test::readState(solver).volumeSolid(grid.dx);
  double worst = 0;
  int steps = 0;
  test::advance(solver, test::RunLimits::until(4.0), [&](const fl::FlowSolver& sv) {
    const auto st = test::readState(sv);
    worst = std::max(worst, std::fabs(st.volumeSolid(grid.dx) / v0 - 1.0));
    ++steps;
    return true;
  });
  std::printf("  pressure-free sheet at its kinetic head: %d steps, worst relative volume error %.2e\n", steps, worst);
  EXPECT_GT(steps, 10);
  EXPECT_LT(worst, 1e-12);
}
