// Independent checks of the analytic shallow-water references in tests/support/Analytic.hpp:
// conservation laws, jump conditions, characteristic invariants and PDE residuals, rather than
// restatements of the closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

#include "support/Analytic.hpp"

namespace an = talus::analytic;

namespace {

constexpr double kG = 9.81;
constexpr double kEps = 2.220446049250313e-16;

/// Integral of f over [lo, hi] split at the sorted breakpoints inside it, n cells per piece, each
/// cell by cellAverage1D (so piecewise polynomials of degree <= 9 integrate to round-off).
double integrate(const std::function<double(double)>& f, double lo, double hi,
                 std::vector<double> breaks, int n = 200) {
  breaks.insert(breaks.begin(), lo);
  breaks.push_back(hi);
  double sum = 0.0;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    const double dx = (breaks[p + 1] - breaks[p]) / n;
    for (int i = 0; i < n; ++i) sum += an::cellAverage1D(f, breaks[p] + (i + 0.5) * dx, dx) * dx;
  }
  return sum;
}

/// Centred finite-difference residuals of the flat-bed 1D equations at (x, t).
void residual1D(const std::function<an::State1D(double, double)>& s, double x, double t, double d,
                double* mass, double* mom) {
  auto flux = [&](double xx, double tt, double* fh, double* fm) {
    const an::State1D q = s(xx, tt);
    *fh = q.h * q.u;
    *fm = q.h * q.u * q.u + 0.5 * kG * q.h * q.h;
  };
  const an::State1D tp = s(x, t + d), tm = s(x, t - d);
  double fhp, fmp, fhm, fmm;
  flux(x + d, t, &fhp, &fmp);
  flux(x - d, t, &fhm, &fmm);
  *mass = (tp.h - tm.h) / (2 * d) + (fhp - fhm) / (2 * d);
  *mom = (tp.h * tp.u - tm.h * tm.u) / (2 * d) + (fmp - fmm) / (2 * d);
}

}  // namespace

TEST(Analytic, RitterConservesVolumeAndMomentum) {
  const double hL = 2.0, x0 = 3.0, c0 = std::sqrt(kG * hL), lo = -60.0, hi = 70.0;
  for (double t : {0.3, 1.0, 2.5, 6.0}) {
    auto h = [&](double x) { return an::ritter(x, t, x0, hL, kG).h; };
    auto hu = [&](double x) { const auto s = an::ritter(x, t, x0, hL, kG); return s.h * s.u; };
    const std::vector<double> breaks{x0 - c0 * t, x0 + 2 * c0 * t};
    EXPECT_NEAR(integrate(h, lo, hi, breaks), hL * (x0 - lo), 1e-12 * hL * (x0 - lo)) << t;
    // No momentum enters through the dry right end; the left end carries g hL^2 / 2 in.
    EXPECT_NEAR(integrate(hu, lo, hi, breaks), 0.5 * kG * hL * hL * t, 1e-12 * kG * hL * hL * t);
    // Blind integration without the breakpoints still agrees (the kinks cost O(dx^2)).
    EXPECT_NEAR(integrate(h, lo, hi, {}, 20000), hL * (x0 - lo), 1e-6 * hL * (x0 - lo));
  }
}

TEST(Analytic, RitterFrontAndDamSiteValues) {
  const double hL = 1.5, x0 = -2.0, c0 = std::sqrt(kG * hL);
  for (double t : {0.1, 1.0, 7.0}) {
    // Locate the wet/dry front by bisection on h > 0.
    double wet = x0, dry = x0 + 100.0 * c0 * t;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (wet + dry);
      (an::ritter(mid, t, x0, hL, kG).h > 0.0 ? wet : dry) = mid;
    }
    EXPECT_NEAR(wet, x0 + 2 * c0 * t, 1e-6 * c0 * t) << t;
    const an::State1D dam = an::ritter(x0, t, x0, hL, kG);
    EXPECT_NEAR(dam.h, 4.0 / 9.0 * hL, 1e-14);
    EXPECT_NEAR(dam.u, 2.0 / 3.0 * c0, 1e-14);
    // Continuous at the rarefaction head; undisturbed behind it.
    EXPECT_NEAR(an::ritter(x0 - c0 * t * (1 - 1e-9), t, x0, hL, kG).h, hL, 1e-8);
    EXPECT_EQ(an::ritter(x0 - c0 * t * 1.01, t, x0, hL, kG).u, 0.0);
  }
  EXPECT_EQ(an::ritter(x0 - 1e-9, 0.0, x0, hL, kG).h, hL);
  EXPECT_EQ(an::ritter(x0 + 1e-9, 0.0, x0, hL, kG).h, 0.0);
  EXPECT_THROW(an::ritter(0.0, 1.0, 0.0, -1.0, kG), std::invalid_argument);
}

TEST(Analytic, RitterAndStokerSatisfyPdeWhereSmooth) {
  // Inside the fan the solution is smooth; centred differences with d = 1e-4 leave an O(d^2)
  // truncation error (~1e-8 times third derivatives of order one here) plus ~eps/d round-off.
  const double hL = 1.0, d = 1e-4, t = 1.0, c0 = std::sqrt(kG * hL);
  const an::StokerStar st = an::stokerStar(hL, 0.1, kG);
  const double cm = std::sqrt(kG * st.hm);
  for (int k = 1; k < 20; ++k) {
    const double xr = -c0 + 3.0 * c0 * k / 20.0;                 // Ritter fan
    const double xs = -c0 + (st.um - cm + c0) * k / 20.0;         // Stoker fan
    double m, p;
    residual1D([&](double x, double tt) { return an::ritter(x, tt, 0.0, hL, kG); }, xr, t, d, &m, &p);
    EXPECT_LT(std::fabs(m), 1e-6) << xr;
    EXPECT_LT(std::fabs(p), 1e-6 * kG) << xr;
    residual1D([&](double x, double tt) { return an::stoker(x, tt, 0.0, hL, 0.1, kG); }, xs, t, d,
               &m, &p);
    EXPECT_LT(std::fabs(m), 1e-6) << xs;
    EXPECT_LT(std::fabs(p), 1e-6 * kG) << xs;
  }
}

TEST(Analytic, StokerRankineHugoniotAndEntropy) {
  const double cases[][2] = {{1.0, 0.5}, {2.0, 0.1}, {10.0, 0.01}, {1.0, 0.9}, {5.0, 1e-4}};
  const double t = 1.7, x0 = 0.5;
  for (const auto& c : cases) {
    const double hL = c[0], hR = c[1];
    const double s = an::stokerStar(hL, hR, kG).shockSpeed;
    const double xs = x0 + s * t, e = 1e-9 * (1.0 + std::fabs(xs));
    const an::State1D l = an::stoker(xs - e, t, x0, hL, hR, kG);
    const an::State1D r = an::stoker(xs + e, t, x0, hL, hR, kG);
    const double massJump = s * (l.h - r.h) - (l.h * l.u - r.h * r.u);
    const double fluxL = l.h * l.u * l.u + 0.5 * kG * l.h * l.h;
    const double fluxR = r.h * r.u * r.u + 0.5 * kG * r.h * r.h;
    const double momJump = s * (l.h * l.u - r.h * r.u) - (fluxL - fluxR);
    EXPECT_LT(std::fabs(massJump), 1e-10 * s * l.h) << hL << " " << hR;
    EXPECT_LT(std::fabs(momJump), 1e-10 * fluxL) << hL << " " << hR;
    // Lax entropy condition: characteristics run into the shock from both sides.
    EXPECT_GT(s, r.u + std::sqrt(kG * r.h));
    EXPECT_LT(s, l.u + std::sqrt(kG * l.h));
    EXPECT_GT(l.h, r.h);
  }
}

TEST(Analytic, StokerRiemannInvariantAcrossRarefaction) {
  const double hL = 3.0, hR = 0.4, t = 2.0, x0 = 1.0, cL = std::sqrt(kG * hL);
  const an::StokerStar st = an::stokerStar(hL, hR, kG);
  const double s = st.shockSpeed, tail = st.um - std::sqrt(kG * st.hm);
  const int n = 2000;
  double prevH = hL;
  for (int i = 0; i <= n; ++i) {
    // From well behind the rarefaction head to just short of the shock.
    const double xi = -1.5 * cL + (s - 1e-9 + 1.5 * cL) * i / n;
    const an::State1D q = an::stoker(x0 + xi * t, t, x0, hL, hR, kG);
    const double c = std::sqrt(kG * q.h);
    EXPECT_NEAR(q.u + 2.0 * c, 2.0 * cL, 1e-12 * cL) << xi;
    if (xi > -cL && xi < tail) {
      EXPECT_NEAR(q.u - c, xi, 1e-12 * cL) << xi;
    }
    // Depth is continuous and non-increasing up to the shock.
    EXPECT_LE(q.h, prevH + 1e-14);
    EXPECT_LT(prevH - q.h, 0.01 * hL) << xi;
    prevH = q.h;
  }
}

TEST(Analytic, StokerStarSolvesMatchingTo1e13) {
  for (double hR : {1e-6, 1e-3, 0.05, 0.3, 0.7, 0.99}) {
    const double hL = 1.0;
    // Independent root of the matching condition by long-double bisection on hm.
    const long double g = kG, cL = std::sqrt(g * hL);
    long double lo = hR, hi = hL;
    for (int i = 0; i < 200; ++i) {
      const long double hm = 0.5L * (lo + hi);
      const long double um = (hm - hR) * std::sqrt(0.5L * g * (1.0L / hm + 1.0L / hR));
      (2.0L * (cL - std::sqrt(g * hm)) - um > 0 ? lo : hi) = hm;
    }
    const an::StokerStar st = an::stokerStar(hL, hR, kG);
    EXPECT_NEAR(st.hm, static_cast<double>(lo), 1e-13 * st.hm) << hR;
    EXPECT_NEAR(st.um, 2.0 * (std::sqrt(kG * hL) - std::sqrt(kG * st.hm)), 1e-13 * st.um);
  }
  EXPECT_THROW(an::stokerStar(1.0, 1.0, kG), std::invalid_argument);
  EXPECT_THROW(an::stoker(0.0, 1.0, 0.0, 1.0, 2.0, kG), std::invalid_argument);
}

TEST(Analytic, StokerApproachesRitterAsHRVanishes) {
  const double hL = 1.0, t = 1.0, cL = std::sqrt(kG * hL), lo = -2 * cL, hi = 3 * cL;
  double prevDiff = INFINITY, prevGap = INFINITY, prevHm = hL;
  for (int k = 2; k <= 12; k += 2) {
    const double hR = std::pow(10.0, -k);
    const an::StokerStar st = an::stokerStar(hL, hR, kG);
    auto diff = [&](double x) {
      return std::fabs(an::stoker(x, t, 0.0, hL, hR, kG).h - an::ritter(x, t, 0.0, hL, kG).h);
    };
    const double l1 = integrate(diff, lo, hi, {st.shockSpeed * t}, 4000);
    const double gap = 2.0 * cL - st.um;
    EXPECT_LT(l1, prevDiff) << hR;
    EXPECT_LT(gap, prevGap) << hR;
    EXPECT_GT(gap, 0.0);
    EXPECT_LT(st.hm, prevHm) << hR;
    prevDiff = l1;
    prevGap = gap;
    prevHm = st.hm;
  }
  // At hR = 1e-12 hL: the star velocity approaches 2 cL only slowly (the gap is ~0.3% of 2 cL),
  // but the depth profiles differ by less than 1e-7 hL in L1 (about 9e-9 measured).
  EXPECT_LT(prevGap, 0.01 * cL);
  EXPECT_LT(prevDiff, 1e-7 * hL);
  EXPECT_EQ(an::stoker(0.3, t, 0.0, hL, 0.0, kG).h, an::ritter(0.3, t, 0.0, hL, kG).h);
  const an::State1D dam = an::stoker(0.0, t, 0.0, hL, 1e-8, kG);
  EXPECT_NEAR(dam.h, 4.0 / 9.0 * hL, 1e-14);  // the dam site lies in the fan for small hR
}

TEST(Analytic, StokerConservesVolumeAndMomentum) {
  const double hL = 2.0, hR = 0.3, x0 = 0.0, lo = -50.0, hi = 60.0, cL = std::sqrt(kG * hL);
  const an::StokerStar st = an::stokerStar(hL, hR, kG);
  const double cm = std::sqrt(kG * st.hm);
  for (double t : {0.5, 2.0, 5.0}) {
    auto h = [&](double x) { return an::stoker(x, t, x0, hL, hR, kG).h; };
    auto hu = [&](double x) { const auto s = an::stoker(x, t, x0, hL, hR, kG); return s.h * s.u; };
    const std::vector<double> breaks{x0 - cL * t, x0 + (st.um - cm) * t, x0 + st.shockSpeed * t};
    const double vol = hL * (x0 - lo) + hR * (hi - x0);
    EXPECT_NEAR(integrate(h, lo, hi, breaks), vol, 1e-12 * vol) << t;
    const double mom = 0.5 * kG * (hL * hL - hR * hR) * t;
    EXPECT_NEAR(integrate(hu, lo, hi, breaks), mom, 1e-12 * mom) << t;
  }
}

namespace {

/// Finite-difference residuals of the 2D conservative equations for a solution given by depth
/// and uniform velocity functions, with gravity gEq used in the equations themselves.
struct Residual2D {
  double mass, momX, momY;
};
Residual2D residual2D(const std::function<double(double, double, double)>& h,
                      const std::function<double(double)>& u, const std::function<double(double)>& v,
                      const an::ThackerPlanar& tp, double gEq, double x, double y, double t, double d) {
  auto hu = [&](double xx, double yy, double tt) { return h(xx, yy, tt) * u(tt); };
  auto hv = [&](double xx, double yy, double tt) { return h(xx, yy, tt) * v(tt); };
  auto p = [&](double xx, double yy) { const double q = h(xx, yy, t); return 0.5 * gEq * q * q; };
  const double dt = 2 * d, U = u(t), V = v(t), H = h(x, y, t);
  const double bx = (tp.bed(x + d, y) - tp.bed(x - d, y)) / dt;  // exact: b is quadratic
  const double by = (tp.bed(x, y + d) - tp.bed(x, y - d)) / dt;
  Residual2D r;
  r.mass = (h(x, y, t + d) - h(x, y, t - d)) / dt + (hu(x + d, y, t) - hu(x - d, y, t)) / dt +
           (hv(x, y + d, t) - hv(x, y - d, t)) / dt;
  r.momX = (hu(x, y, t + d) - hu(x, y, t - d)) / dt +
           U * (hu(x + d, y, t) - hu(x - d, y, t)) / dt + (p(x + d, y) - p(x - d, y)) / dt +
           U * (hv(x, y + d, t) - hv(x, y - d, t)) / dt + gEq * H * bx;
  r.momY = (hv(x, y, t + d) - hv(x, y, t - d)) / dt +
           V * (hu(x + d, y, t) - hu(x - d, y, t)) / dt +
           V * (hv(x, y + d, t) - hv(x, y - d, t)) / dt + (p(x, y + d) - p(x, y - d)) / dt +
           gEq * H * by;
  return r;
}

}  // namespace

TEST(Analytic, ThackerSatisfiesShallowWaterEquations) {
  const an::ThackerPlanar tp;  // SWASHES parameters
  const double w = tp.omega(), d = 1e-4, U = tp.eta * w;
  auto h = [&](double x, double y, double t) { return tp.h(x, y, t); };
  auto u = [&](double t) { return tp.u(t); };
  auto v = [&](double t) { return tp.v(t); };
  std::mt19937 rng(20130701);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    // A point at most 0.9 a from the wet disk's centre, so the whole stencil is wet.
    const double t = 2.0 * tp.period() * uni(rng), th = 6.283185307179586 * uni(rng);
    const double rho = 0.9 * tp.a * std::sqrt(uni(rng));
    const double x = tp.xc + tp.eta * std::cos(w * t) + rho * std::cos(th);
    const double y = tp.yc + tp.eta * std::sin(w * t) + rho * std::sin(th);
    ASSERT_GT(tp.h(x, y, t), 0.0);
    // Tolerance. Time: centred differences err by d^2/6 |q'''|; at fixed (x, y) the unclipped h is
    // a trigonometric polynomial of degree 1 in wt and hu, hv of degree 2, so by Bernstein's
    // inequality |q'''| <= (n w)^3 sup|q|, with sup|h| <= hs = h0 max(1, (R + eta)^2 / a^2 - 1).
    // Space: h, hu, hv, hu^2, huv are quadratic in x and y (differenced exactly); only
    // g h^2 / 2 is quartic, erring by (g/2)(d^2/6)|(h^2)_xxx| = 2 g h0^2 d^2 |X'| / a^4 with
    // |X'| <= a. Round-off: about 10 eps times the largest differenced value over d.
    const double R = std::hypot(x - tp.xc, y - tp.yc);
    const double hs = tp.h0 * std::max(1.0, (R + tp.eta) * (R + tp.eta) / (tp.a * tp.a) - 1.0);
    const double round = 10.0 * kEps / d;
    const double tolMass = 2.0 * (d * d / 6.0 * std::pow(w, 3) * hs) + round * hs * (1.0 + U);
    const double tolMom = 2.0 * (d * d / 6.0 * std::pow(2.0 * w, 3) * hs * U +
                                 2.0 * tp.g * tp.h0 * tp.h0 * d * d / std::pow(tp.a, 3)) +
                          round * (hs * U * (1.0 + U) + tp.g * hs * hs);
    const Residual2D r = residual2D(h, u, v, tp, tp.g, x, y, t, d);
    EXPECT_LT(std::fabs(r.mass), tolMass) << x << " " << y << " " << t;
    EXPECT_LT(std::fabs(r.momX), tolMom) << x << " " << y << " " << t;
    EXPECT_LT(std::fabs(r.momY), tolMom) << x << " " << y << " " << t;
    // Negative controls: a reversed v or a solution built for another gravity fails by far more.
    auto vWrong = [&](double tt) { return -tp.v(tt); };
    EXPECT_GT(std::fabs(residual2D(h, u, vWrong, tp, tp.g, x, y, t, d).mass) +
                  std::fabs(residual2D(h, u, vWrong, tp, tp.g, x, y, t, d).momY),
              1e3 * tolMass);
    an::ThackerPlanar other = tp;
    other.g = 1.21 * tp.g;
    auto hO = [&](double xx, double yy, double tt) { return other.h(xx, yy, tt); };
    auto uO = [&](double tt) { return other.u(tt); };
    auto vO = [&](double tt) { return other.v(tt); };
    const double wo = other.omega();  // same offset from the other solution's wet centre
    const double xo = tp.xc + tp.eta * std::cos(wo * t) + rho * std::cos(th);
    const double yo = tp.yc + tp.eta * std::sin(wo * t) + rho * std::sin(th);
    ASSERT_GT(other.h(xo, yo, t), 0.0);
    const Residual2D ro = residual2D(hO, uO, vO, other, tp.g, xo, yo, t, d);
    EXPECT_GT(std::hypot(ro.momX, ro.momY), 1e3 * tolMom);
  }
  // The residual that remains is truncation error: it falls by 100 when the step falls by 10.
  const double t = 1.234, x = tp.xc + tp.eta * std::cos(w * t) + 0.3;
  const double y = tp.yc + tp.eta * std::sin(w * t) - 0.2;
  const Residual2D c = residual2D(h, u, v, tp, tp.g, x, y, t, 1e-2);
  const Residual2D f = residual2D(h, u, v, tp, tp.g, x, y, t, 1e-3);
  EXPECT_NEAR(c.mass / f.mass, 100.0, 1.0);
  EXPECT_NEAR(c.momX / f.momX, 100.0, 1.0);
  EXPECT_NEAR(c.momY / f.momY, 100.0, 1.0);
}

TEST(Analytic, ThackerConservesVolumeAndMovesWithItsVelocity) {
  const an::ThackerPlanar tp;
  const int n = 1000;
  const double half = tp.a + tp.eta + 0.05, dx = 2.0 * half / n, w = tp.omega();
  // Midpoint-rule moments of h over a square covering every wet disk.
  auto moments = [&](double t, double* m0, double* mx, double* my) {
    *m0 = *mx = *my = 0.0;
    for (int j = 0; j < n; ++j) {
      const double y = tp.yc - half + (j + 0.5) * dx;
      for (int i = 0; i < n; ++i) {
        const double x = tp.xc - half + (i + 0.5) * dx, h = tp.h(x, y, t);
        *m0 += h;
        *mx += h * x;
        *my += h * y;
      }
    }
    *m0 *= dx * dx;
    *mx *= dx * dx;
    *my *= dx * dx;
  };
  const double exact = 0.5 * 3.141592653589793 * tp.a * tp.a * tp.h0;  // paraboloid lens
  EXPECT_NEAR(tp.volume(), exact, 1e-15);
  double v0 = 0.0;
  for (int k = 0; k <= 7; ++k) {
    const double t = k * tp.period() / 7.0, dt = 1e-3;
    double m, mx, my, mp, mxp, myp, mm, mxm, mym;
    moments(t, &m, &mx, &my);
    if (k == 0) v0 = m;
    EXPECT_NEAR(m, exact, 1e-5 * exact) << t;
    EXPECT_NEAR(m, v0, 1e-5 * exact) << t;
    EXPECT_NEAR(mx / m, tp.xc + tp.eta * std::cos(w * t), 1e-5) << t;
    EXPECT_NEAR(my / m, tp.yc + tp.eta * std::sin(w * t), 1e-5) << t;
    // With a uniform velocity the centre of mass must move at (u, v).
    moments(t + dt, &mp, &mxp, &myp);
    moments(t - dt, &mm, &mxm, &mym);
    const double tolV = 1e-4 * tp.eta * w;
    EXPECT_NEAR((mxp / mp - mxm / mm) / (2 * dt), tp.u(t), tolV) << t;
    EXPECT_NEAR((myp / mp - mym / mm) / (2 * dt), tp.v(t), tolV) << t;
  }
}

TEST(Analytic, ThackerIsPeriodicAndSymmetric) {
  const an::ThackerPlanar tp{1.5, 0.2, 0.4, 9.81, 3.0, -1.0};
  const double T = tp.period(), w = tp.omega();
  EXPECT_NEAR(T, 2.0 * 3.141592653589793 * tp.a / std::sqrt(2.0 * tp.g * tp.h0), 1e-14);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    const double X = 2.2 * uni(rng), Y = 2.2 * uni(rng), t = 5.0 * T * (1.0 + uni(rng));
    const an::State2D s = tp.state(tp.xc + X, tp.yc + Y, t);
    const an::State2D p = tp.state(tp.xc + X, tp.yc + Y, t + T);
    EXPECT_NEAR(s.h, p.h, 1e-12);
    EXPECT_NEAR(s.u, p.u, 1e-12);
    EXPECT_NEAR(s.v, p.v, 1e-12);
    // Half a period later the lens is point-reflected through the vertex.
    EXPECT_NEAR(tp.h(tp.xc - X, tp.yc - Y, t + 0.5 * T), s.h, 1e-12);
    EXPECT_GE(s.h, 0.0);
    if (s.h == 0.0) {
      EXPECT_EQ(s.u, 0.0);
      EXPECT_NEAR(tp.surface(tp.xc + X, tp.yc + Y, t), tp.bed(tp.xc + X, tp.yc + Y), 1e-15);
    }
  }
  // Initial state: wet disk of radius a centred at (xc + eta, yc), depth h0 at its centre.
  const an::State2D c = tp.initial(tp.xc + tp.eta, tp.yc);
  EXPECT_NEAR(c.h, tp.h0, 1e-15);
  EXPECT_EQ(c.u, 0.0);
  EXPECT_NEAR(c.v, tp.eta * w, 1e-15);
  EXPECT_GT(tp.initial(tp.xc + tp.eta + 0.999 * tp.a, tp.yc).h, 0.0);
  EXPECT_EQ(tp.initial(tp.xc + tp.eta + 1.001 * tp.a, tp.yc).h, 0.0);
  EXPECT_EQ(tp.initial(tp.xc + tp.eta, tp.yc - 1.001 * tp.a).h, 0.0);
  EXPECT_NEAR(tp.bed(tp.xc, tp.yc), -tp.h0, 1e-15);
  EXPECT_NEAR(tp.bed(tp.xc, tp.yc + tp.a), 0.0, 1e-15);
}

TEST(Analytic, NormsAndObservedOrder) {
  EXPECT_DOUBLE_EQ(an::l1({1, 2, 3}, {1, 1, 1}, 0.5), 1.5);
  EXPECT_DOUBLE_EQ(an::relativeL1({1, 2, 3}, {1, 1, 1}, 0.5), 1.0);
  EXPECT_EQ(an::relativeL1({0, 0}, {0, 0}, 1.0), 0.0);
  EXPECT_TRUE(std::isinf(an::relativeL1({1, 0}, {0, 0}, 1.0)));
  EXPECT_THROW(an::l1({1, 2}, {1}, 1.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(an::observedOrder(3.0 * 0.1 * 0.1, 3.0 * 0.05 * 0.05, 2.0), 2.0);
  EXPECT_DOUBLE_EQ(an::observedOrder(1.0 / 27.0, 1.0 / 729.0, 3.0), 3.0);
  EXPECT_THROW(an::observedOrder(0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(an::observedOrder(1.0, 0.5, 1.0), std::invalid_argument);
  // End to end: point values at cell centres differ from cell averages by f'' dx^2 / 24, so the
  // L1 distance between them converges at second order.
  auto f = [](double x) { return std::sin(3.0 * x) + x * x; };
  std::vector<double> err;
  for (int n : {40, 80, 160}) {
    const double dx = 2.0 / n;
    std::vector<double> pt, avg;
    for (int i = 0; i < n; ++i) {
      const double xc = -1.0 + (i + 0.5) * dx;
      pt.push_back(f(xc));
      avg.push_back(an::cellAverage1D(f, xc, dx));
    }
    err.push_back(an::l1(pt, avg, dx));
  }
  EXPECT_NEAR(an::observedOrder(err[0], err[1], 2.0), 2.0, 0.01);
  EXPECT_NEAR(an::observedOrder(err[1], err[2], 2.0), 2.0, 0.01);
}

TEST(Analytic, CellAverageIsExactForPolynomialsAndSteps) {
  // Degree 9 is integrated exactly: the average of x^9 + x^4 over [0, 2] is (2^10/10 + 2^5/5)/2.
  auto p = [](double x) { return std::pow(x, 9) + std::pow(x, 4); };
  EXPECT_NEAR(an::cellAverage1D(p, 1.0, 2.0), (102.4 + 6.4) / 2.0, 1e-12);
  EXPECT_NEAR(an::cellAverage1D([](double) { return 4.0; }, -3.0, 0.1), 4.0, 1e-15);
  // A step on a sub-interval boundary (a quarter of the cell is wet) is averaged exactly.
  auto step = [](double x) { return x > 0.25 ? 1.0 : 0.0; };
  EXPECT_NEAR(an::cellAverage1D(step, 0.0, 1.0), 0.25, 1e-15);
}
