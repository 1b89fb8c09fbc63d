// Resuming a hybrid-mode run from its checkpoint reproduces the uninterrupted run bitwise: every
// per-particle field (in the solver's order), the particle bookkeeping (outflow, released water) and
// the grid's state travel in the checkpoint. The scene makes all of it matter: a cohesive column
// twice its critical height collapses, yields, loses cohesion and releases its confined water onto
// the grid, where it flows.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/ParticleLayerIO.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

namespace fs = std::filesystem;
using namespace talus;

TEST(Checkpoint, HybridRunResumesBitwise) {
  const fs::path dir = fs::temp_directory_path() / ("talus_resume_particles_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Grid g = Grid::make(30, 30, 0.5);
  Raster dem(g, 0.0), solids(g, 0.0), water(g, 0.0);
  for (int j = 12; j < 18; ++j)
    for (int i = 12; i < 18; ++i) solids.at(i, j) = 4.0, water.at(i, j) = 3.0;
  io::writeRaster((dir / "dem.tif").string(), dem);
  io::writeRaster((dir / "solids.tif").string(), solids);
  io::writeRaster((dir / "water.tif").string(), water);
  std::ofstream(dir / "scene.run") << "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n"
                                   << "Include Initial Solids=1\nInitial Solid Height=solids.tif\nInitial Cohesion=10\n"
                                   << "Initial Solid IFA=0.5236\nEarth Pressure=constant\nEarth Pressure Coefficient=0.333\n"
                                   << "Use Material Point Method=1\nYoung Modulus=1e7\nBoundary Type=wall\n"
                                   << "End Time=0.02\nTimestep=0.5\nPrecision=double\nCheckpoint Interval=0.008\n";
  const io::RunConfig cfg = io::RunConfig::load((dir / "scene.run").string(), talusRunKeys());
  const sim::Scene scene = sim::loadScene(cfg);
  ASSERT_TRUE(scene.particles.enabled);
  sim::RunSummary full;
  {
    sim::Simulation sim(scene, cfg, (dir / "out").string(), sim::OutputMode::New);
    full = sim.run();
  }
  ASSERT_GT(full.checkpoints, 0);
  const io::ParticleLayer before = io::readParticleLayer((dir / "out/particles_final.gpkg").string());
  const std::vector<double> waterBefore = io::readRaster((dir / "out/hffinal.tif").string()).values;
  // The particle phase's peak maps travel in the checkpoint too.
  const std::vector<double> hcmaxBefore = io::readRaster((dir / "out/hcmax.tif").string()).values;
  const std::vector<double> vcmaxBefore = io::readRaster((dir / "out/vcmax.tif").string()).values;
  EXPECT_GT(*std::max_element(vcmaxBefore.begin(), vcmaxBefore.end()), 0.0) << "the column must move";
  ASSERT_GT(before.size(), 0u);
  const std::vector<double>* frac = before.find("cohesion_fraction");
  ASSERT_TRUE(frac);
  double minFrac = 1;
  for (double f : *frac) minFrac = std::min(minFrac, f);
  EXPECT_LT(minFrac, 1.0) << "the column must yield, so the checkpoint carries broken bonds";
  double gridWater = 0;
  for (double h : waterBefore) gridWater += h;
  EXPECT_GT(gridWater, 0.0) << "released water must be on the grid";
  // The particle mass balance counts the released water (double: round-off of ~10^3 masses).
  {
    std::ifstream in(dir / "out/summary.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = json.find("\"balance_error\": ", json.find("\"particles\""));
    ASSERT_NE(at, std::string::npos) << json;
    EXPECT_LT(std::fabs(std::stod(json.substr(at + 17))), 1e-12) << json;
  }

  sim::RunSummary resumed;
  {
    sim::Simulation sim(scene, cfg, (dir / "out").string(), sim::OutputMode::Resume);
    EXPECT_GT(sim.resumeTime(), 0.0);
    resumed = sim.run();
  }
  EXPECT_EQ(resumed.steps, full.steps);
  const io::ParticleLayer after = io::readParticleLayer((dir / "out/particles_final.gpkg").string());
  ASSERT_EQ(after.size(), before.size());
  EXPECT_TRUE(after.worldX == before.worldX);
  EXPECT_TRUE(after.worldY == before.worldY);
  for (const io::ParticleAttribute& a : before.attributes) {
    const std::vector<double>* b = after.find(a.name);
    ASSERT_TRUE(b) << a.name;
    EXPECT_TRUE(*b == a.values) << a.name << " differs after resuming";
  }
  EXPECT_TRUE(io::readRaster((dir / "out/hffinal.tif").string()).values == waterBefore);
  EXPECT_TRUE(io::readRaster((dir / "out/hcmax.tif").string()).values == hcmaxBefore);
  EXPECT_TRUE(io::readRaster((dir / "out/vcmax.tif").string()).values == vcmaxBefore);
  fs::remove_all(dir);
}
