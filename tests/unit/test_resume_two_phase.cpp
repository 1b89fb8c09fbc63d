// Resuming a two-phase run from its checkpoint reproduces the uninterrupted run bitwise: the solid
// state, the static-solid flags and the two-phase maxima travel in the checkpoint too; with
// entrainment also the erodible depth, the lowered bed and its slope fields, and the volume balance
// (whose entrained volume a resumed run recovers from the bed change).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

namespace fs = std::filesystem;
using namespace talus;

namespace {

std::vector<double> map(const fs::path& p) { return io::readRaster(p.string()).values; }

/// Runs the two-phase scene with `extra` run-file lines to its end, then resumes it from its last
/// checkpoint, and compares `maps` and the summary's balance.
void expectResumesBitwise(const std::string& extra, std::vector<std::string> maps) {
  const fs::path dir = fs::temp_directory_path() / ("talus_resume2p_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Grid g = Grid::make(40, 24, 2.0);
  Raster dem(g, 0.0), solids(g, 0.0), water(g, 0.0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      dem.at(i, j) = -0.5 * i + 0.3 * std::cos(0.4 * j);  // a 27 degree slope with a gentle channel
      if (std::hypot(i - 8.0, j - 12.0) < 5) solids.at(i, j) = 1.2, water.at(i, j) = 0.8;
    }
  io::writeRaster((dir / "dem.tif").string(), dem);
  io::writeRaster((dir / "solids.tif").string(), solids);
  io::writeRaster((dir / "water.tif").string(), water);
  std::ofstream(dir / "scene.run") << "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n"
                                   << "Include Initial Solids=1\nInitial Solid Height=solids.tif\n"
                                   << "Initial Solid IFA=0.5\nEnd Time=0.1\nTimestep=2\nPrecision=double\n"
                                   << "Checkpoint Interval=0.03\n" << extra;
  const io::RunConfig cfg = io::RunConfig::load((dir / "scene.run").string(), talusRunKeys());
  const sim::Scene scene = sim::loadScene(cfg);
  ASSERT_TRUE(scene.settings.twoPhase);
  sim::RunSummary full;
  {
    sim::Simulation sim(scene, cfg, (dir / "out").string(), sim::OutputMode::New);
    full = sim.run();
  }
  ASSERT_GT(full.checkpoints, 0);
  for (const char* m : {"hsfinal.tif", "hffinal.tif", "hsmax.tif", "vsmax.tif", "sfracmax.tif", "pimpactmax.tif",
                        "deposit.tif", "tarrival.tif"})
    maps.push_back(m);
  std::vector<std::vector<double>> before;
  for (const std::string& m : maps) before.push_back(map(dir / "out" / m));
  // Resume from the last checkpoint (written before the end) and run the tail again.
  sim::RunSummary resumed;
  {
    sim::Simulation sim(scene, cfg, (dir / "out").string(), sim::OutputMode::Resume);
    EXPECT_GT(sim.resumeTime(), 0.0);
    resumed = sim.run();
  }
  EXPECT_EQ(resumed.steps, full.steps);
  for (std::size_t m = 0; m < before.size(); ++m)
    EXPECT_TRUE(map(dir / "out" / maps[m]) == before[m]) << maps[m] << " differs after resuming";
  // The resumed run recovers the initial erodible volume as (left + eroded) from the checkpoint's
  // fields, a different sum of the same numbers: equal to round-off, not bitwise.
  EXPECT_NEAR(resumed.totalEntrained, full.totalEntrained, 1e-12 * (1.0 + full.totalEntrained));
  EXPECT_NEAR(resumed.volumeBalanceError, full.volumeBalanceError, 1e-14);
  fs::remove_all(dir);
}

}  // namespace

TEST(Checkpoint, TwoPhaseRunResumesBitwise) { expectResumesBitwise("", {}); }

TEST(Checkpoint, EntrainmentRunResumesBitwise) {
  expectResumesBitwise("Include Entrainment=1\nErodible Depth=0.3\nEntrainment Growth Rate=0.02\n",
                       {"basechange.tif", "erodiblefinal.tif"});
}
