// The step-wise control the GUI drives (sim::RunControl over Simulation::begin/stepOnce/finish):
// pausing, single steps and resuming change no result: the outputs equal those of Simulation::run.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "GuiTestSupport.hpp"
#include "plots/PlotPanel.hpp"
#include "results/DiagnosticsTable.hpp"
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

// What the window's log and plots receive with each step (sim::Progress): the mass of the particles
// of a block slide (every particle stays in the walled domain, so the seeded mass throughout, as
// summary.json reports it) and, for a two-phase run, the energy budget that diagnostics.csv holds.
TEST(RunControl, ProgressCarriesTheParticleMassAndTheEnergyBudget) {
  {
    const fs::path dir = guitest::scratchDir("progress_particles");
    io::RunConfig config = io::RunConfig::load(std::string(TALUS_TEST_DATA_DIR) + "/block_slide/block_slide.run",
                                               talusRunKeys());
    config.set("End Time=0.02");
    const sim::Scene scene = sim::loadScene(config);
    sim::Simulation s(scene, config, (dir / "out").string(), sim::OutputMode::New);
    double first = -1, last = -1;
    s.run([&](const sim::Progress& p) {
      if (first < 0) first = p.particleMass;
      last = p.particleMass;
    });
    const std::string summary = guitest::readText(dir / "out" / "summary.json");
    const std::string key = "\"initial_mass_kg\": ";
    const std::size_t at = summary.find(key);
    ASSERT_NE(at, std::string::npos) << summary;
    const double seeded = std::stod(summary.substr(at + key.size()));
    EXPECT_GT(seeded, 0.0);
    EXPECT_DOUBLE_EQ(first, seeded);
    EXPECT_DOUBLE_EQ(last, seeded);
    // The Plots draw it: from progress reports, and from the run's diagnostics.csv when replayed.
    talus::gui::PlotPanel plots;
    talus::gui::RunProgress p;
    p.time = 0.5;
    p.particleMass = seeded;
    plots.addProgress(p, true);
    ASSERT_EQ(plots.massPlot().size(0), 1u);
    EXPECT_DOUBLE_EQ(plots.massPlot().last(0).y(), seeded);
    const auto table = talus::gui::DiagnosticsTable::read(QString::fromStdString((dir / "out" / "diagnostics.csv").string()));
    plots.setDiagnostics(table);
    const std::vector<double>* column = table.column("particle_mass_kg");
    ASSERT_NE(column, nullptr);
    ASSERT_EQ(plots.massPlot().size(0), column->size());
    EXPECT_NEAR(plots.massPlot().last(0).y(), seeded, 1e-8 * seeded);  // the file holds 9 significant digits
  }
  {
    const fs::path dir = guitest::scratchDir("progress_energy");
    const std::string runFile = guitest::writeExampleRunFile(
        dir, "End Time=0.05\nInclude Initial Solids=1\nInitial Solid Height=water.tif\n");
    io::RunConfig config = io::RunConfig::load(runFile, talusRunKeys());
    const sim::Scene scene = sim::loadScene(config);
    sim::Simulation s(scene, config, (dir / "out").string(), sim::OutputMode::New);
    sim::Progress last;
    s.run([&](const sim::Progress& p) { last = p; });
    std::map<std::string, double> values = guitest::lastDiagnosticsRow(dir / "out" / "diagnostics.csv");
    EXPECT_GT(last.energyReleased, 0.0);
    EXPECT_GT(last.frictionWork, 0.0);
    // (the file holds 9 significant digits)
    EXPECT_NEAR(last.energyReleased, values["energy_released_J"], 1e-8 * last.energyReleased);
    EXPECT_NEAR(last.frictionWork, values["friction_drag_work_J"], 1e-8 * last.frictionWork);
    EXPECT_EQ(last.particleMass, 0.0);
  }
}
