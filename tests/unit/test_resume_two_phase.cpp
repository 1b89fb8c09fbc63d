// Resuming a two-phase run from its checkpoint reproduces the uninterrupted run bitwise: the solid
// state, the static-solid flags and the two-phase maxima travel in the checkpoint too.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

namespace fs = std::filesystem;
using namespace talus;

namespace {

std::vector<double> map(const fs::path& p) { return io::readRaster(p.string()).values; }

}  // namespace

TEST(Checkpoint, TwoPhaseRunResumesBitwise) {
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
                                   << "Checkpoint Interval=0.03\n";
  const io::RunConfig cfg = io::RunConfig::load((dir / "scene.run").string(), talusRunKeys());
  const sim::Scene scene = sim::loadScene(cfg);
  ASSERT_TRUE(scene.settings.twoPhase);
  sim::RunSummary full;
  {
    sim::Simulation sim(scene, cfg, (dir / "out").string(), sim::OutputMode::New);
    full = sim.run();
  }
  ASSERT_GT(full.checkpoints, 0);
  const char* maps[] = {"hsfinal.tif", "hffinal.tif", "hsmax.tif", "vsmax.tif", "sfracmax.tif",
                        "pimpactmax.tif", "deposit.tif", "tarrival.tif"};
  std::vector<std::vector<double>> before;
  for (const char* m : maps) before.push_back(map(dir / "out" / m));
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
  fs::remove_all(dir);
}
