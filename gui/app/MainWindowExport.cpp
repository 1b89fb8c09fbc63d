// MainWindow's exports of what the viewer shows: a figure (PNG) and the shown layer as a GeoTIFF.
#include <QFileDialog>
#include <cmath>

#include "app/MainWindow.hpp"
#include "export/FigureComposer.hpp"
#include "export/LayerGeoTiff.hpp"

namespace talus::gui {

QString MainWindow::exportShownLayer(const QString& path) {
  const auto s = viewer_->snapshot();
  const QString layer = layers_->layer();
  if (!s || layer.isEmpty()) return "no layer is shown";
  return writeLayerGeoTiff(*s, layer, path);
}

QString MainWindow::exportFigure(const QString& path) {
  const auto s = viewer_->snapshot();
  if (!s || s->grid.nx < 2 || s->grid.ny < 2) return "no scene is shown";
  if (viewer_->mode() != ViewCamera::Mode::Map) return "figures are made of the map view (View > Tilted 3D view off)";
  FigureContent c;
  c.view = viewer_->grabFramebuffer();
  // The view's georeference from the pixels of two cell centres (widget pixels; the image may have more).
  const Grid& g = s->grid;
  const QPointF a = viewer_->pixelOfCell(0, 0), b = viewer_->pixelOfCell(1, 1);
  if (std::abs(b.x() - a.x()) < 1e-9) return "the view is too far out to export";
  const double ratio = double(c.view.width()) / std::max(1, viewer_->width());
  const double perWidgetPixel = g.geoTransform[1] / (b.x() - a.x());
  c.metresPerPixel = perWidgetPixel / ratio;
  c.x0 = g.cellX(0) - a.x() * perWidgetPixel;
  c.y0 = g.cellY(0) + a.y() * perWidgetPixel;
  c.layer = layers_->layer();
  c.unit = layers_->layerUnit();
  c.ramp = layers_->layerRamp();
  c.min = layers_->layerStyle().min;
  c.max = layers_->layerStyle().max;
  c.time = s->time;
  if (!composeFigure(c).save(path, "PNG")) return "cannot write " + path;
  return {};
}

void MainWindow::chooseAndExportFigure() {
  const QString path = QFileDialog::getSaveFileName(this, "Export figure", "figure.png", "PNG images (*.png)");
  if (path.isEmpty()) return;
  const QString problem = exportFigure(path);
  log_->append(problem.isEmpty() ? "figure saved to " + path : "error: " + problem);
}

void MainWindow::chooseAndExportLayer() {
  const QString name = layers_->layer().isEmpty() ? QString("layer") : layers_->layer();
  const QString path = QFileDialog::getSaveFileName(this, "Export layer as GeoTIFF", name + ".tif", "GeoTIFF (*.tif *.tiff)");
  if (path.isEmpty()) return;
  const QString problem = exportShownLayer(path);
  log_->append(problem.isEmpty() ? "layer '" + layers_->layer() + "' saved to " + path : "error: " + problem);
}

}  // namespace talus::gui
