// The difference of two opened output folders on the same grid: for each map both hold (maxima,
// final, arrival, ...) and each series variable both wrote at the same report time, a layer
// "NAME-diff" = this run's value minus the other's. A cell has no difference value where either run
// has none, or where both are 0 (dry in both), so that only where the runs differ is coloured.
#pragma once
#include <QString>
#include <memory>
#include <vector>

#include "sim/ViewFields.hpp"

namespace talus::gui {

class ResultsReplay;

/// The name of the difference layer of `name`.
std::string differenceLayerName(const std::string& name);
/// a - b per cell, NaN where either is NaN or both are 0.
std::vector<float> layerDifference(const std::vector<float>& a, const std::vector<float>& b);

/// Appends to `into` the difference layers of the layers both `into` and `other` hold.
void addDifferenceLayers(sim::ViewSnapshot& into, const sim::ViewSnapshot& other);

/// The catalogue entries of the difference layers of `layers` that `other` also lists, against
/// the run in `otherName` (a folder's name).
std::vector<sim::GridLayerInfo> differenceCatalogue(const std::vector<sim::GridLayerInfo>& layers,
                                                    const std::vector<sim::GridLayerInfo>& other,
                                                    const QString& otherName);

}  // namespace talus::gui
