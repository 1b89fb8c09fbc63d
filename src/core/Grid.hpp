// The raster grid every map of a run shares: size, square cell size, georeference.
#pragma once
#include <array>
#include <cstddef>
#include <string>

namespace talus {

/// A north-up raster grid. Column i runs east (x), row j runs south in the file; the solver treats
/// j as its y index, so the physics sees the map mirrored in y, which changes nothing physical.
struct Grid {
  int nx = 0;          ///< columns
  int ny = 0;          ///< rows
  double dx = 1.0;     ///< cell size [m] (square cells)
  /// GDAL geotransform: x0, pixel width, row rotation, y0, column rotation, pixel height (negative).
  std::array<double, 6> geoTransform{0.0, 1.0, 0.0, 0.0, 0.0, -1.0};
  std::string projectionWkt;  ///< coordinate reference system as WKT (may be empty)

  std::size_t cells() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
  }
  /// World x of the centre of column i.
  double cellX(int i) const { return geoTransform[0] + (i + 0.5) * geoTransform[1]; }
  /// World y of the centre of row j.
  double cellY(int j) const { return geoTransform[3] + (j + 0.5) * geoTransform[5]; }

  /// A grid of nx x ny square cells of size dx with its top-left corner at (x0, y0).
  static Grid make(int nx, int ny, double dx, double x0 = 0.0, double y0 = 0.0) {
    Grid g;
    g.nx = nx;
    g.ny = ny;
    g.dx = dx;
    g.geoTransform = {x0, dx, 0.0, y0 + ny * dx, 0.0, -dx};
    return g;
  }
};

/// True when two grids have the same size, cell size and origin (within a relative 1e-9 of a cell).
bool sameGrid(const Grid& a, const Grid& b);

}  // namespace talus
