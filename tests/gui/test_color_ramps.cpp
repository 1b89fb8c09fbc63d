// The colour ramps a layer gets by default read the same to people with a colour-vision deficiency:
// their lightness changes monotonically from end to end (deficient vision confuses hues, such as the
// red and green of the old "solids" ramp, not lightness), over a wide range. Lightness is CIE L*,
// computed here from the sRGB values (IEC 61966-2-1 linearisation, Rec. 709 luminance, CIE 1976 L*),
// independently of the application's code.
#include <gtest/gtest.h>

#include <cmath>

#include "render/ColorRamp.hpp"

using talus::gui::ColorRamp;

namespace {

double linear(int channel) {
  const double c = channel / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// CIE L* of an sRGB colour (D65 white).
double lightness(const QColor& c) {
  const double y = 0.2126 * linear(c.red()) + 0.7152 * linear(c.green()) + 0.0722 * linear(c.blue());
  return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : y * 24389.0 / 27.0;
}

}  // namespace

// For every unit a layer has (thickness, speed, time, fractions, pressure, anything else): L* strictly
// monotonic over 201 samples of the default ramp, and at least 45 L* units between its ends (of 100;
// the viridis map spans 80, a grey ramp from black to white 100). The rainbow ("spectral") fails
// both: its yellow is lighter than either end (checked below, so the test can tell).
TEST(ColorRamps, DefaultRampsChangeLightnessMonotonically) {
  auto monotonic = [](const ColorRamp& ramp, double* span) {
    const double l0 = lightness(ramp.at(0.0)), l1 = lightness(ramp.at(1.0));
    const double sign = l1 > l0 ? 1.0 : -1.0;
    double previous = l0;
    bool ok = true;
    for (int k = 1; k <= 200; ++k) {
      const double l = lightness(ramp.at(k / 200.0));
      ok = ok && sign * (l - previous) > 0;
      previous = l;
    }
    *span = std::fabs(l1 - l0);
    return ok;
  };
  for (const char* unit : {"m", "m/s", "s", "-", "Pa", "J", ""}) {
    const QString name = ColorRamp::defaultFor(unit);
    double span = 0;
    EXPECT_TRUE(monotonic(ColorRamp::byName(name), &span)) << unit << ": " << name.toStdString();
    EXPECT_GE(span, 45.0) << unit << ": " << name.toStdString();
  }
  double span = 0;
  EXPECT_FALSE(monotonic(ColorRamp::byName("spectral"), &span)) << "the check cannot tell a rainbow";
}
