// Labels and units of the files of an output folder, from their names (docs/outputs.md): hf/hs/ht
// thickness, vf/vs/vt speed, sf solid fraction, tarrival time, ...; "max" and "final" suffixes.
#pragma once
#include <QString>

#include "sim/ViewFields.hpp"

namespace talus::gui {

/// The layer of a map called `name` (file name without extension); `series`: a series variable.
sim::GridLayerInfo resultsLayerInfo(const QString& name, bool series);
/// The unit of a particle layer's field (vx, speed, I1, mass, ...).
QString resultsParticleUnit(const QString& field);

}  // namespace talus::gui
