// Boundary Type / Nodata Boundary Type: the three values reach the solver, and level edges, which the
// two-phase model does not have, are refused for runs with solids, naming the key (by the scene
// and by the solver itself).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/Error.hpp"
#include "core/Raster.hpp"
#include "flow/FlowSolver.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using namespace talus;

TEST(BoundaryKeys, EveryValueParsesAndAnUnknownOneIsNamed) {
  EXPECT_EQ(fl::parseBoundary("wall"), fl::Boundary::Wall);
  EXPECT_EQ(fl::parseBoundary("open"), fl::Boundary::Open);
  EXPECT_EQ(fl::parseBoundary("level"), fl::Boundary::Level);
  try {
    fl::parseBoundary("sea");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("open, wall, level"), std::string::npos) << e.what();
  }
}

TEST(BoundaryKeys, LevelEdgesAreRefusedForRunsWithSolids) {
  const auto dir = std::filesystem::temp_directory_path() / "talus_boundary_keys";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  io::writeRaster((dir / "dem.tif").string(), Raster(Grid::make(10, 8, 1.0), 0.0));
  for (const std::string key : {"Boundary Type", "Nodata Boundary Type"}) {
    const std::string text = "DEM=dem.tif\nInclude Initial Solids=1\nInitial Solid Height=0.5\nEnd Time=0.01\n" + key +
                             "=level\n";
    const io::RunConfig cfg = io::RunConfig::fromText(text, dir.string(), sim::talusRunKeys(), "solids.run");
    try {
      sim::loadScene(cfg);
      FAIL() << key << ": no error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("key '" + key + "'"), std::string::npos) << what;
      EXPECT_NE(what.find("solids.run"), std::string::npos) << what;
    }
    // Water only, the same key is fine.
    const io::RunConfig water = io::RunConfig::fromText("DEM=dem.tif\nEnd Time=0.01\n" + key + "=level\n", dir.string(),
                                                        sim::talusRunKeys(), "water.run");
    EXPECT_NO_THROW(sim::loadScene(water)) << key;
  }
  // The solver refuses them too (a caller that builds settings itself).
  fl::FlowSettings s;
  s.twoPhase = true;
  s.edge = fl::Boundary::Level;
  EXPECT_THROW(fl::FlowSolver(test::testContext(compute::Precision::Double), Grid::make(8, 8, 1.0), s), InputError);
}
