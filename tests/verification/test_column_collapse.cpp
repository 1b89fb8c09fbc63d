// Granular column collapse against Lube et al. (2005), "Collapses of two-dimensional granular
// columns", Phys. Rev. E 72, 041301 (spec section 10): a rectangular column of length d_i and height
// H0 = a d_i, released from rest against a back wall on a flat horizontal bed, spreads to a final
// runout d_inf (back wall to the front of the deposit). Lube's 2D scalings:
//   (d_inf - d_i) / d_i = 1.2 a            for a <~ 1.8,
//   (d_inf - d_i) / d_i = 1.9 a^(2/3)      for a >~ 2.8.
//
// Model: the two-phase grid model in its dry granular limit (solids only, no fluid), which is
// Savage-Hutter with Coulomb bed friction tan(delta) (docs/two_phase.md). Quasi-2D set-up: a channel
// kWidthCells cells across with walls on every raster edge (FlowSettings::edge = Wall, run-file key
// `Boundary Type=wall`), the back wall at x = 0; every row starts identical, so the flow is 1D and
// the rows must stay bitwise identical (asserted: mirror symmetry in y, every row equal, qsy = 0).
//
// Material: dry quartz sand, the material of Lube's experiments. The friction angles are taken from
// the material, not fitted to the runout: internal friction phi = 32 deg and bed friction
// delta = 27 deg, the middle of the usual ranges for dry quartz sand (phi 30-35 deg, about its angle
// of repose; basal friction on a smooth rigid bed 25-30 deg, a few degrees below phi). Earth pressure:
// Savage-Hutter active/passive K from phi and delta (the default, `Earth Pressure=savage-hutter`;
// K_act = 0.928, K_pass = 2.634 here); the constant K = 1 option (`Earth Pressure=constant`) is run
// for comparison. Density 2650 kg/m^3, grain 0.5 mm, no cohesion (none matters in this limit).
//
// Runout: the outer edge (i + 1) dx of the farthest cell whose final solid thickness exceeds
// kThreshold * H0 (1 %). The validation series also reports 0.1 % H0 and hDry (1e-6 m): the
// continuum Savage-Hutter front is an infinitely thin ballistic tip, so the runout at 0.1 % or hDry is
// larger (2-5 % for a <= 3, up to 10 % at a = 10) and less grid-converged; the conclusions below do
// not depend on the choice.
// "At rest": every solid discharge exactly zero (the implicit Coulomb friction stops motion exactly,
// docs/two_phase.md), checked every 10 steps.
//
// Result (docs/validation_parts/column_collapse.md; measured, 40 cells per d_i): the model runs out
// about twice as far as Lube's experiments for a <= 2 ((d_inf - d_i)/d_i = 2.4a-2.7a against 1.2a)
// and up to three times as far for a = 8-10, where it keeps the linear scaling rel ~ a of every
// depth-averaged Coulomb model instead of Lube's a^(2/3). This is a property of the equations, not of
// the implementation: an independent host solver of the same 1D equations (first-order HLL, the same
// implicit Coulomb friction, refined to 640 cells per d_i) gives the same runouts (asserted below),
// and dimensional analysis of the depth-averaged equations gives rel = F(a / tan(delta), K) with F
// close to 1.3-1.55 K a / tan(delta), so with K = 1 only tan(delta) ~ 1.2 (delta ~ 50 deg, not sand)
// could bring the a <= 1.8 branch to 1.2a; with Savage-Hutter K, raising delta towards phi even
// lengthens the runout (K_act grows to 1.78 at delta = phi = 32 deg; sensitivity run in the series).
// Hence the spec's +-15 % band is not met for any a with physical friction values, and the tests
// below assert what the model must satisfy instead, each bound argued physically:
//  (a) lower bound, statics: a deposit at rest has no slope steeper than repose tan(delta)/K_act
//      (K is active where the velocity gradient is zero, debris_stage.cl) and no point higher than
//      its measured top, so it spans at least the length that holds the column's area under those
//      two constraints (5 % slope allowance for the discrete slope, Granular.PileStopsNearReposeSlope,
//      and one cell);
//  (b) upper bound, dynamics: the tip of the dam-break fan leaves at 2 sqrt(K g H0) and is ballistic
//      (its pressure gradient vanishes), decelerated by tan(delta) g, so no material passes
//      d_i + 2 K H0 / tan(delta) (Mangeney et al. 2000 with theta = 0; the fan extends, K = K_act);
//      asserted on the hDry front (plus one cell);
//  (c) the trend: the runout grows with a;
//  (d) Lube as a one-sided bound: the depth-averaged model lacks every dissipation the experiments
//      add to basal friction (the non-hydrostatic free fall of the column's upper part, the static
//      wedge at the back wall, side-wall friction in Lube's narrow channel), so it must not stop
//      short of Lube's runout by more than the spec's 15 %;
//  (e) the Savage-Hutter K_act < 1 pushes less than K = 1 in the extending collapse: SH runout <= K = 1
//      runout;
//  (f) the K = 1 runs agree with the independent host solver of the same equations within 10 % in
//      d_inf (measured, 20 cells per d_i: -7 % at a = 1, -1 % at a = 3; the engine converges to the
//      reference from below as the grid is refined, see the markdown).
//
// Tests:
//  - ColumnCollapse.RunoutAgainstLube: a in {0.5, 1, 1.5, 3, 8}, 20 cells per d_i, Savage-Hutter K,
//    plus a in {1, 3} with K = 1; mass conserved to round-off, rows identical, the flow comes exactly
//    to rest and (a)-(f). About 7 s on PoCL (2 cores).
//  - ColumnCollapse.SavageHutterDepositComesToRest: regression test of the earth-pressure switching
//    defect this series found (described above that test, now fixed). About 7 s.
//  - ColumnCollapse.DepositComesToRestWithoutKSwitching: its control, the same run with K = 1 and with
//    phi = delta (K_act = K_pass) comes exactly to rest. About 5 s.
//  - ColumnCollapse.ValidationSeries: with TALUS_VALIDATION_OUT set, the full series (40 cells per
//    d_i, both earth-pressure options, a resolution study, the host reference, a delta = phi
//    sensitivity run) written to column_collapse.csv, column_collapse_k1.csv,
//    column_collapse_details.csv and column_profile_a<a>.csv; skipped otherwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kG = 9.81;
constexpr double kPhiDeg = 32.0;     // dry quartz sand, internal friction
constexpr double kDeltaDeg = 27.0;   // dry quartz sand on a smooth rigid bed
constexpr double kDi = 0.1;          // initial column length d_i [m]
constexpr int kWidthCells = 4;       // channel width in cells (even: mirror pairs)
constexpr double kThreshold = 0.01;  // deposit threshold, fraction of H0

/// Lube et al. (2005) 2D runout (d_inf - d_i) / d_i; in the transition 1.8 < a < 2.8, where Lube gives
/// no law, a linear interpolation between the two branches' ends (reported only, never asserted).
double lubeRelativeRunout(double a) {
  if (a <= 1.8) return 1.2 * a;
  if (a >= 2.8) return 1.9 * std::pow(a, 2.0 / 3.0);
  const double lo = 1.2 * 1.8, hi = 1.9 * std::pow(2.8, 2.0 / 3.0);
  return lo + (a - 1.8) / (2.8 - 1.8) * (hi - lo);
}

/// Savage & Hutter (1989) earth-pressure coefficient (as docs/two_phase.md), host side.
double earthPressure(double phi, double delta, bool passive) {
  const double cp = std::cos(phi), cd = std::cos(delta);
  const double root = std::sqrt(std::max(0.0, 1.0 - cp * cp / (cd * cd)));
  return 2.0 / (cp * cp) * (1.0 + (passive ? root : -root)) - 1.0;
}

/// Domain length: the model's runout is at most (b) 2 K a / tan(delta) d_i beyond d_i (K = K_act for
/// Savage-Hutter: 3.6 a d_i here; 3.9 a d_i with K = 1); 10 % and 2 d_i more hold the whole deposit
/// (the far-wall check below fails otherwise).
double domainLength(double a, double K, double deltaDeg) {
  return (2.0 + 1.1 * 2.0 * K * a / std::tan(deltaDeg * kDeg)) * kDi;
}

struct CollapseCase {
  double a = 1.0;
  int cellsPerDi = 20;
  fl::EarthPressure earth = fl::EarthPressure::SavageHutter;
  double deltaDeg = kDeltaDeg;
  double phiDeg = kPhiDeg;
  double tMax = 0;  ///< run at most this long [s]; 0: the default below
  fl::Rheology rheology = fl::Rheology::Coulomb;  ///< basal law (flow/Rheology.hpp)
  std::array<double, 4> rheo{};                   ///< its kernel parameters
};

struct CollapseResult {
  double a = 0, di = kDi, H0 = 0, dx = 0, deltaDeg = kDeltaDeg;
  int nx = 0, ny = 0, steps = 0;
  double dInf = 0;         ///< runout at kThreshold * H0 [m]
  double dInfFine = 0;     ///< runout at 0.1 % H0 [m]
  double dInfDry = 0;      ///< runout at hDry [m]
  double top = 0;          ///< highest final thickness [m]
  double tStop = -1;       ///< time when every solid discharge was exactly zero [s]; -1: never
  double massErr = 0;      ///< |V - V0| / V0 at the end
  double symErr = 0;       ///< max |h(i, j) - h(i, ny-1-j)| and |h(i, j) - h(i, 0)| at the end [m]
  double maxQsy = 0;       ///< max |qsy| at the end
  double wallSeconds = 0;
  double lengthL = 0;      ///< domain length [m]
  std::vector<double> profile;  ///< final h along row 0
  double relative() const { return (dInf - di) / di; }
  double lube() const { return lubeRelativeRunout(a); }
};

/// Farthest outer cell edge with h > thr (0 when none).
double runout(const std::vector<double>& row, double dx, double thr) {
  for (int i = static_cast<int>(row.size()) - 1; i >= 0; --i)
    if (row[i] > thr) return (i + 1) * dx;
  return 0.0;
}

CollapseResult runCollapse(const CollapseCase& c) {
  CollapseResult r;
  r.a = c.a;
  r.deltaDeg = c.deltaDeg;
  r.H0 = c.a * kDi;
  r.dx = kDi / c.cellsPerDi;
  const double kRun = c.earth == fl::EarthPressure::Constant
                          ? 1.0
                          : earthPressure(c.phiDeg * kDeg, c.deltaDeg * kDeg, false);
  r.lengthL = domainLength(c.a, kRun, c.deltaDeg);
  r.nx = static_cast<int>(std::lround(r.lengthL / r.dx));
  r.ny = kWidthCells;
  const Grid grid = Grid::make(r.nx, r.ny, r.dx);
  talus::test::SolidMaterial mat;
  mat.phi = c.phiDeg * kDeg;
  mat.delta = c.deltaDeg * kDeg;
  mat.rhoS = 2650.0;
  mat.grain = 5e-4;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int j = 0; j < r.ny; ++j)
    for (int i = 0; i < c.cellsPerDi; ++i) in.hs[grid.index(i, j)] = r.H0;

  fl::FlowSettings s;
  s.twoPhase = true;
  s.edge = fl::Boundary::Wall;
  s.debris.earthPressure = c.earth;
  s.debris.kConst = 1.0;
  s.debris.deltaFromPhi = false;
  s.debris.rheology = c.rheology;
  s.debris.rheologyParams = c.rheo;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  const double v0 = talus::test::readState(solver).volumeSolid(r.dx);

  // Until every solid discharge is exactly zero, checked every 10 steps; at most tMax (the front
  // stops by 2 sqrt(K g H0) / (g tan(delta)), 0.4 s for a = 1 with K = 1, ~1.2 s for a = 10).
  const double tMax = c.tMax > 0 ? c.tMax : 2.0 + 10.0 * std::sqrt(r.H0 / kG);
  const auto t0 = std::chrono::steady_clock::now();
  int n = 0;
  r.steps = talus::test::advance(solver, talus::test::RunLimits::until(tMax), [&](const fl::FlowSolver& sv) {
    if (++n % 10) return true;
    for (double q : sv.qsx())
      if (q != 0.0) return true;
    for (double q : sv.qsy())
      if (q != 0.0) return true;
    r.tStop = sv.time();
    return false;
  });
  r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const auto st = talus::test::readState(solver);
  r.massErr = std::fabs(st.volumeSolid(r.dx) - v0) / v0;
  for (int j = 0; j < r.ny; ++j)
    for (int i = 0; i < r.nx; ++i) {
      const double h = st.hs[grid.index(i, j)];
      r.symErr = std::max(r.symErr, std::fabs(h - st.hs[grid.index(i, r.ny - 1 - j)]));
      r.symErr = std::max(r.symErr, std::fabs(h - st.hs[grid.index(i, 0)]));
      r.maxQsy = std::max(r.maxQsy, std::fabs(st.qsy[grid.index(i, j)]));
      r.top = std::max(r.top, h);
    }
  r.profile.resize(r.nx);
  for (int i = 0; i < r.nx; ++i) r.profile[i] = st.hs[grid.index(i, 0)];
  r.dInf = runout(r.profile, r.dx, kThreshold * r.H0);
  r.dInfFine = runout(r.profile, r.dx, 1e-3 * r.H0);
  r.dInfDry = runout(r.profile, r.dx, s.hDry);
  return r;
}

/// Independent host solver of the same 1D equations with constant K: h_t + q_x = 0,
/// q_t + (q^2/h + K g h^2 / 2)_x = -tan(delta) g h sgn(u), first-order HLL, reflecting walls at both
/// ends, friction applied implicitly after each step (it stops motion, never reverses it), dry below
/// 1e-6 m, CFL 0.45. Written from the equations for this test, sharing no code with the kernels.
/// Returns the relative runout (d_inf - d_i) / d_i at kThreshold * H0 once every discharge is zero.
double referenceRelativeRunout(double a, double K, double deltaDeg, int cellsPerDi) {
  const double dx = kDi / cellsPerDi, H0 = a * kDi, mu = std::tan(deltaDeg * kDeg), hd = 1e-6;
  const int n = static_cast<int>(std::lround(domainLength(a, K, deltaDeg) / dx));
  std::vector<double> h(n, 0.0), q(n, 0.0), fh(n + 1), fq(n + 1);
  for (int i = 0; i < cellsPerDi; ++i) h[i] = H0;
  auto vel = [hd](double hh, double qq) { return hh > hd ? qq / hh : 0.0; };
  for (double t = 0; t < 20.0;) {
    double smax = 1e-12;
    for (int i = 0; i < n; ++i) smax = std::max(smax, std::fabs(vel(h[i], q[i])) + std::sqrt(K * kG * h[i]));
    const double dt = 0.45 * dx / smax;
    for (int f = 0; f <= n; ++f) {
      double hL, qL, hR, qR;
      if (f == 0) {
        hR = h[0], qR = q[0], hL = hR, qL = -qR;
      } else if (f == n) {
        hL = h[n - 1], qL = q[n - 1], hR = hL, qR = -qL;
      } else {
        hL = h[f - 1], qL = q[f - 1], hR = h[f], qR = q[f];
      }
      const double uL = vel(hL, qL), uR = vel(hR, qR), cL = std::sqrt(K * kG * hL), cR = std::sqrt(K * kG * hR);
      const double sL = std::min(uL - cL, uR - cR), sR = std::max(uL + cL, uR + cR);
      const double fLh = qL, fLq = qL * uL + 0.5 * K * kG * hL * hL;
      const double fRh = qR, fRq = qR * uR + 0.5 * K * kG * hR * hR;
      if (sL >= 0) {
        fh[f] = fLh, fq[f] = fLq;
      } else if (sR <= 0) {
        fh[f] = fRh, fq[f] = fRq;
      } else if (sR > sL) {
        fh[f] = (sR * fLh - sL * fRh + sL * sR * (hR - hL)) / (sR - sL);
        fq[f] = (sR * fLq - sL * fRq + sL * sR * (qR - qL)) / (sR - sL);
      } else {
        fh[f] = fq[f] = 0.0;
      }
    }
    bool moving = false;
    for (int i = 0; i < n; ++i) {
      h[i] = std::max(0.0, h[i] - dt / dx * (fh[i + 1] - fh[i]));
      q[i] -= dt / dx * (fq[i + 1] - fq[i]);
      const double stop = mu * kG * h[i] * dt;
      q[i] = std::fabs(q[i]) <= stop || h[i] <= hd ? 0.0 : q[i] - std::copysign(stop, q[i]);
      moving = moving || q[i] != 0.0;
    }
    t += dt;
    if (!moving) break;
  }
  return (runout(h, dx, kThreshold * H0) - kDi) / kDi;
}

/// (a) The shortest deposit that holds the column's area H0 d_i with no slope above s and no point
/// above `top`: a plateau at `top` and a slope s, or a triangle of slope s when that is lower than
/// `top`. Returned as a relative runout.
double staticMinimumRelative(double H0, double top, double s) {
  const double area = H0 * kDi;
  const double dInf = top * top / (2.0 * s) >= area ? std::sqrt(2.0 * area / s) : area / top + top / (2.0 * s);
  return (dInf - kDi) / kDi;
}

/// (b) The ballistic tip of the dam-break fan: 2 K H0 / tan(delta) beyond d_i, relative.
double ballisticMaximumRelative(double a, double K, double deltaDeg) { return 2.0 * K * a / std::tan(deltaDeg * kDeg); }

double activeK(double deltaDeg) { return earthPressure(kPhiDeg * kDeg, deltaDeg * kDeg, false); }

void print(const CollapseResult& r, const char* tag) {
  std::printf("[ column %s a %.2f ] dx %.4f m (%d x %d), d_inf %.4f m, (d_inf-d_i)/d_i %.3f (Lube %.3f, %+.1f%%), "
              "0.1%%H0: %.3f, hDry: %.3f, top %.4f m, rest at t %.3f s, %d steps, mass err %.1e, sym err %.1e, "
              "|qsy| %.1e, %.1f s\n",
              tag, r.a, r.dx, r.nx, r.ny, r.dInf, r.relative(), r.lube(), 100.0 * (r.relative() / r.lube() - 1.0),
              (r.dInfFine - r.di) / r.di, (r.dInfDry - r.di) / r.di, r.top, r.tStop, r.steps, r.massErr, r.symErr,
              r.maxQsy, r.wallSeconds);
  std::fflush(stdout);
}

/// The invariants every run must satisfy, and the bounds (a), (b), (d).
void checkRun(const CollapseResult& r, double K) {
  EXPECT_LE(r.massErr, 1e-13) << "a " << r.a << ": solid volume not conserved";
  EXPECT_EQ(r.symErr, 0.0) << "a " << r.a << ": rows differ (the quasi-2D channel must stay 1D and mirror-symmetric)";
  EXPECT_EQ(r.maxQsy, 0.0) << "a " << r.a;
  EXPECT_GT(r.tStop, 0.0) << "a " << r.a << ": the collapse never came exactly to rest";
  EXPECT_LT(r.dInfDry, r.lengthL - 2.0 * r.dx) << "a " << r.a << ": the deposit reached the far wall";
  EXPECT_LE(r.top, r.H0) << "a " << r.a;
  const double repose = std::tan(r.deltaDeg * kDeg) / K;
  EXPECT_GE(r.relative(), staticMinimumRelative(r.H0, r.top, 1.05 * repose) - r.dx / r.di)
      << "a " << r.a << ": deposit shorter than any deposit at rest at repose can be";
  EXPECT_LE((r.dInfDry - r.di) / r.di, ballisticMaximumRelative(r.a, K, r.deltaDeg) + r.dx / r.di)
      << "a " << r.a << ": material beyond the ballistic tip of the dam-break fan";
  EXPECT_GE(r.relative(), 0.85 * r.lube()) << "a " << r.a << ": the depth-averaged model stops short of Lube";
}

}  // namespace

TEST(ColumnCollapse, RunoutAgainstLube) {
  const double kAct = activeK(kDeltaDeg);
  std::printf("[ column ] phi %.0f deg, delta %.0f deg, K_act %.4f, K_pass %.4f, repose tan(delta)/K_act %.4f\n",
              kPhiDeg, kDeltaDeg, kAct, earthPressure(kPhiDeg * kDeg, kDeltaDeg * kDeg, true),
              std::tan(kDeltaDeg * kDeg) / kAct);
  std::vector<CollapseResult> sh;
  for (const double a : {0.5, 1.0, 1.5, 3.0, 8.0}) {
    CollapseCase c;
    c.a = a;
    sh.push_back(runCollapse(c));
    print(sh.back(), "SH");
    checkRun(sh.back(), kAct);
  }
  for (std::size_t k = 1; k < sh.size(); ++k)  // (c)
    EXPECT_GT(sh[k].relative(), sh[k - 1].relative()) << "a " << sh[k].a;
  const double slope = std::log(sh[4].relative() / sh[3].relative()) / std::log(sh[4].a / sh[3].a);
  std::printf("[ column ] log-log slope of (d_inf-d_i)/d_i between a = 3 and 8: %.3f (Lube 0.667)\n", slope);
  RecordProperty("column_relative_runout_a1", std::to_string(sh[1].relative()));
  RecordProperty("column_loglog_slope_3_8", std::to_string(slope));

  for (const int idx : {1, 3}) {  // a = 1 and a = 3 with K = 1
    CollapseCase c;
    c.a = sh[idx].a;
    c.earth = fl::EarthPressure::Constant;
    const CollapseResult k1 = runCollapse(c);
    print(k1, "K=1");
    checkRun(k1, 1.0);
    EXPECT_LE(sh[idx].dInf, k1.dInf) << "a " << c.a << ": (e) K_act < 1 must not run out farther than K = 1";
    const double ref = referenceRelativeRunout(c.a, 1.0, kDeltaDeg, 640);
    const double err = (k1.dInf - (1.0 + ref) * kDi) / ((1.0 + ref) * kDi);
    std::printf("[ column K=1 a %.2f ] host reference (640 cells per d_i): (d_inf-d_i)/d_i %.3f, engine d_inf %+.1f%%\n",
                c.a, ref, 100.0 * err);
    EXPECT_LE(std::fabs(err), 0.10) << "a " << c.a << ": (f) engine and host reference of the same equations differ";
  }
  std::fflush(stdout);
}

// Regression test of an engine defect this series found. With `Earth Pressure=savage-hutter`, every
// cell picked K_act or K_pass by the sign of its reconstructed velocity difference, with no threshold,
// so where a deposit settles with velocities at noise level neighbouring cells flipped between
// K_act = 0.928 and K_pass = 2.634. The face pressures of the two sides then differ by
// (K_pass - K_act) g h^2 / 2, a force on the cell (K_pass - K_act) h / (2 tan(delta) dx) times larger
// than the friction tan(delta) g h dx that can hold it (about 80 for h = 6 cm, dx = 1.25 mm), so one
// flip restarted the motion: on a = 1 with 80 cells per d_i the front stopped at t = 0.41 s, but
// 100-170 cells near the back wall still moved at 2-4 cm/s at t = 2.8 s while the deposit at the wall
// sank from 0.077 m to 0.059 m. Fixed: K now rises continuously from K_act to K_pass with the
// contraction rate (kernels/flow/debris_closures.cl, passive_share); the run is at rest at
// t = 0.37 s with a wall height of 0.0818 m. Asserted: the a = 1 deposit on 80 cells per d_i is
// exactly at rest by t = 1.2 s (3 times the front's stopping time), and its height at the back wall
// is within 5 % of that on 40 cells per d_i (10, 20, 40 cells per d_i: 0.0787, 0.0805, 0.0814 m).
TEST(ColumnCollapse, SavageHutterDepositComesToRest) {
  CollapseCase c;
  c.a = 1.0;
  c.cellsPerDi = 40;
  const CollapseResult coarse = runCollapse(c);
  print(coarse, "SH");
  c.cellsPerDi = 80;
  c.tMax = 1.2;
  const CollapseResult fine = runCollapse(c);
  print(fine, "SH");
  EXPECT_GT(fine.tStop, 0.0) << "the Savage-Hutter deposit is still moving at t = " << c.tMax << " s";
  EXPECT_NEAR(fine.profile[0], coarse.profile[0], 0.05 * coarse.profile[0]) << "the deposit at the back wall slumped";
  EXPECT_LE(fine.massErr, 1e-13);
  EXPECT_EQ(fine.symErr, 0.0);
}

// The control for the test above: the same a = 1 run on 80 cells per d_i comes exactly to rest when
// K cannot switch, with K = 1 (measured at rest at t = 0.39 s, wall height 0.0776 m) or with
// Savage-Hutter and phi = delta = 27 deg, where K_act = K_pass = 2 / cos^2(phi) - 1 = 1.519 (measured
// at rest at t = 0.48 s). This localised the defect to the active/passive switching.
TEST(ColumnCollapse, DepositComesToRestWithoutKSwitching) {
  CollapseCase c;
  c.a = 1.0;
  c.cellsPerDi = 80;
  c.tMax = 1.2;
  c.earth = fl::EarthPressure::Constant;
  const CollapseResult k1 = runCollapse(c);
  print(k1, "K=1");
  checkRun(k1, 1.0);
  c.earth = fl::EarthPressure::SavageHutter;
  c.phiDeg = c.deltaDeg = kDeltaDeg;
  const double kEq = earthPressure(c.phiDeg * kDeg, c.deltaDeg * kDeg, false);
  EXPECT_NEAR(kEq, earthPressure(c.phiDeg * kDeg, c.deltaDeg * kDeg, true), 1e-12);
  const CollapseResult eq = runCollapse(c);
  print(eq, "SH phi=delta");
  checkRun(eq, kEq);
}

TEST(ColumnCollapse, ValidationSeries) {
  const char* out = std::getenv("TALUS_VALIDATION_OUT");
  if (!out || !*out) GTEST_SKIP() << "set TALUS_VALIDATION_OUT to write the validation series";
  const std::string dir(out);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir << ": " << ec.message();
  const int fine = 40;
  const double kAct = activeK(kDeltaDeg);
  const char* head = "a,d_i,H0,d_inf,relative_runout,lube_prediction,cells,wall_s\n";
  std::ofstream csv(dir + "/column_collapse.csv"), csvK1(dir + "/column_collapse_k1.csv");
  csv << head;
  csvK1 << head;
  std::ofstream extra(dir + "/column_collapse_details.csv");
  extra << "run,cells_per_di,delta_deg,a,relative_runout_1pct,relative_runout_0p1pct,relative_runout_hdry,"
           "lube_prediction,static_min,ballistic_max,top,t_rest,steps,mass_err,sym_err,wall_s\n";
  auto writeRow = [](std::ofstream& f, const CollapseResult& r) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "%g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.3f\n", r.a, r.di, r.H0, r.dInf, r.relative(),
                  r.lube(), r.nx * r.ny, r.wallSeconds);
    f << buf;
    f.flush();
  };
  auto writeExtra = [&](const char* run, int cpd, double K, const CollapseResult& r) {
    char buf[768];
    std::snprintf(buf, sizeof buf, "%s,%d,%g,%g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.3e,%.3e,%.3f\n", run, cpd,
                  r.deltaDeg, r.a, r.relative(), (r.dInfFine - r.di) / r.di, (r.dInfDry - r.di) / r.di, r.lube(),
                  staticMinimumRelative(r.H0, r.top, std::tan(r.deltaDeg * kDeg) / K),
                  ballisticMaximumRelative(r.a, K, r.deltaDeg), r.top, r.tStop, r.steps, r.massErr, r.symErr,
                  r.wallSeconds);
    extra << buf;
    extra.flush();
  };
  const double series[] = {0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.5, 8.0, 10.0};
  for (const double a : series) {
    CollapseCase c;
    c.a = a;
    c.cellsPerDi = fine;
    const CollapseResult r = runCollapse(c);
    print(r, "SH");
    checkRun(r, kAct);
    writeRow(csv, r);
    writeExtra("savage-hutter", fine, kAct, r);
    char name[64];
    std::snprintf(name, sizeof name, "/column_profile_a%g.csv", a);
    std::ofstream prof(dir + name);
    prof << "x,h\n";
    for (std::size_t i = 0; i < r.profile.size(); ++i) prof << (i + 0.5) * r.dx << "," << r.profile[i] << "\n";
  }
  for (const double a : series) {
    CollapseCase c;
    c.a = a;
    c.cellsPerDi = fine;
    c.earth = fl::EarthPressure::Constant;
    const CollapseResult r = runCollapse(c);
    print(r, "K=1");
    checkRun(r, 1.0);
    writeRow(csvK1, r);
    writeExtra("constant-K1", fine, 1.0, r);
  }
  // Host reference of the K = 1 equations (first-order HLL, 640 cells per d_i).
  for (const double a : series) {
    const double ref = referenceRelativeRunout(a, 1.0, kDeltaDeg, a > 5 ? 320 : 640);
    std::printf("[ column reference K=1 a %.2f ] (d_inf-d_i)/d_i %.3f\n", a, ref);
    char buf[256];
    std::snprintf(buf, sizeof buf, "host-reference-K1,%d,%g,%g,%.6g,,,%.6g,,%.6g,,,,,,\n", a > 5 ? 320 : 640, kDeltaDeg,
                  a, ref, lubeRelativeRunout(a), ballisticMaximumRelative(a, 1.0, kDeltaDeg));
    extra << buf;
    extra.flush();
  }
  // Resolution: a = 1 and a = 5 on 10, 20, 80 cells per d_i (40 above); the 80-cell runs are capped
  // at 1.5 s, long after the front has stopped (0.41 s, 0.84 s).
  for (const double a : {1.0, 5.0})
    for (const int cpd : {10, 20, 80}) {
      CollapseCase c;
      c.a = a;
      c.cellsPerDi = cpd;
      if (cpd == 80) c.tMax = 1.5;
      const CollapseResult r = runCollapse(c);
      print(r, "SH resolution");
      checkRun(r, kAct);
      writeExtra("savage-hutter", cpd, kAct, r);
    }
  // Sensitivity to the bed friction (not a fit): delta = phi = 32 deg, the run-file default
  // `Bed Friction Equals IFA=1`.
  for (const double a : {0.5, 1.0, 2.0, 5.0}) {
    CollapseCase c;
    c.a = a;
    c.cellsPerDi = fine;
    c.deltaDeg = kPhiDeg;
    const CollapseResult r = runCollapse(c);
    print(r, "SH delta=phi");
    checkRun(r, activeK(kPhiDeg));
    writeExtra("savage-hutter-delta-eq-phi", fine, activeK(kPhiDeg), r);
    c.earth = fl::EarthPressure::Constant;
    const CollapseResult k1 = runCollapse(c);
    print(k1, "K=1 delta=phi");
    checkRun(k1, 1.0);
    writeExtra("constant-K1-delta-eq-phi", fine, 1.0, k1);
  }
}

// The collapse with the Pouliquen-Forterre mu(I) basal law (kernels/flow/basal_rheology.cl) and
// the glass-bead parameters of Pouliquen & Forterre (2002): zeta_1 = 21 deg, zeta_2 = 30.7 deg,
// beta = 0.136, L = 0.65 mm, K = 1. Measured (20 cells per d_i): (d_inf - d_i)/d_i = 1.30, 2.80, 4.35,
// 9.30, 26.45 for a = 0.5, 1, 1.5, 3, 8, i.e. 2.2-3.5 times Lube's: mu(I) does not bring the
// depth-averaged collapse to Lube's runouts (issue 19 asked for +-15 %). The friction lies between
// tan(zeta_1) (fast, thick) and mu_stop -> tan(zeta_2) (thin, slow), and what the depth-averaged
// equations miss is not basal friction but the column's non-hydrostatic free fall: the full 2D mu(I)
// rheology reproduces Lube's collapses (Lagree, Staron & Popinet 2011, J. Fluid Mech. 686), while
// shallow models need the vertical motion modelled (Larrieu, Staron & Hinch 2006, J. Fluid Mech.
// 554). Asserted here what the law must give: since tan(zeta_1) <= mu <= tan(zeta_2) pointwise, the
// runout lies between those of the Coulomb collapses with delta = zeta_2 and delta = zeta_1 (the
// same grid, K = 1), strictly inside (the law is neither), and the usual invariants hold.
TEST(ColumnCollapse, MuIRunoutBetweenItsCoulombBounds) {
  const double z1 = 21.0, z2 = 30.7;
  for (const double a : {1.0, 3.0}) {
    CollapseCase c;
    c.a = a;
    c.earth = fl::EarthPressure::Constant;
    c.tMax = 4.0;
    c.deltaDeg = z1;
    const CollapseResult lo = runCollapse(c);  // least friction: longest runout
    c.deltaDeg = z2;
    const CollapseResult hi = runCollapse(c);
    c.deltaDeg = kDeltaDeg;  // unused by mu(I); bounds (a) and (b) of checkRun with delta = zeta_1
    c.rheology = fl::Rheology::MuI;
    c.rheo = {std::tan(z1 * kDeg), std::tan(z2 * kDeg), 0.136, 6.5e-4};
    CollapseResult mi = runCollapse(c);
    print(lo, "Coulomb z1");
    print(hi, "Coulomb z2");
    print(mi, "mu(I)");
    EXPECT_LT(mi.dInf, lo.dInf) << "a " << a << ": mu(I) ran out as far as Coulomb with delta = zeta_1";
    EXPECT_GT(mi.dInf, hi.dInf) << "a " << a << ": mu(I) stopped as short as Coulomb with delta = zeta_2";
    EXPECT_LE(mi.massErr, 1e-13);
    EXPECT_EQ(mi.symErr, 0.0);
    EXPECT_GT(mi.tStop, 0.0) << "a " << a << ": the mu(I) collapse never came exactly to rest";
    mi.deltaDeg = z1;  // the weakest friction the law has, for the static and ballistic bounds
    checkRun(mi, 1.0);
  }
}
