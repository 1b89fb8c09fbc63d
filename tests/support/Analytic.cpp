// Exact shallow-water reference solutions and error norms; see Analytic.hpp for the API.
//
// Sources of the formulas:
//  - Ritter, A. (1892), "Die Fortpflanzung der Wasserwellen", Z. Ver. Deutsch. Ing. 36; in the
//    form of Delestre et al. (2013), SWASHES, J. Numer. Meth. Fluids 72, section 4.1.1.
//  - Stoker, J. J. (1957), "Water Waves", Interscience, ch. 10; SWASHES section 4.1.2. The star
//    state is obtained here from the two conditions derived below, not from a tabulated formula.
//  - Thacker, W. C. (1981), "Some exact solutions to the nonlinear shallow-water wave equations",
//    J. Fluid Mech. 107; SWASHES section 4.2.2 ("planar surface in a paraboloid").
//  - Gauss-Legendre 5-point nodes and weights: Abramowitz & Stegun (1964), table 25.4.
#include "support/Analytic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace talus::analytic {

namespace {

constexpr double kPi = 3.14159265358979323846;

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("talus::analytic: ") + what);
}

/// The centred simple wave of a dam break, in xi = (x - x0) / t. Along the C+ characteristics
/// from the still left state the Riemann invariant u + 2c = 2 cL holds; the fan itself is the
/// family of C- characteristics u - c = xi. Solving both gives c = (2 cL - xi) / 3.
State1D rarefaction(double xi, double cL, double g) {
  const double c = (2.0 * cL - xi) / 3.0;
  return {c * c / g, 2.0 * (xi + cL) / 3.0};
}

/// Velocity behind a shock running into still water of depth hR, when the depth behind is hm:
/// from the Rankine-Hugoniot conditions s (hm - hR) = hm um and
/// s hm um = hm um^2 + g (hm^2 - hR^2) / 2, eliminating s gives
/// um = (hm - hR) q with q = sqrt(g (hm + hR) / (2 hm hR)), and s = hm um / (hm - hR) = hm q.
double shockQ(double hm, double hR, double g) { return std::sqrt(g * (hm + hR) / (2.0 * hm * hR)); }

}  // namespace

State1D ritter(double x, double t, double x0, double hL, double g) {
  require(hL > 0.0 && g > 0.0, "ritter needs hL > 0 and g > 0");
  if (t <= 0.0) return x < x0 ? State1D{hL, 0.0} : State1D{0.0, 0.0};
  const double c0 = std::sqrt(g * hL);
  const double xi = (x - x0) / t;
  if (xi <= -c0) return {hL, 0.0};
  if (xi >= 2.0 * c0) return {0.0, 0.0};
  return rarefaction(xi, c0, g);
}

StokerStar stokerStar(double hL, double hR, double g) {
  require(g > 0.0 && hL > 0.0 && hR >= 0.0 && hR < hL, "stokerStar needs hL > hR >= 0 and g > 0");
  const double cL = std::sqrt(g * hL);
  if (hR == 0.0) return {0.0, 2.0 * cL, 2.0 * cL};
  const double cR = std::sqrt(g * hR);
  // Matching condition in c = sqrt(g hm): the rarefaction gives um = 2 (cL - c), the shock gives
  // um = (hm - hR) q(hm), so F(c) = 2 (cL - c) - (hm - hR) q(hm) = 0. F(cR) = 2 (cL - cR) > 0 and
  // F(cL) < 0; F is strictly decreasing on [cR, cL], so the root is unique and bracketed.
  auto F = [&](double c, double* dF) {
    const double hm = c * c / g;
    const double q = shockQ(hm, hR, g);
    // d/dhm [(hm - hR) q] = q + (hm - hR) dq/dhm, with dq/dhm = -g / (4 q hm^2).
    const double dShock = q - (hm - hR) * g / (4.0 * q * hm * hm);
    *dF = -2.0 - dShock * (2.0 * c / g);
    return 2.0 * (cL - c) - (hm - hR) * q;
  };
  double lo = cR, hi = cL;
  double c = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    double dF = 0.0;
    const double f = F(c, &dF);
    if (f == 0.0) break;
    if (f > 0.0) lo = c; else hi = c;
    double next = c - f / dF;
    // Safeguard: fall back to bisection whenever Newton leaves the bracket.
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::fabs(next - c);
    c = next;
    if (step <= 2.0 * std::numeric_limits<double>::epsilon() * c || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * c) break;
  }
  const double hm = c * c / g;
  const double um = 2.0 * (cL - c);
  return {hm, um, hm * shockQ(hm, hR, g)};
}

State1D stoker(double x, double t, double x0, double hL, double hR, double g) {
  require(g > 0.0 && hL > 0.0 && hR >= 0.0 && hR <= hL, "stoker needs hL >= hR >= 0, hL > 0, g > 0");
  if (hR == 0.0) return ritter(x, t, x0, hL, g);
  if (t <= 0.0) return x < x0 ? State1D{hL, 0.0} : State1D{hR, 0.0};
  if (hR == hL) return {hL, 0.0};
  const StokerStar star = stokerStar(hL, hR, g);
  const double cL = std::sqrt(g * hL);
  const double cm = std::sqrt(g * star.hm);
  const double xi = (x - x0) / t;
  if (xi <= -cL) return {hL, 0.0};
  if (xi < star.um - cm) return rarefaction(xi, cL, g);
  if (xi < star.shockSpeed) return {star.hm, star.um};
  return {hR, 0.0};
}

// Thacker planar solution. Derivation (checked by the PDE-residual test): seek h = zeta - b with a
// planar surface zeta = alpha(t) X + beta(t) Y + gamma(t) and uniform velocity (u(t), v(t)).
// Momentum in non-conservative form, u_t + u u_x + v u_y + g zeta_x = 0, gives u' = -g alpha and
// v' = -g beta. Continuity, h_t + u h_x + v h_y = 0 (the velocity is divergence-free), is a
// polynomial identity in X, Y: alpha' = 2 h0 u / a^2, beta' = 2 h0 v / a^2,
// gamma' = -(u alpha + v beta). Hence u'' = -(2 g h0 / a^2) u, i.e. omega^2 = 2 g h0 / a^2, and
// alpha = 2 eta h0 cos(wt) / a^2, beta = 2 eta h0 sin(wt) / a^2, gamma = -eta^2 h0 / a^2,
// u = -eta omega sin(wt), v = eta omega cos(wt) satisfy all of them (SWASHES eq. for 4.2.2).
// Completing the square, zeta - b = h0 (1 - ((X - eta cos wt)^2 + (Y - eta sin wt)^2) / a^2).

double ThackerPlanar::omega() const { return std::sqrt(2.0 * g * h0) / a; }

double ThackerPlanar::period() const { return 2.0 * kPi / omega(); }

double ThackerPlanar::bed(double x, double y) const {
  const double X = x - xc, Y = y - yc;
  return -h0 * (1.0 - (X * X + Y * Y) / (a * a));
}

double ThackerPlanar::h(double x, double y, double t) const {
  const double wt = omega() * t;
  const double X = x - xc, Y = y - yc;
  const double zeta = eta * h0 / (a * a) * (2.0 * X * std::cos(wt) + 2.0 * Y * std::sin(wt) - eta);
  return std::max(0.0, zeta - bed(x, y));
}

double ThackerPlanar::surface(double x, double y, double t) const { return bed(x, y) + h(x, y, t); }

double ThackerPlanar::u(double t) const { return -eta * omega() * std::sin(omega() * t); }

double ThackerPlanar::v(double t) const { return eta * omega() * std::cos(omega() * t); }

State2D ThackerPlanar::state(double x, double y, double t) const {
  const double depth = h(x, y, t);
  if (depth <= 0.0) return {0.0, 0.0, 0.0};
  return {depth, u(t), v(t)};
}

double ThackerPlanar::volume() const { return 0.5 * kPi * a * a * h0; }

double l1(const std::vector<double>& f, const std::vector<double>& g, double cellArea) {
  require(f.size() == g.size(), "l1 needs vectors of equal size");
  double sum = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) sum += std::fabs(f[i] - g[i]);
  return sum * cellArea;
}

double relativeL1(const std::vector<double>& f, const std::vector<double>& g, double cellArea) {
  const double num = l1(f, g, cellArea);
  double den = 0.0;
  for (double gi : g) den += std::fabs(gi);
  den *= cellArea;
  if (den == 0.0) return num == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return num / den;
}

double observedOrder(double eCoarse, double eFine, double ratio) {
  require(eCoarse > 0.0 && eFine > 0.0 && ratio > 1.0,
          "observedOrder needs positive errors and ratio > 1");
  return std::log(eCoarse / eFine) / std::log(ratio);
}

double cellAverage1D(const std::function<double(double)>& f, double xc, double dx) {
  // Gauss-Legendre on [-1, 1]: nodes 0, +-sqrt(5 -+ 2 sqrt(10/7)) / 3.
  static const double s = std::sqrt(10.0 / 7.0);
  static const double node[5] = {0.0, std::sqrt(5.0 - 2.0 * s) / 3.0, -std::sqrt(5.0 - 2.0 * s) / 3.0,
                                 std::sqrt(5.0 + 2.0 * s) / 3.0, -std::sqrt(5.0 + 2.0 * s) / 3.0};
  static const double r70 = std::sqrt(70.0);
  static const double weight[5] = {128.0 / 225.0, (322.0 + 13.0 * r70) / 900.0,
                                   (322.0 + 13.0 * r70) / 900.0, (322.0 - 13.0 * r70) / 900.0,
                                   (322.0 - 13.0 * r70) / 900.0};
  constexpr int kSub = 4;
  const double sub = dx / kSub;
  double sum = 0.0;
  for (int k = 0; k < kSub; ++k) {
    const double mid = xc - 0.5 * dx + (k + 0.5) * sub;
    for (int i = 0; i < 5; ++i) sum += weight[i] * f(mid + 0.5 * sub * node[i]);
  }
  // Each sub-interval integral is (sub / 2) sum w_i f_i; the average divides by dx = kSub * sub.
  return sum * 0.5 / kSub;
}

double supercriticalThicknessBehindRise(double h, double u, double dz, double pg, double g) {
  const double q2 = h * h * u * u, hc = std::cbrt(q2 / pg), e = 0.5 * u * u + pg * h - g * dz;
  if (!(u * u > pg * h) || !(e > 1.5 * pg * hc))
    throw std::invalid_argument("supercriticalThicknessBehindRise: the flow is not supercritical or chokes");
  double a = h, b = hc;  // f(a) >= 0 > f(b) for f(x) = q^2 / (2 x^2) + pg x - e
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (a + b);
    (0.5 * q2 / (mid * mid) + pg * mid - e > 0 ? a : b) = mid;
  }
  return 0.5 * (a + b);
}

}  // namespace talus::analytic
