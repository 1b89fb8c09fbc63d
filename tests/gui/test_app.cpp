// The application end to end under a (virtual) display: it starts, loads the example run-file, runs
// steps on its worker thread, renders terrain and flow, pauses, resumes and stops, and refuses an
// invalid run-file with the error shown at the field.
#include <gtest/gtest.h>

#include <QImage>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"

using talus::gui::MainWindow;
using talus::gui::RunController;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

/// Colour distance between two pixels (sum of channel differences).
int colourDistance(QRgb a, QRgb b) {
  return std::abs(qRed(a) - qRed(b)) + std::abs(qGreen(a) - qGreen(b)) + std::abs(qBlue(a) - qBlue(b));
}

}  // namespace

TEST(GuiApp, StartsAndLoadsTheExampleRunFile) {
  MainWindow w;
  w.show();
  ASSERT_TRUE(w.openRunFile(QString(TALUS_TEST_DATA_DIR) + "/kot_dambreak/kot_dambreak.run"));
  ASSERT_NE(w.form().field("DEM"), nullptr);
  EXPECT_EQ(w.form().field("DEM")->value(), "dem.tif");
  EXPECT_EQ(w.form().field("Limiter")->value(), "vanleer");
  EXPECT_EQ(w.form().field("Include Initial Water")->value(), "1");
  EXPECT_TRUE(w.form().field("CFL")->error().isEmpty());
  EXPECT_TRUE(w.form().generalErrors().isEmpty());
  // Units and ranges come from the key declarations.
  EXPECT_TRUE(w.form().field("CFL")->toolTip().contains("valid range"));
  EXPECT_EQ(w.controller().state(), RunController::State::Idle);
}

TEST(GuiApp, RunsRendersPausesResumesAndStops) {
  const fs::path dir = scratchDir("run");
  const std::string runFile = writeExampleRunFile(dir);
  MainWindow w;
  w.setAskBeforeOverwrite(false);
  w.resize(1200, 800);
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(runFile)));
  ASSERT_TRUE(w.startRun());
  RunController& run = w.controller();
  ASSERT_TRUE(waitFor([&] { return run.state() == RunController::State::Running; }, 120)) << w.logText().toStdString();
  ASSERT_TRUE(waitFor([&] { return run.lastProgress().steps >= 40; }, 120));

  // Pause: the worker stops between steps and the step count stays put.
  run.pause();
  EXPECT_EQ(run.state(), RunController::State::Paused);
  waitFor([] { return false; }, 0.5);
  const long long pausedAt = run.lastProgress().steps;
  waitFor([] { return false; }, 0.7);
  EXPECT_EQ(run.lastProgress().steps, pausedAt);
  // A snapshot of the paused state reaches the viewer.
  run.requestSnapshot();
  ASSERT_TRUE(waitFor([&] { return w.viewer().snapshot() && w.viewer().snapshot()->steps == pausedAt; }, 30));

  // The rendered frame: terrain that varies, and flow colour exactly where the flow is.
  auto& viewer = w.viewer();
  viewer.setMode(talus::gui::ViewCamera::Mode::Map);
  viewer.resetView();
  talus::gui::LayerStyle style = w.layers().layerStyle();
  ASSERT_EQ(w.layers().layer(), "h");
  style.visible = true;
  viewer.setLayer("h", style);
  const QImage withFlow = viewer.grabFramebuffer();
  style.visible = false;
  viewer.setLayer("h", style);
  const QImage terrainOnly = viewer.grabFramebuffer();
  style.visible = true;
  viewer.setLayer("h", style);
  ASSERT_FALSE(withFlow.isNull());
  ASSERT_EQ(withFlow.size(), terrainOnly.size());
  EXPECT_GT(distinctColours(terrainOnly), 200) << "the terrain is (nearly) one colour";
  EXPECT_GT(greyDeviation(terrainOnly), 8.0) << "the hillshade does not vary";
  const std::vector<float>* h = viewer.snapshot()->layer("h");
  ASSERT_NE(h, nullptr);
  const talus::Grid& g = viewer.snapshot()->grid;
  const double ratio = viewer.devicePixelRatioF();
  int wetCells = 0, dryCells = 0, agree = 0, checked = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const float v = (*h)[g.index(i, j)];
      if (!std::isfinite(v)) continue;  // outside the domain
      const QPointF p = viewer.pixelOfCell(i, j) * ratio;
      const int x = int(std::floor(p.x())), y = int(std::floor(p.y()));
      if (x < 0 || y < 0 || x >= withFlow.width() || y >= withFlow.height()) continue;
      const bool wet = v > style.emptyBelow;
      const bool coloured = colourDistance(withFlow.pixel(x, y), terrainOnly.pixel(x, y)) > 12;
      (wet ? wetCells : dryCells)++;
      ++checked;
      agree += wet == coloured;
    }
  std::printf("rendered frame %dx%d: %d distinct terrain colours, grey deviation %.1f; %d wet and %d dry cells "
              "checked, %d agree\n", withFlow.width(), withFlow.height(), distinctColours(terrainOnly),
              greyDeviation(terrainOnly), wetCells, dryCells, agree);
  EXPECT_GT(wetCells, 500);
  EXPECT_GT(dryCells, 500);
  EXPECT_GE(agree, 0.995 * checked) << agree << " of " << checked << " cells agree";

  // Resume, then stop: the run ends as "stopped" with the headless runner's outputs.
  run.resume();
  ASSERT_TRUE(waitFor([&] { return run.lastProgress().steps > pausedAt + 10; }, 120));
  run.stop();
  ASSERT_TRUE(waitFor([&] { return run.state() == RunController::State::Ended; }, 120));
  const std::string summary = readText(dir / "out" / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"stopped\""), std::string::npos) << summary;
  EXPECT_TRUE(fs::exists(dir / "out" / "hffinal.tif"));
  EXPECT_TRUE(fs::exists(dir / "out" / "run.resolved.run"));
  std::ifstream csv(dir / "out" / "diagnostics.csv");
  long long rows = -1;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, run.lastProgress().steps);
  // Exactly one line says how device data reach OpenGL, and why; on PoCL it is the copy path
  // because the device lacks cl_khr_gl_sharing.
  const QString log = w.logText();
  EXPECT_EQ(log.count("interop: "), 1) << log.toStdString();
  EXPECT_TRUE(log.contains("interop: copy through host memory") || log.contains("interop: OpenCL/OpenGL sharing"))
      << log.toStdString();
  if (!run.simulation()->context().device().hasGlSharing) {
    EXPECT_TRUE(log.contains("does not report cl_khr_gl_sharing")) << log.toStdString();
  }
  EXPECT_TRUE(w.logText().contains("mass balance error"));
  EXPECT_GT(w.plots().volumePlot().size(0), 0u);
}

TEST(GuiApp, InvalidRunFileShowsTheErrorAtTheFieldAndDoesNotStart) {
  const fs::path dir = scratchDir("invalid");
  const std::string runFile = writeExampleRunFile(dir, "CFL=5\nDEM=missing.tif\n");
  MainWindow w;
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(runFile)));
  EXPECT_FALSE(w.startRun());
  EXPECT_EQ(w.controller().state(), RunController::State::Idle);
  EXPECT_TRUE(w.form().field("CFL")->error().contains("outside the valid range")) << w.form().field("CFL")->error().toStdString();
  EXPECT_TRUE(w.form().field("DEM")->error().contains("does not exist")) << w.form().field("DEM")->error().toStdString();
  EXPECT_TRUE(w.form().field("Manning")->error().isEmpty());
  EXPECT_FALSE(fs::exists(dir / "out"));
  // Fixing the value in the form clears its error and the run-file validates again, except the DEM.
  w.document()->setValue("CFL", "0.4");
  EXPECT_FALSE(w.startRun());
  EXPECT_TRUE(w.form().field("CFL")->error().isEmpty());
  EXPECT_FALSE(w.form().field("DEM")->error().isEmpty());
}

TEST(GuiApp, UnknownKeysAreListedAboveTheForm) {
  const fs::path dir = scratchDir("unknown");
  const std::string runFile = writeExampleRunFile(dir, "Manningg=0.1\n");
  MainWindow w;
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(runFile)));
  EXPECT_FALSE(w.startRun());
  EXPECT_TRUE(w.form().generalErrors().contains("unknown key")) << w.form().generalErrors().toStdString();
}
