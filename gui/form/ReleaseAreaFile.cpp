#include "form/ReleaseAreaFile.hpp"

#include <cmath>

#include "core/Error.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"

namespace talus::gui {

ReleaseAreaWritten writeReleaseArea(const Grid& grid, const std::vector<float>& elevation,
                                    const std::vector<MapPoint>& polygon, double thickness,
                                    const std::vector<double>& base, const std::string& path) {
  if (!(thickness > 0) || !std::isfinite(thickness))
    throw InputError("release area " + path + ": the thickness must be a positive number of metres");
  Raster out(grid, 0.0);
  if (base.size() == grid.cells())
    for (std::size_t k = 0; k < grid.cells(); ++k) out.values[k] = std::isfinite(base[k]) ? base[k] : 0.0;
  const std::vector<uint8_t> inside = cellsInsidePolygon(grid, polygon);
  ReleaseAreaWritten w;
  w.polygonArea = polygonArea(polygon);
  for (std::size_t k = 0; k < grid.cells(); ++k) {
    if (k < elevation.size() && !std::isfinite(elevation[k])) {
      out.valid[k] = 0;  // no ground: no material
      continue;
    }
    if (inside[k]) {
      out.values[k] = thickness;
      ++w.cells;
    }
    w.volume += out.values[k] * grid.dx * grid.dx;
  }
  if (w.cells == 0)
    throw InputError("release area " + path + ": the polygon encloses no cell centre of the DEM (draw it larger)");
  w.area = double(w.cells) * grid.dx * grid.dx;
  io::writeRaster(path, out, io::formatForPath(path));
  return w;
}

}  // namespace talus::gui
