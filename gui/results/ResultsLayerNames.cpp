#include "results/ResultsLayerNames.hpp"

#include <utility>

namespace talus::gui {

namespace {

/// What a name's stem means and its unit; ("", "") when unknown.
std::pair<QString, QString> quantity(const QString& stem) {
  if (stem == "hf") return {"fluid thickness", "m"};
  if (stem == "hs") return {"solid thickness", "m"};
  if (stem == "ht" || stem == "h") return {"total thickness", "m"};
  if (stem == "hc") return {"particles' confined thickness", "m"};
  if (stem == "vf") return {"fluid speed", "m/s"};
  if (stem == "vs") return {"solid speed", "m/s"};
  if (stem == "vt" || stem == "v") return {"mixture speed", "m/s"};
  if (stem == "sf" || stem == "sfrac") return {"solid fraction", "-"};
  if (stem == "cfrac") return {"cohesion fraction", "-"};
  if (stem == "erodible") return {"erodible depth", "m"};
  return {};
}

}  // namespace

sim::GridLayerInfo resultsLayerInfo(const QString& name, bool series) {
  QString stem = name, when = series ? "series" : "";
  for (const char* suffix : {"max", "final"})
    if (!series && name.endsWith(suffix) && name.size() > int(qstrlen(suffix))) {
      stem = name.left(name.size() - int(qstrlen(suffix)));
      when = suffix == QString("max") ? "maximum" : "final";
    }
  auto [what, unit] = quantity(stem);
  bool zeroIsEmpty = true;
  if (name == "tarrival") {
    what = "arrival time";
    unit = "s";
    zeroIsEmpty = false;  // arrival at t = 0 is a value; never arrived is nodata
  } else if (name == "basechange") {
    what = "bed change";
    unit = "m";
    zeroIsEmpty = false;
  } else if (name == "releasedfluid") {
    what = "water released by particles";
    unit = "m";
  }
  if (stem == "cfrac") zeroIsEmpty = false;
  sim::GridLayerInfo info;
  info.name = name.toStdString();
  const QString label = what.isEmpty() ? name : name + ": " + what;
  info.label = (when.isEmpty() ? label : label + " (" + when + ")").toStdString();
  info.unit = unit.isEmpty() ? "-" : unit.toStdString();
  info.zeroIsEmpty = zeroIsEmpty;
  return info;
}

QString resultsParticleUnit(const QString& field) {
  if (field == "vx" || field == "vy" || field == "speed") return "m/s";
  if (field == "I1" || field == "sqrtJ2") return "Pa";
  if (field == "mass") return "kg";
  if (field == "thickness") return "m";
  return "-";
}

}  // namespace talus::gui
