// A run with rainfall and infiltration through the whole loop (sim::Simulation): the rain and
// infiltrated volumes in summary.json and diagnostics.csv, a volume balance that closes with them,
// and a run stopped at a checkpoint that resumes to bitwise the same diagnostics and maps (the
// cumulative totals travel in the checkpoint, version 3).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

namespace fs = std::filesystem;
using namespace talus;

namespace {

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// diagnostics.csv without its last column (wall time), and the final depth map's bytes.
std::string fingerprint(const fs::path& out) {
  std::istringstream csv(readFile(out / "diagnostics.csv"));
  std::string all, line;
  while (std::getline(csv, line)) all += line.substr(0, line.rfind(',')) + "\n";
  const Raster r = io::readRaster((out / "hffinal.tif").string());
  all.append(reinterpret_cast<const char*>(r.values.data()), r.values.size() * sizeof(double));
  return all;
}

class RainRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("talus_rain_run_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A dry 30 x 20 plane of 2 m cells tilted 2 % in x, open edges: rain runs off at the low edge.
    const Grid g = Grid::make(30, 20, 2.0, 0.0, 0.0);
    Raster dem(g, 0.0);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) dem.at(i, j) = 0.04 * (g.nx - i);
    io::writeRaster((dir_ / "dem.tif").string(), dem);
    io::writeRaster((dir_ / "flat.tif").string(), Raster(g, 0.0));
    area_ = g.cells() * g.dx * g.dx;
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// 200 mm/h of rain, 20 mm/h infiltration capacity; End Time in minutes.
  io::RunConfig config(double endMinutes, const std::string& dem = "dem.tif") const {
    std::ostringstream run;
    run << "DEM=" << dem << "\nManning=0.03\nInclude Rainfall=1\nRainfall Intensity=200\nInclude Infiltration=1\n"
        << "KSatSimple=20\nEnd Time=" << endMinutes << "\nTimestep=0.25\nCheckpoint Interval=0.25\n"
        << "Precision=double\n";
    return io::RunConfig::fromText(run.str(), dir_.string(), sim::talusRunKeys());
  }

  fs::path dir_;
  double area_ = 0;
};

}  // namespace

TEST_F(RainRun, VolumesAreTalliedAndResumeIsBitwise) {
  const io::RunConfig full = config(1.0);
  const sim::Scene scene = sim::loadScene(full);
  sim::RunSummary s;
  {
    sim::Simulation sim(scene, full, (dir_ / "full").string(), sim::OutputMode::New);
    s = sim.run();
  }
  std::printf("rain %.6g m^3, infiltrated %.6g m^3, outflow %.6g m^3, final %.6g m^3, balance error %.2e\n",
              s.totalRain, s.totalInfiltrated, s.totalOutflow, s.finalVolume, s.volumeBalanceError);
  // 200 mm/h for 60 s on every cell.
  EXPECT_NEAR(s.totalRain, 200.0 / 3.6e6 * 60.0 * area_, 1e-12 * s.totalRain);
  EXPECT_GT(s.totalInfiltrated, 0.0);
  // Infiltration takes at most 20 mm/h of the wet area's time: less than a tenth of the rain.
  EXPECT_LE(s.totalInfiltrated, 0.1 * s.totalRain * (1 + 1e-12));
  EXPECT_GT(s.totalOutflow, 0.0);
  EXPECT_LT(std::fabs(s.volumeBalanceError), 1e-12);
  const std::string json = readFile(dir_ / "full" / "summary.json");
  EXPECT_NE(json.find("\"rain_m3\": "), std::string::npos) << json;
  EXPECT_NE(json.find("\"infiltrated_m3\": "), std::string::npos) << json;
  const std::string csv = readFile(dir_ / "full" / "diagnostics.csv");
  EXPECT_NE(csv.find(",cumulative_rain_m3,cumulative_infiltrated_m3,wall_s\n"), std::string::npos);

  // Stop at 30 s (a checkpoint and report time), then resume to 60 s with a later End Time.
  const io::RunConfig half = config(0.5);
  const sim::Scene halfScene = sim::loadScene(half);
  { sim::Simulation(halfScene, half, (dir_ / "resumed").string(), sim::OutputMode::New).run(); }
  sim::RunSummary r;
  { r = sim::Simulation(scene, full, (dir_ / "resumed").string(), sim::OutputMode::Resume).run(); }
  EXPECT_EQ(r.totalRain, s.totalRain);
  EXPECT_EQ(r.totalInfiltrated, s.totalInfiltrated);
  EXPECT_TRUE(fingerprint(dir_ / "resumed") == fingerprint(dir_ / "full"));
}

// A dry flat plane with open edges: no relief and no initial water, so without the run's rain in
// the health check's energy bound any speed would be unexplained. Uniform rain on it stays at rest
// (the open edges see the same depth outside: no outflow), the depth is i t everywhere.
TEST_F(RainRun, RainOnAFlatPlaneStaysAtRest) {
  const io::RunConfig cfg = config(1.0, "flat.tif");
  const sim::Scene scene = sim::loadScene(cfg);
  sim::Simulation sim(scene, cfg, (dir_ / "flat").string(), sim::OutputMode::New);
  sim::RunSummary s;
  ASSERT_NO_THROW(s = sim.run());
  EXPECT_EQ(s.totalOutflow, 0.0);
  // Infiltration takes 20 of the 200 mm/h from the first step on (every cell is wet by then).
  EXPECT_NEAR(s.finalVolume, 180.0 / 3.6e6 * 60.0 * area_, 1e-12 * s.finalVolume);
  EXPECT_LT(std::fabs(s.volumeBalanceError), 1e-12);
  const Raster h = io::readRaster((dir_ / "flat" / "hffinal.tif").string());
  // The map is stored as 32-bit floats: the depth to float's half ulp, and the same in every cell.
  for (double v : h.values) {
    EXPECT_NEAR(v, 180.0 / 3.6e6 * 60.0, 6e-8 * 0.003);
    EXPECT_EQ(v, h.values[0]);
  }
}

// Rain on a dry slope: what runs off must not depend on how often the run reports. With one report a
// minute, the step that wets the ground keeps within the time step of the wetted state
// (FlowSolver::filmStableDt); before, that step was the whole minute (nothing moves on dry ground),
// so no water had left by 60 s, while a run reporting every second had shed 0.097 m^3. The two
// runs differ only in where report times clip a step: 10 % covers that (measured 3.6 %).
TEST_F(RainRun, RunoffFromADrySlopeDoesNotDependOnTheReportInterval) {
  auto outflow = [&](const char* timestep, const char* out) {
    std::ostringstream run;
    run << "DEM=dem.tif\nManning=0.03\nInclude Rainfall=1\nRainfall Intensity=200\nInclude Infiltration=1\n"
        << "KSatSimple=20\nEnd Time=1\nTimestep=" << timestep << "\nPrecision=double\n";
    const io::RunConfig cfg = io::RunConfig::fromText(run.str(), dir_.string(), sim::talusRunKeys());
    const sim::Scene scene = sim::loadScene(cfg);
    sim::Simulation sim(scene, cfg, (dir_ / out).string(), sim::OutputMode::New);
    return sim.run().totalOutflow;
  };
  const double minute = outflow("60", "minute"), second = outflow("1", "second");
  std::printf("outflow by 60 s: %.6g m^3 reporting every minute, %.6g m^3 every second\n", minute, second);
  ASSERT_GT(second, 0.0);
  EXPECT_NEAR(minute, second, 0.10 * second);
}
