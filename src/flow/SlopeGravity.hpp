// Slope-corrected gravity per cell (spec §1): g_n = g cos^2(theta) for bed-slope gravity and basal
// normal stress, g_p for the depth-pressure terms (g cos^2 by default, g cos^4 as an option), with
// cos^2(theta) = 1 / (1 + |grad b|^2) and grad b from centred differences of the DEM (one-sided
// next to nodata cells and the raster edge).
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
};

SlopeGravity computeSlopeGravity(const Grid& grid, const std::vector<double>& bed, const std::vector<uint8_t>& mask,
                                 const FlowSettings& settings);

}  // namespace talus::flow
