// The particle constitutive update (kernels/particles/constitutive.cl, through its test kernel
// constitutive_test_steps) against the independent CPU reference support/ConstitutiveReference,
// and physics checks of the update itself, in double and float:
// - random particles (random velocity gradients, stresses inside, on and far outside the yield
//   surface, in tension beyond the apex and in compression beyond the in-plane limit; E from 1 MPa
//   to 1 GPa, phi from 15 to 45 deg, c = 0 and c > 0, psi = 0 and 0 < psi <= phi, overburden from
//   0 to -3.9e5 Pa) match the reference after one step and after 20 steps;
// - after every update f <= tol, and plastic steps end on the surface;
// - a small elastic step equals the linear-elastic Jaumann rate result;
// - a rigid rotation keeps I1 and J2 over 10^4 steps (objectivity) and rotates the stress;
// - uniaxial compression yields at the Drucker-Prager strength k_c / (1/sqrt3 - alpha_phi), and
//   plane-strain shear with the plane-strain vertical stress yields at the Mohr-Coulomb radius
//   R = c cos phi - p sin phi (the property the fit of P.20 is built on);
// - cohesion never rises, never drops below 0 and follows P.26 exactly; the structured and
//   confined fractions follow c/c0.
//
// Tolerances. Stress errors are measured relative to the particle's stress scale S = max(|sigma|
// before and after, |sigma_zz|, k_c, the elastic increment). Both sides evaluate the same model
// in IEEE arithmetic along different routes (3x3 tensors and bisection on the host, closed forms
// on the device); each result is a short chain (~50 operations, one cos/sin pair) of terms of at
// most S, so the device carries an absolute error of a few ulps of S per operation: ~1e-14 S in
// double, where we allow 1e-12 S. In float the inputs are rounded to float first (the reference
// sees the same values), and the device's own rounding is ~50 x 6e-8 ~ 3e-6 S in the worst chain;
// we allow 2e-5 S (measured worst figures are printed with TALUS_TEST_VERBOSE=1). A wrong sign, a
// missing term or a wrong factor changes a result by at least dt |L| E ~ 1e-3 S or by the
// plasticity correction, both far above these. The one ill-conditioned spot of the return is the
// square root of R_max^2 = (Y - |q|/sqrt3)(Y + |q|/sqrt3) near the in-plane tension and
// compression limits, where R_max -> 0: an error e S in its factors (each below 2 S) moves R_max^2
// by up to 2 e S^2, so R_max by e S^2 / R_max, and by at most sqrt(2 e) S. With the plane-stress
// corrector many returns end near a limit (the plastic flow takes the in-plane mean toward it), so
// a particle that ends with the shear radius R > 0 (the larger of device and reference) is allowed
// tol + min(sqrt(tol), tol S / R) (the particles that needed more than tol are counted and printed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "core/Constants.hpp"
#include "support/ConstitutiveReference.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus;
using compute::Precision;
using test::ConstitutiveMaterial;
using test::ConstitutiveStress;

constexpr int kIn = 17;   // CONS_TEST_IN of the kernel
constexpr int kOut = 11;  // CONS_TEST_OUT
constexpr int kYielded = 1, kScaled = 2, kTensionCut = 4, kCompressionCap = 8;
constexpr double kDeg = M_PI / 180.0;

struct Particle {
  double L[2][2] = {{0, 0}, {0, 0}};
  ConstitutiveStress s;
  double szz = 0;
  ConstitutiveMaterial mat;
  double c0 = 0, epsC = 0.01, fsc0 = 0, ffc0 = 0;
};

struct DeviceResult {
  ConstitutiveStress s;
  double dlambda = 0, epsV = 0;
  int flags = 0;
  double c = 0, fsc = 0, ffc = 0, fAfter = 0;
  int yieldingSteps = 0;
};

bool verbose() { return std::getenv("TALUS_TEST_VERBOSE") != nullptr; }

double alphaPhi(double phi) { return std::tan(phi) / std::sqrt(9.0 + 12.0 * std::tan(phi) * std::tan(phi)); }
double kcOf(double c, double phi) { return 3.0 * c / std::sqrt(9.0 + 12.0 * std::tan(phi) * std::tan(phi)); }
double shearModulus(const ConstitutiveMaterial& m) { return m.E / (2.0 * (1.0 + m.nu)); }
double bulkModulus(const ConstitutiveMaterial& m) { return m.E / (3.0 * (1.0 - 2.0 * m.nu)); }

/// In-plane shear radius R = sqrt(((xx - yy)/2)^2 + xy^2).
double shearRadius(const ConstitutiveStress& s) { return std::hypot(0.5 * (s.xx - s.yy), s.xy); }

/// I1 and J2 of the 3D state.
void invariants(const ConstitutiveStress& s, double szz, double& I1, double& J2) {
  I1 = s.xx + s.yy + szz;
  const double m = I1 / 3.0, a = s.xx - m, b = s.yy - m, c = szz - m;
  J2 = 0.5 * (a * a + b * b + c * c) + s.xy * s.xy;
}

class ConstitutiveTest : public ::testing::TestWithParam<Precision> {
 protected:
  bool isDouble() const { return GetParam() == Precision::Double; }
  compute::Context& ctx() const { return test::testContext(GetParam()); }
  /// A value as the device holds it.
  double dev(double x) const { return isDouble() ? x : static_cast<double>(static_cast<float>(x)); }
  /// Relative tolerance of stresses against their scale (file header).
  double relTol() const { return isDouble() ? 1e-12 : 2e-5; }

  /// Rounds every input of a particle to the device's precision (so the reference sees them).
  Particle rounded(Particle p) const {
    for (auto& row : p.L)
      for (double& v : row) v = dev(v);
    p.s = {dev(p.s.xx), dev(p.s.yy), dev(p.s.xy)};
    p.szz = dev(p.szz);
    p.mat = {dev(p.mat.E), dev(p.mat.nu), dev(p.mat.phi), dev(p.mat.c), dev(p.mat.psi)};
    p.c0 = dev(p.c0), p.epsC = dev(p.epsC), p.fsc0 = dev(p.fsc0), p.ffc0 = dev(p.ffc0);
    return p;
  }

  /// Runs `steps` updates of every particle on the device with time step dt.
  std::vector<DeviceResult> runDevice(const std::vector<Particle>& ps, double dt, int steps) const {
    const std::size_t n = ps.size();
    std::vector<double> in(n * kIn);
    for (std::size_t i = 0; i < n; ++i) {
      const Particle& p = ps[i];
      const double v[kIn] = {p.L[0][0], p.L[0][1], p.L[1][0], p.L[1][1], p.s.xx, p.s.yy, p.s.xy, p.szz, p.mat.E,
                             p.mat.nu,  p.mat.phi, p.mat.c,   p.mat.psi, p.c0,   p.epsC, p.fsc0, p.ffc0};
      std::copy(v, v + kIn, in.begin() + i * kIn);
    }
    compute::RealBuffer inBuf(ctx(), in.size(), "constitutive in"), outBuf(ctx(), n * kOut, "constitutive out");
    inBuf.upload(in);
    compute::Kernel k(ctx().program("particles/constitutive.cl"), "constitutive_test_steps");
    k.bind(inBuf, outBuf, compute::RealArg{dt}, steps, static_cast<int>(n));
    k.launch(compute::Range{n});
    const std::vector<double> out = outBuf.download();
    std::vector<DeviceResult> r(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double* o = out.data() + i * kOut;
      r[i].s = {o[0], o[1], o[2]};
      r[i].dlambda = o[3], r[i].epsV = o[4], r[i].flags = static_cast<int>(o[5]);
      r[i].c = o[6], r[i].fsc = o[7], r[i].ffc = o[8], r[i].fAfter = o[9];
      r[i].yieldingSteps = static_cast<int>(o[10]);
    }
    return r;
  }

  /// The particle after a device run, as the input of the next run.
  static Particle continued(Particle p, const DeviceResult& r) {
    p.s = r.s;
    p.mat.c = r.c;
    return p;
  }
};

/// Random particles of several kinds (kind = index % 6): 0 well inside the surface with small
/// strain increments, 1 general, 2 stresses far outside the surface, 3 in-plane tension beyond
/// the apex, 4 in-plane compression beyond the in-plane limit, 5 cohesionless with no overburden.
std::vector<Particle> randomParticles(unsigned seed, std::size_t n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, uni(rng)); };
  auto sym = [&]() { return 2.0 * uni(rng) - 1.0; };
  std::vector<Particle> ps(n);
  for (std::size_t i = 0; i < n; ++i) {
    Particle& p = ps[i];
    const int kind = static_cast<int>(i % 6);
    p.mat.E = logUniform(1e6, 1e9);
    p.mat.nu = 0.1 + 0.35 * uni(rng);
    p.mat.phi = (15.0 + 30.0 * uni(rng)) * kDeg;
    p.mat.c = (uni(rng) < 0.3 || kind == 5) ? 0.0 : logUniform(1e2, 1e6);
    p.mat.psi = uni(rng) < 0.5 ? 0.0 : p.mat.phi * uni(rng);
    p.c0 = p.mat.c * (1.0 + uni(rng));
    p.epsC = logUniform(1e-3, 1e-1);
    p.fsc0 = uni(rng), p.ffc0 = uni(rng);
    const double rho = 1500.0 + 1100.0 * uni(rng), H = 0.1 + 30.0 * uni(rng);
    p.szz = (uni(rng) < 0.2 || kind == 5) ? 0.0 : -0.5 * rho * kGravity * H;
    const double S = std::max({kcOf(p.mat.c, p.mat.phi), std::fabs(p.szz), 1e3});
    // Velocity gradient: entries up to 10 / s at dt = 1e-4 s (strain increments up to 1e-3).
    const double gscale = kind == 0 ? 1e-3 : logUniform(1e-3, 10.0);
    for (auto& row : p.L)
      for (double& v : row) v = gscale * sym();
    switch (kind) {
      case 0: p.s = {p.szz + 0.01 * S * sym(), p.szz + 0.01 * S * sym(), 0.01 * S * sym()}; break;
      case 2: p.s = {100.0 * S * sym(), 100.0 * S * sym(), 100.0 * S * sym()}; break;
      case 3: {
        const double m = S * logUniform(1.0, 100.0);
        p.s = {m + 0.3 * S * sym(), m + 0.3 * S * sym(), 0.3 * S * sym()};
        break;
      }
      case 4: {
        const double m = -S * logUniform(10.0, 100.0);
        p.s = {m + 0.3 * S * sym(), m + 0.3 * S * sym(), 0.3 * S * sym()};
        break;
      }
      default: p.s = {3.0 * S * sym(), 3.0 * S * sym(), 3.0 * S * sym()}; break;
    }
  }
  return ps;
}

/// Stress scale of a particle (file header).
double stressScale(const Particle& p, const ConstitutiveStress& after, double dt) {
  const double G = shearModulus(p.mat), K = bulkModulus(p.mat);
  double gmax = 0;
  for (const auto& row : p.L)
    for (double v : row) gmax = std::max(gmax, std::fabs(v));
  return std::max({std::fabs(p.s.xx), std::fabs(p.s.yy), std::fabs(p.s.xy), std::fabs(after.xx), std::fabs(after.yy),
                   std::fabs(after.xy), std::fabs(p.szz), kcOf(p.mat.c, p.mat.phi), dt * (K + 2.0 * G) * 2.0 * gmax});
}

/// The reference over `steps` steps with the kernel's sequence (stress, cohesion, fractions).
struct ReferenceRun {
  ConstitutiveStress s;
  test::ConstitutiveStep last;
  double c = 0, fsc = 0, ffc = 0;
  double cUsed = 0;  // cohesion of the last stress update
  int yieldingSteps = 0;
};

ReferenceRun referenceRun(const Particle& p, double dt, int steps) {
  ReferenceRun r;
  r.s = p.s;
  r.c = p.mat.c;
  for (int k = 0; k < steps; ++k) {
    ConstitutiveMaterial m = p.mat;
    m.c = r.c;
    r.cUsed = r.c;
    r.last = test::referenceStressUpdate(r.s, p.L, p.szz, m, dt);
    r.s = r.last.stress;
    r.yieldingSteps += r.last.yielded;
    r.c = test::referenceCohesion(r.c, p.c0, r.last.epsVRate, p.epsC, dt, r.last.yielded);
  }
  const double b = test::referenceBondFraction(r.c, p.c0);
  r.fsc = p.fsc0 * b, r.ffc = p.ffc0 * b;
  return r;
}

/// Compares device and reference for every particle after `steps` steps.
void expectMatchesReference(const std::vector<Particle>& ps, const std::vector<DeviceResult>& got, double dt,
                            int steps, double tol, bool isDouble, const char* what) {
  double worstStress = 0, worstC = 0;
  int bad = 0, flagDiffs = 0, yielded = 0, cut = 0, capped = 0, scaled = 0, beyondApex = 0, nearLimits = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const ReferenceRun ref = referenceRun(ps[i], dt, steps);
    const DeviceResult& d = got[i];
    const double S = stressScale(ps[i], ref.s, dt);
    const double err = std::max({std::fabs(d.s.xx - ref.s.xx), std::fabs(d.s.yy - ref.s.yy),
                                 std::fabs(d.s.xy - ref.s.xy)}) / S;
    // The ill-conditioned end near the in-plane limits (file header).
    const double rEnd = std::max(shearRadius(ref.s), shearRadius(d.s));
    const double allowed = tol + (rEnd > 0.0 ? std::min(std::sqrt(tol), tol * S / rEnd) : 0.0);
    nearLimits += err > tol;
    worstStress = std::max(worstStress, err / allowed);
    yielded += (d.flags & kYielded) != 0, cut += (d.flags & kTensionCut) != 0;
    capped += (d.flags & kCompressionCap) != 0;
    scaled += (d.flags & kScaled) != 0;
    {
      double I1, J2;
      invariants(ps[i].s, ps[i].szz, I1, J2);
      beyondApex += alphaPhi(ps[i].mat.phi) * I1 > kcOf(ps[i].mat.c, ps[i].mat.phi);
    }
    // A trial state within rounding of the surface may be judged either way; the results then
    // differ by a multiple of that rounding only, which the stress check covers.
    const bool borderline = std::fabs(ref.last.trialYield) <= tol * S;
    // Over several steps a particle that stays on the surface under near-neutral loading meets
    // such a borderline trial every step, so the counts of yielding steps are compared for one
    // step only.
    if (((d.flags & kYielded) != 0) != ref.last.yielded && !borderline) ++flagDiffs;
    if (steps == 1 && !borderline) {
      EXPECT_EQ(d.yieldingSteps, ref.yieldingSteps) << what << " particle " << i;
    }
    if (!(err <= allowed) && ++bad <= 5)
      ADD_FAILURE() << what << " particle " << i << ": device (" << d.s.xx << ", " << d.s.yy << ", " << d.s.xy
                    << "), reference (" << ref.s.xx << ", " << ref.s.yy << ", " << ref.s.xy << "), |diff|/S "
                    << err << " > " << allowed << ", flags " << d.flags;
    // The multiplier as a stress: dlambda times the 3D form of its denominator, 9 alpha alpha_psi K + G
    // (a scale: the plane-stress denominator h of the kernel lies between G/3 and it).
    const ConstitutiveMaterial& m = ps[i].mat;
    const double h = 9.0 * alphaPhi(m.phi) * alphaPhi(m.psi) * bulkModulus(m) + shearModulus(m);
    EXPECT_LE(std::fabs(d.dlambda - ref.last.dlambda) * h, 4 * tol * S) << what << " particle " << i;
    // L_xx + L_yy: one correctly rounded addition on both sides (exact in double for float inputs).
    const double epsV = isDouble ? ref.last.epsVRate : static_cast<double>(static_cast<float>(ref.last.epsVRate));
    EXPECT_EQ(d.epsV, epsV) << what << " particle " << i;
    const double cScale = std::max(ps[i].c0, 1e-300);
    const double cErr = std::fabs(d.c - ref.c) / cScale;
    worstC = std::max(worstC, cErr);
    EXPECT_LE(cErr, tol) << what << " particle " << i << " cohesion";
    EXPECT_NEAR(d.fsc, ref.fsc, tol) << what << " particle " << i;
    EXPECT_NEAR(d.ffc, ref.ffc, tol) << what << " particle " << i;
  }
  EXPECT_EQ(bad, 0) << what << ": worst |diff|/S " << worstStress;
  EXPECT_EQ(flagDiffs, 0) << what;
  // The sample must exercise every branch of the return.
  EXPECT_GT(yielded, static_cast<int>(ps.size() / 4)) << what;
  EXPECT_GT(cut, 0) << what;
  EXPECT_GT(capped, 0) << what;
  EXPECT_GT(scaled, static_cast<int>(ps.size() / 20)) << what;
  EXPECT_GT(beyondApex, static_cast<int>(ps.size() / 10)) << what;
  if (verbose())
    std::fprintf(stderr, "%s: %zu particles (%d start beyond the apex), %d yielded (%d scaled, %d tension cut, "
                 "%d compression cap), %d needed more than tol (ending near an in-plane limit), worst stress "
                 "|diff|/S over its allowance %.3g (tol %.1g), worst cohesion |diff|/c0 %.3g\n",
                 what, ps.size(), beyondApex, yielded, scaled, cut, capped, nearLimits, worstStress, tol, worstC);
}

TEST_P(ConstitutiveTest, MatchesCpuReferenceOnRandomParticles) {
  std::vector<Particle> ps = randomParticles(20240611u, 6000);
  for (Particle& p : ps) p = rounded(p);
  const double dt = dev(1e-4);
  expectMatchesReference(ps, runDevice(ps, dt, 1), dt, 1, relTol(), isDouble(), "one step");
}

TEST_P(ConstitutiveTest, MatchesCpuReferenceOverTwentySteps) {
  // Twenty steps with a fixed velocity gradient: rotation, loading, plastic flow and cohesion loss
  // compound; errors add up over the steps (tolerance x 20).
  std::vector<Particle> ps = randomParticles(77u, 1200);
  for (Particle& p : ps) p = rounded(p);
  const double dt = dev(1e-4);
  expectMatchesReference(ps, runDevice(ps, dt, 20), dt, 20, 20 * relTol(), isDouble(), "twenty steps");
}

TEST_P(ConstitutiveTest, UpdateEndsInsideOrOnTheYieldSurface) {
  std::vector<Particle> ps = randomParticles(99u, 6000);
  for (Particle& p : ps) p = rounded(p);
  const double dt = dev(1e-4);
  const std::vector<DeviceResult> got = runDevice(ps, dt, 1);
  double worst = -1e300, worstOnSurface = 0;
  int onSurface = 0, yielded = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const DeviceResult& d = got[i];
    const double S = stressScale(ps[i], d.s, dt);
    // f of the device's stress, evaluated on the host in double, and the device's own f.
    const double f = test::referenceYield(d.s, ps[i].szz, ps[i].mat);
    worst = std::max(worst, f / S);
    EXPECT_LE(f, relTol() * S) << "particle " << i << " flags " << d.flags;
    EXPECT_LE(d.fAfter, relTol() * S) << "particle " << i << " (device f) flags " << d.flags;
    if (d.flags & kYielded) ++yielded;
    // A plastic step that scaled or cut ends on the surface, not inside it.
    if (d.flags & (kScaled | kTensionCut | kCompressionCap)) {
      ++onSurface;
      worstOnSurface = std::max(worstOnSurface, std::fabs(f) / S);
      EXPECT_LE(std::fabs(f), relTol() * S) << "particle " << i << " flags " << d.flags;
    }
  }
  EXPECT_GT(yielded, 1000);
  if (verbose())
    std::fprintf(stderr, "max f/S after the update %.3g; %d of %d yielded particles end on the surface, "
                 "worst |f|/S there %.3g\n", worst, onSurface, yielded, worstOnSurface);
}

TEST_P(ConstitutiveTest, ElasticStepEqualsLinearElasticJaumannRate) {
  // Strong cohesion keeps every state inside the surface; strain increments ~1e-6.
  std::mt19937_64 rng(5u);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<Particle> ps(500);
  for (Particle& p : ps) {
    p.mat = {1e8 * (1.5 + uni(rng)), 0.25 + 0.1 * uni(rng), (30 + 10 * uni(rng)) * kDeg, 1e7, 5 * kDeg};
    p.c0 = p.mat.c;
    p.szz = -1e5 * (1.0 + uni(rng));
    p.s = {-1e5 + 1e5 * uni(rng), -1e5 + 1e5 * uni(rng), 1e5 * uni(rng)};
    for (auto& row : p.L)
      for (double& v : row) v = 1e-2 * uni(rng);
    p = rounded(p);
  }
  const double dt = dev(1e-4);
  const std::vector<DeviceResult> got = runDevice(ps, dt, 1);
  double worst = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Particle& p = ps[i];
    ASSERT_EQ(got[i].flags, 0) << "particle " << i << " yielded";
    EXPECT_EQ(got[i].dlambda, 0.0);
    // sigma + dt (sigma w^T + w sigma + 2G eps' + lambda* tr(eps') I), in-plane components, with the
    // plane-stress lambda* = E nu / (1 - nu^2) (the layer's vertical stress is prescribed).
    const double G = shearModulus(p.mat), lameStar = p.mat.E * p.mat.nu / (1.0 - p.mat.nu * p.mat.nu);
    const double exx = p.L[0][0], eyy = p.L[1][1], exy = 0.5 * (p.L[0][1] + p.L[1][0]);
    const double w = 0.5 * (p.L[0][1] - p.L[1][0]), ev = exx + eyy;
    const double rxx = 2 * w * p.s.xy, ryy = -2 * w * p.s.xy, rxy = w * (p.s.yy - p.s.xx);
    const ConstitutiveStress lin{p.s.xx + dt * (rxx + 2 * G * exx + lameStar * ev),
                                 p.s.yy + dt * (ryy + 2 * G * eyy + lameStar * ev),
                                 p.s.xy + dt * (rxy + 2 * G * exy)};
    // The exact rotation differs from its forward-Euler form by at most (2 w dt)^2 R (header of
    // the kernel, step 2); the rest is rounding.
    const double S = stressScale(p, lin, dt);
    const double allow = std::pow(2 * w * dt, 2) * shearRadius(p.s) + relTol() * S;
    const double err = std::max({std::fabs(got[i].s.xx - lin.xx), std::fabs(got[i].s.yy - lin.yy),
                                 std::fabs(got[i].s.xy - lin.xy)});
    worst = std::max(worst, err / S);
    EXPECT_LE(err, allow) << "particle " << i;
  }
  if (verbose()) std::fprintf(stderr, "elastic step: worst |device - linear Jaumann|/S %.3g\n", worst);
}

TEST_P(ConstitutiveTest, RigidRotationIsObjective) {
  // L = [[0, -W], [W, 0]] (v = W e_z x r): no strain, spin -W; the body turns by W t. Over 10^4
  // steps of W dt = 1e-3 (10 rad) the stress must turn with it and keep I1 and J2. Forward Euler
  // of the Jaumann terms would multiply J2's deviatoric part by (1 + (2 W dt)^2)^N = 1.04 here.
  const double W = 10.0, dt = dev(1e-4);
  const int steps = isDouble() ? 10000 : 2000;
  std::vector<Particle> ps;
  std::mt19937_64 rng(11u);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int i = 0; i < 64; ++i) {
    Particle p;
    p.L[0][1] = -W, p.L[1][0] = W;
    p.mat = {1e8, 0.3, 35 * kDeg, 1e7, 0.0};
    p.c0 = p.mat.c;
    p.szz = -2e5 * (1.0 + uni(rng)) * 0.5;
    p.s = {-1e5 + 2e5 * uni(rng), -1e5 + 2e5 * uni(rng), 2e5 * uni(rng)};
    ps.push_back(rounded(p));
  }
  const std::vector<DeviceResult> got = runDevice(ps, dt, steps);
  // Accumulated rounding: a few ulps per step.
  const double eps = isDouble() ? 2.2e-16 : 1.2e-7, tol = 8.0 * steps * eps;
  double worstInv = 0, worstRot = 0;
  const double a = W * steps * dt, cs = std::cos(a), sn = std::sin(a);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Particle& p = ps[i];
    ASSERT_EQ(got[i].yieldingSteps, 0) << "particle " << i;
    double I10, J20, I1, J2;
    invariants(p.s, p.szz, I10, J20);
    invariants(got[i].s, p.szz, I1, J2);
    const double S = std::max({std::fabs(p.s.xx), std::fabs(p.s.yy), std::fabs(p.s.xy), std::fabs(p.szz)});
    const double invErr = std::max(std::fabs(I1 - I10) / S, std::fabs(std::sqrt(J2) - std::sqrt(J20)) / S);
    worstInv = std::max(worstInv, invErr);
    EXPECT_LE(invErr, tol) << "particle " << i;
    // sigma(t) = R sigma0 R^T, R the rotation by +W t.
    const double xx = cs * cs * p.s.xx - 2 * cs * sn * p.s.xy + sn * sn * p.s.yy;
    const double yy = sn * sn * p.s.xx + 2 * cs * sn * p.s.xy + cs * cs * p.s.yy;
    const double xy = cs * sn * (p.s.xx - p.s.yy) + (cs * cs - sn * sn) * p.s.xy;
    // The angle itself accumulates rounding of W dt (the host's a carries its own).
    const double rotErr = std::max({std::fabs(got[i].s.xx - xx), std::fabs(got[i].s.yy - yy),
                                    std::fabs(got[i].s.xy - xy)}) / S;
    worstRot = std::max(worstRot, rotErr);
    EXPECT_LE(rotErr, tol + 2.0 * a * eps * steps) << "particle " << i;
  }
  if (verbose())
    std::fprintf(stderr, "rigid rotation, %d steps: worst invariant drift %.3g, worst |sigma - R sigma0 R^T|/S "
                 "%.3g (tol %.3g)\n", steps, worstInv, worstRot, tol);
}

TEST_P(ConstitutiveTest, UniaxialCompressionYieldsAtDruckerPragerStrength) {
  // sigma_zz = 0 and L = diag(-e, nu e) keep sigma_yy = 0 while elastic: sigma_xx = -E e t (plane
  // stress: the bar law of Hooke, E and nu themselves; E* and nu* below are computed from G and
  // lambda* = 2G lambda / (lambda + 2G) as the kernel does, and equal E and nu). Drucker-Prager then yields at |sigma_xx| = k_c / (1/sqrt3 -
  // alpha_phi) (I1 = sigma_xx, sqrt(J2) = |sigma_xx| / sqrt3). The increment per step is set so the
  // strength lies at 500.5 increments: the first yielding step must be step 501.
  const double dt = dev(1e-4);
  std::vector<Particle> ps;
  std::vector<double> strength, increment;
  for (double phiDeg : {15.0, 25.0, 35.0, 45.0})
    for (double c : {1e3, 5e4}) {
      Particle p;
      p.mat = {2e7, 0.3, phiDeg * kDeg, c, 0.0};
      p.c0 = c;
      const double G = shearModulus(p.mat), lame3 = bulkModulus(p.mat) - 2.0 * G / 3.0;
      const double lame = 2.0 * G * lame3 / (lame3 + 2.0 * G);
      const double nuStar = lame / (lame + 2.0 * G), eStar = 4.0 * G * (lame + G) / (lame + 2.0 * G);
      const double sigmaU = kcOf(c, p.mat.phi) / (1.0 / std::sqrt(3.0) - alphaPhi(p.mat.phi));
      const double e = sigmaU / 500.5 / (eStar * dt);
      p.L[0][0] = -e, p.L[1][1] = nuStar * e;
      ps.push_back(rounded(p));
      strength.push_back(sigmaU);
      increment.push_back(eStar * e * dt);
    }
  std::vector<DeviceResult> got = runDevice(ps, dt, 500);
  std::vector<Particle> next;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    ASSERT_EQ(got[i].yieldingSteps, 0) << "particle " << i << " yielded before the strength";
    const double tolS = 1e-4 * strength[i] + relTol() * strength[i] * 500;  // float: input rounding of e
    EXPECT_NEAR(got[i].s.xx, -500.0 * increment[i], tolS) << "elastic path, particle " << i;
    EXPECT_NEAR(got[i].s.yy, 0.0, tolS) << "particle " << i;
    EXPECT_LT(-got[i].s.xx, strength[i]);
    next.push_back(continued(ps[i], got[i]));
  }
  got = runDevice(next, dt, 1);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    EXPECT_EQ(got[i].flags & kYielded, kYielded) << "particle " << i << " did not yield at step 501";
    EXPECT_NEAR(got[i].fAfter, 0.0, relTol() * strength[i] * 10) << "particle " << i;
    // On the surface within one increment of the predicted strength.
    EXPECT_NEAR(-got[i].s.xx, strength[i], 1.0 * increment[i]) << "particle " << i;
    if (verbose()) {
      const double phi = ps[i].mat.phi, c = ps[i].mat.c;
      std::fprintf(stderr, "uniaxial phi %.0f c %.0f: DP strength %.6g, stress at yield %.6g, Mohr-Coulomb "
                   "2c cos/(1 - sin) %.6g\n", phi / kDeg, c, strength[i], -got[i].s.xx,
                   2 * c * std::cos(phi) / (1 - std::sin(phi)));
    }
  }
}

TEST_P(ConstitutiveTest, PlaneStrainShearYieldsAtMohrCoulombRadius) {
  // In-plane mean p, vertical stress at the plane-strain value of a Drucker-Prager state at
  // failure (zero vertical plastic strain rate: s_zz = -2 alpha sqrt(J2), i.e. p - szz = 3 alpha
  // sqrt(J2)), and isochoric in-plane shear L = diag(e, -e): R grows by 2 G e dt a step. The fit of
  // P.20 makes Drucker-Prager yield exactly at Mohr-Coulomb's R = c cos phi - p sin phi.
  const double dt = dev(1e-4);
  std::vector<Particle> ps;
  std::vector<double> rMC, increment;
  for (double phiDeg : {15.0, 30.0, 45.0})
    for (double c : {0.0, 2e4})
      for (double pMean : {-1e4, -3e5}) {
        Particle p;
        p.mat = {5e7, 0.25, phiDeg * kDeg, c, 0.0};
        p.c0 = c;
        const double phi = p.mat.phi, alpha = alphaPhi(phi);
        const double R = c * std::cos(phi) - pMean * std::sin(phi);
        const double sqJ2 = R / std::sqrt(1.0 - 3.0 * alpha * alpha);
        p.szz = pMean - 3.0 * alpha * sqJ2;
        p.s = {pMean, pMean, 0.0};
        const double e = R / 400.5 / (2.0 * shearModulus(p.mat) * dt);
        p.L[0][0] = e, p.L[1][1] = -e;
        ps.push_back(rounded(p));
        rMC.push_back(R);
        increment.push_back(2.0 * shearModulus(p.mat) * e * dt);
      }
  std::vector<DeviceResult> got = runDevice(ps, dt, 400);
  std::vector<Particle> next;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    ASSERT_EQ(got[i].yieldingSteps, 0) << "particle " << i << " yielded before the Mohr-Coulomb radius";
    EXPECT_LT(shearRadius(got[i].s), rMC[i]);
    next.push_back(continued(ps[i], got[i]));
  }
  got = runDevice(next, dt, 1);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    EXPECT_EQ(got[i].flags & kYielded, kYielded) << "particle " << i << " did not yield at step 401";
    const double R = shearRadius(got[i].s);
    EXPECT_NEAR(R, rMC[i], increment[i]) << "particle " << i;
    if (verbose())
      std::fprintf(stderr, "plane strain phi %.0f c %.0f p %.0f: Mohr-Coulomb R %.6g, R at yield %.6g "
                   "(increment %.3g)\n", ps[i].mat.phi / kDeg, ps[i].mat.c, ps[i].s.xx, rMC[i], R, increment[i]);
  }
}

TEST_P(ConstitutiveTest, CohesionNeverRisesNorGoesNegativeAndFractionsFollow) {
  // Particles sheared and dilated hard enough to yield every step; some lose all cohesion within
  // the run. c is read back every 10 steps.
  std::mt19937_64 rng(3u);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<Particle> ps;
  for (int i = 0; i < 200; ++i) {
    Particle p;
    p.mat = {1e8, 0.3, (15 + 30 * uni(rng)) * kDeg, (i % 10 == 0) ? 0.0 : 1e3 * (1 + 100 * uni(rng)),
             (i % 2) ? 0.0 : 10 * kDeg * uni(rng)};
    p.c0 = (i % 20 == 5) ? 0.0 : p.mat.c * (1.0 + uni(rng));  // some with c0 = 0 (never bonded)
    if (p.c0 == 0.0) p.mat.c = 0.0;
    p.epsC = 1e-3 * (1 + 10 * uni(rng));
    p.fsc0 = uni(rng), p.ffc0 = uni(rng);
    p.szz = -1e4 * uni(rng);
    const double g = 0.5 + 5 * uni(rng);
    p.L[0][0] = g * (uni(rng) - 0.2), p.L[1][1] = -g * uni(rng), p.L[0][1] = g * (2 * uni(rng) - 1);
    p.L[1][0] = g * (2 * uni(rng) - 1);
    ps.push_back(rounded(p));
  }
  const double dt = dev(1e-4);
  std::vector<double> cPrev(ps.size());
  std::vector<int> yieldingSteps(ps.size(), 0);
  for (std::size_t i = 0; i < ps.size(); ++i) cPrev[i] = ps[i].mat.c;
  int exhausted = 0;
  for (int round = 0; round < 20; ++round) {
    const std::vector<DeviceResult> got = runDevice(ps, dt, 10);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const DeviceResult& d = got[i];
      const Particle& p = ps[i];
      EXPECT_LE(d.c, cPrev[i]) << "cohesion rose, particle " << i;
      EXPECT_GE(d.c, 0.0) << "particle " << i;
      // P.26: each yielding step removes dt c0 |eps_v| / (2 eps_c), until c = 0.
      const double drop = dt * p.c0 * std::fabs(p.L[0][0] + p.L[1][1]) / (2 * p.epsC);
      const double expect = std::max(0.0, cPrev[i] - d.yieldingSteps * drop);
      EXPECT_NEAR(d.c, expect, 20 * relTol() * std::max(p.c0, 1.0)) << "particle " << i;
      // Fractions follow c/c0 (and keep their initial values when c0 = 0).
      const double b = p.c0 > 0 ? d.c / p.c0 : 1.0;
      EXPECT_NEAR(d.fsc, p.fsc0 * b, 4 * relTol()) << "particle " << i;
      EXPECT_NEAR(d.ffc, p.ffc0 * b, 4 * relTol()) << "particle " << i;
      if (p.c0 > 0 && d.c == 0.0 && cPrev[i] > 0.0) ++exhausted;
      if (d.c == 0.0 && p.c0 > 0) {
        EXPECT_EQ(d.fsc, 0.0);
        EXPECT_EQ(d.ffc, 0.0);
      }
      yieldingSteps[i] += d.yieldingSteps;
      cPrev[i] = d.c;
      ps[i] = continued(ps[i], d);
    }
  }
  int everYielded = 0;
  for (int y : yieldingSteps) everYielded += y > 0;
  EXPECT_GT(everYielded, 100);
  EXPECT_GT(exhausted, 5);  // some particles lose all their cohesion during the run
  if (verbose())
    std::fprintf(stderr, "cohesion: %d of %zu particles yielded, %d lost all cohesion\n", everYielded, ps.size(),
                 exhausted);
}

INSTANTIATE_TEST_SUITE_P(Precisions, ConstitutiveTest, ::testing::Values(Precision::Double, Precision::Float),
                         [](const ::testing::TestParamInfo<Precision>& info) {
                           return std::string(compute::precisionName(info.param));
                         });

}  // namespace
