// File > Export figure writes the map view framed by coordinate ticks, with a colour-bar legend,
// the time, a scale bar and a north arrow: the PNG's size and the pixels of each part are checked.
#include <gtest/gtest.h>

#include <QApplication>
#include <QFileDialog>
#include <QTest>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "export/FigureComposer.hpp"
#include "render/ColorRamp.hpp"

using talus::gui::FigureLayout;
using talus::gui::MainWindow;
using namespace talus::guitest;

namespace {
/// Number of pixels of `r` in `image` that are near black (all channels below 60).
int darkPixels(const QImage& image, const QRect& r) {
  int n = 0;
  for (int y = r.top(); y <= r.bottom(); ++y)
    for (int x = r.left(); x <= r.right(); ++x) {
      const QColor c = image.pixelColor(x, y);
      n += c.red() < 60 && c.green() < 60 && c.blue() < 60;
    }
  return n;
}
bool near(const QColor& a, const QColor& b) {
  return std::abs(a.red() - b.red()) <= 3 && std::abs(a.green() - b.green()) <= 3 && std::abs(a.blue() - b.blue()) <= 3;
}
}  // namespace

TEST(FigureExport, PngHasTheViewLegendScaleBarNorthArrowAndTicks) {
  const auto dir = scratchDir("figure_export");
  MainWindow w;
  ASSERT_NO_FATAL_FAILURE(showExampleWindow(w, dir));
  const QString path = QString::fromStdString((dir / "figure.png").string());
  ASSERT_EQ(w.exportFigure(path), "");
  const QImage figure(path);
  ASSERT_FALSE(figure.isNull());
  const QSize view = w.viewer().grabFramebuffer().size();
  const FigureLayout l = FigureLayout::of(view);
  ASSERT_EQ(figure.size(), l.size);
  // The view: the hillshade and the layer (many colours).
  EXPECT_GT(distinctColours(figure.copy(l.view)), 200);
  // The colour bar is the layer's ramp: max at the top, min at the bottom, many shades between.
  const QImage bar = figure.copy(l.colourBar);
  EXPECT_GT(distinctColours(bar), 50);
  const talus::gui::ColorRamp ramp = talus::gui::ColorRamp::byName(w.layers().layerRamp());
  EXPECT_TRUE(near(bar.pixelColor(bar.width() / 2, 0), ramp.at(1.0)));
  EXPECT_TRUE(near(bar.pixelColor(bar.width() / 2, bar.height() - 1), ramp.at(0.0)));
  // The legend's title and labels (text right of and above the bar).
  EXPECT_GT(darkPixels(figure, QRect(l.colourBar.left(), l.colourBar.top() - 36, 150, 34)), 20);
  EXPECT_GT(darkPixels(figure, QRect(l.colourBar.right() + 8, l.colourBar.top() - 8, 80, l.colourBar.height() + 16)), 40);
  // The scale bar (a black bar and its label) and the north arrow over the view.
  EXPECT_GT(darkPixels(figure, l.scaleBar), 100);
  EXPECT_GT(darkPixels(figure, l.northArrow), 100);
  // Coordinate ticks and labels below and left of the view; the time above it.
  EXPECT_GT(darkPixels(figure, QRect(l.view.left(), l.view.bottom() + 2, l.view.width(), 24)), 50);
  EXPECT_GT(darkPixels(figure, QRect(0, l.view.top(), l.view.left() - 1, l.view.height())), 50);
  EXPECT_GT(darkPixels(figure, QRect(l.view.left(), 0, l.view.width(), l.view.top() - 1)), 20);
}

TEST(FigureExport, TheTiltedViewIsRefused) {
  const auto dir = scratchDir("figure_export_tilted");
  MainWindow w;
  w.setReportInDialogs(false);
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir))));
  w.viewer().setMode(talus::gui::ViewCamera::Mode::Tilted);
  EXPECT_FALSE(w.exportFigure(QString::fromStdString((dir / "f.png").string())).isEmpty());
  EXPECT_FALSE(std::filesystem::exists(dir / "f.png"));
}

TEST(FigureExport, ScaleBarAndTicksFollowTheViewsScale) {
  // A 400 x 300 px view at 2 m per pixel with its top-left corner at (1000, 5000): the scale bar is
  // 200 m (100 px) long and x ticks fall every 200 m, at x = 1000, 1200, ... (every 100 px).
  talus::gui::FigureContent c;
  c.view = QImage(400, 300, QImage::Format_RGB32);
  c.view.fill(Qt::white);
  c.x0 = 1000;
  c.y0 = 5000;
  c.metresPerPixel = 2;
  const QImage figure = talus::gui::composeFigure(c);
  const FigureLayout l = FigureLayout::of(c.view.size());
  ASSERT_EQ(figure.size(), l.size);
  EXPECT_EQ(darkPixels(figure, l.colourBar), 0) << "no layer: no colour bar";
  // The bar: the longest run of dark pixels in a row of the scale-bar box.
  int longest = 0;
  for (int y = l.scaleBar.top(); y <= l.scaleBar.bottom(); ++y) {
    int run = 0;
    for (int x = l.scaleBar.left(); x <= l.scaleBar.right(); ++x) {
      run = darkPixels(figure, QRect(x, y, 1, 1)) ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  EXPECT_EQ(longest, 100);
  // Tick marks just below the frame, at every 100th column of the view.
  const int y = l.view.bottom() + 4;
  for (int k = 0; k <= 4; ++k) EXPECT_EQ(darkPixels(figure, QRect(l.view.left() + 100 * k, y, 1, 1)), 1) << k;
  EXPECT_EQ(darkPixels(figure, QRect(l.view.left() + 50, y, 1, 1)), 0);
}

TEST(FigureExport, BothPngMenuActionsWriteTheFigureOfTheMapView) {
  const auto dir = scratchDir("figure_export_menu");
  QApplication::setAttribute(Qt::AA_DontUseNativeDialogs);  // the Qt dialog, which the test can answer
  MainWindow w;
  ASSERT_NO_FATAL_FAILURE(showExampleWindow(w, dir));
  const FigureLayout l = FigureLayout::of(w.viewer().grabFramebuffer().size());
  int n = 0;
  for (const QString& text : {QString("Export &figure..."), QString("Export &screenshot (PNG)...")}) {
    QAction* action = nullptr;
    for (QAction* a : w.findChildren<QAction*>())
      if (a->text() == text) action = a;
    ASSERT_NE(action, nullptr) << text.toStdString();
    const auto file = dir / ("menu" + std::to_string(n++) + ".png");
    onNextModal([&](QWidget* modal) {
      auto* dialog = qobject_cast<QFileDialog*>(modal);
      if (!dialog) return modal->close(), void();
      chooseInFileDialog(dialog, file);
    });
    action->trigger();
    ASSERT_TRUE(waitFor([&] { return std::filesystem::exists(file); }, 10)) << text.toStdString() << "\n" << w.logText().toStdString();
    const QImage png(QString::fromStdString(file.string()));
    EXPECT_EQ(png.size(), l.size) << text.toStdString();
    EXPECT_GT(distinctColours(png.copy(l.colourBar)), 50) << text.toStdString();
    EXPECT_GT(darkPixels(png, l.scaleBar), 100) << text.toStdString();
  }
}
