// The solids' basal law from the run-file (key Solid Rheology and its parameters, flow/Rheology.cpp)
// through scene loading and a whole run: the parameters reach the kernels (a Voellmy mass whose mu
// exceeds the slope's tangent stays at rest, one with a small mu slides, with the speed a Coulomb
// run of the same mu cannot reach), and bad combinations are refused with the key named: mu(I)
// angles in the wrong order, another law with the particles, snow-light solids in water; and an
// entrainment run writes its bed change (basechange) consistent with the erodible layer left.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "core/Constants.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"
#include "support/ExpectInputError.hpp"

namespace fs = std::filesystem;
using talus::Grid;
using talus::Raster;
using talus::io::RunConfig;
using talus::sim::talusRunKeys;
using talus::test::expectInputError;

namespace {

constexpr int kNx = 30, kNy = 8;
constexpr double kDx = 1.0, kSlope = 0.4;  // tan(theta): 21.8 degrees

class RheologyKeys : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("talus_rheology_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A plane falling along +x, with a 2 m block of solids near the top.
    Raster dem(Grid::make(kNx, kNy, kDx), 0.0), hs(Grid::make(kNx, kNy, kDx), 0.0);
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) {
        dem.at(i, j) = 100.0 - kSlope * i * kDx;
        hs.at(i, j) = (i >= 3 && i < 8 && j >= 2 && j < 6) ? 2.0 : 0.0;
      }
    talus::io::writeRaster(path("dem.tif"), dem);
    talus::io::writeRaster(path("hs.tif"), hs);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& rel) const { return (dir_ / rel).string(); }
  /// A run-file of the block with `extra` lines appended.
  std::string writeRun(const std::string& extra) {
    std::ofstream(path("case.run"), std::ios::binary)
        << "DEM=dem.tif\nInclude Initial Solids=1\nInitial Solid Height=hs.tif\nEnd Time=0.05\nTimestep=3\n"
           "Precision=double\nDrag Law=off\nBoundary Type=wall\nOutput Directory=out\nReport Series=0\n"
        << extra;
    return path("case.run");
  }
  talus::sim::Scene loadScene(const std::string& runFile) {
    cfg_.emplace(RunConfig::load(runFile, talusRunKeys()));
    return talus::sim::loadScene(*cfg_);
  }
  /// Largest solid speed of a run of `runFile` (vsmax) [m/s].
  double peakSpeed(const std::string& runFile) {
    const talus::sim::Scene scene = loadScene(runFile);
    talus::sim::Simulation sim(scene, *cfg_, path("out"), talus::sim::OutputMode::Overwrite);
    sim.run({});
    const Raster v = talus::io::readRaster(path("out/vsmax.tif"));
    double m = 0;
    for (std::size_t k = 0; k < v.values.size(); ++k)
      if (v.valid[k]) m = std::max(m, v.values[k]);
    return m;
  }

  fs::path dir_;
  std::optional<RunConfig> cfg_;
};

}  // namespace

TEST_F(RheologyKeys, VoellmyParametersReachTheScene) {
  const talus::sim::Scene s = loadScene(writeRun("Solid Rheology=voellmy\nVoellmy Mu=0.2\nVoellmy Xi=500\n"));
  EXPECT_EQ(s.settings.debris.rheology, talus::flow::Rheology::Voellmy);
  EXPECT_EQ(s.settings.debris.rheologyParams[0], 0.2);
  EXPECT_DOUBLE_EQ(s.settings.debris.rheologyParams[1], talus::kGravity / 500.0);
  // The default is Coulomb with the bed friction angle.
  EXPECT_EQ(loadScene(writeRun("")).settings.debris.rheology, talus::flow::Rheology::Coulomb);
}

TEST_F(RheologyKeys, VoellmyFrictionHoldsOrReleasesTheBlock) {
  // mu = 0.6 > tan(theta) = 0.4 (K = 1 spreading aside): the block's interior is held; with the
  // same xi and mu = 0.1 it slides. With xi very large the turbulent term vanishes and Voellmy is
  // Coulomb with delta = atan(mu): the same peak speed to round-off as the Coulomb run.
  const std::string common = "Earth Pressure=constant\nEarth Pressure Coefficient=1\n";
  const double held = peakSpeed(writeRun(common + "Solid Rheology=voellmy\nVoellmy Mu=0.6\nVoellmy Xi=400\n"));
  const double slides = peakSpeed(writeRun(common + "Solid Rheology=voellmy\nVoellmy Mu=0.1\nVoellmy Xi=400\n"));
  const double coulomb = peakSpeed(writeRun(common + "Bed Friction Equals IFA=0\nBed Friction Angle=" +
                                            std::to_string(std::atan(0.1)) + "\n"));
  const double noTurbulence = peakSpeed(writeRun(common + "Solid Rheology=voellmy\nVoellmy Mu=0.1\nVoellmy Xi=1e7\n"));
  std::printf("[ block ] peak speed: held %.4f, sliding %.4f, Coulomb %.4f, xi = 1e7 %.6f m/s\n", held, slides, coulomb, noTurbulence);
  // 3 s on a 0.4 slope: the frictionless bound is g sin(theta) t ~ 11 m/s; the held block only
  // spreads its edges (pressure, not the slope), well below the sliding one.
  EXPECT_GT(slides, 2.0 * held);
  EXPECT_LT(slides, coulomb);  // the turbulent drag slows it
  EXPECT_NEAR(noTurbulence, coulomb, 1e-3 * coulomb);  // xi = 1e7: the drag term is ~1e-5 of friction here
}

TEST_F(RheologyKeys, BadCombinationsAreRefused) {
  expectInputError([&] { loadScene(writeRun("Solid Rheology=mu-i\nPouliquen Angle 1=0.5\nPouliquen Angle 2=0.4\n")); },
                   {"Pouliquen Angle 2", "Pouliquen Angle 1"});
  expectInputError([&] { loadScene(writeRun("Solid Rheology=plastic\n")); }, {"case.run", "Solid Rheology", "plastic"});
  expectInputError([&] { loadScene(writeRun("Solid Rheology=bingham\nUse Material Point Method=1\n")); },
                   {"case.run", "Solid Rheology", "bingham", "Material Point Method"});
  // Snow (300 kg/m^3) runs dry, but not in water, which would float it.
  EXPECT_NO_THROW(loadScene(writeRun("Initial Solid Density=300\n")));
  expectInputError([&] { loadScene(writeRun("Initial Solid Density=300\nInclude Initial Water=1\nInitial Fluid Height=0.1\n")); },
                   {"case.run", "Initial Solid Density", "column 3", "Fluid Density"});
}

TEST_F(RheologyKeys, EntrainmentRunWritesBedChange) {
  // The block slides over a 0.5 m erodible layer: what the bed lost (basechange < 0) is what the
  // layer lost, cell by cell, and the run's volume balance counts the entrained volume as a source.
  const std::string run = writeRun("Include Entrainment=1\nErodible Depth=0.5\nEntrainment Growth Rate=0.02\n"
                                   "Bed Friction Equals IFA=0\nBed Friction Angle=0.2\n");
  const talus::sim::Scene scene = loadScene(run);
  ASSERT_TRUE(scene.settings.entrainment.enabled);
  talus::sim::Simulation sim(scene, *cfg_, path("out"), talus::sim::OutputMode::Overwrite);
  const talus::sim::RunSummary s = sim.run({});
  const Raster change = talus::io::readRaster(path("out/basechange.tif"));
  const Raster left = talus::io::readRaster(path("out/erodiblefinal.tif"));
  double eroded = 0, worst = 0;
  for (std::size_t k = 0; k < change.values.size(); ++k) {
    eroded -= change.values[k] * kDx * kDx;
    // float32 maps: 0.5 m to ~3e-8.
    worst = std::max(worst, std::fabs(change.values[k] + (0.5 - left.values[k])));
  }
  std::printf("[ entrainment run ] entrained %.4f m^3 (maps %.4f), balance error %.2e\n", s.totalEntrained, eroded,
              s.volumeBalanceError);
  EXPECT_GT(s.totalEntrained, 0.1);
  EXPECT_NEAR(eroded, s.totalEntrained, 1e-6 * (1 + s.totalEntrained));
  EXPECT_LT(worst, 1e-7);
  EXPECT_LT(std::fabs(s.volumeBalanceError), 1e-12);
  expectInputError([&] { loadScene(writeRun("Include Entrainment=1\nErodible Depth=0.5\nUse Material Point Method=1\n")); },
                   {"case.run", "Include Entrainment", "Material Point Method"});
}
