// The parameter form shows a small picture of each map a map field names (issue 17 item 2): opened
// with the example run-file, the DEM field's preview is on screen, laid out at the picture's size
// (it was laid out 0 px high: a word-wrapping label asked for a height for its width, which a
// picture does not give), and its grey levels span black (the DEM's lowest cell) to white (its
// highest); a field naming a missing file says so instead.
#include <gtest/gtest.h>

#include <QLabel>
#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "form/KeyField.hpp"
#include "form/MapPreview.hpp"
#include "form/ParameterForm.hpp"

using talus::gui::MainWindow;
using namespace talus::guitest;

TEST(MapPreview, TheDemFieldShowsItsMapAtItsSize) {
  const auto dir = scratchDir("map_preview");
  MainWindow w;
  ASSERT_NO_FATAL_FAILURE(showExampleWindow(w, dir, 1400, 900));
  auto* dem = w.form().field("DEM");
  ASSERT_NE(dem, nullptr);
  auto* preview = dem->findChild<talus::gui::MapPreview*>();
  ASSERT_NE(preview, nullptr);
  ASSERT_TRUE(preview->isVisibleTo(&w));
  const QPixmap* pixmap = preview->pixmap();
  ASSERT_TRUE(pixmap && !pixmap->isNull()) << preview->text().toStdString();
  EXPECT_GE(preview->height(), pixmap->height()) << "laid out smaller than its picture";
  EXPECT_GE(preview->width(), pixmap->width());
  EXPECT_GE(std::max(pixmap->width(), pixmap->height()), 100);
  const QImage img = pixmap->toImage();
  int darkest = 255, lightest = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const int g = qGray(img.pixel(x, y));
      darkest = std::min(darkest, g);
      lightest = std::max(lightest, g);
    }
  EXPECT_LE(darkest, 10);
  EXPECT_GE(lightest, 245);
  // A missing file: a line that says so, laid out too.
  dem->setValue("nope.tif");
  waitFor([] { return false; }, 0.2);
  EXPECT_TRUE(preview->text().contains("file not found")) << preview->text().toStdString();
  EXPECT_GT(preview->height(), 5);
}
