// Exact references for the granular (Savage-Hutter) and two-phase grid model; see
// GranularAnalytic.hpp for the API.
//
// Sources of the formulas:
//  - Mangeney, A., Heinrich, P. & Roche, R. (2000), "Analytical solution for testing debris
//    avalanche numerical models", Pure Appl. Geophys. 157, 1081-1096, eqs. 20-22. Re-derived here
//    in horizontal coordinates: with xi = x - x0 - m t^2 / 2 and v = u - m t the system
//    h_t + (hu)_x = 0, u_t + u u_x + kp h_x = m becomes h_t + (h v)_xi = 0,
//    v_t + v v_xi + kp h_xi = 0 (the source is absorbed by the accelerating frame), whose dam-break
//    solution is Ritter's (Analytic.cpp) with g replaced by kp = c0^2 / H0.
//  - Slope corrections g_n = g cos^2(theta), g_p = g cos^2 or cos^4(theta): Talus spec section 1.
//  - Savage, S. B. & Hutter, K. (1989), "The motion of a finite mass of granular material down a
//    rough incline", J. Fluid Mech. 199, 177-215 (earth-pressure coefficients, eq. 2.22 there).
//  - Drag relaxation: exact integration of the two linear (or Riccati) ODEs, derived in the
//    comments below; the drag and virtual-mass forms follow Pudasaini (2012), JGR 117, F03010.
#include "support/GranularAnalytic.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace talus::analytic {

namespace {

constexpr double kHalfPi = 1.57079632679489661923;

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("talus::analytic: ") + what);
}

bool isAngle(double a) { return a >= 0.0 && a < kHalfPi; }

/// Antiderivative of h in xi = x - x0 - m t^2 / 2 at time t > 0, zero at the rarefaction head
/// xi = -c0 t. In the fan, with y = 2 c0 - s / t (ds = -t dy):
///   int_{-c0 t}^{xi} H0 (2 c0 - s/t)^2 / (9 c0^2) ds = H0 t (27 c0^3 - (2 c0 - xi/t)^3) / (27 c0^2),
/// which reaches H0 c0 t at the front: the volume moved from the reservoir into the fan.
double antiderivative(const MangeneyDamBreak& d, double xi, double t) {
  if (xi <= -d.c0 * t) return d.H0 * (xi + d.c0 * t);
  if (xi >= 2.0 * d.c0 * t) return d.H0 * d.c0 * t;
  const double y = 2.0 * d.c0 - xi / t;
  return d.H0 * t * (27.0 * d.c0 * d.c0 * d.c0 - y * y * y) / (27.0 * d.c0 * d.c0);
}

void checkDamBreak(const MangeneyDamBreak& d) {
  require(d.H0 > 0.0 && d.c0 > 0.0, "MangeneyDamBreak needs H0 > 0 and c0 > 0");
}

void checkPhases(double ms, double mf, double k, double mvm) {
  require(ms > 0.0 && mf > 0.0 && k >= 0.0 && mvm >= 0.0,
          "drag relaxation needs ms, mf > 0 and k, mvm >= 0");
}

/// Splits the relative velocity w back into the two phase velocities at constant total momentum
/// P = ms us + mf uf: with U = P / (ms + mf), us = U - mf w / (ms + mf), uf = U + ms w / (ms + mf)
/// (then uf - us = w and ms us + mf uf = P).
PhaseVelocities split(double ms, double mf, double us0, double uf0, double w) {
  const double M = ms + mf;
  const double U = (ms * us0 + mf * uf0) / M;
  return {U - mf / M * w, U + ms / M * w};
}

}  // namespace

double MangeneyDamBreak::h(double x, double t) const {
  checkDamBreak(*this);
  if (t <= 0.0) return x < x0 ? H0 : 0.0;
  const double xi = x - x0 - 0.5 * m * t * t;
  if (xi <= -c0 * t) return H0;
  if (xi >= 2.0 * c0 * t) return 0.0;
  const double y = 2.0 * c0 - xi / t;
  return H0 * y * y / (9.0 * c0 * c0);
}

double MangeneyDamBreak::u(double x, double t) const {
  checkDamBreak(*this);
  if (t <= 0.0) return 0.0;
  const double xi = x - x0 - 0.5 * m * t * t;
  if (xi <= -c0 * t) return m * t;
  if (xi >= 2.0 * c0 * t) return 0.0;
  return 2.0 * (c0 + xi / t) / 3.0 + m * t;
}

State1D MangeneyDamBreak::state(double x, double t) const { return {h(x, t), u(x, t)}; }

double MangeneyDamBreak::front(double t) const { return x0 + 2.0 * c0 * t + 0.5 * m * t * t; }

double MangeneyDamBreak::rear(double t) const { return x0 - c0 * t + 0.5 * m * t * t; }

double MangeneyDamBreak::integralH(double a, double b, double t) const {
  checkDamBreak(*this);
  if (t <= 0.0) return H0 * (std::fmin(b - x0, 0.0) - std::fmin(a - x0, 0.0));
  const double shift = x0 + 0.5 * m * t * t;
  return antiderivative(*this, b - shift, t) - antiderivative(*this, a - shift, t);
}

double MangeneyDamBreak::validFrom(double xUpper, double t) const {
  return xUpper + c0 * t + 0.5 * m * t * t;
}

double MangeneyDamBreak::validUntil(double xUpper) const {
  checkDamBreak(*this);
  require(xUpper < x0, "validUntil needs xUpper < x0");
  return (x0 - xUpper) / (2.0 * c0);
}

MangeneyDamBreak mangeneyFromSlope(double H0, double thetaRad, double deltaRad, double K, bool cos4,
                                   double x0) {
  require(H0 > 0.0 && K > 0.0, "mangeneyFromSlope needs H0 > 0 and K > 0");
  require(isAngle(thetaRad) && isAngle(deltaRad), "mangeneyFromSlope needs angles in [0, pi/2)");
  require(std::tan(thetaRad) >= std::tan(deltaRad),
          "mangeneyFromSlope needs tan(theta) >= tan(delta)");
  const double cos2 = std::cos(thetaRad) * std::cos(thetaRad);
  const double gn = kGravity * cos2;
  const double gp = cos4 ? kGravity * cos2 * cos2 : gn;
  MangeneyDamBreak d;
  d.H0 = H0;
  d.c0 = std::sqrt(K * gp * H0);
  d.m = gn * (std::tan(thetaRad) - std::tan(deltaRad));
  d.x0 = x0;
  return d;
}

double slidingAcceleration(double thetaRad, double deltaRad) {
  require(isAngle(thetaRad) && isAngle(deltaRad), "slidingAcceleration needs angles in [0, pi/2)");
  const double tt = std::tan(thetaRad), td = std::tan(deltaRad);
  if (tt <= td) return 0.0;
  const double c = std::cos(thetaRad);
  return kGravity * c * c * (tt - td);
}

double slidingPosition(double x0, double thetaRad, double deltaRad, double t) {
  const double a = slidingAcceleration(thetaRad, deltaRad);
  return t <= 0.0 ? x0 : x0 + 0.5 * a * t * t;
}

double slidingVelocity(double thetaRad, double deltaRad, double t) {
  const double a = slidingAcceleration(thetaRad, deltaRad);
  return t <= 0.0 ? 0.0 : a * t;
}

double reposeSlope(double deltaRad, double K) {
  require(K > 0.0 && isAngle(deltaRad), "reposeSlope needs K > 0 and delta in [0, pi/2)");
  return std::tan(deltaRad) / K;
}

double earthPressure(double phiRad, double deltaRad, bool passive) {
  require(isAngle(phiRad) && isAngle(deltaRad), "earthPressure needs angles in [0, pi/2)");
  const double cp = std::cos(phiRad), cd = std::cos(deltaRad);
  const double arg = std::fmax(0.0, 1.0 - (cp * cp) / (cd * cd));
  const double s = std::sqrt(arg);
  return 2.0 / (cp * cp) * (passive ? 1.0 + s : 1.0 - s) - 1.0;
}

double linearDragRate(double ms, double mf, double k, double mvm) {
  checkPhases(ms, mf, k, mvm);
  // Subtracting the two momentum equations (divided by ms and mf):
  // dw/dt = -(k w + mvm dw/dt) beta, so dw/dt (1 + mvm beta) = -k beta w.
  const double beta = 1.0 / ms + 1.0 / mf;
  return k * beta / (1.0 + mvm * beta);
}

PhaseVelocities linearDragRelaxation(double ms, double mf, double us0, double uf0, double k,
                                     double t, double mvm) {
  const double r = linearDragRate(ms, mf, k, mvm);
  if (t <= 0.0) return {us0, uf0};
  return split(ms, mf, us0, uf0, (uf0 - us0) * std::exp(-r * t));
}

PhaseVelocities quadraticDragRelaxation(double ms, double mf, double us0, double uf0, double k,
                                        double t, double mvm) {
  // Same reduction with F = k |w| w: dw/dt = -k' |w| w, k' = k beta / (1 + mvm beta). Then
  // d(1/|w|)/dt = k' (w keeps its sign), so |w| = |w0| / (1 + k' |w0| t).
  const double kq = linearDragRate(ms, mf, k, mvm);
  if (t <= 0.0) return {us0, uf0};
  const double w0 = uf0 - us0;
  return split(ms, mf, us0, uf0, w0 / (1.0 + kq * std::fabs(w0) * t));
}

}  // namespace talus::analytic
