#include "render/ColorRamp.hpp"

#include <algorithm>
#include <cmath>

namespace talus::gui {

namespace {

// Control points: each ramp runs from a light or dark end to a saturated one and keeps away from the
// terrain's greys and browns, so flow stays visible over any hillshade. The ramps a layer gets by
// default (defaultFor) change lightness monotonically from end to end, so they read the same to
// people with any colour-vision deficiency (which confuse hues, not lightness): water and heat as
// drawn here, time the plasma and other units the viridis colour map (van der Walt & Smith 2015,
// matplotlib; five of their published stops), fractions ColorBrewer's BuPu (Harrower & Brewer
// 2003). "spectral" (a rainbow, whose yellow is lighter than both its ends) stays for who asks.
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
      {"solids", {{0.0, {237, 248, 251}}, {0.25, {179, 205, 227}}, {0.5, {140, 150, 198}}, {0.75, {136, 86, 167}},
                  {1.0, {129, 15, 124}}}},
      {"time", {{0.0, {13, 8, 135}}, {0.25, {126, 3, 168}}, {0.5, {204, 71, 120}}, {0.75, {248, 149, 64}},
                {1.0, {240, 249, 33}}}},
      {"viridis", {{0.0, {68, 1, 84}}, {0.25, {59, 82, 139}}, {0.5, {33, 145, 140}}, {0.75, {94, 201, 98}},
                   {1.0, {253, 231, 37}}}},
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
  return "viridis";
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
