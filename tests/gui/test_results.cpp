// File > Open results (and talus-gui --results DIR): a finished output folder, written in the test
// by the engine on the example scene with Report Series=1, replays in the window: its maps in the
// layer list, the series frames on the time slider (the viewer's layer holds the frame's raster,
// read here independently), diagnostics.csv in the plots; and folders that cannot be opened or
// hold an incomplete run are reported naming the folder.
#include <gtest/gtest.h>

#include <QDropEvent>
#include <QMimeData>
#include <QProcess>
#include <QUrl>
#include <QTest>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "core/Raster.hpp"
#include "io/ParticleLayerIO.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

using talus::gui::MainWindow;
using namespace talus;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

/// A raster as the viewer holds a layer: floats, NaN where nodata.
std::vector<float> rasterValues(const fs::path& file) {
  const Raster r = io::readRaster(file.string());
  std::vector<float> v(r.values.size());
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = r.valid[k] ? float(r.values[k]) : NAN;
  return v;
}

/// Cells where two layers differ (NaN equals NaN).
std::size_t differences(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  std::size_t n = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!(a[k] == b[k] || (std::isnan(a[k]) && std::isnan(b[k])))) ++n;
  return n;
}

std::size_t diagnosticsRows(const fs::path& out) {
  std::istringstream in(readText(out / "diagnostics.csv"));
  std::size_t rows = 0;
  for (std::string line; std::getline(in, line);) rows += line.empty() ? 0 : 1;
  return rows - 1;  // the header
}

void setStatus(const fs::path& out, const std::string& status) {
  std::string text = readText(out / "summary.json");
  const std::string from = "\"status\": \"completed\"";
  text.replace(text.find(from), from.size(), "\"status\": \"" + status + "\"");
  std::ofstream(out / "summary.json") << text;
}

}  // namespace

TEST(OpenResults, TheLayerListOffersEveryMapAndThePlotsHoldTheDiagnostics) {
  const fs::path out = writeExampleResults(scratchDir("results_open"));
  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  QString problems = "unset";
  ASSERT_TRUE(w.openResults(QString::fromStdString(out.string()), &problems)) << problems.toStdString();
  EXPECT_TRUE(problems.isEmpty()) << problems.toStdString();
  const QStringList names = w.layers().layerNames();
  for (const char* map : {"hffinal", "hfmax", "vffinal", "vfmax", "tarrival", "hf", "vf"})
    EXPECT_TRUE(names.contains(map)) << map << " not in " << names.join(", ").toStdString();
  EXPECT_EQ(w.layers().layer(), "hf");  // the series shows first
  EXPECT_EQ(w.replayBar().frameCount(), 4);
  EXPECT_TRUE(w.replayBar().isEnabled());
  // Every row of diagnostics.csv is a point of the volume, outflow and energy plots.
  const std::size_t rows = diagnosticsRows(out);
  ASSERT_GT(rows, 10u);
  EXPECT_EQ(w.plots().volumePlot().size(0), rows);
  EXPECT_EQ(w.plots().outflowPlot().size(0), rows);
  EXPECT_EQ(w.plots().energyPlot().size(0), rows);
  // The maps are on screen: the DEM's terrain under them, the maximum thickness as it is on disk.
  ASSERT_TRUE(w.viewer().snapshot());
  const std::vector<float>* hmax = w.viewer().snapshot()->layer("hfmax");
  ASSERT_TRUE(hmax);
  EXPECT_EQ(differences(*hmax, rasterValues(out / "hfmax.tif")), 0u);
  EXPECT_EQ(w.results()->elevation().size(), hmax->size());
  EXPECT_TRUE(w.logText().contains("opened results " + QString::fromStdString(fs::absolute(out).string())))
      << w.logText().toStdString();
  EXPECT_FALSE(w.windowTitle().contains("partial"));
  EXPECT_TRUE(w.status().text().startsWith("results")) << w.status().text().toStdString();
}

// A two-phase run's energy plot holds its energy budget: the kinetic energy, the potential energy
// released and the work of friction and drag (series 0, 1, 2), one point per row of diagnostics.csv,
// the last one the file's last row (read here independently).
TEST(OpenResults, TwoPhaseResultsPlotTheEnergyBudget) {
  const fs::path out = writeExampleResults(scratchDir("results_energy"), "Include Initial Solids=1\nInitial Solid Height=water.tif\n");
  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  QString problems;
  ASSERT_TRUE(w.openResults(QString::fromStdString(out.string()), &problems)) << problems.toStdString();
  std::map<std::string, double> last = lastDiagnosticsRow(out / "diagnostics.csv");
  for (const char* column : {"energy_released_J", "friction_drag_work_J", "kinetic_energy_J"})
    ASSERT_EQ(last.count(column), 1u) << column;
  const auto& plot = w.plots().energyPlot();
  const std::size_t rows = diagnosticsRows(out);
  for (int series : {0, 1, 2}) EXPECT_EQ(plot.size(series), rows) << series;
  const double released = last["energy_released_J"], work = last["friction_drag_work_J"];
  EXPECT_GT(released, 0.0);
  EXPECT_GT(work, 0.0);
  EXPECT_DOUBLE_EQ(plot.last(1).y(), released);
  EXPECT_DOUBLE_EQ(plot.last(2).y(), work);
  EXPECT_DOUBLE_EQ(plot.last(0).y(), last["kinetic_energy_J"]);
}

TEST(OpenResults, MovingTheSliderShowsThatFramesRaster) {
  const fs::path out = writeExampleResults(scratchDir("results_slider"));
  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  ASSERT_TRUE(w.openResults(QString::fromStdString(out.string())));
  const std::vector<float> first = *w.viewer().snapshot()->layer("hf");
  EXPECT_EQ(differences(first, rasterValues(out / "series" / "hf_0000.tif")), 0u);
  for (int frame : {2, 1, 3}) {
    w.replayBar().slider().setValue(frame);
    ASSERT_TRUE(w.viewer().snapshot());
    const std::vector<float>* hf = w.viewer().snapshot()->layer("hf");
    const std::vector<float>* vf = w.viewer().snapshot()->layer("vf");
    ASSERT_TRUE(hf && vf);
    char name[32];
    std::snprintf(name, sizeof name, "hf_%04d.tif", frame);
    EXPECT_EQ(differences(*hf, rasterValues(out / "series" / name)), 0u) << "frame " << frame;
    std::snprintf(name, sizeof name, "vf_%04d.tif", frame);
    EXPECT_EQ(differences(*vf, rasterValues(out / "series" / name)), 0u) << "frame " << frame;
    EXPECT_GT(differences(*hf, first), 100u) << "frame " << frame << " shows the first frame's flow";
    EXPECT_DOUBLE_EQ(w.viewer().snapshot()->time, double(frame));
    EXPECT_TRUE(w.replayBar().timeText().startsWith(QString("t = %1 s").arg(frame))) << w.replayBar().timeText().toStdString();
  }
  // Play steps through the frames and stops at the last.
  w.replayBar().setFrame(0);
  QTest::mouseClick(&w.replayBar().playButton(), Qt::LeftButton);
  EXPECT_TRUE(w.replayBar().isPlaying());
  EXPECT_TRUE(waitFor([&] { return !w.replayBar().isPlaying(); }, 20));
  EXPECT_EQ(w.replayBar().frame(), 3);
  EXPECT_EQ(differences(*w.viewer().snapshot()->layer("hf"), rasterValues(out / "series" / "hf_0003.tif")), 0u);
}

TEST(OpenResults, AMissingFolderOrOneThatIsNoOutputIsRefusedNamingIt) {
  const fs::path dir = scratchDir("results_refused");
  MainWindow w;
  w.setReportInDialogs(false);
  const QString missing = QString::fromStdString((dir / "nowhere").string());
  QString problems;
  EXPECT_FALSE(w.openResults(missing, &problems));
  EXPECT_TRUE(problems.contains("'" + missing + "' does not exist")) << problems.toStdString();
  // A folder with maps but no summary.json (here: the run-file's folder) is no Talus output.
  writeExampleRunFile(dir);
  const QString notOutput = QString::fromStdString(fs::absolute(dir).string());
  EXPECT_FALSE(w.openResults(notOutput, &problems));
  EXPECT_TRUE(problems.contains("'" + notOutput + "' is not a Talus output folder")) << problems.toStdString();
  EXPECT_TRUE(problems.contains("summary.json"));
  EXPECT_TRUE(w.logText().contains(notOutput)) << w.logText().toStdString();
  EXPECT_EQ(w.results(), nullptr);
  EXPECT_FALSE(w.replayBar().isEnabled());
}

TEST(OpenResults, AnIncompleteRunOpensMarkedAsPartial) {
  const fs::path out = writeExampleResults(scratchDir("results_partial"));
  setStatus(out, "stopped");
  fs::remove(out / "series" / "hf_0003.tif");  // the frames it did not reach
  fs::remove(out / "series" / "vf_0003.tif");
  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  const QString dir = QString::fromStdString(fs::absolute(out).string());
  QString problems;
  ASSERT_TRUE(w.openResults(dir, &problems));
  EXPECT_TRUE(problems.contains("'" + dir + "' is incomplete (status \"stopped\")")) << problems.toStdString();
  EXPECT_TRUE(problems.contains("partial"));
  EXPECT_TRUE(w.windowTitle().contains("(partial)")) << w.windowTitle().toStdString();
  EXPECT_TRUE(w.status().text().startsWith("partial results (stopped)")) << w.status().text().toStdString();
  EXPECT_TRUE(w.logText().contains("incomplete")) << w.logText().toStdString();
  EXPECT_EQ(w.replayBar().frameCount(), 3);
  EXPECT_TRUE(w.layers().layerNames().contains("hfmax"));
  // Opening a run-file afterwards puts the results away.
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("results_then_run")))));
  EXPECT_EQ(w.results(), nullptr);
  EXPECT_FALSE(w.layers().layerNames().contains("hfmax"));
}

TEST(OpenResults, TheCommandLineRefusesAFolderThatIsNoOutput) {
  const fs::path dir = scratchDir("results_cli");
  QProcess gui;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("XDG_CONFIG_HOME", QString::fromStdString(scratchDir("results_cli_settings").string()));
  gui.setProcessEnvironment(env);
  const QString folder = QString::fromStdString(fs::absolute(dir).string());
  gui.start(TALUS_GUI_BINARY, {"--results", folder});
  ASSERT_TRUE(gui.waitForFinished(60000));
  EXPECT_EQ(gui.exitCode(), 2);
  const QString err = QString::fromLocal8Bit(gui.readAllStandardError());
  EXPECT_TRUE(err.contains("'" + folder + "' is not a Talus output folder")) << err.toStdString();
}

TEST(CompareResults, DifferenceLayersHoldTheOpenedRunMinusTheComparedOne) {
  const fs::path a = writeExampleResults(scratchDir("compare_a"));
  // The same scene with another roughness: the flow differs, the grid is the same.
  const fs::path dirB = scratchDir("compare_b");
  const std::string runFile = writeExampleRunFile(dirB, "End Time=0.05\nTimestep=1\nReport Series=1\nManning=0.2\n");
  const io::RunConfig config = io::RunConfig::load(runFile, sim::talusRunKeys());
  sim::Simulation(sim::loadScene(config), config, (dirB / "out").string(), sim::OutputMode::New).run();
  const fs::path b = dirB / "out";

  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  QString problems;
  EXPECT_FALSE(w.compareResults(QString::fromStdString(b.string()), &problems));  // nothing open yet
  EXPECT_TRUE(problems.contains("no results are open")) << problems.toStdString();
  ASSERT_TRUE(w.openResults(QString::fromStdString(a.string())));
  EXPECT_FALSE(w.compareResults(QString::fromStdString((dirB / "none").string()), &problems));
  EXPECT_TRUE(problems.contains("does not exist")) << problems.toStdString();
  EXPECT_FALSE(w.layers().layerNames().contains("hfmax-diff"));
  ASSERT_TRUE(w.compareResults(QString::fromStdString(b.string()), &problems)) << problems.toStdString();
  const QStringList names = w.layers().layerNames();
  for (const char* layer : {"hfmax-diff", "vfmax-diff", "hffinal-diff", "tarrival-diff", "hf-diff", "vf-diff"})
    EXPECT_TRUE(names.contains(layer)) << layer << " not in " << names.join(", ").toStdString();
  EXPECT_EQ(w.layers().layer(), "hf-diff");  // the difference of the layer shown
  EXPECT_TRUE(w.logText().contains("comparing with the results in")) << w.logText().toStdString();

  // Independently: a - b where either has a value and not both are 0.
  auto expected = [](const fs::path& fa, const fs::path& fb) {
    const std::vector<float> va = rasterValues(fa), vb = rasterValues(fb);
    std::vector<float> d(va.size(), NAN);
    for (std::size_t k = 0; k < d.size(); ++k)
      if (std::isfinite(va[k]) && std::isfinite(vb[k]) && (va[k] != 0 || vb[k] != 0)) d[k] = va[k] - vb[k];
    return d;
  };
  const std::vector<float> maxDiff = expected(a / "hfmax.tif", b / "hfmax.tif");
  ASSERT_TRUE(w.viewer().snapshot()->layer("hfmax-diff"));
  EXPECT_EQ(differences(*w.viewer().snapshot()->layer("hfmax-diff"), maxDiff), 0u);
  std::size_t differing = 0;
  for (float v : maxDiff) differing += std::isfinite(v) && v != 0 ? 1 : 0;
  EXPECT_GT(differing, 100u) << "the two runs should differ";
  w.replayBar().slider().setValue(2);
  ASSERT_TRUE(w.viewer().snapshot()->layer("hf-diff"));
  EXPECT_EQ(differences(*w.viewer().snapshot()->layer("hf-diff"),
                        expected(a / "series" / "hf_0002.tif", b / "series" / "hf_0002.tif")), 0u);
}

TEST(OpenResults, ParticleLayersAreDrawnAtTheirFrame) {
  // The block slide (hybrid mode: particles), 1.2 s with a report every 0.5 s: 3 particle frames.
  io::RunConfig config = io::RunConfig::load(std::string(TALUS_TEST_DATA_DIR) + "/block_slide/block_slide.run",
                                             sim::talusRunKeys());
  for (const char* set : {"End Time=0.02", "Timestep=0.5", "Report Series=1"}) config.set(set);
  const fs::path out = scratchDir("results_particles") / "out";
  sim::Simulation(sim::loadScene(config), config, out.string(), sim::OutputMode::New).run();
  ASSERT_TRUE(fs::exists(out / "particles" / "particles_0002.gpkg"));

  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  ASSERT_TRUE(w.openResults(QString::fromStdString(out.string())));
  const auto& attributes = w.results()->particleAttributes();
  ASSERT_TRUE(std::any_of(attributes.begin(), attributes.end(), [](const auto& a) { return a.name == "speed"; }));
  for (int frame : {2, 0}) {
    w.replayBar().slider().setValue(frame);
    const auto s = w.viewer().snapshot();
    const io::ParticleLayer layer =
        io::readParticleLayer((out / "particles" / ("particles_000" + std::to_string(frame) + ".gpkg")).string());
    ASSERT_GT(layer.size(), 0u);
    ASSERT_EQ(s->particleCount, layer.size()) << "frame " << frame;
    const std::vector<float>* speed = s->particleAttribute("speed");
    ASSERT_TRUE(speed && layer.find("speed"));
    std::size_t wrong = 0;
    for (std::size_t p = 0; p < layer.size(); ++p) {
      wrong += float(layer.worldX[p]) == s->particlePositions[3 * p] ? 0 : 1;
      wrong += float(layer.worldY[p]) == s->particlePositions[3 * p + 1] ? 0 : 1;
      const float v = float((*layer.find("speed"))[p]);
      wrong += (v == (*speed)[p] || (std::isnan(v) && std::isnan((*speed)[p]))) ? 0 : 1;
    }
    EXPECT_EQ(wrong, 0u) << "frame " << frame;
  }
}

/// The window's drop handler, called as the window system's drop calls it.
struct DropTarget : MainWindow {
  using MainWindow::dropEvent;
};

TEST(OpenResults, DroppingAnOutputFolderOnTheWindowOpensIt) {
  const fs::path out = writeExampleResults(scratchDir("results_drop"));
  DropTarget w;
  w.setReportInDialogs(false);
  w.show();
  QMimeData mime;
  mime.setUrls({QUrl::fromLocalFile(QString::fromStdString(out.string()))});
  QDropEvent drop(QPointF(w.width() / 2.0, w.height() / 2.0), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  w.dropEvent(&drop);
  ASSERT_TRUE(w.results()) << w.logText().toStdString();
  EXPECT_EQ(w.results()->folder().dir, QString::fromStdString(fs::absolute(out).string()));
  EXPECT_EQ(w.replayBar().frameCount(), 4);
}

TEST(OpenResults, OpenLisemNamedSeriesReplayToo) {
  // Series Names=openlisem: hf000000.002 in the output folder itself.
  const fs::path out = writeExampleResults(scratchDir("results_lisem"), "Series Names=openlisem\n");
  ASSERT_TRUE(fs::exists(out / "hf000000.002"));
  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  ASSERT_TRUE(w.openResults(QString::fromStdString(out.string())));
  EXPECT_EQ(w.replayBar().frameCount(), 4);
  EXPECT_TRUE(w.layers().layerNames().contains("hf"));
  w.replayBar().slider().setValue(2);
  ASSERT_TRUE(w.viewer().snapshot()->layer("hf"));
  EXPECT_EQ(differences(*w.viewer().snapshot()->layer("hf"), rasterValues(out / "hf000000.002")), 0u);
  EXPECT_DOUBLE_EQ(w.viewer().snapshot()->time, 2.0);
}
