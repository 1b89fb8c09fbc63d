// The dimensionally split time scheme (FlowSettings::scheme = Split, run-file key Time Scheme):
// its sweep order alternates between steps, so the order of the next step is state, and a solver
// restored from a checkpoint taken after an odd number of steps must continue with the same order
// (bitwise the run that did not stop); the key reaches the solver and is refused for two-phase runs;
// a CFL above 1/2 is taken by the split sweeps only (kernels/flow/stage.cl, draining time), and a
// run-file that asks otherwise is refused with the key named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/Constants.hpp"
#include "core/Error.hpp"
#include "core/Raster.hpp"
#include "flow/FlowSolver.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "support/FlowScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;

namespace {

/// A dam break on a bumpy tilted bed, flowing diagonally so both sweeps matter.
fl::FlowInput scene(const Grid& g) {
  return talus::test::makeInput(
      g, [](double x, double y) { return -0.05 * x - 0.03 * y + 0.2 * std::sin(0.7 * x) * std::cos(0.5 * y); },
      [](double x, double y) { return std::hypot(x - 10.0, y - 8.0) < 5.0 ? 2.0 : 0.0; });
}

struct State {
  std::vector<double> h, qx, qy;
  bool operator==(const State& o) const { return h == o.h && qx == o.qx && qy == o.qy; }
};
State stateOf(const fl::FlowSolver& s) { return {s.h(), s.qx(), s.qy()}; }

void advance(fl::FlowSolver& s, int steps) {
  for (int k = 0; k < steps; ++k) s.step(s.stableDt());
}

}  // namespace

TEST(SplitScheme, RestoredSolverContinuesWithTheSweepOrderOfTheCheckpoint) {
  const Grid g = Grid::make(40, 32, 1.0);
  const fl::FlowInput in = scene(g);
  fl::FlowSettings s;
  s.scheme = fl::TimeScheme::Split;
  auto& ctx = talus::test::testContext(Precision::Double);
  constexpr int kBefore = 3, kAfter = 4;  // an odd count before the checkpoint: the next step is y first

  fl::FlowSolver full(ctx, g, s);
  full.setInput(in);
  advance(full, kBefore);
  const std::vector<char> saved = full.saveState();
  const double savedTime = full.time();
  const State atCheckpoint = stateOf(full);
  advance(full, kAfter);
  const State expected = stateOf(full);

  fl::FlowSolver resumed(ctx, g, s);
  resumed.setInput(in);
  resumed.restoreState(saved, savedTime);
  advance(resumed, kAfter);
  EXPECT_TRUE(stateOf(resumed) == expected) << "the restored solver did not continue bitwise";

  // The order matters: the same state taken up as a new input (x first) gives another result, so
  // the equality above is the checkpoint's order at work, not an order-free scheme.
  fl::FlowInput mid = in;
  mid.h = atCheckpoint.h;
  mid.qx = atCheckpoint.qx;
  mid.qy = atCheckpoint.qy;
  fl::FlowSolver fresh(ctx, g, s);
  fresh.setInput(mid, savedTime);
  advance(fresh, kAfter);
  EXPECT_FALSE(stateOf(fresh) == expected) << "x-first and y-first sweeps gave the same state";

  // An unsplit checkpoint (no order byte) is refused by a split solver, naming the sizes.
  fl::FlowSettings unsplit;
  fl::FlowSolver other(ctx, g, unsplit);
  other.setInput(in);
  EXPECT_THROW(resumed.restoreState(other.saveState(), 0.0), talus::InputError);
}

TEST(SplitScheme, TwoPhaseRunsAreRefused) {
  const Grid g = Grid::make(8, 8, 1.0);
  fl::FlowSettings s;
  s.scheme = fl::TimeScheme::Split;
  s.twoPhase = true;
  EXPECT_THROW(fl::FlowSolver(talus::test::testContext(Precision::Double), g, s), talus::InputError);
}

TEST(SplitScheme, RunFilesAskingForWhatTheSchemesCannotDoAreRefusedByKey) {
  const auto dir = std::filesystem::temp_directory_path() / "talus_split_scheme_keys";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  talus::io::writeRaster((dir / "dem.tif").string(), talus::Raster(Grid::make(10, 8, 1.0), 0.0));
  const auto load = [&](const std::string& extra) {
    const std::string text = "DEM=dem.tif\nEnd Time=0.01\n" + extra;
    return talus::sim::loadScene(
        talus::io::RunConfig::fromText(text, dir.string(), talus::sim::talusRunKeys(), "keys.run"));
  };
  const auto refusedFor = [&](const std::string& extra, const std::string& key) {
    try {
      load(extra);
      ADD_FAILURE() << "accepted: " << extra;
    } catch (const talus::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("key '" + key + "'"), std::string::npos) << e.what();
    }
  };
  EXPECT_EQ(load("Time Scheme=split\nCFL=0.9\n").settings.cfl, 0.9);
  EXPECT_EQ(load("CFL=0.5\n").settings.cfl, 0.5);
  refusedFor("CFL=0.9\n", "CFL");                   // unsplit: positive only up to 1/2
  refusedFor("Time Scheme=split\nCFL=1.1\n", "CFL");  // beyond the sweeps' stability limit
  refusedFor("Time Scheme=split\nInclude Initial Solids=1\nInitial Solid Height=0.5\n", "Time Scheme");
  // The MUSCL-Hancock sweeps (Time Scheme=hancock) take the same per-direction CFL and are water only.
  const auto hancock = load("Time Scheme=hancock\nCFL=0.9\n");
  EXPECT_EQ(hancock.settings.scheme, fl::TimeScheme::Hancock);
  EXPECT_EQ(hancock.settings.cfl, 0.9);
  refusedFor("Time Scheme=hancock\nCFL=1.1\n", "CFL");
  refusedFor("Time Scheme=hancock\nInclude Initial Solids=1\nInitial Solid Height=0.5\n", "Time Scheme");
}

TEST(SplitScheme, StableStepIsPerDirection) {
  // A uniform layer h = 1 m moving at (u, v) = (2, 1) m/s on a flat bed: c = sqrt(g h), no slope
  // speed. Unsplit: dt = cfl dx / (|u| + |v| + 2 c); split: cfl dx / (max(|u|, |v|) + c).
  const Grid g = Grid::make(16, 16, 2.0);
  const fl::FlowInput in = talus::test::makeInput(
      g, [](double, double) { return 0.0; }, [](double, double) { return 1.0; },
      [](double, double) { return 2.0; }, [](double, double) { return 1.0; });
  const double c = std::sqrt(talus::kGravity * 1.0);
  for (const auto scheme : {fl::TimeScheme::Unsplit, fl::TimeScheme::Split}) {
    fl::FlowSettings s;
    s.scheme = scheme;
    s.slopeCorrection = false;
    fl::FlowSolver solver(talus::test::testContext(Precision::Double), g, s);
    solver.setInput(in);
    const double speed = scheme == fl::TimeScheme::Split ? 2.0 + c : 3.0 + 2 * c;
    // 1e-12: the device evaluates the same formula in double (a few ulps).
    EXPECT_NEAR(solver.stableDt(), s.cfl * g.dx / speed, 1e-12 * s.cfl * g.dx / speed);
  }
}

TEST(SplitScheme, StableStepOfAFilmOnASlopeAddsTheSlopeSpeedOnce) {
  // A 1 mm film at rest on a 0.3 plane: c = sqrt(g h) and the slope speed w = sqrt(g |grad b| dx)
  // (the solver's, kernels/flow/diagnostics.cl). Split: dt = cfl dx / (c + w), one direction's
  // speed; unsplit: cfl dx / (2 (c + w)). The split step keeps w at full weight (docs/numerics.md:
  // a smaller weight lets a lake against an open edge drain).
  const Grid g = Grid::make(16, 16, 2.0);
  const fl::FlowInput in = talus::test::makeInput(
      g, [](double x, double) { return -0.3 * x; }, [](double, double) { return 1e-3; });
  for (const auto scheme : {fl::TimeScheme::Unsplit, fl::TimeScheme::Split}) {
    fl::FlowSettings s;
    s.scheme = scheme;
    fl::FlowSolver solver(talus::test::testContext(Precision::Double), g, s);
    solver.setInput(in);
    double wMax = 0;
    for (double w : solver.slopeSpeed()) wMax = std::max(wMax, w);
    const double speed = std::sqrt(talus::kGravity * 1e-3) + wMax;
    const double expected = s.cfl * g.dx / (scheme == fl::TimeScheme::Split ? speed : 2 * speed);
    EXPECT_NEAR(solver.stableDt(), expected, 1e-12 * expected);
  }
}
