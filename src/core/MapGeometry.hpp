// Geometry drawn on a map, taken onto the grid: a polygon (a release area) becomes the cells whose
// centres it encloses, a polyline (a profile) becomes samples at even distances along it, each with
// the cell it falls in. Coordinates are the grid's world coordinates (its georeference).
#pragma once
#include <cstdint>
#include <vector>

#include "core/Grid.hpp"

namespace talus {

struct MapPoint {
  double x = 0, y = 0;  ///< world coordinates [m]
};

/// Area enclosed by a simple polygon (shoelace formula, either orientation) [m^2]; 0 below 3 vertices.
double polygonArea(const std::vector<MapPoint>& polygon);

/// 1 for each cell whose centre lies inside the polygon (even-odd rule, so a self-intersecting
/// outline leaves its doubly covered parts out), else 0; grid.index order. The polygon closes
/// itself (its last vertex joins its first). A centre exactly on an edge counts on one side only,
/// so two polygons that share an edge never both claim a cell.
std::vector<uint8_t> cellsInsidePolygon(const Grid& grid, const std::vector<MapPoint>& polygon);

/// The cell (i, j) containing a world point; false when it lies off the grid.
bool cellOfPoint(const Grid& grid, MapPoint p, int& i, int& j);

struct ProfileSample {
  double distance = 0;  ///< along the polyline from its first vertex [m]
  MapPoint point;
  int i = -1, j = -1;   ///< the cell it falls in (-1, -1 off the grid)
};

/// Samples along a polyline every `spacing` metres from its first vertex, plus its last vertex
/// (so both ends are always sampled). Empty for fewer than 2 vertices or a spacing <= 0.
std::vector<ProfileSample> sampleProfile(const Grid& grid, const std::vector<MapPoint>& line, double spacing);

}  // namespace talus
