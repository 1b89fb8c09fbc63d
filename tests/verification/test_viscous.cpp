// Verification of the fluid's viscous stress in the two-phase model (OpenLISEM Hazard P.30,
// Pudasaini 2012; kernels/flow/debris_viscous.cl), double precision:
//  - Viscous.ShearWaveDecaysAtTheViscousRate: a shear wave u_f = U cos(k y) across a channel decays
//    as exp(-nu (k^2 + chi / H^2) t) (analytic solution of the Newtonian part, with and without the
//    basal shear term chi);
//  - Viscous.StressDivergenceConvergesToTheAnalyticOne: the viscous acceleration of smooth fields
//    (Newtonian and interfacial parts, varying alpha_s, both phases moving) against the divergence
//    of the continuous P.30 stress, second order under refinement; the viscous fluxes conserve the
//    total fluid momentum to round-off;
//  - Viscous.ProfileTermDampsTheRelativeVelocity: the xi term relaxes u_f - u_s at its rate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/Constants.hpp"
#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;
using talus::test::cellX;
using talus::test::cellY;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = talus::kGravity;

fl::FlowSettings viscousSettings(double nR, double nRA) {
  fl::FlowSettings s;
  s.twoPhase = true;
  s.edge = fl::Boundary::Wall;
  s.debris.drag = fl::DragLaw::Off;
  s.debris.reynolds = nR;
  s.debris.reynoldsInterfacial = nRA;
  return s;
}

/// nu = sqrt(g H) H / (max(alpha_f, 0.1) N) (debris_viscous.cl header).
double nu(double H, double alphaF, double N) { return std::sqrt(kG * H) * H / (std::max(alphaF, 0.1) * N); }

}  // namespace

// ------------------------------------------------------------------------------------------------
// Shear wave. Pure fluid (h_s = 0, so alpha_f = 1) of depth H = 1 m on a flat frictionless bed in a
// walled channel 100 m long (x) and L = 10 m wide (y), dx = 0.5 m, with u_f = U cos(pi y / L), v = 0.
// Uniform in x, the flow has no advection or pressure gradient; HLLC moves no tangential momentum
// through faces with zero normal velocity; so the only force is the viscous one, u_t = nu u_yy
// - chi nu u / H^2 with free slip (u_y = 0) at the side walls: u = U cos(pi y / L) e^{-r t},
// r = nu ((pi / L)^2 + chi / H^2). The end walls send disturbances in at sqrt(g H) = 3.1 m/s; the
// middle of the channel stays untouched for 16 s, and we stop at 8 s.
// The discrete mode cos(pi (j + 1/2) / 20) is an exact eigenvector of the face-difference Laplacian
// with zero wall flux, with eigenvalue 4 sin^2(pi / 40) / dx^2 = k^2 (1 - 2.1e-3): the decay exponent
// r t <= 0.5 is off by <= 1e-3 from it, and SSP-RK2 / the implicit basal term add O((r dt)^2) per
// step (r dt <= 3e-3). Tolerance 2e-3 on A(t)/A(0); the amplitude must have fallen below 0.8 so a
// missing or halved viscosity fails by far.
TEST(Viscous, ShearWaveDecaysAtTheViscousRate) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const int nx = 200, ny = 20;
  const double dx = 0.5, L = ny * dx, H = 1.0, U = 0.5, N = 10.0, T = 8.0;
  const Grid grid = Grid::make(nx, ny, dx);
  for (double chi : {0.0, 0.1}) {
    fl::FlowSettings s = viscousSettings(N, 0.0);
    s.debris.chi = chi;
    fl::FlowInput in = talus::test::debrisInput(grid);
    in.h.assign(grid.cells(), H);
    in.qx.assign(grid.cells(), 0.0);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) in.qx[grid.index(i, j)] = H * U * std::cos(kPi * cellY(grid, j) / L);
    fl::FlowSolver solver(ctx, grid, s);
    solver.setInput(in);
    talus::test::advance(solver, talus::test::RunLimits::until(T));
    const talus::test::DebrisState st = talus::test::readState(solver);
    const std::vector<double> u = st.ufx(s.hDry), v = st.ufy(s.hDry);
    double num = 0, den = 0, vmax = 0;
    const int ic = nx / 2;
    for (int j = 0; j < ny; ++j) {
      const double c = std::cos(kPi * cellY(grid, j) / L);
      num += u[grid.index(ic, j)] * c;
      den += U * c * c;
      vmax = std::max(vmax, std::fabs(v[grid.index(ic, j)]));
    }
    const double amp = num / den;
    const double r = nu(H, 1.0, N) * ((kPi / L) * (kPi / L) + chi / (H * H));
    const double exact = std::exp(-r * solver.time());
    std::printf("shear wave chi=%g: A/A0 %.6f, exact %.6f, |v| <= %.2e\n", chi, amp, exact, vmax);
    EXPECT_NEAR(amp, exact, 2e-3) << "chi " << chi;
    EXPECT_LT(amp, 0.8);
    EXPECT_LT(vmax, 1e-10);  // symmetric in x away from the end walls: no transverse flow
  }
}

// ------------------------------------------------------------------------------------------------
// Stress divergence. On a flat bed, mixture depth H = 1 m, solid fraction alpha_s(x, y) smooth in
// [0.2, 0.6], smooth fluid and solid velocities (one period over the 2 m x 2 m box), Reynolds numbers
// N_R = 2, N_RA = 3 so both parts matter. One step of dt = 1e-9 s with the stresses on and one with
// them off differ by dt times the viscous acceleration of q_f, up to O(dt^2): the second stage's
// fluxes and bed/buoyancy terms see the first stage's viscous change (measured 6e-7 of the change at
// dt = 1e-6, so ~6e-10 here); the differences |dq| ~ 2e-8 of q ~ 1 keep 8 digits in double. The reference is the
// divergence of the continuous stress, d_j (h_f nu T_ij), with T = [grad u_f + grad u_f^T] for
// N_R and -[grad alpha_s (x) w + w (x) grad alpha_s] for N_RA, evaluated by nested central
// differences of the analytic fields (step 1e-4: truncation ~1e-8, round-off ~1e-8 relative).
// Compared on cells at least 3 cells from the walls (no viscous flux crosses a wall). The face
// differences are second order: the max error relative to the max acceleration must fall by at
// least 3x (order >= 1.6) from 40^2 to 80^2 and be below 1% at 80^2. The sum over the domain of the
// viscous change of q_f must vanish up to that O(dt^2) part (fluxes cancel pairwise, none cross the
// walls): below 1e-8 of the sum of |change| (a face evaluated differently by its two cells, or a
// flux through a wall, would leave O(1) of it).
TEST(Viscous, StressDivergenceConvergesToTheAnalyticOne) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const double Lb = 2.0, H = 1.0, nR = 2.0, nRA = 3.0, dt = 1e-9;
  const double k = 2 * kPi / Lb;
  auto alphaS = [&](double x, double y) { return 0.4 + 0.2 * std::sin(k * x) * std::cos(k * y); };
  auto uf = [&](double x, double y) { return 0.8 * std::sin(k * y) + 0.3 * std::cos(k * x); };
  auto vf = [&](double x, double y) { return 0.5 * std::sin(k * x) * std::sin(k * y); };
  auto us = [&](double x, double y) { return 0.2 * std::cos(k * (x + y)); };
  auto vs = [&](double x, double) { return -0.1 * std::sin(k * x); };
  const double e = 1e-4;
  auto d = [&](const std::function<double(double, double)>& f, int axis, double x, double y) {
    return axis == 0 ? (f(x + e, y) - f(x - e, y)) / (2 * e) : (f(x, y + e) - f(x, y - e)) / (2 * e);
  };
  // h_f nu (per N) as a function of position; the stress components T_ij (both parts summed).
  auto coef = [&](double x, double y, double N) {
    const double af = 1 - alphaS(x, y);
    return af * H * nu(H, af, N);
  };
  std::function<double(double, double)> U = uf, V = vf, A = alphaS;
  auto stress = [&](int i, int j, double x, double y) {
    const double gu[2][2] = {{d(U, 0, x, y), d(U, 1, x, y)}, {d(V, 0, x, y), d(V, 1, x, y)}};  // gu[c][axis]
    const double ga[2] = {d(A, 0, x, y), d(A, 1, x, y)};
    const double w[2] = {uf(x, y) - us(x, y), vf(x, y) - vs(x, y)};
    const double newtonian = gu[i][j] + gu[j][i];
    const double interfacial = -(ga[i] * w[j] + w[i] * ga[j]);
    return coef(x, y, nR) * newtonian + coef(x, y, nRA) * interfacial;
  };
  auto accel = [&](int i, double x, double y) {
    return (stress(i, 0, x + e, y) - stress(i, 0, x - e, y)) / (2 * e) +
           (stress(i, 1, x, y + e) - stress(i, 1, x, y - e)) / (2 * e);
  };

  double prevErr = 0;
  for (int n : {40, 80}) {
    const double dx = Lb / n;
    const Grid grid = Grid::make(n, n, dx);
    fl::FlowInput in = talus::test::debrisInput(grid);
    in.hs.assign(grid.cells(), 0.0);
    in.h = in.hs;
    in.qx = in.qy = in.qsx = in.qsy = in.hs;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = cellX(grid, i), y = cellY(grid, j);
        const std::size_t c = grid.index(i, j);
        in.hs[c] = alphaS(x, y) * H;
        in.h[c] = H - in.hs[c];
        in.qx[c] = in.h[c] * uf(x, y);
        in.qy[c] = in.h[c] * vf(x, y);
        in.qsx[c] = in.hs[c] * us(x, y);
        in.qsy[c] = in.hs[c] * vs(x, y);
      }
    std::vector<double> qOn[2], qOff[2];
    for (bool on : {true, false}) {
      fl::FlowSettings s = viscousSettings(on ? nR : 0.0, on ? nRA : 0.0);
      s.debris.deltaFromPhi = false;  // frictionless bed: the solids keep moving in both runs
      in.delta.assign(grid.cells(), 0.0);
      fl::FlowSolver solver(ctx, grid, s);
      solver.setInput(in);
      ASSERT_GT(solver.stableDt(), dt);
      solver.step(dt);
      (on ? qOn : qOff)[0] = solver.qx();
      (on ? qOn : qOff)[1] = solver.qy();
    }
    double err = 0, amax = 0, sum[2] = {0, 0}, sumAbs = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = grid.index(i, j);
        for (int comp = 0; comp < 2; ++comp) {
          const double got = (qOn[comp][c] - qOff[comp][c]) / dt;
          sum[comp] += qOn[comp][c] - qOff[comp][c];
          sumAbs += std::fabs(qOn[comp][c] - qOff[comp][c]);
          if (i < 3 || j < 3 || i >= n - 3 || j >= n - 3) continue;
          const double want = accel(comp, cellX(grid, i), cellY(grid, j));
          err = std::max(err, std::fabs(got - want));
          amax = std::max(amax, std::fabs(want));
        }
      }
    const double rel = err / amax;
    std::printf("viscous divergence %dx%d: max |a| %.4f m^2/s^2, max error %.3e (relative %.3e), momentum sum %.1e %.1e of %.1e\n",
                n, n, amax, err, rel, sum[0], sum[1], sumAbs);
    EXPECT_LT(std::fabs(sum[0]) + std::fabs(sum[1]), 1e-8 * sumAbs);
    if (prevErr > 0) {
      EXPECT_GT(prevErr / rel, 3.0) << "second-order face differences";
      EXPECT_LT(rel, 1e-2);
    }
    prevErr = rel;
  }
}

// ------------------------------------------------------------------------------------------------
// Profile term. Uniform layer h_s = 0.4 m, h_f = 0.6 m, solids at rest held by bed friction (30
// degrees; nothing drives them), fluid at u0 = 1 m/s, drag off, N_RA = 30, xi chosen so that the
// rate r = xi alpha_s nu_A / H^2 gives r dt = 0.05 per step at a fixed dt. The middle cell of a
// 61 x 61 walled box is untouched by the walls for 5 steps (a stage reads 2 cells either side, the
// middle is 30 cells in). The implicit source applied per stage (dt, then dt/2 on the average,
// debris_stage.cl) multiplies w per step by (1 + 1/(1 + x)) / (2 (1 + x/2)) = 1 - x + x^2 + O(x^3)
// against e^{-x} = 1 - x + x^2/2: relative error x^2 / 2 per step, 5 x 1.25e-3 = 0.63% after 5 steps.
// Tolerance 1% relative to exp(-5 x); the solids stay at rest.
TEST(Viscous, ProfileTermDampsTheRelativeVelocity) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const int n = 61, steps = 5;
  const double dx = 1.0, hs = 0.4, hf = 0.6, H = hs + hf, u0 = 1.0, nRA = 30.0;
  const Grid grid = Grid::make(n, n, dx);
  fl::FlowSettings s = viscousSettings(0.0, nRA);
  fl::FlowInput in = talus::test::debrisInput(grid);
  in.hs.assign(grid.cells(), hs);
  in.h.assign(grid.cells(), hf);
  in.qx.assign(grid.cells(), hf * u0);
  fl::FlowSolver probe(ctx, grid, s);
  probe.setInput(in);
  const double dt = 0.5 * probe.stableDt(), x = 0.05;
  const double rate = x / dt;
  s.debris.xi = rate * H * H / (0.4 * nu(H, hf / H, nRA));
  fl::FlowSolver solver(ctx, grid, s);
  solver.setInput(in);
  for (int k = 0; k < steps; ++k) solver.step(dt);
  const talus::test::DebrisState st = talus::test::readState(solver);
  const std::size_t c = grid.index(n / 2, n / 2);
  const double u = st.qfx[c] / st.hf[c], want = u0 * std::exp(-steps * x);
  std::printf("profile term: u_f %.6f, exact %.6f (xi %.3g)\n", u, want, s.debris.xi);
  EXPECT_NEAR(u / want, 1.0, 1e-2);
  EXPECT_EQ(st.qsx[c], 0.0);
  EXPECT_EQ(st.qsy[c], 0.0);
}
