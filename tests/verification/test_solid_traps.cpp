// Solids trapped by the terrain stay at rest: a cohesive solid (no lateral pressure) lying in a DEM
// pit deeper than the solid layer, on a steep regional slope, and one pressed against a wall by the
// slope, and one on the rim of a pit filled with static solids. The hydrostatic reconstruction keeps
// their mass in place, so the bed force must not push
// them either: before this was handled, such a cell gained momentum for ever (158 m/s in the
// kot_debrisflow example). Exact expectation: momentum exactly zero, thickness bitwise unchanged.
#include <gtest/gtest.h>

#include <cmath>

#include "flow/FlowSolver.hpp"
#include "support/TestDevice.hpp"

using namespace talus;

namespace {

/// Runs `steps` steps of a two-phase scene with solids only; returns max |q_s| and whether the
/// solid thickness stayed bitwise the initial one.
std::pair<double, bool> runTrapped(const flow::FlowInput& in, const Grid& g, flow::Boundary edge, int steps) {
  flow::FlowSettings s;
  s.twoPhase = true;
  s.edge = edge;
  flow::FlowSolver solver(test::testContext(compute::Precision::Double), g, s);
  solver.setInput(in);
  for (int n = 0; n < steps; ++n) {
    double dt = solver.stableDt();
    if (!std::isfinite(dt)) dt = 0.01;
    solver.step(dt);
  }
  const std::vector<double> hs = solver.hs(), qx = solver.qsx(), qy = solver.qsy();
  double qmax = 0;
  for (std::size_t k = 0; k < hs.size(); ++k) qmax = std::max(qmax, std::hypot(qx[k], qy[k]));
  return {qmax, hs == in.hs};
}

flow::FlowInput solids(const Grid& g) {
  flow::FlowInput in;
  const std::size_t n = g.cells();
  in.mask.assign(n, 1);
  in.bed.assign(n, 0.0);
  in.manning.assign(n, 0.0);
  in.h.assign(n, 0.0);
  in.hs.assign(n, 0.0);
  in.phi.assign(n, 0.2);             // tan(0.2) = 0.2: far less than the 0.7 slope below
  in.cohesion.assign(n, 1e6);        // rigid: no lateral pressure
  return in;
}

}  // namespace

TEST(SolidTraps, SolidInAPitOnASteepSlopeStaysAtRest) {
  const Grid g = Grid::make(9, 9, 5.0);
  flow::FlowInput in = solids(g);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) in.bed[g.index(i, j)] = -0.7 * 5.0 * i;  // 35 degree slope in x
  in.bed[g.index(4, 4)] -= 6.0;  // a 6 m deep pit (2.5 m below its downhill neighbour)
  in.hs[g.index(4, 4)] = 0.5;
  const auto [qmax, unchanged] = runTrapped(in, g, flow::Boundary::Open, 200);
  EXPECT_EQ(qmax, 0.0) << "a solid that cannot leave its pit must not gain momentum";
  EXPECT_TRUE(unchanged);
}

TEST(SolidTraps, SolidPressedAgainstAWallStaysAtRest) {
  const Grid g = Grid::make(6, 3, 5.0);
  flow::FlowInput in = solids(g);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      in.bed[g.index(i, j)] = 0.7 * 5.0 * i;  // falls towards the west wall at i = 0
      if (i == 0) in.hs[g.index(i, j)] = 0.5;
    }
  const auto [qmax, unchanged] = runTrapped(in, g, flow::Boundary::Wall, 200);
  EXPECT_EQ(qmax, 0.0) << "the wall holds the solid: no momentum may build up against it";
  EXPECT_TRUE(unchanged);
}

// A 6 m deep pit in flat ground, filled with static solids up to the 0.5 m solid layer around it
// (a flat solid surface, rigid material: no lateral pressure). The cells on the rim see a centred
// bed gradient of 0.6 towards the pit, three times the friction 0.2, but their solids cannot go down
// there: the pit is full of material at rest that acts as ground. Before this was handled the rim
// accelerated into the full pit without releasing any potential energy (found by the two-phase
// stress soak: 12 g on the rim of a filled 18 m pit). Exact expectation: nothing moves.
TEST(SolidTraps, SolidOnTheRimOfAFilledPitStaysAtRest) {
  const Grid g = Grid::make(9, 9, 5.0);
  flow::FlowInput in = solids(g);
  in.hs.assign(g.cells(), 0.5);
  in.bed[g.index(4, 4)] = -6.0;
  in.hs[g.index(4, 4)] = 6.5;
  const auto [qmax, unchanged] = runTrapped(in, g, flow::Boundary::Wall, 200);
  EXPECT_EQ(qmax, 0.0) << "solids next to a filled pit must not be pushed into it";
  EXPECT_TRUE(unchanged);
}

// A pile at rest (0.54 m, cohesionless, phi = 34 degrees) on a ledge 1.25 m above its downhill
// neighbour, which holds a film just thicker than the film threshold (0.10001 mm), everything at
// rest: friction holds the pile (bed push 0.1 g against 0.67 g), and the film has nothing to push it.
// Before the fix the static face between them carried a share of the pile's pressure, which
// accelerated the film to 180 m/s within one step (found in data/kot_debrisflow at t = 112 s, where
// the health check stopped the run). Exact expectation: nothing moves.
TEST(SolidTraps, FilmBesideAPileAtRestStaysAtRest) {
  const Grid g = Grid::make(5, 3, 5.0);
  flow::FlowInput in = solids(g);
  in.phi.assign(g.cells(), 0.6);
  in.cohesion.assign(g.cells(), 0.0);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < 2; ++i) in.bed[g.index(i, j)] = 1.25;
    in.hs[g.index(1, j)] = 0.54;
    in.hs[g.index(2, j)] = 1.0001e-4;
  }
  const auto [qmax, unchanged] = runTrapped(in, g, flow::Boundary::Wall, 20);
  EXPECT_EQ(qmax, 0.0) << "a film beside a pile at rest must not be pushed by it";
  EXPECT_TRUE(unchanged);
}
