#include "render/ColorRamp.hpp"

#include <algorithm>
#include <cmath>

namespace talus::gui {

namespace {

// Control points chosen by hand: each ramp runs from a light or dark end to a saturated one and
// keeps away from the terrain's greys and browns, so flow stays visible over any hillshade.
struct RampDef {
  const char* name;
  std::vector<std::pair<double, std::array<int, 3>>> stops;
};

const std::vector<RampDef>& ramps() {
  static const std::vector<RampDef> defs = {
      {"water", {{0.0, {198, 233, 255}}, {0.35, {66, 160, 235}}, {0.7, {20, 70, 190}}, {1.0, {40, 10, 110}}}},
      {"heat", {{0.0, {255, 245, 150}}, {0.35, {255, 170, 40}}, {0.7, {220, 50, 30}}, {1.0, {110, 0, 60}}}},
      {"spectral", {{0.0, {50, 60, 200}}, {0.25, {40, 180, 220}}, {0.5, {120, 220, 90}},
                    {0.75, {250, 200, 40}}, {1.0, {215, 30, 40}}}},
      {"solids", {{0.0, {230, 250, 200}}, {0.5, {140, 200, 60}}, {1.0, {150, 40, 20}}}},
      {"time", {{0.0, {255, 60, 200}}, {0.5, {120, 80, 230}}, {1.0, {20, 200, 220}}}},
  };
  return defs;
}

}  // namespace

ColorRamp ColorRamp::byName(const QString& name) {
  const auto& defs = ramps();
  const RampDef* def = &defs.front();
  for (const auto& d : defs)
    if (name == d.name) def = &d;
  std::vector<Stop> stops;
  for (const auto& s : def->stops) stops.push_back({s.first, s.second});
  return ColorRamp(def->name, std::move(stops));
}

QStringList ColorRamp::names() {
  QStringList out;
  for (const auto& d : ramps()) out << d.name;
  return out;
}

QString ColorRamp::defaultFor(const QString& unit) {
  if (unit == "m") return "water";
  if (unit == "m/s") return "heat";
  if (unit == "s") return "time";
  if (unit == "-") return "solids";
  return "spectral";
}

QColor ColorRamp::at(double t) const {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  for (std::size_t k = 1; k < stops_.size(); ++k) {
    if (t > stops_[k].t && k + 1 < stops_.size()) continue;
    const Stop& a = stops_[k - 1];
    const Stop& b = stops_[k];
    const double w = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
    auto mix = [&](int c) { return static_cast<int>(std::lround(a.rgb[c] + w * (b.rgb[c] - a.rgb[c]))); };
    return QColor(mix(0), mix(1), mix(2));
  }
  const auto& c = stops_.front().rgb;
  return QColor(c[0], c[1], c[2]);
}

std::vector<uint8_t> ColorRamp::table() const {
  std::vector<uint8_t> rgba(256 * 4);
  for (int k = 0; k < 256; ++k) {
    const QColor c = at(k / 255.0);
    rgba[4 * k + 0] = static_cast<uint8_t>(c.red());
    rgba[4 * k + 1] = static_cast<uint8_t>(c.green());
    rgba[4 * k + 2] = static_cast<uint8_t>(c.blue());
    rgba[4 * k + 3] = 255;
  }
  return rgba;
}

}  // namespace talus::gui
