// Guarded runs and checkpoint/restart: the checkpoint file format, the per-step health check
// (each failure names the quantity and the cell), a run that turns unstable keeps its outputs, and
// a run killed (SIGKILL) at random moments leaves readable outputs and resumes with `talus run
// --resume` to bitwise the same maps and diagnostics as an uninterrupted run.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "core/Error.hpp"
#include "ensemble/Json.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/Checkpoint.hpp"
#include "sim/HealthCheck.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"
#include "support/TestDevice.hpp"

namespace fs = std::filesystem;
using namespace talus;

namespace {

/// A per-test folder, removed at the end.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("talus_ck_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A small dam break over a tilted, bumpy plane with open edges: water leaves, fronts wet and dry.
/// Returns the run-file path.
fs::path writeScene(const fs::path& dir, double endMinutes, double checkpointMinutes) {
  const int nx = 60, ny = 48;
  const Grid g = Grid::make(nx, ny, 2.0, 1000.0, 5000.0);
  Raster dem(g, 0.0), water(g, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      dem.at(i, j) = 0.05 * i + 0.3 * std::sin(0.4 * i) * std::cos(0.3 * j);
      if (std::hypot(i - 15.0, j - 24.0) < 8.0) water.at(i, j) = 3.0;
    }
  io::writeRaster((dir / "dem.tif").string(), dem);
  io::writeRaster((dir / "water.tif").string(), water);
  std::ofstream run(dir / "scene.run");
  run << "[Input]\nDEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n"
      << "[Flow]\nManning=0.02\n[Time]\nEnd Time=" << endMinutes << "\nTimestep=3\n"
      << "[Numerics]\nPrecision=double\n[Output]\nCheckpoint Interval=" << checkpointMinutes << "\n";
  return dir / "scene.run";
}

int runTalus(const std::string& args) {
  const std::string cmd = std::string(TALUS_BINARY) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Maps and diagnostics of a finished run, for comparing two runs (wall-clock column removed).
std::string runFingerprint(const fs::path& out) {
  std::string all;
  for (const char* name : {"hffinal.tif", "hfmax.tif", "vfmax.tif", "tarrival.tif"}) {
    const Raster r = io::readRaster((out / name).string());
    all.append(reinterpret_cast<const char*>(r.values.data()), r.values.size() * sizeof(double));
  }
  std::istringstream csv(readFile(out / "diagnostics.csv"));
  std::string line;
  long columns = -1;
  while (std::getline(csv, line)) {
    // Every row has the header's columns (a run without particles writes zeros in theirs).
    const long commas = std::count(line.begin(), line.end(), ',');
    if (columns < 0) columns = commas;
    EXPECT_EQ(commas, columns) << out << ": " << line;
    all += line.substr(0, line.rfind(',')) + "\n";
  }
  all += readFile(out / "series" / "index.csv");
  for (const auto& e : fs::directory_iterator(out / "series"))
    if (e.path().extension() == ".tif") {
      const Raster r = io::readRaster(e.path().string());
      all.append(reinterpret_cast<const char*>(r.values.data()), r.values.size() * sizeof(double));
    }
  return all;
}

}  // namespace

TEST(Checkpoint, FileRoundTripAndCorruption) {
  TempDir t;
  sim::Checkpoint c;
  c.precision = "double";
  c.nx = 3;
  c.ny = 2;
  c.time = 12.5;
  c.steps = 77;
  c.reportIndex = 4;
  c.initialVolume = 10.25;
  c.totalOutflow = 0.125;
  c.totalRain = 2.75;
  c.totalInfiltrated = 0.5;
  c.totalSourceWork = 6.25;
  c.elapsedWall = 3.5;
  c.seriesIndex = "index,time_s\n0,0\n";
  c.state = {'a', '\0', 'b', '\x7f'};
  const std::string path = (t.path / "checkpoint.bin").string();
  sim::writeCheckpoint(path, c);
  const sim::Checkpoint r = sim::readCheckpoint(path);
  EXPECT_EQ(r.precision, c.precision);
  EXPECT_EQ(r.nx, 3);
  EXPECT_EQ(r.ny, 2);
  EXPECT_EQ(r.time, 12.5);
  EXPECT_EQ(r.steps, 77);
  EXPECT_EQ(r.reportIndex, 4);
  EXPECT_EQ(r.initialVolume, 10.25);
  EXPECT_EQ(r.totalOutflow, 0.125);
  EXPECT_EQ(r.totalRain, 2.75);
  EXPECT_EQ(r.totalInfiltrated, 0.5);
  EXPECT_EQ(r.totalSourceWork, 6.25);
  EXPECT_EQ(r.elapsedWall, 3.5);
  EXPECT_EQ(r.seriesIndex, c.seriesIndex);
  EXPECT_EQ(r.state, c.state);
  const std::string bytes = readFile(path);
  const std::size_t totals = 8 + (8 + c.precision.size()) + 4 + 4 + 8 + 8 + 4 + 8 + 8;
  // An older file: this one's bytes without `length` bytes from `from`, magic "TALUSCK<version>" at
  // both ends.
  auto older = [&](char version, std::size_t from, std::size_t length) {
    std::string old = bytes.substr(0, from) + bytes.substr(from + length);
    old[7] = old[old.size() - 1] = version;
    const std::string oldPath = (t.path / (std::string("v") + version + ".bin")).string();
    std::ofstream(oldPath, std::ios::binary).write(old.data(), static_cast<std::streamsize>(old.size()));
    return sim::readCheckpoint(oldPath);
  };
  // Version 3 (before the work of friction and drag, after the infiltration) reads with zero work.
  const sim::Checkpoint o3 = older('3', totals + 16, 8);
  EXPECT_EQ(o3.totalInfiltrated, 0.5);
  EXPECT_EQ(o3.totalSourceWork, 0.0);
  EXPECT_EQ(o3.elapsedWall, 3.5);
  EXPECT_EQ(o3.state, c.state);
  // Version 2 (before rain and infiltration too) reads with zero totals.
  const sim::Checkpoint o2 = older('2', totals, 24);
  EXPECT_EQ(o2.totalOutflow, 0.125);
  EXPECT_EQ(o2.totalRain, 0.0);
  EXPECT_EQ(o2.totalInfiltrated, 0.0);
  EXPECT_EQ(o2.elapsedWall, 3.5);
  EXPECT_EQ(o2.state, c.state);
  // A truncated checkpoint (a kill during a copy, a full disk) is refused by name, at every length.
  for (std::size_t cut : {std::size_t{0}, std::size_t{5}, std::size_t{20}, bytes.size() - 1}) {
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(cut));
    try {
      sim::readCheckpoint(path);
      ADD_FAILURE() << "a checkpoint cut to " << cut << " bytes was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(sim::readCheckpoint((t.path / "missing.bin").string()), InputError);
}

TEST(HealthCheck, NamesTheFailingQuantityAndCell) {
  const Grid g = Grid::make(20, 10, 1.0);
  Raster dem(g, 0.0);
  flow::FlowInput calm;
  calm.mask.assign(g.cells(), 1);
  calm.bed.assign(g.cells(), 0.0);
  calm.manning.assign(g.cells(), 0.0);
  calm.h.assign(g.cells(), 1.0);
  // Flat 1 m lake: a fall of Z = 1 m (surface to bed) and a 1 m column, so no flow is faster than
  // sqrt(2 g) + 2 sqrt(g) ~ 10.7 m/s (HealthCheck::speedBound).
  compute::Context& ctx = test::testContext(compute::Precision::Double);
  flow::FlowSettings settings;
  const sim::HealthCheck health(dem, calm, settings);
  EXPECT_NEAR(health.speedBound(), std::sqrt(2 * 9.81) + 2 * std::sqrt(9.81), 1e-12);
  flow::FlowSolver solver(ctx, g, settings);

  solver.setInput(calm);
  EXPECT_EQ(health.check(solver, 0.5 * solver.stableDt()), "");

  flow::FlowInput jet = calm;  // 50 m/s in cell (7, 3): no energy in this scene can do that
  jet.qx.assign(g.cells(), 0.0);
  jet.qy.assign(g.cells(), 0.0);
  jet.qx[g.index(7, 3)] = 50.0;
  solver.setInput(jet);
  std::string why = health.check(solver, 1e-4);
  EXPECT_NE(why.find("runaway velocity"), std::string::npos) << why;
  EXPECT_NE(why.find("column 7, row 3"), std::string::npos) << why;

  flow::FlowInput nan = calm;
  nan.h[g.index(12, 8)] = std::nan("");
  solver.setInput(nan);
  why = health.check(solver, 1e-4);
  EXPECT_NE(why.find("NaN"), std::string::npos) << why;
  EXPECT_NE(why.find("column 12, row 8"), std::string::npos) << why;

  flow::FlowInput negative = calm;
  negative.h[g.index(2, 5)] = -0.5;
  solver.setInput(negative);
  why = health.check(solver, 1e-4);
  EXPECT_NE(why.find("negative thickness"), std::string::npos) << why;
  EXPECT_NE(why.find("column 2, row 5"), std::string::npos) << why;

  // A step of 1 s at wave speeds of ~6 m/s on 1 m cells is a Courant number of ~6.
  solver.setInput(calm);
  why = health.check(solver, 1.0);
  EXPECT_NE(why.find("CFL violation"), std::string::npos) << why;
}

// A dry granular run (two-phase model, no fluid at all): the diagnosis must name the cell of the
// fast solids, not a cell of the empty fluid fields (before: "cell (0, 0) with h = 0", issue 13).
TEST(HealthCheck, NamesTheSolidCellInADryRun) {
  const Grid g = Grid::make(20, 10, 1.0);
  Raster dem(g, 0.0);
  flow::FlowInput dry;
  dry.mask.assign(g.cells(), 1);
  dry.bed.assign(g.cells(), 0.0);
  dry.manning.assign(g.cells(), 0.0);
  dry.h.assign(g.cells(), 0.0);
  dry.hs.assign(g.cells(), 0.5);
  dry.qsx.assign(g.cells(), 0.0);
  dry.qsy.assign(g.cells(), 0.0);
  compute::Context& ctx = test::testContext(compute::Precision::Double);
  flow::FlowSettings settings;
  settings.twoPhase = true;
  const sim::HealthCheck health(dem, dry, settings);  // the scene at rest sets the bound
  dry.qsx[g.index(13, 6)] = 30.0;  // 60 m/s in 0.5 m of solids on flat ground
  flow::FlowSolver solver(ctx, g, settings);
  solver.setInput(dry);
  const std::string why = health.check(solver, 1e-4);
  EXPECT_NE(why.find("runaway velocity"), std::string::npos) << why;
  EXPECT_NE(why.find("column 13, row 6"), std::string::npos) << why;
  EXPECT_NE(why.find("solids"), std::string::npos) << why;
}

// The check judges the quantity it names: the flow speed against the energy bound, the wave speed
// only for the CFL condition, and never films below Minimum Flow Height (issue 14: legal earth
// pressure and viscosity stopped runs at step 1 as "runaway velocity"; a 1.5 nm film on a cliff
// stopped one as a "CFL violation").
TEST(HealthCheck, JudgesFlowSpeedNotWaveSpeedAndIgnoresFilms) {
  const Grid g = Grid::make(20, 10, 1.0);
  Raster dem(g, 0.0);
  flow::FlowInput pile;
  pile.mask.assign(g.cells(), 1);
  pile.bed.assign(g.cells(), 0.0);
  pile.manning.assign(g.cells(), 0.0);
  pile.h.assign(g.cells(), 0.0);
  pile.hs.assign(g.cells(), 0.0);
  pile.qsx.assign(g.cells(), 0.0);
  pile.qsy.assign(g.cells(), 0.0);
  for (int j = 3; j < 7; ++j)
    for (int i = 5; i < 9; ++i) {
      pile.hs[g.index(i, j)] = 2.0;
      pile.qsx[g.index(i, j)] = 2.0 * 3.0;  // 3 m/s
    }
  compute::Context& ctx = test::testContext(compute::Precision::Double);
  flow::FlowSettings settings;
  settings.twoPhase = true;
  settings.debris.earthPressure = flow::EarthPressure::Constant;
  settings.debris.kConst = 100.0;  // the range end of Earth Pressure Coefficient
  const sim::HealthCheck health(dem, pile, settings);
  // K = 100 pushes the front of a 2 m pile to at most 2 sqrt(100 g 2) ~ 89 m/s, the fall adds
  // sqrt(2 g 2), the initial speed 3 m/s.
  EXPECT_NEAR(health.speedBound(), std::sqrt(2 * 9.81 * 2) + 2 * std::sqrt(9.81 * 100 * 2) + 3.0, 1e-9);
  flow::FlowSolver solver(ctx, g, settings);
  solver.setInput(pile);
  // Wave speed ~ 2 sqrt(100 g 2) + 3 ~ 92 m/s, far above the flow speed of 3 m/s: healthy.
  EXPECT_GT(solver.diagnostics().maxSpeed, 80.0);
  EXPECT_NEAR(solver.diagnostics().maxFlowSpeed, 3.0, 1e-12);
  EXPECT_EQ(health.check(solver, 0.4 * solver.stableDt()), "");

  // A film of 1.5 nm (below Minimum Flow Height, 1 um) on a 50 m cliff: the slope gives it a wave
  // speed of 2 sqrt(g 50 m) ~ 44 m/s, but it carries no velocity, and a dt taken for the calm pile
  // beside it is no CFL violation.
  flow::FlowInput cliff = pile;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 15; i < g.nx; ++i) cliff.bed[g.index(i, j)] = 50.0;
  cliff.hs[g.index(14, 5)] = 1.5e-9;
  settings.debris.kConst = 1.0;
  const sim::HealthCheck cliffHealth(dem, cliff, settings);
  flow::FlowSolver cliffSolver(ctx, g, settings);
  cliffSolver.setInput(cliff);
  EXPECT_GT(cliffSolver.diagnostics().maxSpeed, 40.0);
  const double pileDt = 0.5 * 1.0 / (2 * 3.0 + 2 * 2 * std::sqrt(9.81 * 2));  // CFL 0.5 of the pile
  EXPECT_EQ(cliffHealth.check(cliffSolver, pileDt), "");
}

TEST(Checkpoint, UnstableRunKeepsItsOutputs) {
  TempDir t;
  const fs::path runFile = writeScene(t.path, 0.2, 0.05);
  io::RunConfig cfg = io::RunConfig::load(runFile.string(), talusRunKeys());
  sim::Scene scene = sim::loadScene(cfg);
  // The health check must stop a run whose state becomes non-finite: inject a NaN (the loader
  // rejects one in a map, so this can only come from the numerics).
  scene.flow.h[scene.dem.grid.index(30, 20)] = std::nan("");
  sim::Simulation sim(scene, cfg, (t.path / "out").string(), sim::OutputMode::New);
  try {
    sim.run();
    FAIL() << "the run did not stop";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("column 30, row 20"), std::string::npos) << e.what();
  }
  const std::string summary = readFile(t.path / "out" / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"failed\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("column 30, row 20"), std::string::npos) << summary;
  // Still JSON: the volumes and energies the NaN reached are null, not "nan" (which no reader takes).
  EXPECT_NO_THROW(ensemble::JsonValue::parse(summary, "summary.json")) << summary;
  EXPECT_NO_THROW(io::readRaster((t.path / "out" / "hfmax.tif").string()));
}

TEST(Checkpoint, KilledRunsResumeBitwise) {
  TempDir t;
  // 30 s of simulated time, a checkpoint every 3 s (0.05 min).
  const fs::path runFile = writeScene(t.path, 0.5, 0.05);
  const fs::path ref = t.path / "reference";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(runTalus("run " + runFile.string() + " --out " + ref.string() + " --quiet"), 0);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string expected = runFingerprint(ref);

  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<double> when(0.4, 0.97);
  int resumed = 0;
  for (int attempt = 0; attempt < 4; ++attempt) {
    const fs::path out = t.path / ("killed" + std::to_string(attempt));
    const double delay = when(rng) * wall;
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::execl(TALUS_BINARY, TALUS_BINARY, "run", runFile.c_str(), "--out", out.c_str(), "--quiet",
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    if (attempt % 2 == 0) {
      // Every other kill lands a random moment after the first checkpoint exists, so resuming is
      // exercised however slow the machine is; the others land at a random moment of the run.
      const auto t0 = std::chrono::steady_clock::now();
      while (!fs::exists(out / "checkpoint.bin") &&
             std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      std::this_thread::sleep_for(std::chrono::duration<double>(0.5 * (delay / wall - 0.4) * wall));
    } else {
      std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    }
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    // Whatever moment the kill hit, every map already in the folder is a complete raster.
    for (const auto& e : fs::recursive_directory_iterator(out)) {
      if (e.path().extension() == ".tif") {
        EXPECT_NO_THROW(io::readRaster(e.path().string())) << e.path();
      }
    }
    if (!fs::exists(out / "checkpoint.bin")) {
      // Killed before the first checkpoint: resuming must say so, by folder.
      EXPECT_EQ(runTalus("run --resume " + out.string()), 2) << "after a kill at " << delay << " s";
      continue;
    }
    ASSERT_EQ(runTalus("run --resume " + out.string() + " --quiet"), 0) << "after a kill at " << delay << " s";
    ++resumed;
    EXPECT_TRUE(runFingerprint(out) == expected) << "resumed run differs from the uninterrupted one (kill at "
                                                 << delay << " s of " << wall << " s)";
    EXPECT_NE(readFile(out / "summary.json").find("completed"), std::string::npos);
  }
  std::printf("[ %d of 4 killed runs resumed from a checkpoint; uninterrupted run %.2f s ]\n", resumed, wall);
  EXPECT_GT(resumed, 0) << "no kill landed after a checkpoint: the test exercised nothing";
}
