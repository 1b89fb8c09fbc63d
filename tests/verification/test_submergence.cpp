// Verification of the buoyancy of partly submerged solids in the two-phase grid model
// (submerged_gamma, kernels/flow/debris_closures.cl): the fluid fills the pores of the solid
// skeleton (packing phi_p, `Solid Packing Fraction`) from the bed up, so the buoyancy ratio is
// gamma_eff = (rho_f / rho_s) min(1, h_f phi_p / (h_s (1 - phi_p))), growing continuously from zero
// instead of switching to its saturated value at the first film of fluid.
//
// Scene: a uniform solid layer h_s = 1 m (rho_s 2500, delta = 30 deg, B = 1) sliding at 5 m/s over a
// flat bed with a fluid layer h_f moving with it (drag off, Manning 0: the fluid keeps its speed),
// closed strip of 8N + 17 cells (the middle cells stay bitwise uniform for N steps, see
// test_two_phase.cpp). There the only force on the solids is the Coulomb friction
// tan(delta) (1 - B gamma_eff) g h_s, applied implicitly per stage; while the layer moves, the
// SSP-RK2 step reduces its speed by exactly tan(delta) (1 - B gamma_eff) g dt (stage 1 removes
// a dt, stage 2 a dt / 2 from the mean (u0 + u1) / 2). The deceleration measured over N steps is
// compared with the host formula (an independent implementation of the law above) for fluid
// thicknesses from a film of 10 um (old switch: already the saturated buoyancy) to saturation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;

namespace {

constexpr double kHs = 1.0, kRhoS = 2500.0, kU0 = 5.0, kG = 9.81, kDt = 0.01;
const double kDelta = 30.0 * 3.14159265358979323846 / 180.0;

/// Host law of the header.
double gammaEff(const fl::DebrisSettings& d, double hs, double hf) {
  const double chi = std::min(1.0, hf * d.packing / (hs * (1.0 - d.packing)));
  return d.fluidDensity / kRhoS * chi;
}

/// Mean deceleration of the solids over N steps with fluid thickness hf [m/s^2].
double deceleration(double hf, double packing, bool& uniform) {
  const int N = 20, nx = 8 * N + 17, ic = nx / 2, safe = 4 * N + 3;
  const Grid grid = Grid::make(nx, 1, 10.0);
  talus::test::SolidMaterial mat;
  mat.delta = kDelta;
  mat.rhoS = kRhoS;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int i = 0; i < nx; ++i) {
    in.hs[i] = kHs;
    in.qsx[i] = kHs * kU0;
    in.h[i] = hf;
    in.qx[i] = hf * kU0;
  }
  fl::FlowSettings s;
  s.twoPhase = true;
  s.edge = fl::Boundary::Wall;
  s.debris.deltaFromPhi = false;
  s.debris.drag = fl::DragLaw::Off;
  s.debris.packing = packing;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  EXPECT_LE(kDt, solver.stableDt());
  for (int n = 0; n < N; ++n) solver.step(kDt);
  const auto st = talus::test::readState(solver);
  for (int i = safe; i < nx - safe; ++i) uniform = uniform && st.qsx[i] == st.qsx[ic] && st.hs[i] == st.hs[ic];
  return (kU0 - st.qsx[ic] / st.hs[ic]) / (N * kDt);
}

}  // namespace

// The deceleration follows tan(delta) (1 - B gamma_eff) g for every fluid thickness, to 1e-9
// relative (the per-step speed change is exact up to the rounding of 20 subtractions of a number
// ~0.06 from ~5, i.e. ~1e-14 absolute over 0.2 s, ~1e-13 relative; 1e-9 leaves room for the
// float-free but reordered arithmetic and is 1e5 times smaller than the smallest change of
// gamma_eff probed here). A 10 um film gives almost the dry deceleration (the earlier switch gave
// the saturated one: 40 % less friction); the deceleration falls linearly in h_f until the pores
// are full (h_f = h_s (1 - phi_p) / phi_p) and stays there above.
TEST(Submergence, BuoyancyGrowsWithTheSubmergedShareOfTheSolids) {
  fl::DebrisSettings d;
  for (const double packing : {0.6, 0.5}) {
    d.packing = packing;
    const double full = kHs * (1.0 - packing) / packing;
    double prev = 1e300;
    for (const double share : {0.0, 1e-5, 0.25, 0.5, 1.0, 2.0}) {
      const double hf = share * full;
      bool uniform = true;
      const double a = deceleration(hf, packing, uniform);
      const double expect = std::tan(kDelta) * (1.0 - d.poreB * gammaEff(d, kHs, hf)) * kG;
      std::printf("[ submergence ] packing %.2f, h_f %.4g m (%.3g of the pores): deceleration %.9f m/s^2, "
                  "law %.9f\n", packing, hf, share, a, expect);
      EXPECT_TRUE(uniform);
      EXPECT_NEAR(a, expect, 1e-9 * expect) << "h_f = " << hf;
      EXPECT_LE(a, prev + 1e-12) << "friction grew with more fluid";
      prev = a;
    }
  }
}
