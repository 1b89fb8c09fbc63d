#include "export/LayerGeoTiff.hpp"

#include <cmath>
#include <exception>

#include "io/RasterIO.hpp"

namespace talus::gui {

QString writeLayerGeoTiff(const sim::ViewSnapshot& snapshot, const QString& layer, const QString& path) {
  const std::vector<float>* values = snapshot.layer(layer.toStdString());
  if (!values) return "the scene shown has no layer '" + layer + "'";
  if (values->size() != snapshot.grid.cells()) return "layer '" + layer + "' does not cover the grid";
  Raster r(snapshot.grid, 0.0);
  for (std::size_t k = 0; k < values->size(); ++k) {
    const float v = (*values)[k];
    r.valid[k] = std::isfinite(v) ? 1 : 0;
    r.values[k] = r.valid[k] ? v : r.nodata;
  }
  try {
    io::writeRaster(path.toStdString(), r, io::RasterFormat::GeoTiff);
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

}  // namespace talus::gui
