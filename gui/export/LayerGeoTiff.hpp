// Writes one grid layer of a snapshot as a GeoTIFF with the snapshot's georeference, through the
// engine's io library (the GUI itself does not use GDAL).
#pragma once
#include <QString>

#include "sim/ViewFields.hpp"

namespace talus::gui {

/// Writes layer `layer` of `snapshot` to `path` (Float32; cells without value become nodata).
/// Returns "" or the problem.
QString writeLayerGeoTiff(const sim::ViewSnapshot& snapshot, const QString& layer, const QString& path);

}  // namespace talus::gui
