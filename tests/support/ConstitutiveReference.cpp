// The CPU reference of the particle constitutive update (see ConstitutiveReference.hpp for how it
// differs in arithmetic from kernels/particles/constitutive.cl).
#include "support/ConstitutiveReference.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace talus::test {
namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 zero3() { return Mat3{}; }

Mat3 identity3() {
  Mat3 m{};
  for (int i = 0; i < 3; ++i) m[i][i] = 1.0;
  return m;
}

Mat3 mul(const Mat3& a, const Mat3& b) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[k][j];
  return r;
}

Mat3 transpose(const Mat3& a) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = a[j][i];
  return r;
}

Mat3 add(const Mat3& a, const Mat3& b, double sb = 1.0) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = a[i][j] + sb * b[i][j];
  return r;
}

Mat3 scale(const Mat3& a, double s) { return add(zero3(), a, s); }

double trace(const Mat3& a) { return a[0][0] + a[1][1] + a[2][2]; }

double contract(const Mat3& a, const Mat3& b) {
  double s = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += a[i][j] * b[i][j];
  return s;
}

Mat3 deviator(const Mat3& a) { return add(a, identity3(), -trace(a) / 3.0); }

/// The 3D stress of an in-plane state with the prescribed vertical stress.
Mat3 stress3(const ConstitutiveStress& s, double szz) {
  Mat3 m{};
  m[0][0] = s.xx, m[1][1] = s.yy, m[0][1] = m[1][0] = s.xy, m[2][2] = szz;
  return m;
}

ConstitutiveStress inPlane(const Mat3& m) { return {m[0][0], m[1][1], 0.5 * (m[0][1] + m[1][0])}; }

/// Drucker-Prager constants, written through sin/cos: alpha = sin phi / sqrt(9 + 3 sin^2 phi),
/// k_c = 3 c cos phi / sqrt(9 + 3 sin^2 phi) (equal to the tan forms of P.20).
struct Constants {
  double G, K, alpha, alphaPsi, kc;
};

Constants constantsOf(const ConstitutiveMaterial& m) {
  Constants k{};
  k.G = m.E / (2.0 * (1.0 + m.nu));
  k.K = m.E / (3.0 * (1.0 - 2.0 * m.nu));
  const double sp = std::sin(m.phi), ss = std::sin(m.psi);
  k.alpha = sp / std::sqrt(9.0 + 3.0 * sp * sp);
  k.alphaPsi = ss / std::sqrt(9.0 + 3.0 * ss * ss);
  k.kc = 3.0 * m.c * std::cos(m.phi) / std::sqrt(9.0 + 3.0 * sp * sp);
  return k;
}

double yield3(const Mat3& s, const Constants& k) {
  const Mat3 dev = deviator(s);
  return k.alpha * trace(s) + std::sqrt(0.5 * contract(dev, dev)) - k.kc;
}

/// The 3D elastic operator D : X = 2G dev(X) + K tr(X) I.
Mat3 elastic(const Mat3& x, const Constants& k) {
  return add(scale(deviator(x), 2.0 * k.G), identity3(), k.K * trace(x));
}

/// The plane-stress response to an in-plane strain (rate) X: D : X' where X' is X with its zz entry
/// replaced by the vertical strain that keeps (D : X')_zz = 0, found here by solving that linear
/// equation in X'_zz numerically (the vertical stress is prescribed; the kernel uses the closed
/// form lambda* = 2G lambda / (lambda + 2G) instead).
Mat3 elasticPlaneStress(const Mat3& x, const Constants& k) {
  Mat3 a = x, b = x;
  a[2][2] = 0.0;
  b[2][2] = 1.0;
  const double za = elastic(a, k)[2][2], zb = elastic(b, k)[2][2];  // (D : X')_zz is affine in X'_zz
  Mat3 c = x;
  c[2][2] = -za / (zb - za);
  Mat3 out = elastic(c, k);
  out[2][2] = 0.0;  // zero up to rounding
  return out;
}

/// Largest x in [lo, hi] with fn(x) <= 0, for fn increasing across one sign change in [lo, hi]
/// (fn(lo) <= 0 < fn(hi)); bisection down to adjacent doubles.
template <class F>
double bisectLast(F fn, double lo, double hi) {
  for (int it = 0; it < 4000; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    (fn(mid) <= 0.0 ? lo : hi) = mid;
  }
  return lo;
}

/// The stress remapping with sigma_zz held (kernel header, step 6), by bisection on f.
ConstitutiveStress remap(const ConstitutiveStress& s, double szz, const Constants& k, bool snap) {
  auto fOf = [&](double p, double d, double t) {
    return yield3(stress3({p + d, p - d, t}, szz), k);
  };
  const double p = 0.5 * (s.xx + s.yy), d = 0.5 * (s.xx - s.yy), t = s.xy;
  if (!snap && !(fOf(p, d, t) > 0.0)) return s;
  if (3.0 * k.alpha * szz > k.kc) return {szz, szz, 0.0};  // no admissible state
  // f along the in-plane isotropic line: convex, smallest (<= 0) at p = szz.
  const double base = std::max({1.0, std::fabs(szz), k.kc});
  double hi = szz + base;
  while (fOf(hi, 0, 0) <= 0.0) hi = szz + 2.0 * (hi - szz);
  const double pHi = bisectLast([&](double x) { return fOf(x, 0, 0); }, szz, hi);
  double lo = szz - base;
  while (fOf(lo, 0, 0) <= 0.0) lo = szz - 2.0 * (szz - lo);
  // Decreasing on [lo, szz]: search in the mirrored variable y = -x.
  const double pLo = -bisectLast([&](double y) { return fOf(-y, 0, 0); }, -szz, -lo);
  if (p > pHi) return {pHi, pHi, 0.0};
  if (p < pLo) return {pLo, pLo, 0.0};
  if (d == 0.0 && t == 0.0) return {p, p, 0.0};
  auto h = [&](double r) { return fOf(p, r * d, r * t); };
  if (!snap && !(h(1.0) > 0.0)) return s;
  if (!(h(0.0) <= 0.0)) return {p, p, 0.0};
  double rHi = 1.0;
  while (h(rHi) <= 0.0) rHi *= 2.0;
  const double r = bisectLast(h, 0.0, rHi);
  return {p + r * d, p - r * d, r * t};
}

}  // namespace

double referenceYield(const ConstitutiveStress& s, double szz, const ConstitutiveMaterial& m) {
  return yield3(stress3(s, szz), constantsOf(m));
}

ConstitutiveStep referenceStressUpdate(const ConstitutiveStress& s0, const double L[2][2], double szz,
                                       const ConstitutiveMaterial& m, double dt) {
  const Constants k = constantsOf(m);
  Mat3 grad{};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) grad[a][b] = L[a][b];
  const Mat3 rate = scale(add(grad, transpose(grad)), 0.5);  // P.79 (plus sign)
  const Mat3 spin = scale(add(grad, transpose(grad), -1.0), 0.5);  // P.80
  ConstitutiveStep out;
  out.epsVRate = trace(rate);

  // Q = exp(spin dt): spin = [[0, w], [-w, 0]] generates the rotation by the angle w dt below.
  const double angle = spin[0][1] * dt;
  Mat3 Q = identity3();
  Q[0][0] = Q[1][1] = std::cos(angle);
  Q[0][1] = std::sin(angle);
  Q[1][0] = -std::sin(angle);
  Mat3 trial = mul(mul(Q, stress3(s0, szz)), transpose(Q));
  trial = add(trial, elasticPlaneStress(rate, k), dt);
  trial[2][2] = szz;  // the vertical stress is prescribed, not integrated
  const double f = yield3(trial, k);
  out.trialYield = f;
  if (!(f > 0.0)) {
    out.stress = inPlane(trial);
    return out;
  }
  out.yielded = true;
  const Mat3 s = deviator(trial);
  const double sqJ2 = std::sqrt(0.5 * contract(s, s));
  Mat3 dfds = scale(identity3(), k.alpha), dgds = scale(identity3(), k.alphaPsi);
  if (sqJ2 > 0.0) {
    dfds = add(dfds, s, 0.5 / sqJ2);
    dgds = add(dgds, s, 0.5 / sqJ2);
  }
  const Mat3 flow = elasticPlaneStress(dgds, k);  // the in-plane stress rate of a plastic strain rate dg/dsigma
  out.dlambda = f / contract(dfds, flow);
  // The flow is G s / sqrt(J2) plus an in-plane isotropic part; that part times dlambda is removed,
  // and of s at most all of it.
  Mat3 iso = flow;
  if (sqJ2 > 0.0) iso = add(iso, s, -k.G / sqJ2);
  iso[2][2] = 0.0;
  const double devShare = sqJ2 > 0.0 ? std::min(1.0, k.G * out.dlambda / sqJ2) : 1.0;
  Mat3 corrected = add(add(trial, iso, -out.dlambda), s, -devShare);
  out.stress = remap(inPlane(corrected), szz, k, true);
  return out;
}

double referenceCohesion(double c, double c0, double epsVRate, double epsC, double dt, bool yielding) {
  if (!yielding || c <= 0.0) return c;
  const double rate = -c0 * std::fabs(epsVRate) / (2.0 * epsC);  // dc/dt of P.26
  const double next = c + rate * dt;
  return next < 0.0 ? 0.0 : next;
}

double referenceBondFraction(double c, double c0) {
  if (c0 <= 0.0) return 1.0;
  return std::clamp(c / c0, 0.0, 1.0);
}

}  // namespace talus::test
