// Manning's friction on a steep plane in its slope-consistent form (kernels/flow/manning.cl): with the
// slope correction on (the model's bed force g cos^2(theta) grad b, spec §1), a uniform sheet reaches
// Manning's law along the bed, U = sqrt(sin theta) h_n^(2/3) / n with h_n = h cos(theta) the
// bed-normal thickness; its horizontal velocity is u = U cos(theta). The horizontal form
// -g n^2 |u| u / h^(4/3) used before gives a steady u larger by cos(theta)^(-7/6) (26 % at 35 deg).
//
// Scene: 400 cells of 1 m on a 35 degree plane, h = 0.5 m everywhere, n = 0.05, open edges, double.
// The upper edge drains the sheet from the top; that rarefaction travels at most u + c ~ 9 m/s, so
// over 10 s the cells from x = 200 m on keep the uniform flow. Two starts: at the steady velocity
// (it must stay there: the forces balance) and at 0.7 of it (it must relax to it; the relaxation time
// u / (2 g sin cos) is 0.74 s, so after 10 s the remaining deviation is e^-13 of the start), and at
// half the time step (the friction update is first order in time).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/Constants.hpp"
#include "flow/FlowSolver.hpp"
#include "support/DebrisScene.hpp"
#include "support/FlowScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;

namespace {

constexpr double kTheta = 35.0 * 3.14159265358979323846 / 180.0, kH = 0.5, kN = 0.05;

/// Horizontal velocity of Manning's steady uniform flow along the bed.
double steadyU() {
  const double hn = kH * std::cos(kTheta);
  return std::sqrt(std::sin(kTheta)) * std::pow(hn, 2.0 / 3.0) / kN * std::cos(kTheta);
}

/// Largest relative deviation of u from the steady velocity over the cells x in [200, 390] m at t = 10 s.
double runSheet(double startFraction, double cfl) {
  const int nx = 400;
  const double dx = 1.0;
  const talus::Grid grid = talus::Grid::make(nx, 1, dx);
  fl::FlowInput in;
  in.mask.assign(nx, 1);
  in.bed.resize(nx);
  in.manning.assign(nx, kN);
  in.h.assign(nx, kH);
  in.qx.assign(nx, kH * startFraction * steadyU());
  in.qy.assign(nx, 0.0);
  for (int i = 0; i < nx; ++i) in.bed[i] = -std::tan(kTheta) * (i + 0.5) * dx;
  fl::FlowSettings s;
  s.slopeCorrection = true;
  s.edge = fl::Boundary::Open;
  s.cfl = cfl;
  fl::FlowSolver solver(talus::test::testContext(talus::compute::Precision::Double), grid, s);
  solver.setInput(in);
  talus::test::advance(solver, talus::test::RunLimits::until(10.0));
  const std::vector<double> h = solver.h(), qx = solver.qx();
  double worst = 0;
  for (int i = 200; i < 390; ++i) worst = std::max(worst, std::fabs(qx[i] / h[i] / steadyU() - 1.0));
  return worst;
}

}  // namespace

TEST(ManningSlope, UniformSheetOnASteepPlaneFollowsManningAlongTheBed) {
  std::printf("[ Manning on 35 deg, h 0.5 m, n 0.05 ] steady u = %.4f m/s (along the bed %.4f m/s)\n", steadyU(),
              steadyU() / std::cos(kTheta));
  const double stay = runSheet(1.0, 0.5), relax = runSheet(0.7, 0.5), fine = runSheet(1.0, 0.25);
  std::printf("  CFL 0.5: started at the steady velocity, worst deviation %.3e; at 0.7 of it %.3e; CFL 0.25: %.3e\n",
              stay, relax, fine);
  // The semi-implicit friction q / (1 + dt k |u|) takes |u| before friction, so its fixed point lies
  // below the exact one by O(dt) (u (u + dt g sin cos) = exact^2: measured 0.87 % at CFL 0.5, about
  // half at 0.25). 2 % covers it and is far below the 26 % of the horizontal form; the relaxed start
  // must reach the same fixed point, and halving dt must halve the deviation (first order in time).
  EXPECT_LT(stay, 0.02);
  EXPECT_NEAR(relax, stay, 1e-4);
  EXPECT_NEAR(fine / stay, 0.5, 0.1);
}
