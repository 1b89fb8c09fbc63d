// Entrainment of an erodible bed layer (kernels/flow/entrainment.cl, docs/entrainment.md) through
// the whole two-phase solver:
//  - Entrainment.UniformLayerGrowsLinearly: a uniform solid layer moving at u_0 over a flat,
//    frictionless (delta = 0), uniform erodible bed. The growth law dh/dt = E s |q| with q unchanged
//    by entrainment (the material enters at rest) gives, exactly, h(t) = h_0 + min(E q_0 t, e_0) and
//    q(t) = q_0 (momentum conserved: the flow slows by dilution, u = q_0 / h), the bed lowered by what
//    was taken (b = b_0 - (h - h_0), basechange = b - b_0) and h + erodible conserved per cell.
//    Cohesion removes the lateral pressure, so the drainage from the closed-to-inflow upper edge
//    only travels down with the material (as in test_rheology_steady.cpp): the lowest 15 m are an
//    infinite layer.
//  - Entrainment.SlideOnErodiblePlaneConservesVolume: a block sliding down a 30 degree plane onto an
//    erodible layer over a kink of the plane: solid + erodible volume conserved to round-off at every
//    step, erosion only in cells the flow has reached, the bed lowered by exactly what was taken,
//    and the bed's slope fields (g_n) those of the lowered bed.
//  - Entrainment.MaterialAtRestDoesNotErode: a block held by friction on an erodible slope stays
//    bitwise at rest and takes nothing.
// Double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "flow/SlopeGravity.hpp"
#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;

namespace {

constexpr double kDeg = M_PI / 180.0;

fl::FlowSettings entrainmentSettings(double growth) {
  fl::FlowSettings s;
  s.twoPhase = true;
  s.debris.earthPressure = fl::EarthPressure::Constant;
  s.debris.kConst = 1.0;
  s.debris.deltaFromPhi = false;
  s.entrainment.enabled = true;
  s.entrainment.growthRate = growth;
  return s;
}

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

}  // namespace

TEST(Entrainment, UniformLayerGrowsLinearly) {
  constexpr int nx = 100, from = 70;
  constexpr double dx = 0.5, h0 = 0.5, u0 = 2.0, E = 0.01, e0 = 0.05, T = 8.0;
  const double q0 = h0 * u0;  // E q0 = 0.01 m/s: the layer is used up at t = 5 s
  const Grid grid = Grid::make(nx, 1, dx);
  talus::test::SolidMaterial mat;
  mat.delta = 0.0;
  mat.cohesion = 1e6;  // no lateral pressure (file header)
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  in.erodible.assign(nx, e0);
  for (int i = 0; i < nx; ++i) {
    in.hs[i] = h0;
    in.qsx[i] = q0;
  }
  fl::FlowSettings s = entrainmentSettings(E);
  s.edge = fl::Boundary::Open;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  double hErr = 0, qErr = 0, bedErr = 0, sumErr = 0;
  const int steps = talus::test::advance(solver, talus::test::RunLimits::until(T), [&](const fl::FlowSolver& sv) {
    const auto st = talus::test::readState(sv);
    const std::vector<double> bed = sv.bed(), change = sv.bedChange(), left = sv.erodibleDepth();
    const double exact = h0 + std::min(E * q0 * sv.time(), e0);
    for (int i = from; i < nx; ++i) {
      hErr = std::max(hErr, std::fabs(st.hs[i] - exact));
      qErr = std::max(qErr, std::fabs(st.qsx[i] - q0));
      bedErr = std::max(bedErr, std::fabs(bed[i] - (st.hs[i] - h0) * -1.0));
      bedErr = std::max(bedErr, std::fabs(change[i] - bed[i]));
      sumErr = std::max(sumErr, std::fabs(st.hs[i] + left[i] - (h0 + e0)));
    }
    return true;
  });
  std::printf("[ uniform layer ] %d steps: |h - exact| %.2e m, |q - q0| %.2e m^2/s, bed %.2e m, h + e %.2e m\n", steps,
              hErr, qErr, bedErr, sumErr);
  // Each step adds E q0 dt exactly (q unchanged), so h is exact to the round-off of the sum of the
  // step's additions: ~steps x ulp(h) ~ 3e-14; 1e-12 allows it, a wrong factor s or rate is O(1e-3).
  EXPECT_LT(hErr, 1e-12);
  EXPECT_LT(qErr, 1e-12);
  EXPECT_LT(bedErr, 1e-12);
  EXPECT_LT(sumErr, 1e-12);
}

namespace {

struct SlideRun {
  double volumeErr = 0;        ///< max |sum(h_s + e) - V0| / V0
  double surfaceErr = 0;       ///< max |bed change + depth taken| [m]
  double erodedAhead = 0;      ///< erosion in cells the flow never reached [m]
  double eroded = 0;           ///< total erosion [m^3]
  double geometryErr = 0;      ///< final g_n against the host's of the final bed
  double geometryChange = 0;   ///< largest change of g_n from the initial bed's
  double speedEnd = 0;
  bool bitwiseRest = true;
};

SlideRun slide(double thetaDeg, double deltaDeg, double cohesion, double T) {
  constexpr int nx = 120;
  constexpr double dx = 0.25, e0 = 0.2;
  const Grid grid = Grid::make(nx, 1, dx);
  talus::test::SolidMaterial mat;
  mat.delta = deltaDeg * kDeg;
  mat.phi = deltaDeg * kDeg;
  mat.cohesion = cohesion;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  in.erodible.assign(nx, 0.0);
  for (int i = 0; i < nx; ++i) {
    // The plane steepens to theta and then flattens at x = 20 m (a kink: the slopes change there).
    const double x = talus::test::cellX(grid, i);
    in.bed[i] = -std::tan(thetaDeg * kDeg) * std::min(x, 20.0);
    in.hs[i] = x > 1.0 && x < 4.0 ? 1.0 : 0.0;
    if (x > 6.0) in.erodible[i] = e0;
  }
  fl::FlowSettings s = entrainmentSettings(0.05);
  s.edge = fl::Boundary::Wall;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  const double V0 = sum(in.hs) + sum(in.erodible);
  std::vector<uint8_t> reached(nx, 0);
  SlideRun r;
  talus::test::advance(solver, talus::test::RunLimits::until(T), [&](const fl::FlowSolver& sv) {
    const auto st = talus::test::readState(sv);
    const std::vector<double> left = sv.erodibleDepth(), bed = sv.bed();
    r.volumeErr = std::max(r.volumeErr, std::fabs(sum(st.hs) + sum(left) - V0) / V0);
    for (int i = 0; i < nx; ++i) {
      if (st.hs[i] > 0) reached[i] = 1;
      if (!reached[i]) r.erodedAhead = std::max(r.erodedAhead, in.erodible[i] - left[i]);
      r.bitwiseRest = r.bitwiseRest && st.hs[i] == in.hs[i] && st.qsx[i] == 0.0;
      // The bed lowered by exactly what was taken.
      r.surfaceErr = std::max(r.surfaceErr, std::fabs((bed[i] - in.bed[i]) + (in.erodible[i] - left[i])));
    }
    r.speedEnd = st.maxSpeed(s.hDry);
    return true;
  });
  const std::vector<double> left = solver.erodibleDepth();
  for (int i = 0; i < nx; ++i) r.eroded += (in.erodible[i] - left[i]) * dx * dx;
  const fl::SlopeGravity host = fl::computeSlopeGravity(grid, solver.bed(), in.mask, s);
  const std::vector<double> gn = solver.gn();
  const fl::SlopeGravity initial = fl::computeSlopeGravity(grid, in.bed, in.mask, s);
  for (int i = 0; i < nx; ++i) {
    r.geometryErr = std::max(r.geometryErr, std::fabs(gn[i] - host.gn[i]));
    r.geometryChange = std::max(r.geometryChange, std::fabs(gn[i] - initial.gn[i]));
  }
  return r;
}

}  // namespace

TEST(Entrainment, SlideOnErodiblePlaneConservesVolume) {
  const SlideRun r = slide(30.0, 20.0, 0.0, 6.0);
  std::printf("[ slide ] eroded %.4f m^3, volume error %.2e, bed vs taken %.2e m, eroded ahead of the flow %.2e m, "
              "g_n vs host %.2e (g_n changed by up to %.3f m/s^2), max speed at the end %.3f m/s\n",
              r.eroded, r.volumeErr, r.surfaceErr, r.erodedAhead, r.geometryErr, r.geometryChange, r.speedEnd);
  EXPECT_GT(r.eroded, 0.05) << "the flow took up almost nothing";
  EXPECT_LT(r.volumeErr, 1e-13);   // sums of ~100 terms of ~1 m: round-off ~1e-15
  EXPECT_LT(r.surfaceErr, 1e-13);
  EXPECT_EQ(r.erodedAhead, 0.0);
  EXPECT_LT(r.geometryErr, 1e-12);  // device recompute of the eroded bed = host formula (test_bed_geometry)
  EXPECT_GT(r.geometryChange, 1e-3);  // and the erosion did change the slopes
}

TEST(Entrainment, MaterialAtRestDoesNotErode) {
  // delta = 35 deg > theta = 30 deg and no lateral pressure (cohesion; with K = 1 the block's ends
  // would spread): the block is held and the erodible layer under it stays.
  const SlideRun r = slide(30.0, 35.0, 1e6, 1.0);
  EXPECT_TRUE(r.bitwiseRest);
  EXPECT_EQ(r.eroded, 0.0);
}
