// Verification of the two-phase (solids + fluid) grid model, FlowSettings::twoPhase
// (kernels/flow/debris_stage.cl, spec sections 4 and 10), with both phases present:
//  - TwoPhase.DragRelaxationConservesMomentum: uniform layers with different phase velocities and
//    no other force: the drag relaxes the relative velocity as the exact two-phase relaxation with
//    the drag coefficient of the closure (computed independently on the host,
//    support/DebrisScene.hpp), linear and quadratic, with and without virtual mass, conserving
//    rho_s q_s + rho_f q_f to round-off; with the drag off the phases keep their velocities;
//  - TwoPhase.QuadraticDragIsIsotropic: the quadratic law acts on |u_f - u_s| of the vector;
//  - TwoPhase.VolumeConservedWithWalls: the volume of each phase over a rough bed, closed, open and
//    level edges;
//  - TwoPhase.SymmetricReleaseStaysSymmetric: x <-> y and mirror symmetry;
//  - TwoPhase.MixtureAtRestStaysAtRest: a lake over a submerged solid layer held by friction, between
//    walls and against level edges.
// Double precision throughout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/Constants.hpp"
#include "support/Analytic.hpp"
#include "support/DebrisScene.hpp"
#include "support/GranularAnalytic.hpp"
#include "support/TestDevice.hpp"

namespace an = talus::analytic;
namespace fl = talus::flow;
namespace dr = talus::test::drag;
using talus::Grid;
using talus::compute::Precision;
using talus::test::cellX;
using talus::test::cellY;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

fl::FlowSettings twoPhaseSettings(fl::Boundary edge) {
  fl::FlowSettings s;
  s.twoPhase = true;
  s.edge = edge;
  return s;
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// Drag relaxation. A uniform layer h_s, h_f at rest on a flat frictionless bed (delta = 0,
// Manning 0, no slope), solids moving at us0 = 0.2 m/s and the fluid at uf0 = 1.0 m/s along x, in a
// closed strip of nx cells of 1 m (ny = 1, walls). Away from the walls every face sees the same
// states on both sides, so the fluxes cancel bitwise and the only force is the exchange: the
// SSP-RK2 step applies the exact momentum-conserving relaxation S_ds (w = u_f - u_s decays as
// exp(-lambda ds), or w / (1 + lambda |w| ds) for the quadratic law) once per stage:
//   stage 1: U1 = S_dt(U0),   stage 2: U = S_dt/2((U0 + U1) / 2)          (debris_stage.cl header).
// The walls disturb the strip, but a stage reads two cells either side, so after N steps cells more
// than 4N + 2 cells from the walls are still bitwise uniform; nx = 8N + 17 keeps the middle cells
// there. Checked in each case, for every step:
//  - h_s, h_f unchanged and the middle cells bitwise uniform;
//  - rho_s q_s + rho_f q_f conserved to 1e-14 relative (measured <= 6e-16: the relaxation writes
//    q_s, q_f from the conserved total P and the new w, exact up to a few roundings);
//  - w equals the recursion above with the host coefficient (DebrisScene.cpp, an independent
//    implementation of the closure of debris_closures.cl) to 1e-12 relative (measured <= 4e-15):
//    this pins the drag coefficient C, the virtual-mass coefficient and the relaxation law;
//  - w against the exact continuous relaxation analytic::linearDragRelaxation /
//    quadraticDragRelaxation with the same coefficient: the stage structure above is a splitting
//    whose step factor for the linear law is e^{-x/2} (1 + e^{-x}) / 2 = e^{-x} (1 + x^2/8 + O(x^3)),
//    x = lambda dt, i.e. a relative error of exp(N x^2 / 8) - 1 after N steps (first order in dt:
//    halving dt at fixed lambda t halves it, printed). With x = 0.1 and lambda t = 4 that is 5.1%
//    (measured 5.13%); asserted <= 1.25 (exp(N x0^2 / 8) - 1) with x0 = lambda dt (linear) or
//    k' |w0| dt (quadratic, where the rate falls with |w| so the bound is conservative; measured
//    0.93%). A drag coefficient off by 1% would move w by about lambda t = 4% at the end and fail the
//    recursion check by orders of magnitude;
//  - w never changes sign and |w| never grows (the exchange never overshoots);
//  - stiff drag (multiplier 1e4 times larger, x = 1e3): after one step both phases move with the
//    mixture velocity P / (m_s + m_f): w = 0 to 1e-13 (linear: w0 e^{-500} (1 + e^{-1000}) / 2) or
//    about 2 w0 / x (quadratic, whose stiff limit decays algebraically);
//  - drag off: both velocities bitwise unchanged.
// Grain sizes cover the three settling-velocity regimes of the closure (Stokes d <= 0.1 mm, blend,
// Zanke d >= 1 mm) and solid fractions 0.3 to 0.6.
namespace {

constexpr double kUs0 = 0.2, kUf0 = 1.0, kRhoS = 2500.0;

struct DragCase {
  const char* name;
  fl::DragLaw law;
  bool virtualMass;
  double hs, hf, grain, multiplier;
  double x0 = 0.1;  ///< lambda dt (linear) or k' |w0| dt (quadratic)
  int steps = 40;
};

/// One step of the documented stage structure for the relative velocity w.
double relaxStep(fl::DragLaw law, double rate, double w, double dt) {
  auto relax = [&](double v, double ds) {
    if (law == fl::DragLaw::Linear) return v * std::exp(-rate * ds);
    if (law == fl::DragLaw::Quadratic) return v / (1.0 + rate * std::fabs(v) * ds);
    return v;
  };
  const double w1 = relax(w, dt);
  return relax(0.5 * (w + w1), 0.5 * dt);
}

struct DragResult {
  double momentumErr = 0, recursionErr = 0, analyticErr = 0, analyticBound = 0, rate = 0, dt = 0;
  double wEnd = 0, wExact = 0;
  bool uniform = true, thicknessKept = true, monotone = true;
};

DragResult runDragCase(const DragCase& c, double multiplierScale = 1.0) {
  const int N = c.steps;
  const int nx = 8 * N + 17, ic = nx / 2, safe = 4 * N + 3;
  const Grid grid = Grid::make(nx, 1, 1.0);
  talus::test::SolidMaterial mat;
  mat.delta = 0.0;
  mat.rhoS = kRhoS;
  mat.grain = c.grain;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int i = 0; i < nx; ++i) {
    in.hs[i] = c.hs;
    in.h[i] = c.hf;
    in.qsx[i] = c.hs * kUs0;
    in.qx[i] = c.hf * kUf0;
  }
  fl::FlowSettings s = twoPhaseSettings(fl::Boundary::Wall);
  s.debris.deltaFromPhi = false;
  s.debris.drag = c.law;
  s.debris.virtualMass = c.virtualMass;
  s.debris.dragMultiplier = c.multiplier * multiplierScale;
  const dr::UniformLayer layer = dr::uniformLayer(s.debris, c.hs, c.hf, kRhoS, c.grain);
  DragResult r;
  r.rate = layer.rate();
  const double w0 = kUf0 - kUs0;
  const double speedRate = c.law == fl::DragLaw::Quadratic ? r.rate * std::fabs(w0) : r.rate;
  r.dt = c.law == fl::DragLaw::Off ? 0.01 : c.x0 / speedRate;
  r.analyticBound = 1.25 * std::expm1(N * c.x0 * c.x0 / 8.0);

  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  EXPECT_LE(r.dt, solver.stableDt()) << c.name;
  const double rhoF = s.debris.fluidDensity;
  const double P0 = kRhoS * c.hs * kUs0 + rhoF * c.hf * kUf0;
  const double Pscale = kRhoS * c.hs * std::fabs(kUs0) + rhoF * c.hf * std::fabs(kUf0);
  double wd = w0, wPrev = w0;
  for (int n = 1; n <= N; ++n) {
    solver.step(r.dt);
    const auto st = talus::test::readState(solver);
    for (int i = safe; i < nx - safe; ++i) {
      r.uniform = r.uniform && st.hs[i] == st.hs[ic] && st.hf[i] == st.hf[ic] && st.qsx[i] == st.qsx[ic] &&
                  st.qfx[i] == st.qfx[ic] && st.qsy[i] == 0.0 && st.qfy[i] == 0.0;
      r.thicknessKept = r.thicknessKept && st.hs[i] == c.hs && st.hf[i] == c.hf;
    }
    const double us = st.qsx[ic] / st.hs[ic], uf = st.qfx[ic] / st.hf[ic], w = uf - us;
    const double P = kRhoS * st.qsx[ic] + rhoF * st.qfx[ic];
    r.momentumErr = std::max(r.momentumErr, std::fabs(P - P0) / Pscale);
    wd = relaxStep(c.law, r.rate, wd, r.dt);
    r.recursionErr = std::max(r.recursionErr, std::fabs(w - wd) / std::fabs(wd));
    const double t = n * r.dt;
    const an::PhaseVelocities ex =
        c.law == fl::DragLaw::Quadratic
            ? an::quadraticDragRelaxation(layer.ms, layer.mf, kUs0, kUf0, layer.k, t, layer.mvm)
            : an::linearDragRelaxation(layer.ms, layer.mf, kUs0, kUf0, layer.k, t, layer.mvm);
    const double wEx = ex.uf - ex.us;
    r.analyticErr = std::max(r.analyticErr, std::fabs(w - wEx) / std::fabs(wEx));
    r.monotone = r.monotone && w * w0 >= 0.0 && std::fabs(w) <= std::fabs(wPrev);
    wPrev = w;
    r.wEnd = w;
    r.wExact = wEx;
  }
  return r;
}

}  // namespace

TEST(TwoPhase, DragRelaxationConservesMomentum) {
  const DragCase cases[] = {
      {"linear, virtual mass, Zanke d = 1 cm", fl::DragLaw::Linear, true, 0.5, 0.5, 0.01, 100.0},
      {"linear, no virtual mass, Stokes d = 50 um", fl::DragLaw::Linear, false, 0.3, 0.7, 5e-5, 100.0},
      {"quadratic, virtual mass, blend d = 0.5 mm", fl::DragLaw::Quadratic, true, 0.6, 0.4, 5e-4, 1000.0},
      {"quadratic, no virtual mass, Zanke d = 1 cm", fl::DragLaw::Quadratic, false, 0.5, 0.5, 0.01, 1000.0},
      {"drag off", fl::DragLaw::Off, true, 0.5, 0.5, 0.01, 100.0},
  };
  for (const DragCase& c : cases) {
    const DragResult r = runDragCase(c);
    std::printf("[ drag: %s ] alpha_s %.1f, rate %.5g %s, dt %.4g s, %d steps: w %.6e (exact %.6e)\n"
                "  momentum error %.2e, recursion error %.2e, analytic error %.3e (bound %.3e)\n",
                c.name, c.hs / (c.hs + c.hf), r.rate, c.law == fl::DragLaw::Quadratic ? "1/m" : "1/s", r.dt, c.steps,
                r.wEnd, r.wExact, r.momentumErr, r.recursionErr, r.analyticErr, r.analyticBound);
    EXPECT_TRUE(r.uniform) << c.name;
    EXPECT_TRUE(r.thicknessKept) << c.name;
    EXPECT_TRUE(r.monotone) << c.name;
    EXPECT_LE(r.momentumErr, 1e-14) << c.name;
    EXPECT_LE(r.recursionErr, 1e-12) << c.name;
    if (c.law == fl::DragLaw::Off) {
      EXPECT_EQ(r.rate, 0.0);
      EXPECT_EQ(r.wEnd, kUf0 - kUs0) << "with the drag off the phases keep their velocities";
      EXPECT_EQ(r.momentumErr, 0.0);
    } else {
      EXPECT_GT(r.analyticErr, 0.0);
      EXPECT_LE(r.analyticErr, r.analyticBound) << c.name;
    }
  }

  // Splitting order: the linear case with half the step at the same lambda t.
  DragCase fine = cases[0];
  fine.x0 = 0.05;
  fine.steps = 80;
  const double coarseErr = runDragCase(cases[0]).analyticErr, fineErr = runDragCase(fine).analyticErr;
  const double order = an::observedOrder(coarseErr, fineErr, 2.0);
  std::printf("[ drag: time step ] lambda dt 0.1 -> 0.05 at lambda t = 4: analytic error %.3e -> %.3e, order %.3f "
              "(the per-stage exact relaxation inside SSP-RK2 is first order in dt)\n",
              coarseErr, fineErr, order);
  EXPECT_GE(order, 0.9);

  // Stiff drag: one step with lambda dt ~ 1e3 leaves both phases at the mixture velocity.
  for (const bool quadratic : {false, true}) {
    DragCase stiff = cases[quadratic ? 3 : 0];
    stiff.steps = 1;
    stiff.x0 = 1e3;
    const DragResult r = runDragCase(stiff, 1e4);
    const double ms = kRhoS * stiff.hs, mf = 1000.0 * stiff.hf;
    const double U = (ms * kUs0 + mf * kUf0) / (ms + mf);
    // w after one step: w0 e^{-500} (1 + e^{-1000}) / 2 (linear) or ~ 2 w0 / x0 (quadratic).
    std::printf("[ drag: stiff %s ] lambda dt %.0f: w %.3e, mixture velocity %.6f, momentum error %.2e\n",
                quadratic ? "quadratic" : "linear", stiff.x0, r.wEnd, U, r.momentumErr);
    EXPECT_LE(r.momentumErr, 1e-14);
    EXPECT_LE(std::fabs(r.wEnd), quadratic ? 4.0 * (kUf0 - kUs0) / stiff.x0 : 1e-13);
    EXPECT_TRUE(r.monotone);
  }
  std::fflush(stdout);
}

// ------------------------------------------------------------------------------------------------
// Isotropy of the quadratic drag. The drag of spec section 4 (P.31) is D (u_f - u_s) with
// D ~ |u_f - u_s|^{j-1}, the magnitude of the relative velocity vector, so the exchange does not
// depend on the direction of the flow. Same uniform layer as above on a square grid (97 x 97 cells,
// walls, N = 10 steps, the centre cell bitwise uniform by the same domain-of-dependence argument),
// with the relative velocity along the diagonal: each component of w must follow the 1D recursion
// with |w| the vector magnitude, and for the linear law with lambda (drag_step, phase_exchange.cl;
// a per-component |w_c| would give the rate lambda |w| / sqrt(2) on the diagonal: a drag that
// depends on the orientation of the grid).
TEST(TwoPhase, QuadraticDragIsIsotropic) {
  const int N = 10, n = 8 * N + 17, ic = n / 2;
  const double hs = 0.5, hf = 0.5, grain = 0.01;
  const double c45 = std::sqrt(0.5);
  for (const fl::DragLaw law : {fl::DragLaw::Linear, fl::DragLaw::Quadratic}) {
    const bool quadratic = law == fl::DragLaw::Quadratic;
    const Grid grid = Grid::make(n, n, 1.0);
    talus::test::SolidMaterial mat;
    mat.delta = 0.0;
    mat.rhoS = kRhoS;
    mat.grain = grain;
    fl::FlowInput in = talus::test::debrisInput(grid, mat);
    for (std::size_t k = 0; k < grid.cells(); ++k) {
      in.hs[k] = hs;
      in.h[k] = hf;
      in.qsx[k] = in.qsy[k] = hs * kUs0 * c45;
      in.qx[k] = in.qy[k] = hf * kUf0 * c45;
    }
    fl::FlowSettings s = twoPhaseSettings(fl::Boundary::Wall);
    s.debris.deltaFromPhi = false;
    s.debris.drag = law;
    s.debris.dragMultiplier = quadratic ? 1000.0 : 100.0;
    const double rate = dr::uniformLayer(s.debris, hs, hf, kRhoS, grain).rate();
    const double w0 = kUf0 - kUs0;
    const double dt = 0.4 / (quadratic ? rate * w0 : rate);
    fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
    solver.setInput(in);
    double wd = w0, err = 0, asym = 0, wMag = 0;
    for (int step = 1; step <= N; ++step) {
      solver.step(dt);
      wd = relaxStep(law, rate, wd, dt);  // the magnitude; the direction stays on the diagonal
      const auto st = talus::test::readState(solver);
      const std::size_t k = grid.index(ic, ic);
      const double wx = st.qfx[k] / st.hf[k] - st.qsx[k] / st.hs[k], wy = st.qfy[k] / st.hf[k] - st.qsy[k] / st.hs[k];
      wMag = std::hypot(wx, wy);
      err = std::max(err, std::fabs(wMag - wd) / wd);
      asym = std::max(asym, std::fabs(wx - wy) / wMag);
    }
    std::printf("[ drag 2D %s ] relative velocity along the diagonal: |w| %.6e, expected %.6e, error %.3e, "
                "|wx - wy| / |w| %.1e\n",
                quadratic ? "quadratic" : "linear", wMag, wd, err, asym);
    EXPECT_LE(asym, 1e-14);
    EXPECT_LE(err, 1e-12) << (quadratic ? "quadratic" : "linear") << " drag is not isotropic";
  }
  std::fflush(stdout);
}

// ------------------------------------------------------------------------------------------------
// Volume conservation. 48 x 48 cells of 1 m over the rough DEM of support/FlowScene.hpp (hills of
// +-1.2 m and +-0.2 m per-cell noise, slopes up to ~0.5), random h_s in [0, 0.4] m and h_f in
// [0, 0.6] m (each zero in 20% of the cells, so there are dry cells, solid-only, fluid-only and
// mixed cells), random phi 25-35 deg, rho_s 2200-2800 kg/m^3 and grain sizes 30 um - 3 cm (every
// settling regime), Savage-Hutter K, drag with virtual mass, Manning 0.03; 300 CFL steps (about
// 11-15 s). The interior fluxes cancel pairwise and each phase's update is in conservation form, so
// with walls each phase's volume must stay constant, and with open edges the volume plus the
// cumulative outflow of the phase (diagnostics outflow / outflowSolid, summed over steps). The
// tolerance 1e-12 relative covers the summation of ~2300 terms per step over 300 steps (measured
// <= 3.1e-16, the last bits of the reduction); no thickness may go negative.
namespace {

fl::FlowInput randomScene(const Grid& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  fl::FlowInput in = talus::test::debrisInput(g, {}, 0.03);
  in.bed = talus::test::roughDem(g, seed, 0.2);
  for (std::size_t k = 0; k < g.cells(); ++k) {
    in.hs[k] = u01(rng) < 0.2 ? 0.0 : 0.4 * u01(rng);
    in.h[k] = u01(rng) < 0.2 ? 0.0 : 0.6 * u01(rng);
    in.phi[k] = (25.0 + 10.0 * u01(rng)) * kDeg;
    in.rhoS[k] = 2200.0 + 600.0 * u01(rng);
    in.grain[k] = std::pow(10.0, -4.5 + 3.0 * u01(rng));
  }
  return in;
}

}  // namespace

TEST(TwoPhase, VolumeConservedWithWalls) {
  const Grid g = Grid::make(48, 48, 1.0);
  for (const fl::Boundary edge : {fl::Boundary::Wall, fl::Boundary::Open, fl::Boundary::Level}) {
    const bool open = edge != fl::Boundary::Wall;
    const fl::FlowSettings s = twoPhaseSettings(edge);
    fl::FlowSolver solver(talus::test::testContext(Precision::Double), g, s);
    solver.setInput(randomScene(g, 7u));
    const double vs0 = solver.diagnostics().volumeSolid, vf0 = solver.diagnostics().volume;
    double outS = 0, outF = 0, errS = 0, errF = 0, minH = 0;
    const int steps = talus::test::advance(solver, talus::test::RunLimits::steps(300), [&](const fl::FlowSolver& sv) {
      const fl::FlowDiagnostics& d = sv.diagnostics();
      outS += d.outflowSolid;
      outF += d.outflow;
      errS = std::max(errS, std::fabs(d.volumeSolid + outS - vs0) / vs0);
      errF = std::max(errF, std::fabs(d.volume + outF - vf0) / vf0);
      return true;
    });
    const auto st = talus::test::readState(solver);
    for (std::size_t k = 0; k < g.cells(); ++k) minH = std::min({minH, st.hs[k], st.hf[k]});
    // The host sum of the final fields agrees with the device reduction.
    const double hostS = std::fabs(st.volumeSolid(g.dx) + outS - vs0) / vs0;
    const double hostF = std::fabs(st.volumeFluid(g.dx) + outF - vf0) / vf0;
    std::printf("[ volume, %s edges ] %d steps, t %.2f s: solids %.4f m^3 (out %.4f), fluid %.4f m^3 (out %.4f); "
                "max relative error solids %.2e, fluid %.2e (host sums %.1e, %.1e), min thickness %.1e\n",
                open ? (edge == fl::Boundary::Level ? "level" : "open") : "wall", steps, solver.time(), vs0, outS, vf0, outF, errS, errF, hostS, hostF, minH);
    EXPECT_EQ(steps, 300);
    EXPECT_LE(errS, 1e-12);
    EXPECT_LE(errF, 1e-12);
    EXPECT_LE(hostS, 1e-12);
    EXPECT_LE(hostF, 1e-12);
    EXPECT_GE(minH, 0.0);
    if (open) {
      EXPECT_GT(outS, 0.0) << "solids should leave through the open and level edges";
      EXPECT_GT(outF, 0.0) << "fluid should leave through the open and level edges";
    } else {
      EXPECT_EQ(outS, 0.0);
      EXPECT_EQ(outF, 0.0);
    }
  }
  std::fflush(stdout);
}

// ------------------------------------------------------------------------------------------------
// Symmetry. 48 x 48 cells of 1 m, walls, default settings (Savage-Hutter K with active/passive
// switching, drag with virtual mass, Manning 0.04, slope correction on), 150 CFL steps (4-5 s,
// speeds up to 10-16 m/s): a conical solid release and a fluid cone of different shape on a bowl plus
// per-cell noise.
//  - Transposition scene: everything symmetric under x <-> y (bowl centred on the diagonal, noise
//    r(min(i,j), max(i,j)), release centred at (0.35 L, 0.35 L)), not mirror symmetric. The two
//    directions run the same code with the roles of the axes swapped and every cross-direction
//    sum is commutative, so the run is bitwise transposition-symmetric, except that the slope
//    correction cos^2 = 1 / (1 + bx^2 + by^2) (flow/SlopeGravity.cpp) evaluates (1 + bx^2) + by^2,
//    which is not bitwise symmetric: with the slope correction the fields agree to round-off
//    (asserted 1e-13 of the field maxima, measured 2e-15), without it bitwise (asserted).
//  - Mirror scene: symmetric under x -> L - x (bowl and release centred on x = L/2, noise
//    r(min(i, n-1-i), j)). Mirroring swaps the arguments of every limiter and flux evaluation, so
//    this holds to round-off only, amplified by the limiter and friction switches over 150 steps:
//    asserted 2e-12 of the field maxima (measured 3e-15 at 150 steps with the kernels before the
//    solids' faces between different beds, 3e-13 with an earlier version). Since those faces (issue
//    13) the mass reaches cells whose solid momentum passes through zero after 11-18 steps (11
//    with the curvature term off, the default; 18 with it on), where the friction stop decides on a
//    round-off difference in one frame and not in the other, and the cell's lock then closes faces
//    to mass in one frame only; from then on the frames differ by O(1e-5) locally (measured 2e-16
//    at step 10, 1.6e-6 at step 11). So the mirror is checked over the first 10 steps (0.29 s, max
//    speed 2.0 m/s), where every such switch still agrees.
namespace {

constexpr int kMirrorSteps = 10;

fl::FlowInput symmetricScene(const Grid& g, bool transposition) {
  const int n = g.nx;
  std::mt19937 rng(99u);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<double> r(static_cast<std::size_t>(n) * n);
  for (double& v : r) v = u01(rng);
  fl::FlowInput in = talus::test::debrisInput(g, {}, 0.04);
  const double L = n * g.dx;
  const double bx = transposition ? 0.6 * L : 0.5 * L, by = transposition ? 0.6 * L : 0.7 * L;
  const double xs = transposition ? 0.35 * L : 0.5 * L, ys = transposition ? 0.35 * L : 0.3 * L;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::size_t k = g.index(i, j);
      const double x = cellX(g, i), y = cellY(g, j);
      const int a = transposition ? std::min(i, j) : std::min(i, n - 1 - i);
      const int b = transposition ? std::max(i, j) : j;
      const double noise = r[static_cast<std::size_t>(a) * n + b];
      in.bed[k] = 0.02 * ((x - bx) * (x - bx) + (y - by) * (y - by)) + 0.15 * noise;
      const double rr = std::hypot(x - xs, y - ys);
      in.hs[k] = std::max(0.0, 1.2 - 0.15 * rr);
      in.h[k] = std::max(0.0, 0.8 - 0.08 * rr) * (0.5 + 0.5 * noise);
      in.phi[k] = (28.0 + 6.0 * noise) * kDeg;
    }
  return in;
}

struct SymmetryResult {
  double errH = 0, errQ = 0;  ///< max differences relative to max thickness / max discharge
  long bitsDiffer = 0;        ///< values (of 6 per cell) that differ from their image at all
  double maxSpeed = 0, time = 0;
};

SymmetryResult runSymmetry(bool transposition, bool slopeCorrection, int steps = 150) {
  const int n = 48;
  const Grid g = Grid::make(n, n, 1.0);
  fl::FlowSettings s = twoPhaseSettings(fl::Boundary::Wall);
  s.slopeCorrection = slopeCorrection;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), g, s);
  solver.setInput(symmetricScene(g, transposition));
  EXPECT_EQ(talus::test::advance(solver, talus::test::RunLimits::steps(steps)), steps);
  const auto st = talus::test::readState(solver);
  SymmetryResult r;
  r.time = solver.time();
  r.maxSpeed = st.maxSpeed(s.hDry);
  double dh = 0, dq = 0, hmax = 0, qmax = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::size_t k = g.index(i, j);
      const std::size_t m = transposition ? g.index(j, i) : g.index(n - 1 - i, j);
      // The image of (qx, qy) at the image cell: swapped (transposition) or qx negated (mirror).
      const double img[6] = {st.hs[m], st.hf[m],
                             transposition ? st.qsy[m] : -st.qsx[m], transposition ? st.qsx[m] : st.qsy[m],
                             transposition ? st.qfy[m] : -st.qfx[m], transposition ? st.qfx[m] : st.qfy[m]};
      const double own[6] = {st.hs[k], st.hf[k], st.qsx[k], st.qsy[k], st.qfx[k], st.qfy[k]};
      for (int c = 0; c < 6; ++c) {
        (c < 2 ? dh : dq) = std::max(c < 2 ? dh : dq, std::fabs(own[c] - img[c]));
        (c < 2 ? hmax : qmax) = std::max(c < 2 ? hmax : qmax, std::fabs(own[c]));
        r.bitsDiffer += own[c] != img[c];
      }
    }
  r.errH = dh / hmax;
  r.errQ = dq / qmax;
  return r;
}

}  // namespace

TEST(TwoPhase, SymmetricReleaseStaysSymmetric) {
  const SymmetryResult t = runSymmetry(true, true), tPlain = runSymmetry(true, false);
  const SymmetryResult m = runSymmetry(false, true, kMirrorSteps);
  std::printf("[ symmetry x <-> y ] t %.2f s, max speed %.2f m/s: h %.2e, q %.2e relative, %ld of %d values not "
              "bitwise equal; without slope correction: h %.2e, q %.2e, %ld not bitwise equal\n",
              t.time, t.maxSpeed, t.errH, t.errQ, t.bitsDiffer, 6 * 48 * 48, tPlain.errH, tPlain.errQ,
              tPlain.bitsDiffer);
  std::printf("[ symmetry x -> L - x ] t %.2f s, max speed %.2f m/s: h %.2e, q %.2e relative, %ld values not bitwise "
              "equal\n",
              m.time, m.maxSpeed, m.errH, m.errQ, m.bitsDiffer);
  EXPECT_GT(t.maxSpeed, 1.0);
  EXPECT_GT(m.maxSpeed, 1.0);
  EXPECT_LE(t.errH, 1e-13);
  EXPECT_LE(t.errQ, 1e-13);
  EXPECT_EQ(tPlain.bitsDiffer, 0) << "without the slope correction the transposed run should be bitwise equal";
  EXPECT_LE(m.errH, 2e-12);
  EXPECT_LE(m.errQ, 2e-12);
  std::fflush(stdout);
}

// ------------------------------------------------------------------------------------------------
// Mixture at rest. A lake over a submerged solid layer: 40 x 40 cells of 2 m, rough DEM (hills of
// +-1.2 m over 80 m, per-cell noise +-0.05 m: slopes up to ~0.15), a solid layer 0.20-0.21 m thick
// everywhere (phi = delta = 35 deg, rho_s 2500), and fluid up to a flat mixture surface
// eta = b + h_s + h_f: (a) 0.5 m above the highest solid surface (all submerged), (b) at 0.3 m, with
// dry islands where solids lie on land (gamma = 0 there). Walls, 300 CFL steps (20-30 s); and the
// same against level edges (the fluid's characteristic ghost against still water at its initial
// surface over the solids, b + h_s + h_f: a ghost level taken without the solids would drain the
// lake through the edges).
// The fluid sees the bed b + h_s and is a lake at rest over it (hydrostatic reconstruction, exact
// to round-off); the solids feel lateral pressure, buoyancy and the bed slope, whose imbalance over
// this bed is far below the Coulomb friction tan(35 deg) (1 - gamma) g_n h_s, so friction holds
// them exactly (q_s set to 0, the cells stay locked and pass no mass). Expected: h_s bitwise
// unchanged, q_s exactly 0, fluid speeds and surface deviation at round-off (asserted 1e-12 m/s and
// 1e-12 m; measured 1e-14 m/s and 9e-16 m with the drag off).
// With the drag on (the default) the lake must stay at rest too: the basal law and the drag are
// solved together (phase_exchange.cl), so the friction impulse that cancels the static imbalance
// on the held solids enters before the relaxation and none of that imbalance reaches the fluid.
// (Drag applied before friction handed part of it to the fluid: 0.9-1.7e-2 m/s after 300 steps.)
TEST(TwoPhase, MixtureAtRestStaysAtRest) {
  const Grid g = Grid::make(40, 40, 2.0);
  for (const fl::Boundary edge : {fl::Boundary::Wall, fl::Boundary::Level})
  for (const fl::DragLaw drag : {fl::DragLaw::Off, fl::DragLaw::Linear})
    for (const bool shore : {false, true}) {
      fl::FlowSettings s = twoPhaseSettings(edge);
      s.debris.drag = drag;
      talus::test::SolidMaterial mat;
      mat.phi = mat.delta = 35.0 * kDeg;
      fl::FlowInput in = talus::test::debrisInput(g, mat, 0.05);
      in.bed = talus::test::roughDem(g, 5u, 0.05);
      std::mt19937 rng(3u);
      std::uniform_real_distribution<double> u01(0.0, 1.0);
      double top = -1e9;
      for (std::size_t k = 0; k < g.cells(); ++k) {
        in.hs[k] = 0.2 + 0.01 * u01(rng);
        top = std::max(top, in.bed[k] + in.hs[k]);
      }
      const double eta = shore ? 0.3 : top + 0.5;
      int dry = 0;
      for (std::size_t k = 0; k < g.cells(); ++k) {
        in.h[k] = std::max(0.0, eta - in.bed[k] - in.hs[k]);
        dry += in.h[k] == 0.0;
      }
      fl::FlowSolver solver(talus::test::testContext(Precision::Double), g, s);
      solver.setInput(in);
      const int steps = talus::test::advance(solver, talus::test::RunLimits::steps(300));
      const auto st = talus::test::readState(solver);
      double fluidSpeed = 0, surface = 0;
      int solidsChanged = 0, solidsMoving = 0;
      const auto ufx = st.ufx(s.hDry), ufy = st.ufy(s.hDry);
      for (std::size_t k = 0; k < g.cells(); ++k) {
        fluidSpeed = std::max({fluidSpeed, std::fabs(ufx[k]), std::fabs(ufy[k])});
        if (in.h[k] > 0.0) surface = std::max(surface, std::fabs(in.bed[k] + st.hs[k] + st.hf[k] - eta));
        solidsChanged += st.hs[k] != in.hs[k];
        solidsMoving += st.qsx[k] != 0.0 || st.qsy[k] != 0.0;
      }
      const std::string name = std::string(edge == fl::Boundary::Wall ? "walls, " : "level edges, ") +
                               (drag == fl::DragLaw::Off ? "drag off" : "linear drag") +
                               (shore ? ", shoreline" : ", submerged");
      std::printf("[ mixture at rest, %s ] %d dry cells, %d steps (t %.1f s): fluid speed %.2e m/s, surface %.2e m, "
                  "solid cells changed %d, moving %d\n",
                  name.c_str(), dry, steps, solver.time(), fluidSpeed, surface, solidsChanged, solidsMoving);
      EXPECT_EQ(solidsChanged, 0) << name;
      EXPECT_EQ(solidsMoving, 0) << name;
      EXPECT_LE(fluidSpeed, 1e-12) << name;
      EXPECT_LE(surface, 1e-12) << name;
    }
  std::fflush(stdout);
}
