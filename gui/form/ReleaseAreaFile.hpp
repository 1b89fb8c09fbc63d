// A release area drawn on the map, written as the raster of an initial-thickness key: the cells
// whose centres the polygon encloses (core/MapGeometry) get the thickness, the others keep the
// values of a base map (the key's current map) or 0; cells where the DEM has no value stay
// without one. Written through the engine's io library on the DEM's grid and georeference.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "core/Grid.hpp"
#include "core/MapGeometry.hpp"

namespace talus::gui {

struct ReleaseAreaWritten {
  std::size_t cells = 0;  ///< cells set to the thickness
  double area = 0;        ///< their area [m^2]
  double polygonArea = 0; ///< the drawn polygon's area [m^2]
  double volume = 0;      ///< total volume of the written map [m^3]
};

/// Writes the release area to `path` (GeoTIFF, or PCRaster for .map). `elevation` is the DEM on
/// `grid` (NaN where it has no value); `base` holds the values the cells outside the polygon keep
/// (grid.index order; empty for 0). Throws talus::InputError naming the file when the polygon
/// encloses no cell centre of the DEM, the thickness is not positive and finite, or the file
/// cannot be written.
ReleaseAreaWritten writeReleaseArea(const Grid& grid, const std::vector<float>& elevation,
                                    const std::vector<MapPoint>& polygon, double thickness,
                                    const std::vector<double>& base, const std::string& path);

}  // namespace talus::gui
