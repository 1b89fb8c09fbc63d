#include "support/ValleyBead.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/Constants.hpp"

namespace talus::test {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

Valley::Valley(double alpha1Deg, double alpha2Deg, double width, double z0, double margin)
    : s1(std::tan(alpha1Deg * kDeg)), s2(std::tan(alpha2Deg * kDeg)), w(width) {
  xa = z0 / s1 + margin;
  xf = xa + w * s1 / (s1 + s2);
}

double Valley::slope(double x) const {
  if (x < xa) return -s1;
  if (x > xa + w) return s2;
  return -s1 + (s1 + s2) * (x - xa) / w;
}

double Valley::curvature(double x) const { return x > xa && x < xa + w ? (s1 + s2) / w : 0.0; }

double Valley::bed(double x) const {
  // b(x) = integral of the slope from the floor; prim is a continuous antiderivative.
  auto prim = [&](double u) {
    if (u <= xa) return -s1 * (u - xa);
    if (u <= xa + w) return -s1 * (u - xa) + 0.5 * (s1 + s2) * (u - xa) * (u - xa) / w;
    return -s1 * w + 0.5 * (s1 + s2) * w + s2 * (u - xa - w);
  };
  return prim(x) - prim(xf);
}

double beadTurningPoint(const Valley& v, double x0, double mu, double dt) {
  double x = x0, u = 0;
  // The friction opposes the direction of sliding at the start of each step (downhill from rest):
  // with its sign taken per RK stage instead, a bead about to stop on a gentle floor (|b'| < mu)
  // would see the stages' friction cancel and never stop.
  double dir = 0;
  auto acc = [&](double xx, double uu) {
    const double bp = v.slope(xx);
    const double lambda = std::max(0.0, (kGravity + v.curvature(xx) * uu * uu) / (1 + bp * bp));
    return -lambda * (bp + mu * dir);
  };
  for (int n = 0; n < 10000000; ++n) {
    dir = u > 0 ? 1.0 : u < 0 ? -1.0 : (v.slope(x) < 0 ? 1.0 : -1.0);
    const double k1x = u, k1u = acc(x, u);
    const double k2x = u + 0.5 * dt * k1u, k2u = acc(x + 0.5 * dt * k1x, u + 0.5 * dt * k1u);
    const double k3x = u + 0.5 * dt * k2u, k3u = acc(x + 0.5 * dt * k2x, u + 0.5 * dt * k2u);
    const double k4x = u + dt * k3u, k4u = acc(x + dt * k3x, u + dt * k3u);
    const double xn = x + dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double un = u + dt / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
    if (un <= 0) return n == 0 ? x0 : xn;  // turned, or held by friction from the start
    x = xn;
    u = un;
  }
  throw std::runtime_error("beadTurningPoint: the bead did not turn within 10^7 steps");
}

}  // namespace talus::test
