// The step-wise control the GUI drives (sim::RunControl over Simulation::begin/stepOnce/finish):
// pausing, single steps and resuming change no result: the outputs equal those of Simulation::run.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "GuiTestSupport.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunControl.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"

using namespace talus;
namespace fs = std::filesystem;

namespace {

/// diagnostics.csv without its last column (wall time).
std::string diagnosticsWithoutWall(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream out;
  for (std::string line; std::getline(in, line);) out << line.substr(0, line.rfind(',')) << "\n";
  return out.str();
}

}  // namespace

TEST(RunControl, PausedAndSteppedRunsWriteWhatRunWrites) {
  const fs::path dir = guitest::scratchDir("runcontrol");
  const std::string runFile = guitest::writeExampleRunFile(dir, "End Time=0.05\nTimestep=1\n");
  io::RunConfig config = io::RunConfig::load(runFile, talusRunKeys());
  const sim::Scene scene = sim::loadScene(config);
  {
    sim::Simulation reference(scene, config, (dir / "plain").string(), sim::OutputMode::New);
    reference.run();
  }
  sim::Simulation sim(scene, config, (dir / "controlled").string(), sim::OutputMode::New);
  std::atomic<long long> steps{0};
  std::atomic<bool> ended{false};
  sim::RunOutcome outcome;
  sim::RunControl control(sim, {[&](const sim::Progress& p) { steps = p.steps; },
                                [&](const sim::RunOutcome& o) {
                                  outcome = o;
                                  ended = true;
                                }});
  control.start(/*paused=*/true);
  ASSERT_TRUE(guitest::waitFor([&] { return control.isRunning(); }, 10));
  guitest::waitFor([] { return false; }, 0.2);
  EXPECT_EQ(steps, 0);  // started paused
  for (int k = 1; k <= 3; ++k) {
    control.stepOnce();
    ASSERT_TRUE(guitest::waitFor([&] { return steps == k; }, 30));
  }
  std::atomic<int> jobs{0};
  control.post([&](sim::Simulation& s) { jobs += s.steps() == 3 ? 1 : 100; });
  ASSERT_TRUE(guitest::waitFor([&] { return jobs > 0; }, 30));
  EXPECT_EQ(jobs, 1);  // the job ran between steps, while paused
  control.resume();
  ASSERT_TRUE(guitest::waitFor([&] { return bool(ended); }, 300));
  control.wait();
  EXPECT_EQ(outcome.kind, sim::RunOutcome::Kind::Completed);
  EXPECT_EQ(diagnosticsWithoutWall(dir / "plain" / "diagnostics.csv"),
            diagnosticsWithoutWall(dir / "controlled" / "diagnostics.csv"));
  const Raster a = io::readRaster((dir / "plain" / "hffinal.tif").string());
  const Raster b = io::readRaster((dir / "controlled" / "hffinal.tif").string());
  EXPECT_EQ(a.values, b.values);
}

TEST(RunControl, StopWritesAStoppedSummary) {
  const fs::path dir = guitest::scratchDir("runcontrol_stop");
  const std::string runFile = guitest::writeExampleRunFile(dir);
  io::RunConfig config = io::RunConfig::load(runFile, talusRunKeys());
  const sim::Scene scene = sim::loadScene(config);
  sim::Simulation sim(scene, config, "", sim::OutputMode::New);
  std::atomic<long long> steps{0};
  sim::RunControl control(sim, {[&](const sim::Progress& p) { steps = p.steps; }, {}});
  control.start();
  ASSERT_TRUE(guitest::waitFor([&] { return steps >= 5; }, 60));
  control.stop();
  control.wait();
  std::ifstream in(dir / "out" / "summary.json");
  std::ostringstream s;
  s << in.rdbuf();
  EXPECT_NE(s.str().find("\"status\": \"stopped\""), std::string::npos) << s.str();
}
