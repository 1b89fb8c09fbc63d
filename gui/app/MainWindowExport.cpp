// MainWindow's exports of what the viewer shows: the shown layer as a GeoTIFF.
#include <QFileDialog>

#include "app/MainWindow.hpp"
#include "export/LayerGeoTiff.hpp"

namespace talus::gui {

QString MainWindow::exportShownLayer(const QString& path) {
  const auto s = viewer_->snapshot();
  const QString layer = layers_->layer();
  if (!s || layer.isEmpty()) return "no layer is shown";
  return writeLayerGeoTiff(*s, layer, path);
}

void MainWindow::chooseAndExportLayer() {
  const QString name = layers_->layer().isEmpty() ? QString("layer") : layers_->layer();
  const QString path = QFileDialog::getSaveFileName(this, "Export layer as GeoTIFF", name + ".tif", "GeoTIFF (*.tif *.tiff)");
  if (path.isEmpty()) return;
  const QString problem = exportShownLayer(path);
  log_->append(problem.isEmpty() ? "layer '" + layers_->layer() + "' saved to " + path : "error: " + problem);
}

}  // namespace talus::gui
