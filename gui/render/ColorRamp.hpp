// Colour ramps of the viewer's layers and particles: a few named ramps given by control points,
// sampled into a 256-entry table that the shaders read as a texture and the legend paints.
#pragma once
#include <QColor>
#include <QString>
#include <QStringList>
#include <array>
#include <cstdint>
#include <vector>

namespace talus::gui {

class ColorRamp {
 public:
  /// The ramp with this name (see names()); an unknown name gives the first ramp.
  static ColorRamp byName(const QString& name);
  /// The names of the ramps, in menu order.
  static QStringList names();
  /// The ramp that suits a layer or attribute by its unit ("m", "m/s", "s", "-", ...).
  static QString defaultFor(const QString& unit);

  const QString& name() const { return name_; }
  /// The colour at t in [0, 1] (clamped).
  QColor at(double t) const;
  /// 256 RGBA8 entries from t = 0 to t = 1, for a texture.
  std::vector<uint8_t> table() const;

 private:
  struct Stop {
    double t;
    std::array<int, 3> rgb;
  };
  ColorRamp(QString name, std::vector<Stop> stops) : name_(std::move(name)), stops_(std::move(stops)) {}
  QString name_;
  std::vector<Stop> stops_;
};

}  // namespace talus::gui
