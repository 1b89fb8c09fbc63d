// Cohesion carried with the solids (kernels/flow/debris_stage.cl, passive scalar h_s c, issue 13
// item 6): the cohesion c of Bell's reduction of the lateral pressure, Pi = max(0, K (1 - gamma)
// g_p H / 2 - 2 c sqrt(K) / rho_s) (OpenLISEM Hazard P.43), belongs to the material, not to the
// ground it happens to lie on.
//
// CohesionTransport.CohesiveBlockSlidesOffItsReleaseAreaWithoutSpreading: a 4 m long, 0.5 m thick
// block on a 30 degree plane (delta = 15 degrees, K = 1) with c = 10 kPa only in its release cells;
// the ground around has none. Its cohesion exceeds rho_s K g_p H / (4 sqrt(K)) = 2.3 kPa, so Pi = 0
// throughout the block: it has no lateral pressure wherever it goes. The independent reference is
// the same block with no cohesion and K = 0, whose Pi is zero by definition. After 2 s the block
// has travelled 4.55 m, more than its length, so (all but its thin trail, asserted < 1 % of the
// volume) it lies outside its release area. Asserted:
//  - thickness and momentum of the two runs agree to 1e-9 of the block's thickness and momentum.
//    They differ only where a cell is thinner than the dry threshold (1e-12 m here): there the
//    cohesion is undefined and taken as 0, so those cells carry a pressure K g_p h / 2 with
//    h <= 1e-12 m; measured differences 2.1e-15 m (h) and 1.4e-14 m^2/s (q). With the cohesion a fixed map of the
//    release area (as before) the block spread once it had left it, as a loose block does: a
//    cohesionless block with K = 1 differs from the reference by 0.28 m (printed);
//  - the cohesion per cell c = (h_s c) / h_s equals 10 kPa to 1e-12 wherever the block is thicker
//    than 1 mm (an upwinded scalar of uniform value stays uniform; measured 9e-16), and the integral
//    of h_s c over the cells where c is defined (thicker than the dry threshold) is conserved
//    between walls to 1e-11 (measured 9.7e-13; the cells at or below 1e-12 m, whose c is not counted,
//    hold at most 1e-8 Pa m each of the 1e5 Pa m).
// 1D: one row of cells with walls on all edges, double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;
using talus::test::cellX;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kTheta = 30.0 * kDeg, kDelta = 15.0 * kDeg;
constexpr double kH = 0.5, kFrom = 2.0, kTo = 6.0, kDx = 0.1, kT = 2.0;
constexpr double kCohesion = 1e4;  // [Pa]
constexpr int kNx = 160;

struct BlockRun {
  talus::test::DebrisState state;
  std::vector<double> cohesion;  ///< solidScalar(3) at the end [Pa]
  double carriedStart = 0, carriedEnd = 0;  ///< sum of h_s c over the cells [Pa m]
};

double carried(const std::vector<double>& hs, const std::vector<double>& c) {
  double sum = 0;
  for (std::size_t i = 0; i < hs.size(); ++i) sum += hs[i] * c[i];
  return sum;
}

/// The block with cohesion `c` in its release cells only and a constant earth-pressure coefficient K.
BlockRun slide(double c, double K) {
  const Grid grid = Grid::make(kNx, 1, kDx);
  talus::test::SolidMaterial mat;
  mat.phi = kDelta;
  mat.delta = kDelta;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int i = 0; i < kNx; ++i) {
    const double x = cellX(grid, i);
    in.bed[i] = -std::tan(kTheta) * x;
    const bool block = x > kFrom && x < kTo;
    in.hs[i] = block ? kH : 0.0;
    in.cohesion[i] = block ? c : 0.0;
  }
  fl::FlowSettings s = talus::test::granularBetweenWalls(K);
  s.debris.filmThickness = 0.0;
  s.hDry = 1e-12;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  BlockRun r;
  r.carriedStart = carried(solver.hs(), solver.solidScalar(3));
  talus::test::advance(solver, talus::test::RunLimits::until(kT));
  r.state = talus::test::readState(solver);
  r.cohesion = solver.solidScalar(3);
  r.carriedEnd = carried(r.state.hs, r.cohesion);
  return r;
}

}  // namespace

TEST(CohesionTransport, CohesiveBlockSlidesOffItsReleaseAreaWithoutSpreading) {
  const BlockRun cohesive = slide(kCohesion, 1.0);
  const BlockRun reference = slide(0.0, 0.0);
  const BlockRun loose = slide(0.0, 1.0);  // the scale of what the cohesion does (printed only)
  double dh = 0, dq = 0, dc = 0, qmax = 0, inside = 0, total = 0, dLoose = 0;
  for (int i = 0; i < kNx; ++i) {
    dh = std::max(dh, std::fabs(cohesive.state.hs[i] - reference.state.hs[i]));
    dq = std::max(dq, std::fabs(cohesive.state.qsx[i] - reference.state.qsx[i]));
    qmax = std::max(qmax, std::fabs(reference.state.qsx[i]));
    dLoose = std::max(dLoose, std::fabs(loose.state.hs[i] - reference.state.hs[i]));
    if (cohesive.state.hs[i] > 1e-3) dc = std::max(dc, std::fabs(cohesive.cohesion[i] / kCohesion - 1.0));
    const double x = (i + 0.5) * kDx;
    total += cohesive.state.hs[i];
    if (x > kFrom && x < kTo) inside += cohesive.state.hs[i];
  }
  const double conservation = std::fabs(cohesive.carriedEnd - cohesive.carriedStart) / cohesive.carriedStart;
  std::printf("[ cohesive block ] |h - h_ref| %.2e m, |q - q_ref| %.2e of %.3f m^2/s, c error %.2e, "
              "h_s c conserved to %.2e; %.2e of the volume still in the release area; a loose block (c = 0, "
              "K = 1) differs from the reference by %.3f m\n",
              dh, dq, qmax, dc, conservation, inside / total, dLoose);
  ASSERT_LE(inside, 1e-2 * total) << "the block should have left its release area";
  EXPECT_LE(dh, 1e-9 * kH) << "the cohesion should travel with the block, keeping its lateral pressure zero";
  EXPECT_LE(dq, 1e-9 * qmax);
  EXPECT_LE(dc, 1e-12) << "a uniform cohesion carried with the material stays uniform";
  EXPECT_LE(conservation, 1e-11) << "the carried cohesion is a conserved scalar between walls";
}
