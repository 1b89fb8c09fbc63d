// A raster map on a Grid: values in double precision plus a validity mask (nodata -> invalid).
#pragma once
#include <cstdint>
#include <vector>

#include "core/Grid.hpp"

namespace talus {

struct Raster {
  Grid grid;
  std::vector<double> values;   ///< row-major, grid.index(i, j)
  std::vector<uint8_t> valid;   ///< 1 where the value is data, 0 where the file had nodata
  double nodata = -9999.0;      ///< value written for invalid cells

  Raster() = default;
  Raster(const Grid& g, double fill) : grid(g), values(g.cells(), fill), valid(g.cells(), 1) {}

  double& at(int i, int j) { return values[grid.index(i, j)]; }
  double at(int i, int j) const { return values[grid.index(i, j)]; }
  bool isValid(int i, int j) const { return valid[grid.index(i, j)] != 0; }
};

}  // namespace talus
