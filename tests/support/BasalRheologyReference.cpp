#include "support/BasalRheologyReference.hpp"

#include <cmath>
#include <functional>

#include "core/Constants.hpp"

namespace talus::test {
namespace {

/// Root of the non-decreasing f on [lo, hi] with f(lo) <= 0 <= f(hi), by bisection to round-off.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (int it = 0; it < 200 && hi - lo > 1e-16 * std::fabs(hi); ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

/// q of q + ds T(q) = q* for the horizontal stress per density T (non-decreasing in q >= 0).
double implicitStep(const std::function<double(double)>& T, double qStar, double ds) {
  if (qStar - ds * T(0.0) <= 0) return 0.0;
  return bisect([&](double q) { return q + ds * T(q) - qStar; }, 0.0, qStar);
}

}  // namespace

double herschelBulkleySpeed(double tau, double tauY, double K, double n, double H) {
  if (tau <= tauY) return 0.0;
  // Shear rate ((tau (1 - z/H) - tau_y) / K)^(1/n) up to the plug at z_p = H (1 - tau_y/tau); u(z)
  // by Simpson over [0, z], the plug moves with u(z_p). Average over [0, H].
  const double zp = H * (1.0 - tauY / tau);
  const auto rate = [&](double z) { return std::pow(std::max(tau * (1.0 - z / H) - tauY, 0.0) / K, 1.0 / n); };
  constexpr int kN = 400;  // even; u on the nodes by cumulative Simpson pairs
  const double dz = zp / kN;
  double u[kN + 1];
  u[0] = 0;
  for (int i = 1; i <= kN; ++i) {
    // Simpson over [z_{i-1}, z_i] with its midpoint.
    const double a = (i - 1) * dz, b = i * dz;
    u[i] = u[i - 1] + dz / 6.0 * (rate(a) + 4.0 * rate(0.5 * (a + b)) + rate(b));
  }
  double sheared = u[0] + u[kN];
  for (int i = 1; i < kN; ++i) sheared += (i % 2 ? 4.0 : 2.0) * u[i];
  sheared *= dz / 3.0;
  return (sheared + (H - zp) * u[kN]) / H;
}

double basalFactorRef(flow::Rheology law, const std::array<double, 4>& p, const BasalColumnRef& c, double qStar,
                      double ds) {
  const double H = c.h * c.cosT;
  const auto speed = [&](double q) { return c.stretch * q / c.h; };  // along-bed |U|
  double q = 0;
  switch (law) {
    case flow::Rheology::Coulomb:
      q = implicitStep([&](double) { return c.tanDelta * c.nG * c.hSt; }, qStar, ds);
      break;
    case flow::Rheology::Voellmy: {
      // tau / rho = mu sigma_n / rho + g U^2 / xi on the bed, p[1] = g / xi; horizontal part / (s cos).
      q = implicitStep([&](double qq) {
        const double U = speed(qq);
        return p[0] * c.nG * c.hSt + p[1] * U * U / (c.stretch * c.cosT);
      }, qStar, ds);
      break;
    }
    case flow::Rheology::MuI: {
      const double t1 = p[0], t2 = p[1], beta = p[2], L = p[3];
      q = implicitStep([&](double qq) {
        const double Fr = speed(qq) / std::sqrt(c.gN * c.h);  // U / sqrt(g cos H), g cos H = g_n h
        const double hStop = Fr >= beta ? beta * H / Fr : H;  // mu_stop(H) below Fr = beta
        const double mu = t1 + (t2 - t1) / (1.0 + hStop / L);
        return mu * c.nG * c.hSt;
      }, qStar, ds);
      break;
    }
    case flow::Rheology::HerschelBulkley: {
      // q + m tau = q*, q = h U(tau) / s, m = ds / (rho cos s): bisection on tau.
      const double m = ds / (c.rho * c.cosT * c.stretch);
      if (qStar <= m * p[0]) return 0.0;
      const double tau = bisect([&](double t) {
        return c.h / c.stretch * herschelBulkleySpeed(t, p[0], p[1], p[2], H) + m * t - qStar;
      }, p[0], qStar / m);
      q = qStar - m * tau;
      break;
    }
  }
  return q / qStar;
}

}  // namespace talus::test
