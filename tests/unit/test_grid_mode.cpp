// Model selection (spec §3): a scene that asks for solids but has none runs exactly the
// single-phase shallow-water path, bit for bit; a scene with solids runs the two-phase model.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

namespace fs = std::filesystem;
using namespace talus;

namespace {

fs::path makeScene(const fs::path& dir, const std::string& extra) {
  fs::create_directories(dir);
  const Grid g = Grid::make(40, 30, 2.0);
  Raster dem(g, 0.0), water(g, 0.0), none(g, 0.0), solids(g, 0.0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      dem.at(i, j) = 0.1 * i + 0.2 * std::sin(0.5 * j);
      if (std::hypot(i - 10.0, j - 15.0) < 6) water.at(i, j) = 1.5, solids.at(i, j) = 1.0;
    }
  io::writeRaster((dir / "dem.tif").string(), dem);
  io::writeRaster((dir / "water.tif").string(), water);
  io::writeRaster((dir / "none.tif").string(), none);
  io::writeRaster((dir / "solids.tif").string(), solids);
  std::ofstream(dir / "scene.run") << "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n"
                                   << "Manning=0.03\nEnd Time=0.1\nTimestep=2\nPrecision=double\n" << extra;
  return dir / "scene.run";
}

struct Result {
  sim::Scene scene;
  std::vector<double> h, qx, hmax;
};

Result run(const fs::path& runFile, const fs::path& out) {
  const io::RunConfig cfg = io::RunConfig::load(runFile.string(), talusRunKeys());
  Result r;
  r.scene = sim::loadScene(cfg);
  sim::Simulation sim(r.scene, cfg, out.string(), sim::OutputMode::Overwrite);
  sim.run();
  r.h = sim.solver().h();
  r.qx = sim.solver().qx();
  r.hmax = io::readRaster((out / "hfmax.tif").string()).values;
  return r;
}

}  // namespace

TEST(GridMode, SceneWithoutSolidsRunsTheSinglePhasePathBitForBit) {
  const fs::path dir = fs::temp_directory_path() / ("talus_gridmode_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Result water = run(makeScene(dir / "a", ""), dir / "a" / "out");
  const Result asked = run(makeScene(dir / "b", "Include Initial Solids=1\nInitial Solid Height=none.tif\n"),
                           dir / "b" / "out");
  EXPECT_FALSE(water.scene.settings.twoPhase);
  EXPECT_FALSE(asked.scene.settings.twoPhase) << "no solid in the map: the two-phase model must not run";
  ASSERT_EQ(water.h.size(), asked.h.size());
  EXPECT_TRUE(water.h == asked.h && water.qx == asked.qx && water.hmax == asked.hmax)
      << "a scene without solids must reproduce the shallow-water results bit for bit";
  const Result debris = run(makeScene(dir / "c", "Include Initial Solids=1\nInitial Solid Height=solids.tif\n"),
                            dir / "c" / "out");
  EXPECT_TRUE(debris.scene.settings.twoPhase);
  EXPECT_TRUE(fs::exists(dir / "c" / "out" / "hsmax.tif"));
  EXPECT_FALSE(fs::exists(dir / "a" / "out" / "hsmax.tif"));
  fs::remove_all(dir);
}

// Stop At Rest Fraction (com1DFA's stopCrit): a granular pile (phi = delta = 34 deg) on a gentle
// slope (6 deg) slumps and comes to rest well before End Time (2 min). With the criterion on the run
// ends at rest (summary.json says so, status completed) with the same final deposit as the full run
// (friction holds it exactly: nothing changes after rest); without it the run goes on to End Time.
TEST(GridMode, RunEndsWhenTheFlowHasComeToRest) {
  const fs::path dir = fs::temp_directory_path() / ("talus_rest_" + std::to_string(::getpid()));
  makeScene(dir, "");  // writes the rasters
  auto runFile = [&](const std::string& name, const std::string& extra) {
    std::ofstream(dir / name) << "DEM=dem.tif\nInclude Initial Solids=1\nInitial Solid Height=solids.tif\n"
                              << "Initial Solid IFA=0.6\nEnd Time=2\nTimestep=30\nPrecision=double\n" << extra;
    return dir / name;
  };
  auto summaryOf = [](const fs::path& out) {
    std::ifstream in(out / "summary.json");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  auto simulated = [](const std::string& summary) {
    const std::size_t at = summary.find("\"simulated_s\": ");
    return at == std::string::npos ? -1.0 : std::atof(summary.c_str() + at + 15);
  };
  const Result stopped = run(runFile("rest.run", "Stop At Rest Fraction=0.001\n"), dir / "stopped");
  const Result full = run(runFile("full.run", ""), dir / "full");
  const std::string a = summaryOf(dir / "stopped"), b = summaryOf(dir / "full");
  EXPECT_NE(a.find("\"ended_at_rest\""), std::string::npos) << a;
  EXPECT_NE(a.find("\"status\": \"completed\""), std::string::npos) << a;
  EXPECT_EQ(b.find("\"ended_at_rest\""), std::string::npos) << b;
  EXPECT_LT(simulated(a), 0.9 * simulated(b)) << a;
  EXPECT_NEAR(simulated(b), 120.0, 1e-9);
  const std::vector<double> d1 = io::readRaster((dir / "stopped" / "deposit.tif").string()).values;
  const std::vector<double> d2 = io::readRaster((dir / "full" / "deposit.tif").string()).values;
  EXPECT_EQ(d1, d2) << "the deposit at rest is final";
  fs::remove_all(dir);
}
