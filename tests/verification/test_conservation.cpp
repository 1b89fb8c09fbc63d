// Discrete conservation and symmetry of the shallow-water solver.
//  - Volume: the finite-volume update changes a cell's h only by the difference of its face mass
//    fluxes, and each interior face flux is computed once and used with opposite signs by its two
//    cells, so the interior fluxes cancel in pairs in the total; walls pass no mass. The total
//    volume can change only by rounding, O(eps) relative per step per cell at worst and in practice
//    a random walk far below that. With open edges, what the boundary faces pass must be exactly
//    what the solver reports as outflow (diagnostics().outflow, kernels/flow/stage.cl).
//  - Symmetry: the x and y sweeps share one kernel with the roles of the axes swapped, so a
//    radially symmetric dam break on a square grid must stay symmetric under x <-> y and under the
//    mirror reflections of the axes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "support/FlowScene.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::test::cellX;
using talus::test::cellY;

namespace {

/// Rough DEM and a random depth field with dry patches: h uniform in [0, 1.5] m, a quarter of the
/// cells dry, on 64 x 48 cells of 2 m (fixed seeds).
fl::FlowInput randomScene(const Grid& grid) {
  fl::FlowInput in;
  in.mask.assign(grid.cells(), 1);
  in.manning.assign(grid.cells(), 0.0);
  in.bed = talus::test::roughDem(grid, 977u, 0.5);
  std::mt19937 rng(4242u);
  std::uniform_real_distribution<double> depth(0.0, 1.5), coin(0.0, 1.0);
  in.h.resize(grid.cells());
  for (double& h : in.h) {
    const double d = depth(rng);
    h = coin(rng) < 0.25 ? 0.0 : d;
  }
  return in;
}

double hostVolume(const std::vector<double>& h, double area) {
  double v = 0;
  for (double x : h) v += x;
  return v * area;
}

// 1e-12 relative: each step changes the total by rounding only, a few eps per cell-face operation,
// and the errors of different cells and steps mostly cancel (measured drift in the output, about
// 1e-15). 1e-12 (4500 eps) is far below any real leak: a single face with a wrong sign or a
// missed wall would move percent-level volumes in 300 steps.
constexpr double kVolumeTol = 1e-12;
constexpr int kSteps = 300;

}  // namespace

TEST(Conservation, ClosedBasinVolumeToRoundOff) {
  const Grid grid = Grid::make(64, 48, 2.0);
  const fl::FlowInput in = randomScene(grid);
  const double area = grid.dx * grid.dx;
  const double v0 = hostVolume(in.h, area);

  // Closed: walls on the raster edge.
  fl::FlowSettings closed;
  closed.edge = fl::Boundary::Wall;
  const auto c = talus::test::runFlow(grid, in, closed, talus::test::RunLimits::steps(kSteps));
  ASSERT_EQ(c.steps, kSteps);
  const double closedDrift = std::fabs(c.volume - c.volume0) / c.volume0;
  const double closedHostDrift = std::fabs(hostVolume(c.h, area) - v0) / v0;
  std::printf("[ closed basin, %d steps, %.2f s simulated ] |V - V0| / V0: %.2e (solver), %.2e (host sum); "
              "outflow %.1e m^3\n",
              kSteps, c.time, closedDrift, closedHostDrift, c.outflow);
  EXPECT_LT(closedDrift, kVolumeTol);
  EXPECT_LT(closedHostDrift, kVolumeTol);
  EXPECT_EQ(c.outflow, 0.0) << "walls pass no mass";
  EXPECT_NEAR(c.volume0, v0, kVolumeTol * v0) << "device and host volume sums disagree";

  // Open: the raster edge lets water leave; V(t) + cumulative outflow must still equal V0.
  fl::FlowSettings open;
  open.edge = fl::Boundary::Open;
  // The per-step tally is signed. Open edges are outflow-only (a wall while the edge cell's flow
  // points into the domain), so no step may bring water in: the tally must never be negative.
  int inflowSteps = 0;
  double inflow = 0, exchange = 0;
  const auto o = talus::test::runFlow(grid, in, open, talus::test::RunLimits::steps(kSteps),
                                      talus::compute::Precision::Double, [&](const fl::FlowSolver& solver) {
                                        const double out = solver.diagnostics().outflow;
                                        exchange += std::fabs(out);
                                        if (out < 0) ++inflowSteps, inflow -= out;
                                      });
  ASSERT_EQ(o.steps, kSteps);
  const double openBalance = std::fabs(o.volume + o.outflow - o.volume0) / o.volume0;
  const double openHostBalance = std::fabs(hostVolume(o.h, area) + o.outflow - v0) / v0;
  std::printf("[ open edges, %d steps ] net outflow %.4f of V0 (%d steps with net inflow, %.4f of V0 in); "
              "|V + out - V0| / V0: %.2e (solver), %.2e (host sum)\n",
              kSteps, o.outflow / o.volume0, inflowSteps, inflow / o.volume0, openBalance, openHostBalance);
  std::fflush(stdout);
  EXPECT_GT(exchange, 0.05 * o.volume0) << "the open edge must pass real volumes for the balance to mean anything";
  EXPECT_LT(openBalance, kVolumeTol);
  EXPECT_LT(openHostBalance, kVolumeTol);
  EXPECT_EQ(inflowSteps, 0) << "water entered through an outflow-only open edge";
  RecordProperty("closed_volume_drift", std::to_string(closedDrift));
  RecordProperty("open_volume_balance", std::to_string(openBalance));
}

namespace {

struct SymmetryError {
  double transpose = 0;  ///< max |h(i,j) - h(j,i)|, |qx(i,j) - qy(j,i)| over max |h|, max |q|
  double mirrorX = 0;    ///< same for i -> nx-1-i (qx changes sign)
  double mirrorY = 0;    ///< same for j -> ny-1-j (qy changes sign)
};

SymmetryError symmetry(const talus::test::FlowRun& r) {
  const Grid& g = r.grid;
  double hMax = 0, qMax = 0;
  for (std::size_t k = 0; k < g.cells(); ++k)
    hMax = std::max(hMax, std::fabs(r.h[k])), qMax = std::max({qMax, std::fabs(r.qx[k]), std::fabs(r.qy[k])});
  SymmetryError e;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j), t = g.index(j, i), mx = g.index(g.nx - 1 - i, j),
                        my = g.index(i, g.ny - 1 - j);
      e.transpose = std::max({e.transpose, std::fabs(r.h[k] - r.h[t]) / hMax,
                              std::fabs(r.qx[k] - r.qy[t]) / qMax, std::fabs(r.qy[k] - r.qx[t]) / qMax});
      e.mirrorX = std::max({e.mirrorX, std::fabs(r.h[k] - r.h[mx]) / hMax, std::fabs(r.qx[k] + r.qx[mx]) / qMax,
                            std::fabs(r.qy[k] - r.qy[mx]) / qMax});
      e.mirrorY = std::max({e.mirrorY, std::fabs(r.h[k] - r.h[my]) / hMax, std::fabs(r.qx[k] - r.qx[my]) / qMax,
                            std::fabs(r.qy[k] + r.qy[my]) / qMax});
    }
  return e;
}

// Symmetry tolerance, relative to the field maxima. Under x <-> y the face fluxes are the same code
// with the axes swapped and the update adds the x and y terms with commutative sums, so the
// transpose must be bitwise exact (asserted as 0). The mirror images evaluate the Riemann solver
// with left and right exchanged
// (e.g. u* = (uL + uR)/2 + cL - cR), which rounds differently too. The differences are a few ulps
// per step and do not grow through the limiter and wet/dry switches (measured ~1e-15 after 80
// steps, printed); 1e-12 would still catch any real asymmetry (a wrong sign or index in one
// direction), which shows up at O(1) relative size within a few steps.
constexpr double kSymmetryTol = 1e-12;

}  // namespace

TEST(Conservation, RadialDamBreakSymmetry) {
  // 81 x 81 cells of 1 m, flat, walls; a cylinder of radius 20 m and depth 1 m centred on the
  // middle cell (40, 40). With dx = 1 the cell offsets from the centre are exact integers, so
  // the initial state is exactly symmetric.
  const Grid grid = Grid::make(81, 81, 1.0);
  const double xc = cellX(grid, 40), yc = cellY(grid, 40);
  constexpr int steps = 80;
  std::printf("[ radial dam break 81 x 81, %d steps: max relative asymmetry ]\n", steps);
  for (const auto riemann : {fl::RiemannSolver::HLLC, fl::RiemannSolver::HLL})
    for (const double outside : {0.0, 0.1}) {
      const auto in = talus::test::makeInput(
          grid, [](double, double) { return 0.0; },
          [&](double x, double y) {
            const double r2 = (x - xc) * (x - xc) + (y - yc) * (y - yc);
            return r2 < 400.0 ? 1.0 : outside;
          });
      fl::FlowSettings s;
      s.riemann = riemann;
      s.edge = fl::Boundary::Wall;
      const auto run = talus::test::runFlow(grid, in, s, talus::test::RunLimits::steps(steps));
      const SymmetryError e = symmetry(run);
      const std::string tag = std::string(riemann == fl::RiemannSolver::HLLC ? "HLLC" : "HLL") +
                              (outside > 0 ? ", wet outside" : ", dry outside");
      std::printf("  %-20s t %.2f s  transpose %.2e%s  mirror x %.2e%s  mirror y %.2e%s\n", tag.c_str(), run.time,
                  e.transpose, e.transpose == 0 ? " (bitwise)" : "", e.mirrorX, e.mirrorX == 0 ? " (bitwise)" : "",
                  e.mirrorY, e.mirrorY == 0 ? " (bitwise)" : "");
      EXPECT_EQ(e.transpose, 0.0) << tag << ": x <-> y transposition is not bitwise";
      EXPECT_LT(e.mirrorX, kSymmetryTol) << tag;
      EXPECT_LT(e.mirrorY, kSymmetryTol) << tag;
    }
  std::fflush(stdout);
}
