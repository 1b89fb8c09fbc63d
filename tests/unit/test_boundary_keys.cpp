// Boundary Type / Nodata Boundary Type: the three values reach the solver, for water-only runs and
// for runs with solids (the two-phase fluid has the level edge's characteristic ghost too).
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

TEST(BoundaryKeys, LevelEdgesReachTheSolverForWaterAndForSolids) {
  const auto dir = std::filesystem::temp_directory_path() / "talus_boundary_keys";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  io::writeRaster((dir / "dem.tif").string(), Raster(Grid::make(10, 8, 1.0), 0.0));
  for (const std::string key : {"Boundary Type", "Nodata Boundary Type"})
    for (const std::string solids : {"", "Include Initial Solids=1\nInitial Solid Height=0.5\n"}) {
      const std::string text = "DEM=dem.tif\n" + solids + "End Time=0.01\n" + key + "=level\n";
      const io::RunConfig cfg = io::RunConfig::fromText(text, dir.string(), sim::talusRunKeys(), "level.run");
      const sim::Scene scene = sim::loadScene(cfg);
      EXPECT_EQ(scene.settings.twoPhase, !solids.empty());
      EXPECT_EQ(key == "Boundary Type" ? scene.settings.edge : scene.settings.nodata, fl::Boundary::Level) << key;
    }
  // The two-phase solver takes them (its fluid has the water's characteristic ghost).
  fl::FlowSettings s;
  s.twoPhase = true;
  s.edge = fl::Boundary::Level;
  EXPECT_NO_THROW(fl::FlowSolver(test::testContext(compute::Precision::Double), Grid::make(8, 8, 1.0), s));
}
