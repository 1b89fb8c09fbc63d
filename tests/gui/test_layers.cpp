// The layer panel's colour ranges: automatic ranges follow the layer shown, also when the run sends
// no more snapshots (paused or ended), and fractions keep their 0..1 range whatever the flow holds.
#include <gtest/gtest.h>

#include <QApplication>
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "view/LayerPanel.hpp"

using talus::gui::LayerPanel;
using talus::gui::MainWindow;
using talus::gui::RunController;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

/// The automatic range the panel should give a layer: smallest value above `emptyBelow` (or 0 when
/// smaller) to the largest, as the spin boxes round them (4 decimals).
std::pair<double, double> expectedRange(const std::vector<float>& v, double emptyBelow) {
  double lo = 0, hi = -HUGE_VAL;
  for (float x : v)
    if (std::isfinite(x) && x > emptyBelow) {
      lo = std::min(lo, double(x));
      hi = std::max(hi, double(x));
    }
  return {std::round(lo * 1e4) / 1e4, std::round(hi * 1e4) / 1e4};
}

/// A snapshot of a 4x1 grid: h 0..2 m, velocity 0..7 m/s, solid fraction 0.2..0.45; particles with
/// velocity 1..3 m/s and cohesion fraction 0.3..0.6.
std::shared_ptr<talus::sim::ViewSnapshot> syntheticSnapshot() {
  auto s = std::make_shared<talus::sim::ViewSnapshot>();
  s->grid = talus::Grid::make(4, 1, 1.0);
  s->layerNames = {"h", "velocity", "solid fraction"};
  s->layers = {{0.0f, 0.5f, 2.0f, NAN}, {0.0f, 3.0f, 7.0f, NAN}, {0.2f, 0.3f, 0.45f, NAN}};
  s->particleCount = 2;
  s->particlePositions = {0, 0, 0, 1, 0, 0};
  s->particleAttributeNames = {"velocity", "cohesion fraction"};
  s->particleAttributes = {{1.0f, 3.0f}, {0.3f, 0.6f}};
  return s;
}

}  // namespace

TEST(LayerRanges, EachLayerChosenGetsItsOwnRangeFromTheLastSnapshot) {
  LayerPanel panel;
  panel.setCatalogue({{"h", "flow thickness", "m", true},
                      {"velocity", "velocity", "m/s", true},
                      {"solid fraction", "solid fraction", "-", true}},
                     {{"velocity", "m/s"}, {"cohesion fraction", "-"}});
  panel.setSnapshot(syntheticSnapshot());
  ASSERT_EQ(panel.layer(), "h");
  EXPECT_DOUBLE_EQ(panel.layerStyle().min, 0.0);
  EXPECT_DOUBLE_EQ(panel.layerStyle().max, 2.0);
  // No snapshot follows (the run is paused): the new layer's range comes from the one kept.
  panel.selectLayer("velocity");
  EXPECT_DOUBLE_EQ(panel.layerStyle().min, 0.0);
  EXPECT_DOUBLE_EQ(panel.layerStyle().max, 7.0);
  // A fraction: 0..1, not the 0.2..0.45 it holds.
  panel.selectLayer("solid fraction");
  EXPECT_DOUBLE_EQ(panel.layerStyle().min, 0.0);
  EXPECT_DOUBLE_EQ(panel.layerStyle().max, 1.0);
  panel.selectLayer("h");
  EXPECT_DOUBLE_EQ(panel.layerStyle().max, 2.0);

  EXPECT_EQ(panel.particleStyle().attribute, "velocity");
  EXPECT_DOUBLE_EQ(panel.particleStyle().min, 1.0);
  EXPECT_DOUBLE_EQ(panel.particleStyle().max, 3.0);
  panel.selectAttribute("cohesion fraction");
  EXPECT_DOUBLE_EQ(panel.particleStyle().min, 0.0);
  EXPECT_DOUBLE_EQ(panel.particleStyle().max, 1.0);
  panel.selectAttribute("velocity");
  EXPECT_DOUBLE_EQ(panel.particleStyle().max, 3.0);

  // A new scene forgets the old snapshot: no range of it survives into the next layer chosen.
  panel.clear();
  EXPECT_EQ(panel.layer(), "");
  panel.setCatalogue({{"velocity", "velocity", "m/s", true}}, {});
  EXPECT_DOUBLE_EQ(panel.layerStyle().max, 1.0);
}

TEST(LayerRanges, SwitchingLayersOfAPausedTwoPhaseRunRefitsTheRange) {
  const fs::path dir = scratchDir("layer_ranges");
  const std::string runFile =
      writeExampleRunFile(dir, "Include Initial Solids=1\nInitial Solid Height=water.tif\nEnd Time=20\n");
  MainWindow w;
  w.setAskBeforeOverwrite(false);
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(runFile)));
  ASSERT_TRUE(w.startRun()) << w.logText().toStdString();
  RunController& run = w.controller();
  ASSERT_TRUE(waitFor([&] { return run.lastProgress().steps >= 20; }, 120)) << w.logText().toStdString();
  run.pause();
  run.requestSnapshot();
  ASSERT_TRUE(waitFor([&] {
    return w.viewer().snapshot() && w.viewer().snapshot()->steps == run.lastProgress().steps;
  }, 30));
  const auto snap = w.viewer().snapshot();
  LayerPanel& layers = w.layers();
  ASSERT_EQ(layers.layer(), "h");
  for (const char* name : {"velocity", "hs", "h", "velocity"}) {
    layers.selectLayer(name);
    ASSERT_EQ(layers.layer(), name);
    const auto [lo, hi] = expectedRange(*snap->layer(name), layers.layerStyle().emptyBelow);
    EXPECT_NEAR(layers.layerStyle().min, lo, 1e-5) << name;
    EXPECT_NEAR(layers.layerStyle().max, hi, 1e-5) << name;
  }
  // The two ranges differ, so the check above tells them apart.
  EXPECT_GT(std::abs(expectedRange(*snap->layer("velocity"), 0).second - expectedRange(*snap->layer("h"), 0).second), 0.01);
  layers.selectLayer("solid fraction");
  EXPECT_EQ(layers.layer(), "solid fraction");
  EXPECT_EQ(layers.layerStyle().min, 0.0f);
  EXPECT_EQ(layers.layerStyle().max, 1.0f);
  run.stop();
  ASSERT_TRUE(waitFor([&] { return run.state() == RunController::State::Ended; }, 120));
  // Ended: still the chosen layer's range (of the last snapshot shown).
  layers.selectLayer("vs");
  const auto [lo, hi] = expectedRange(*w.viewer().snapshot()->layer("vs"), layers.layerStyle().emptyBelow);
  EXPECT_NEAR(layers.layerStyle().min, lo, 1e-5);
  EXPECT_NEAR(layers.layerStyle().max, hi, 1e-5);
}
