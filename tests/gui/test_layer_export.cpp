// File > Export layer as GeoTIFF writes the shown layer's values with the scene's georeference;
// read back through the engine's io library they equal what the viewer shows.
#include <gtest/gtest.h>

#include <cmath>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "io/RasterIO.hpp"

using talus::gui::MainWindow;
using namespace talus::guitest;

TEST(LayerExport, GeoTiffReadBackEqualsTheShownLayerAndItsGeoreference) {
  const auto dir = scratchDir("layer_export");
  MainWindow w;
  w.setReportInDialogs(false);
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir))));
  ASSERT_EQ(w.layers().layer(), "initial water height");
  const auto s = w.viewer().snapshot();
  ASSERT_NE(s, nullptr);
  const std::vector<float>& shown = *s->layer("initial water height");
  const QString path = QString::fromStdString((dir / "layer.tif").string());
  ASSERT_EQ(w.exportShownLayer(path), "");
  const talus::Raster r = talus::io::readRaster(path.toStdString());
  const talus::Raster dem = talus::io::readRaster(std::string(TALUS_TEST_DATA_DIR) + "/kot_dambreak/dem.tif");
  EXPECT_EQ(r.grid.nx, dem.grid.nx);
  EXPECT_EQ(r.grid.ny, dem.grid.ny);
  for (int c = 0; c < 6; ++c) EXPECT_DOUBLE_EQ(r.grid.geoTransform[c], dem.grid.geoTransform[c]) << c;
  EXPECT_FALSE(r.grid.projectionWkt.empty());
  EXPECT_EQ(r.grid.projectionWkt, dem.grid.projectionWkt);
  ASSERT_EQ(r.values.size(), shown.size());
  std::size_t wet = 0;
  for (std::size_t k = 0; k < shown.size(); ++k) {
    if (!std::isfinite(shown[k])) {
      EXPECT_FALSE(r.valid[k]) << k;
      continue;
    }
    ASSERT_TRUE(r.valid[k]) << k;
    EXPECT_FLOAT_EQ(static_cast<float>(r.values[k]), shown[k]) << k;
    wet += shown[k] > 0;
  }
  EXPECT_GT(wet, 0u);
}

TEST(LayerExport, WithoutALayerShownNothingIsWritten) {
  const auto dir = scratchDir("layer_export_none");
  MainWindow w;
  const QString path = QString::fromStdString((dir / "layer.tif").string());
  EXPECT_FALSE(w.exportShownLayer(path).isEmpty());
  EXPECT_FALSE(std::filesystem::exists(dir / "layer.tif"));
}
