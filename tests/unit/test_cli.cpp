// End-to-end tests of the talus command line (src/cli/main.cpp): the executable named by
// TALUS_BINARY (set in tests/CMakeLists.txt) is run through std::system on tiny scenes written to a
// per-test temporary folder, and its exit status (0 ok, 2 bad input, 3 device), standard output,
// standard error and output folder are checked.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "compute/Device.hpp"
#include "core/Grid.hpp"
#include "core/Raster.hpp"
#include "io/ParticleLayerIO.hpp"
#include "io/RasterIO.hpp"

#ifndef TALUS_BINARY
#define TALUS_BINARY ""
#endif

namespace fs = std::filesystem;
using talus::Grid;
using talus::Raster;

#include "support/CliRun.hpp"

namespace {

using talus::test::Outcome;
using talus::test::shellQuote;
using talus::test::slurp;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// Fixture: a fresh temporary folder per test holding a tiny scene (20x16 cells, a block of water on
/// a gentle slope, open edges, 3 s simulated), and a runner for the executable.
class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(std::string(TALUS_BINARY).empty()) << "TALUS_BINARY is not defined (tests/CMakeLists.txt)";
    ASSERT_TRUE(fs::is_regular_file(TALUS_BINARY)) << "talus executable not found at " << TALUS_BINARY;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_cli_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::remove_all(dir_);
  }

  /// Writes dem.tif, water.tif and the run-file `name` (body appended after the scene keys).
  std::string writeScene(const std::string& extra = "", const std::string& name = "case.run") {
    return talus::test::writeCliScene(dir_, extra, name);
  }

  /// Runs `talus ARGS` (args already shell-quoted as needed) in the temp folder.
  Outcome talus(const std::string& args) {
    return talus::test::runIn(dir_, TALUS_BINARY, args);
  }

  fs::path dir_;
};

}  // namespace

TEST_F(Cli, DevicesListsADevice) {
  const Outcome r = talus("devices");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_TRUE(contains(r.out, "[0] ")) << r;
  const auto devices = talus::compute::listDevices();
  ASSERT_FALSE(devices.empty());
  EXPECT_TRUE(contains(r.out, devices.front().name)) << r;
}

TEST_F(Cli, KeysMarkdownPrintsTable) {
  const Outcome r = talus("keys --markdown");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_TRUE(contains(r.out, "Initial Fluid Height")) << r;
  EXPECT_TRUE(contains(r.out, "|---")) << r;
  const Outcome plain = talus("keys");
  ASSERT_EQ(plain.status, 0) << plain;
  EXPECT_TRUE(contains(plain.out, "Initial Fluid Height")) << plain;
}

TEST_F(Cli, RunsGoodScene) {
  writeScene();
  const Outcome r = talus("run case.run");
  ASSERT_EQ(r.status, 0) << r;
  const std::string json = slurp(dir_ / "out/summary.json");
  EXPECT_TRUE(contains(json, "\"status\": \"completed\"")) << json;
  EXPECT_TRUE(contains(json, "\"precision\": \"float\"")) << json;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "out/hffinal.tif"));
  EXPECT_TRUE(contains(r.err, "done")) << r;
}

TEST_F(Cli, QuietRunPrintsNothing) {
  const std::string runFile = writeScene();
  const Outcome r = talus("run " + shellQuote(runFile) + " --quiet --out quiet_out");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_EQ(r.err, "") << r;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "quiet_out/summary.json"));
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, BadKeyExits2NamingFileLineAndKey) {
  writeScene("[Flow]\nManing=0.05\n");  // line 12 of the run-file
  const Outcome r = talus("run case.run");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "case.run:12")) << r;
  EXPECT_TRUE(contains(r.err, "Maning")) << r;
  EXPECT_TRUE(contains(r.err, "did you mean 'Manning'")) << r;
  EXPECT_FALSE(fs::exists(dir_ / "out")) << "no output before the run-file is valid";
}

TEST_F(Cli, MissingRunFileExits2) {
  const Outcome r = talus("run nothere.run");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "nothere.run")) << r;
}

TEST_F(Cli, UnknownOptionExits2) {
  writeScene();
  const Outcome r = talus("run case.run --frobnicate");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "--frobnicate")) << r;
  const Outcome noValue = talus("run case.run --out");
  EXPECT_EQ(noValue.status, 2) << noValue;
  EXPECT_TRUE(contains(noValue.err, "--out")) << noValue;
}

TEST_F(Cli, SetOutOfRangeExits2NamingRange) {
  writeScene();
  const Outcome r = talus("run case.run --set \"CFL=5\"");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "CFL")) << r;
  EXPECT_TRUE(contains(r.err, "[0.01, 1]")) << r;
  EXPECT_TRUE(contains(r.err, "command line")) << r;
}

TEST_F(Cli, PrecisionDoubleReachesSummary) {
  writeScene();
  const Outcome r = talus("run case.run --precision double --quiet");
  ASSERT_EQ(r.status, 0) << r;
  const std::string json = slurp(dir_ / "out/summary.json");
  EXPECT_TRUE(contains(json, "\"precision\": \"double\"")) << json;
  EXPECT_TRUE(contains(json, "\"status\": \"completed\"")) << json;
  const Outcome bad = talus("run case.run --precision quad --overwrite");
  EXPECT_EQ(bad.status, 2) << bad;
  EXPECT_TRUE(contains(bad.err, "quad")) << bad;
}

TEST_F(Cli, ExistingOutputNeedsOverwrite) {
  writeScene();
  ASSERT_EQ(talus("run case.run --quiet").status, 0);
  const Outcome again = talus("run case.run --quiet");
  EXPECT_EQ(again.status, 2) << again;
  EXPECT_TRUE(contains(again.err, (dir_ / "out").string())) << again;
  EXPECT_TRUE(contains(again.err, "--overwrite")) << again;
  const Outcome forced = talus("run case.run --quiet --overwrite");
  EXPECT_EQ(forced.status, 0) << forced;
  EXPECT_TRUE(contains(slurp(dir_ / "out/summary.json"), "\"status\": \"completed\""));
}

TEST_F(Cli, BogusDeviceExits3ListingDevices) {
  writeScene();
  const Outcome r = talus("run case.run --device bogus");
  EXPECT_EQ(r.status, 3) << r;
  EXPECT_TRUE(contains(r.err, "bogus")) << r;
  const auto devices = talus::compute::listDevices();
  ASSERT_FALSE(devices.empty());
  EXPECT_TRUE(contains(r.err, devices.front().describe())) << r;
}

// An unstable run (exit status 4 when the health check trips) is not tested here: no honest tiny
// scene makes the solver produce NaN or a negative thickness. Robustness tests come later.

// Hybrid mode end to end: a cohesive layer over the whole scene at rest on a 2.5 % slope (bed
// friction 30 degrees holds it, cohesion 100 kPa leaves no lateral push) becomes particles, runs,
// and writes the particle layers, the particle columns of diagnostics.csv and the particle mass
// balance in summary.json; nothing moves (the terrain force stays below friction, so the implicit
// friction keeps every particle exactly at rest) and no particle is lost.
TEST_F(Cli, HybridRunWritesParticleLayers) {
  writeScene(
      "[Solids]\nInclude Initial Solids=1\nInitial Solid Height=2\nInitial Cohesion=100\n"
      "[Particles]\nUse Material Point Method=1\nYoung Modulus=1e7\n");
  const Outcome r = talus("run case.run");
  ASSERT_EQ(r.status, 0) << r;
  const std::string json = slurp(dir_ / "out/summary.json");
  // Seeding: the thickest cells (2 m of solids + 0.5 m of confined water) get the 4 particles per
  // cell, the others round(2 / 2.5 * 4) = 3: 30 x 4 + 290 x 3 = 990.
  EXPECT_TRUE(contains(json, "\"particles\": {\"count\": 990,")) << json;
  EXPECT_TRUE(contains(json, "\"balance_error\": 0}")) << json;
  const std::string csv = slurp(dir_ / "out/diagnostics.csv");
  EXPECT_TRUE(contains(csv, ",particles,particle_mass_kg,particle_outflow_kg,particle_kinetic_J,particle_viscous_dissipation_J,particle_art_stress_work_J,particle_friction_work_J,particle_potential_released_J,cumulative_rain_m3,cumulative_infiltrated_m3,wall_s\n")) << csv.substr(0, 400);
  ASSERT_TRUE(fs::is_regular_file(dir_ / "out/particles/particles_0000.gpkg"));
  const talus::io::ParticleLayer layer = talus::io::readParticleLayer((dir_ / "out/particles_final.gpkg").string());
  ASSERT_EQ(layer.size(), 990u);
  const std::vector<double>* speed = layer.find("speed");
  const std::vector<double>* frac = layer.find("cohesion_fraction");
  ASSERT_TRUE(speed && frac);
  for (std::size_t q = 0; q < layer.size(); ++q) {
    EXPECT_EQ((*speed)[q], 0.0) << q;
    EXPECT_EQ((*frac)[q], 1.0) << q;
  }
  // The particles on the grid (P2G, weights a partition of unity folded at the raster edge): the
  // confined volume 320 cells x 2 m + 30 cells x 0.5 m of confined water, times 4 m^2 = 2620 m^3,
  // to float round-off (1e-5); intact bonds everywhere.
  const Raster hc = talus::io::readRaster((dir_ / "out/hcfinal.tif").string());
  const Raster cf = talus::io::readRaster((dir_ / "out/cfracfinal.tif").string());
  double volume = 0;
  for (std::size_t k = 0; k < hc.values.size(); ++k) {
    volume += hc.values[k] * 4.0;
    EXPECT_NEAR(cf.values[k], 1.0, 1e-6) << k;
  }
  EXPECT_NEAR(volume, 2620.0, 1e-5 * 2620.0);
}

TEST_F(Cli, HybridRunRejectsAbsurdParticleCount) {
  writeScene("[Solids]\nInclude Initial Solids=1\nInitial Solid Height=1\n"
             "[Particles]\nUse Material Point Method=1\nParticle Fractional Dimension=1e-9\n");
  const Outcome r = talus("run case.run");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "Particle Fractional Dimension")) << r;
  EXPECT_TRUE(contains(r.err, "more than")) << r;
}

TEST_F(Cli, HybridRunRejectsImpossibleShearModulus) {
  writeScene("[Solids]\nInclude Initial Solids=1\nInitial Solid Height=1\n"
             "[Particles]\nUse Material Point Method=1\nYoung Modulus=1e7\nShear Modulus=1e6\n");
  const Outcome r = talus("run case.run");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "case.run")) << r;
  EXPECT_TRUE(contains(r.err, "Shear Modulus")) << r;
}

// The series of a run are those of the phases it can hold (issue 15): a dry granular run writes the
// solids' thickness and speed at each report time and no all-zero fluid series, and the final speed
// maps vffinal / vsfinal that OpenLISEM writes. The final solid speed never exceeds its maximum, and
// the last report (at End Time) is the final state.
TEST_F(Cli, DryGranularRunWritesSolidSeriesAndFinalSpeeds) {
  writeScene("[Solids]\nInclude Initial Solids=1\nInitial Solid Height=water.tif\nInitial Solid IFA=0.1\n", "dry.run");
  const Outcome r = talus("run dry.run --set \"Include Initial Water=0\" --set \"Timestep=1.5\"");
  ASSERT_EQ(r.status, 0) << r;
  const fs::path out = dir_ / "out";
  EXPECT_FALSE(fs::exists(out / "series/hf_0000.tif"));
  EXPECT_FALSE(fs::exists(out / "series/vf_0000.tif"));
  const std::string index = slurp(out / "series/index.csv");
  EXPECT_TRUE(contains(index, "0,0,series/hs_0000,series/vs_0000")) << index;
  const Raster vs = talus::io::readRaster((out / "vsfinal.tif").string());
  const Raster vsmax = talus::io::readRaster((out / "vsmax.tif").string());
  const Raster last = talus::io::readRaster((out / "series/vs_0002.tif").string());  // t = 3 s = End Time
  const Raster early = talus::io::readRaster((out / "series/vs_0001.tif").string());  // t = 1.5 s
  double fastest = 0;
  for (std::size_t k = 0; k < vs.values.size(); ++k) {
    EXPECT_LE(vs.values[k], vsmax.values[k] * (1 + 1e-6) + 1e-12) << k;  // float maps
    EXPECT_LE(early.values[k], vsmax.values[k] * (1 + 1e-6) + 1e-12) << k;
    EXPECT_EQ(vs.values[k], last.values[k]) << k;
    fastest = std::max(fastest, early.values[k]);
  }
  EXPECT_GT(fastest, 0.0);  // the 0.5 m block slumps (and has come to rest by 3 s)
  EXPECT_TRUE(fs::is_regular_file(out / "vffinal.tif"));
}
