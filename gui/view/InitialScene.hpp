// What a run-file shows before it runs: the DEM (for the hillshade) and its initial maps as layers
// (the initial water height and the initial solid height, each when its Include key is on), read
// through the engine's io library. The layers reach the viewer and layer panel as one snapshot.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/Grid.hpp"
#include "io/RunConfig.hpp"
#include "sim/ViewFields.hpp"

namespace talus::gui {

struct InitialScene {
  Grid grid;
  std::vector<float> elevation;  ///< DEM times its multiplier, NaN where the DEM has no value
  std::vector<sim::GridLayerInfo> layers;
  std::shared_ptr<sim::ViewSnapshot> snapshot;  ///< time 0, one layer per entry of `layers`
  std::vector<std::string> warnings;            ///< initial maps that could not be shown, and why

  /// Reads the scene of a validated configuration; throws when the DEM cannot be read (a map
  /// that cannot be read or has another grid is left out with a warning).
  static InitialScene read(const io::RunConfig& config);
};

}  // namespace talus::gui
