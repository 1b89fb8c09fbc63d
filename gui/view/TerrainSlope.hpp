// The slope the status bar reports under the cursor.
#pragma once
#include <vector>

#include "core/Grid.hpp"

namespace talus::gui {

/// Steepest slope of cell (i, j) in degrees, atan(sqrt(dz/dx^2 + dz/dy^2)), from finite differences
/// of `z` (grid.index order): centred, (z[i+1] - z[i-1]) / (2 dx), where both neighbours have a
/// value; one-sided, (z[i+1] - z[i]) / dx or (z[i] - z[i-1]) / dx, where only one has; 0 where none
/// has. dx and dy are the absolute pixel width and height of the geotransform. NaN when the cell
/// has no value.
double slopeDegrees(const Grid& grid, const std::vector<float>& z, int i, int j);

}  // namespace talus::gui
