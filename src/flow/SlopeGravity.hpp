// Slope-corrected gravity per cell (spec §1): g_n = g cos^2(theta) for bed-slope gravity and basal
// normal stress, g_p for the depth-pressure terms (g cos^2 by default, g cos^4 as an option),
// cos^2(theta) = 1 / (1 + |grad b|^2). (The bed's curvature enters the solids along their path,
// from the change of this slope between cells: kernels/flow/solid_bed.cl, point 1.)
// grad b is the bed slope the solids' reconstruction uses: per axis the minmod of the two one-sided
// differences (next to nodata cells and the raster edge the one-sided difference, limited by the
// next difference inward), so a plane has its exact slope, and a cell beside a DEM step is flat (the
// step itself is a face of the reconstructed bed, a wall to the material below it).
#pragma once
#include <cstdint>
#include <vector>

#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"

namespace talus::flow {

struct SlopeGravity {
  std::vector<double> gn;  ///< [m/s^2]
  std::vector<double> gp;  ///< [m/s^2]
  /// sqrt(g |grad b| dx) [m/s]: the speed water at rest gains from the bed slope over one cell,
  /// added to the CFL speed of wet cells so thin films on slopes cannot outrun the time step.
  std::vector<double> slopeSpeed;
  /// Bed slope b_x, b_y per cell (limited, see above) [-].
  std::vector<double> slopeX, slopeY;
};

SlopeGravity computeSlopeGravity(const Grid& grid, const std::vector<double>& bed, const std::vector<uint8_t>& mask,
                                 const FlowSettings& settings);

/// The limited bed slope along one axis at cell (i, j): minmod of the one-sided differences of
/// `field` where both neighbours are inside; next to an outside cell the one-sided difference
/// limited by the next one inward (unlimited where the domain is two cells wide there); 0 without
/// inside neighbours along the axis (per unit length: divided by dx).
double limitedBedSlope(const Grid& grid, const std::vector<double>& field, const std::vector<uint8_t>& mask, int i,
                       int j, int di, int dj);

}  // namespace talus::flow
