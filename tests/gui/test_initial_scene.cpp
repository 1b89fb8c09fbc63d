// Before pressing Run, an opened run-file shows its scene: the DEM and the initial maps as layers,
// and the status bar reports coordinates, elevation, slope and the layers' values under the cursor.
#include <gtest/gtest.h>

#include <QRegularExpression>
#include <cmath>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "io/RasterIO.hpp"

using talus::gui::MainWindow;
using namespace talus::guitest;

namespace {

const std::string kData = std::string(TALUS_TEST_DATA_DIR) + "/kot_dambreak";

/// The number after `label` in the status bar text (NaN when it is not there).
double numberAfter(const QString& text, const QString& label) {
  const QRegularExpression re(QRegularExpression::escape(label) + " (-?[0-9.eE+-]+)");
  const auto m = re.match(text);
  return m.hasMatch() ? m.captured(1).toDouble() : NAN;
}

/// Slope [degrees] of the DEM at (i, j) from centred differences (the cell is interior).
double centredSlope(const talus::Raster& dem, int i, int j) {
  const auto& g = dem.grid;
  auto z = [&](int ii, int jj) { return dem.values[g.index(ii, jj)]; };
  const double p = (z(i + 1, j) - z(i - 1, j)) / (2 * std::abs(g.geoTransform[1]));
  const double q = (z(i, j + 1) - z(i, j - 1)) / (2 * std::abs(g.geoTransform[5]));
  return std::atan(std::hypot(p, q)) * 180.0 / M_PI;
}

}  // namespace

TEST(InitialScene, OpeningTheExampleListsItsInitialWaterAsALayerWithTheRastersValues) {
  const auto dir = scratchDir("initial_scene_water");
  MainWindow w;
  w.setReportInDialogs(false);
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir))));
  EXPECT_FALSE(w.controller().isActive());
  EXPECT_TRUE(w.layers().layerNames().contains("initial water height")) << w.layers().layerNames().join(", ").toStdString();
  EXPECT_EQ(w.layers().layer(), "initial water height");
  const auto s = w.viewer().snapshot();
  ASSERT_NE(s, nullptr);
  const std::vector<float>* shown = s->layer("initial water height");
  ASSERT_NE(shown, nullptr);
  const talus::Raster water = talus::io::readRaster(kData + "/water.tif");
  const talus::Raster dem = talus::io::readRaster(kData + "/dem.tif");
  ASSERT_EQ(shown->size(), water.values.size());
  std::size_t wet = 0;
  for (std::size_t k = 0; k < shown->size(); ++k) {
    if (!water.valid[k] || !dem.valid[k]) {
      EXPECT_TRUE(std::isnan((*shown)[k])) << k;
      continue;
    }
    EXPECT_FLOAT_EQ((*shown)[k], static_cast<float>(water.values[k])) << k;
    wet += water.values[k] > 0;
  }
  EXPECT_GT(wet, 0u) << "the example's water map is empty: the comparison checks nothing";
}

TEST(InitialScene, InitialSolidHeightIsListedWhenItsIncludeKeyIsOn) {
  const auto dir = scratchDir("initial_scene_solids");
  MainWindow w;
  w.setReportInDialogs(false);
  QString problems;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir, "Include Initial Solids=1\nInitial Solid Height=water.tif\n")), &problems));
  ASSERT_TRUE(problems.isEmpty()) << problems.toStdString();
  EXPECT_TRUE(w.layers().layerNames().contains("initial solid height")) << w.layers().layerNames().join(", ").toStdString();
  EXPECT_TRUE(w.layers().layerNames().contains("initial water height"));
}

TEST(InitialScene, HoveringACellReportsItsCoordinatesElevationSlopeAndLayerValue) {
  const auto dir = scratchDir("initial_scene_hover");
  MainWindow w;
  w.setReportInDialogs(false);
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir))));
  const talus::Raster dem = talus::io::readRaster(kData + "/dem.tif");
  const talus::Raster water = talus::io::readRaster(kData + "/water.tif");
  const auto& g = dem.grid;
  // A wet interior cell whose neighbours all have elevations, on a slope.
  int ci = -1, cj = -1;
  for (int j = 1; j + 1 < g.ny && ci < 0; ++j)
    for (int i = 1; i + 1 < g.nx && ci < 0; ++i) {
      const std::size_t k = g.index(i, j);
      bool ok = dem.valid[k] && water.valid[k] && water.values[k] > 0 && centredSlope(dem, i, j) > 0.5;
      for (const std::size_t n : {g.index(i - 1, j), g.index(i + 1, j), g.index(i, j - 1), g.index(i, j + 1)}) ok = ok && dem.valid[n];
      if (ok) ci = i, cj = j;
    }
  ASSERT_GE(ci, 0) << "no wet sloping interior cell in the example";
  emit w.viewer().hovered(ci, cj, true);
  const QString text = w.cursorReadout();
  const std::size_t k = g.index(ci, cj);
  const double x = g.geoTransform[0] + (ci + 0.5) * g.geoTransform[1];
  const double y = g.geoTransform[3] + (cj + 0.5) * g.geoTransform[5];
  EXPECT_NEAR(numberAfter(text, "x"), x, 0.051) << text.toStdString();
  EXPECT_NEAR(numberAfter(text, "y"), y, 0.051) << text.toStdString();
  EXPECT_NEAR(numberAfter(text, "elevation"), dem.values[k], 0.0051) << text.toStdString();
  EXPECT_NEAR(numberAfter(text, "slope"), centredSlope(dem, ci, cj), 0.051) << text.toStdString();
  EXPECT_NEAR(numberAfter(text, "initial water height"), water.values[k], 1e-3 * std::max(1.0, water.values[k])) << text.toStdString();
  emit w.viewer().hovered(-1, -1, false);
  EXPECT_TRUE(w.cursorReadout().isEmpty());
}
