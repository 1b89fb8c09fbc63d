// The tools that draw on the map (Tools menu, issue 17 items 3 and 9): a release area drawn with the
// mouse becomes the raster of the run-file's initial water and the run starts with its volume; a
// point gives a layer's time series over the frames of opened results (compared with the frame
// rasters read here); a drawn line gives the layer's and the terrain's profile (compared with the
// rasters along the line). The polygon and profile geometry itself is checked in
// tests/unit/test_map_geometry.cpp; here the clicks, files, keys and plots.
#include <gtest/gtest.h>

#include <QApplication>
#include <QTest>
#include <QWheelEvent>
#include <cmath>
#include <filesystem>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "core/Raster.hpp"
#include "form/ReleaseAreaDialog.hpp"
#include "io/RasterIO.hpp"

using talus::gui::MainWindow;
using talus::gui::MapSketch;
using talus::gui::ReleaseAreaDialog;
using namespace talus;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

const std::string kData = std::string(TALUS_TEST_DATA_DIR) + "/kot_dambreak";

/// Metres a pixel spans in the map view now.
double metresPerPixel(const talus::gui::ViewerWidget& v, const Grid& g) {
  const QPointF a = v.pixelOfCell(10, 10), b = v.pixelOfCell(20, 10);
  return 10 * g.dx / std::hypot(b.x() - a.x(), b.y() - a.y());
}

/// Zooms the map view in around its centre until a cell spans at least 10 pixels, so that a
/// click's rounding to a pixel moves a vertex by a small part of a cell.
void zoomIn(talus::gui::ViewerWidget& v, const Grid& g) {
  const QPointF centre(v.width() / 2.0, v.height() / 2.0);
  for (int n = 0; n < 8 && metresPerPixel(v, g) > g.dx / 10; ++n) {
    QWheelEvent e(centre, v.mapToGlobal(centre.toPoint()), QPoint(), QPoint(0, 480), Qt::NoButton, Qt::NoModifier,
                  Qt::NoScrollPhase, false);
    QApplication::sendEvent(&v, &e);
  }
  v.update();
  waitFor([] { return false; }, 0.2);
}

/// Winding number of a closed polygon around p (an independent point test).
int winding(const std::vector<QPointF>& poly, QPointF p) {
  int wn = 0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const QPointF a = poly[k], b = poly[(k + 1) % poly.size()];
    const double side = (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && side > 0) ++wn;
    } else if (b.y() <= p.y() && side < 0) {
      --wn;
    }
  }
  return wn;
}

double distanceToOutline(const std::vector<QPointF>& poly, QPointF p) {
  double d = 1e300;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const QPointF a = poly[k], b = poly[(k + 1) % poly.size()];
    const QPointF ab = b - a;
    const double t = std::clamp(QPointF::dotProduct(p - a, ab) / QPointF::dotProduct(ab, ab), 0.0, 1.0);
    const QPointF q = a + t * ab;
    d = std::min(d, std::hypot(p.x() - q.x(), p.y() - q.y()));
  }
  return d;
}

/// Clicks the centres of the cells in the map view (world coordinates of the clicked points in
/// `world`), the last one with a double click when `doubleClickLast`.
void clickCells(talus::gui::ViewerWidget& v, const Grid& g, const std::vector<std::pair<int, int>>& cells,
                bool doubleClickLast, std::vector<QPointF>& world) {
  for (std::size_t n = 0; n < cells.size(); ++n) {
    const auto [i, j] = cells[n];
    const QPoint px = v.pixelOfCell(i, j).toPoint();
    world.emplace_back(g.cellX(i), g.cellY(j));
    QTest::mouseClick(&v, Qt::LeftButton, {}, px);
    // A double click reaches a widget as press, release, double-click, release; QTest's
    // mouseDClick sends only the second half.
    if (doubleClickLast && n + 1 == cells.size()) QTest::mouseDClick(&v, Qt::LeftButton, {}, px);
  }
}


}  // namespace

TEST(ReleaseArea, DrawnPolygonBecomesTheInitialWaterAndTheRunStartsWithItsVolume) {
  const fs::path dir = scratchDir("release_area");
  MainWindow w;
  w.setReportInDialogs(false);
  w.setAskBeforeOverwrite(false);
  w.resize(1200, 800);
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir, "End Time=0.02\n"))));
  waitFor([] { return false; }, 0.3);
  const Raster dem = io::readRaster(kData + "/dem.tif");
  const Grid& g = dem.grid;
  zoomIn(w.viewer(), g);

  // A quadrilateral around the view's centre cell, drawn with the mouse, closed by a double click.
  int ci = 0, cj = 0;
  ASSERT_TRUE(w.viewer().cellAt(QPoint(w.viewer().width() / 2, w.viewer().height() / 2), ci, cj));
  w.startSketch(MapSketch::Tool::Polygon);
  ASSERT_TRUE(w.viewer().sketch().active());
  std::vector<QPointF> drawn;
  clickCells(w.viewer(), g, {{ci - 12, cj - 8}, {ci + 10, cj - 11}, {ci + 14, cj + 9}, {ci - 9, cj + 12}}, true, drawn);
  EXPECT_FALSE(w.viewer().sketch().active()) << "the double click closes the polygon";

  // The dialog asks what it releases.
  ReleaseAreaDialog* dialog = nullptr;
  ASSERT_TRUE(waitFor([&] { return (dialog = w.findChild<ReleaseAreaDialog*>()) != nullptr; }, 5));
  const fs::path file = dir / "release.tif";
  dialog->setMaterial(ReleaseAreaDialog::Material::Water);
  dialog->setThickness(2.5);
  dialog->setPath(QString::fromStdString(file.string()));
  dialog->setAddToCurrentMap(false);
  dialog->accept();
  ASSERT_TRUE(waitFor([&] { return fs::exists(file); }, 5)) << w.logText().toStdString();

  // The raster: 2.5 m in the cells whose centres the drawn polygon encloses, 0 elsewhere. The
  // clicks land within half a pixel of the cell centres, so cells whose centre lies farther than a
  // pixel from the outline are decided the same way for the drawn and the intended polygon.
  const Raster r = io::readRaster(file.string());
  ASSERT_TRUE(sameGrid(r.grid, g));
  const double tolerance = metresPerPixel(w.viewer(), g);
  ASSERT_LE(tolerance, g.dx / 10) << "zoomed in: a click lands within a twentieth of a cell of the centre";
  int inside = 0, decided = 0, valid = 0;
  double volume = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      if (!r.valid[k]) {
        EXPECT_FALSE(dem.valid[k]) << "only cells without ground lack a value";
        continue;
      }
      volume += r.values[k] * g.dx * g.dx;
      ++valid;
      const QPointF c(g.cellX(i), g.cellY(j));
      if (distanceToOutline(drawn, c) <= tolerance) continue;
      ++decided;
      const bool in = winding(drawn, c) != 0;
      inside += in;
      ASSERT_EQ(r.values[k], in ? 2.5 : 0.0) << "cell " << i << "," << j;
    }
  EXPECT_GT(inside, 300);
  EXPECT_GT(decided, valid - 100) << "only cells the outline passes within a pixel are left undecided";

  // The run-file now takes its initial water from the file (named absolutely: it lies outside
  // the run-file's map folder), and the scene shows it as the initial water layer.
  ASSERT_NE(w.document(), nullptr);
  EXPECT_EQ(w.document()->value("Include Initial Water"), "1");
  EXPECT_EQ(fs::path(w.document()->value("Initial Fluid Height")), file);
  EXPECT_TRUE(w.document()->isModified());
  EXPECT_EQ(w.layers().layer(), "initial water height");
  const auto shown = w.viewer().snapshot();
  ASSERT_TRUE(shown);
  const std::vector<float>* layer = shown->layer("initial water height");
  ASSERT_NE(layer, nullptr);
  for (std::size_t k = 0; k < g.cells(); ++k)
    if (r.valid[k]) {
      ASSERT_EQ((*layer)[k], float(r.values[k])) << k;
    }

  // The run starts with that volume (a few steps; water is conserved to round-off and none
  // reaches the edge in 0.02 s).
  // A time series at the area's centre cell grows with the run's snapshots.
  w.layers().selectLayer("h");
  w.probeCell(ci, cj);
  ASSERT_TRUE(w.startRun());
  ASSERT_TRUE(waitFor([&] { return w.controller().state() == talus::gui::RunController::State::Ended; }, 120));
  const auto& series = w.probe().pointPlot().points(0);
  ASSERT_GE(series.size(), 2u);
  for (std::size_t n = 1; n < series.size(); ++n) EXPECT_GT(series[n].x(), series[n - 1].x());
  // Its last value is the run's final thickness there, as the engine wrote it.
  const Raster final = io::readRaster((dir / "out" / "hffinal.tif").string());
  EXPECT_FLOAT_EQ(float(series.back().y()), float(final.at(ci, cj)));
  EXPECT_GT(series.back().y(), 1.0) << "the cell is inside the released block";
  const auto row = lastDiagnosticsRow(dir / "out" / "diagnostics.csv");
  ASSERT_TRUE(row.count("volume_m3"));
  EXPECT_NEAR(row.at("volume_m3"), volume, 1e-5 * volume);  // float precision (the example runs in float)
}

TEST(ReleaseArea, AddedAreaKeepsTheCurrentMapOutsideThePolygonAndBadInputIsRefused) {
  const fs::path dir = scratchDir("release_area_add");
  MainWindow w;
  ASSERT_NO_FATAL_FAILURE(showExampleWindow(w, dir));
  const Raster water = io::readRaster(kData + "/water.tif");
  const Grid& g = water.grid;
  // A triangle given in world coordinates (the drawing is tested above).
  const std::vector<MapPoint> triangle = {{g.cellX(20), g.cellY(30)}, {g.cellX(60), g.cellY(35)}, {g.cellX(30), g.cellY(80)}};
  const fs::path file = dir / "added.tif";
  ASSERT_EQ(w.saveReleaseArea(triangle, ReleaseAreaDialog::Material::Water, 0.75, QString::fromStdString(file.string()), true),
            QString());
  const Raster r = io::readRaster(file.string());
  std::vector<QPointF> poly;
  for (const auto& p : triangle) poly.emplace_back(p.x, p.y);
  int kept = 0, set = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      if (!r.valid[k]) continue;
      const QPointF c(g.cellX(i), g.cellY(j));
      if (distanceToOutline(poly, c) < 1e-6) continue;
      if (winding(poly, c) != 0) {
        ASSERT_EQ(r.values[k], 0.75);
        ++set;
      } else {
        ASSERT_FLOAT_EQ(float(r.values[k]), float(water.valid[k] ? water.values[k] : 0.0)) << i << "," << j;
        kept += r.values[k] > 0;
      }
    }
  EXPECT_GT(set, 500);
  EXPECT_GT(kept, 100) << "the example's water outside the triangle stays";

  // Refusals name the problem and change nothing.
  const std::string before = w.document()->value("Initial Fluid Height");
  const QString none = w.saveReleaseArea({{-1e6, -1e6}, {-1e6 + 1, -1e6}, {-1e6, -1e6 + 1}},
                                         ReleaseAreaDialog::Material::Water, 1.0, QString::fromStdString((dir / "x.tif").string()), false);
  EXPECT_NE(none.indexOf("encloses no cell"), -1) << none.toStdString();
  const QString folder = w.saveReleaseArea(triangle, ReleaseAreaDialog::Material::Water, 1.0,
                                           QString::fromStdString((dir / "missing" / "x.tif").string()), false);
  EXPECT_FALSE(folder.isEmpty());
  EXPECT_EQ(w.document()->value("Initial Fluid Height"), before);
  EXPECT_FALSE(fs::exists(dir / "x.tif"));
}

TEST(Probe, PointSeriesOfReplayedResultsAreTheFrameRastersValues) {
  const fs::path dir = scratchDir("probe_point");
  const fs::path out = writeExampleResults(dir);
  MainWindow w;
  w.setReportInDialogs(false);
  w.resize(1200, 800);
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  ASSERT_TRUE(w.openResults(QString::fromStdString(out.string())));
  ASSERT_NE(w.results(), nullptr);
  const auto& folder = w.results()->folder();
  ASSERT_FALSE(folder.series.empty());
  const auto& series = folder.series.front();
  w.layers().selectLayer(series.name);
  waitFor([] { return false; }, 0.2);
  zoomIn(w.viewer(), w.results()->grid());
  // The wettest cell of the last frame, read here.
  const Raster last = io::readRaster(series.files.back().toStdString());
  std::size_t wettest = 0;
  for (std::size_t k = 0; k < last.values.size(); ++k)
    if (last.valid[k] && last.values[k] > last.values[wettest]) wettest = k;
  const Grid& g = last.grid;
  const int i = int(wettest % std::size_t(g.nx)), j = int(wettest / std::size_t(g.nx));
  // Bring it into view: the map view is centred on the grid, so probe through the API when the
  // cell lies off screen, else click it.
  const QPointF px = w.viewer().pixelOfCell(i, j);
  if (w.viewer().rect().contains(px.toPoint())) {
    w.startSketch(MapSketch::Tool::Point);
    QTest::mouseClick(&w.viewer(), Qt::LeftButton, {}, px.toPoint());
  } else {
    w.probeCell(i, j);
  }
  const auto& points = w.probe().pointPlot().points(0);
  ASSERT_EQ(int(points.size()), w.results()->frameCount());
  for (int f = 0; f < w.results()->frameCount(); ++f) {
    const Raster frame = io::readRaster(series.files[std::size_t(f)].toStdString());
    EXPECT_DOUBLE_EQ(points[std::size_t(f)].x(), folder.frameTimes[std::size_t(f)]);
    EXPECT_EQ(float(points[std::size_t(f)].y()), float(frame.values[wettest])) << "frame " << f;
  }
  EXPECT_NE(w.probe().pointCaption().indexOf(QString("cell (%1, %2)").arg(i).arg(j)), -1);
}

TEST(Probe, ProfileAlongADrawnLineFollowsTheLayerAndTheTerrain) {
  const fs::path dir = scratchDir("probe_profile");
  MainWindow w;
  ASSERT_NO_FATAL_FAILURE(showExampleWindow(w, dir));
  const Raster dem = io::readRaster(kData + "/dem.tif");
  const Raster water = io::readRaster(kData + "/water.tif");
  const Grid& g = dem.grid;
  w.layers().selectLayer("initial water height");
  zoomIn(w.viewer(), g);
  int ci = 0, cj = 0;
  ASSERT_TRUE(w.viewer().cellAt(QPoint(w.viewer().width() / 2, w.viewer().height() / 2), ci, cj));
  // Along the row of the centre cell, 30 cells long, ended with Enter.
  w.startSketch(MapSketch::Tool::Profile);
  std::vector<QPointF> drawn;
  clickCells(w.viewer(), g, {{ci - 15, cj}, {ci + 15, cj}}, false, drawn);
  QTest::keyClick(&w.viewer(), Qt::Key_Return);
  EXPECT_FALSE(w.viewer().sketch().active());
  const auto& terrain = w.probe().elevationPlot().points(0);
  ASSERT_GE(terrain.size(), 60u);  // every half cell over 30 cells
  EXPECT_NEAR(terrain.back().x(), 30 * g.dx, 2 * metresPerPixel(w.viewer(), g));
  // Each sample's cell: on the row (the clicks are within half a pixel of it), at the column the
  // distance walked reaches; samples within a pixel of a column boundary may fall either side.
  const double slack = metresPerPixel(w.viewer(), g);
  int compared = 0;
  for (const QPointF& p : terrain) {
    const double x = drawn.front().x() + p.x() - g.geoTransform[0];
    const double inCell = std::fmod(x, g.dx);
    if (inCell < slack || g.dx - inCell < slack) continue;
    const int i = int(std::floor(x / g.dx));
    EXPECT_FLOAT_EQ(float(p.y()), float(dem.at(i, cj))) << "at " << p.x() << " m";
    ++compared;
  }
  EXPECT_GT(compared, 25);  // every second sample lies on a column boundary (half-cell spacing from a centre)
  const auto& values = w.probe().profilePlot().points(0);
  for (const QPointF& p : values) {
    const double x = drawn.front().x() + p.x() - g.geoTransform[0];
    const double inCell = std::fmod(x, g.dx);
    if (inCell < slack || g.dx - inCell < slack) continue;
    const int i = int(std::floor(x / g.dx));
    EXPECT_FLOAT_EQ(float(p.y()), float(water.at(i, cj)));
  }
}
