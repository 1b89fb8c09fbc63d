// Verification of the two-phase grid model (FlowSettings::twoPhase, kernels/flow/debris_stage.cl) in
// its dry granular limit h_f = 0, where spec section 4 reduces it exactly to Savage-Hutter with
// Coulomb bed friction tan(delta), slope-corrected gravities g_n = g cos^2(theta) (bed and
// friction) and g_p = g cos^2 or g cos^4(theta) (depth pressure), spec section 1:
//  - Granular.MangeneyDamBreakConverges: the Mangeney et al. (2000) dam break on a uniform plane,
//    constant K = 1, both depth-pressure options, L1 convergence on four grids;
//  - Granular.RigidBlockSlidesWithExactAcceleration: a block whose cohesion removes the lateral
//    pressure (Bell's reduction clipped at zero) slides as a rigid body with the exact horizontal
//    acceleration g cos^2(theta) (tan(theta) - tan(delta)), or stays bitwise at rest when
//    delta > theta;
//  - Granular.RigidBlockFirstOrderScheme: the same block with the first-order option
//    (Limiter::None);
//  - Granular.CoulombFrontLagsLikeWater: the 1 cm front of that dam break within a few cells of the
//    exact one whatever the friction (not more than water's);
//  - Granular.PileStopsNearReposeSlope: a 1D pile steeper than repose spreads, stops exactly, and
//    rests with a surface slope close to tan(delta) / K.
// Every run is 1D: one row of cells (ny = 1) with walls on all raster edges; both y faces of a cell
// are walls that pass no mass, so the runs stay exactly 1D (qsy = 0). The bed of the uniform plane
// is b = -x tan(theta) with x = (i + 1/2) dx, so x points downslope; g_n and g_p are then exactly
// the plane's values in every cell (the bed gradient is exact for a linear bed, also one-sided at
// the ends). Double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/Constants.hpp"
#include "support/Analytic.hpp"
#include "support/DebrisScene.hpp"
#include "support/GranularAnalytic.hpp"
#include "support/TestDevice.hpp"
#include "verification/ValidationOut.hpp"

namespace an = talus::analytic;
namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;
using talus::test::cellX;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Dry granular settings: two-phase model, walls, constant K = 1, bed friction from the delta map.
fl::FlowSettings dryGranularSettings() {
  fl::FlowSettings s = talus::test::granularBetweenWalls(1.0);
  // No film regularisation: these are continuum solutions down to h = 0 (see "Film" below).
  s.debris.filmThickness = 0.0;
  return s;
}

/// A 1D scene on the plane b = -x tan(theta) with solids hs(x), bed friction delta everywhere.
fl::FlowInput planeScene(const Grid& grid, double theta, double delta, double cohesion, double grain,
                         const std::function<double(double)>& hs) {
  talus::test::SolidMaterial mat;
  mat.phi = delta;
  mat.delta = delta;
  mat.cohesion = cohesion;
  mat.grain = grain;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int i = 0; i < grid.nx; ++i) {
    const double x = cellX(grid, i);
    in.bed[i] = -std::tan(theta) * x;
    in.hs[i] = hs(x);
  }
  return in;
}

// ------------------------------------------------------------------------------------------------
// Mangeney dam break. theta = 35 deg, delta = 22 deg, H0 = 1 m (vertical thickness), reservoir from
// the upper wall at x = 0 to the dam at x0 = 20 m, domain [0, 50] m, t = 3 s. With K = 1:
//   cos2: c0 = sqrt(g cos^2 H0) = 2.566 m/s, cos4: c0 = sqrt(g cos^4 H0) = 2.102 m/s,
//   m = g cos^2 (tan 35 - tan 22) = 1.950 m/s^2.
// The wall's disturbance reaches the fan at validUntil(0) = x0 / (2 c0) = 3.90 s (cos2) / 4.76 s
// (cos4) > 3 s, and the exact solution holds downslope of validFrom(0, 3 s) = c0 t + m t^2 / 2
// = 16.47 m (cos2) / 15.08 m (cos4); the window is [17 m, 50 m] (a cell edge of every grid), which
// holds the accelerated reservoir, the whole fan and the front at 44.2 m / 41.1 m, well inside the
// domain. The L1 error sum |h_i - hbar_i| dx [m^2] is taken against exact cell averages hbar_i
// (MangeneyDamBreak::integralH), as in test_dambreak.cpp.
//
// Film. The kernels desingularise the solid velocity in films thinner than
// DebrisSettings::filmThickness (solid_velocity in debris_closures.cl, eps = max(hDry, film)) and
// rewrite q = h u, i.e. they remove momentum from such films. Mangeney's solution is a continuum
// solution down to h = 0 at the front, so the tests set the film thickness to 0 (eps = hDry).
// Measured when eps was the grain size (nx 100..800, cos2): eps = 0.1 mm orders 1.09, 1.09, 0.90;
// 1 mm 0.90, 0.67, 0.35; 1 cm 0.34, 0.12, 0.06 with the L1 error stuck at 2.5% of the mass: a
// thin-front error of fixed width that no grid refinement removes (hence the 0.1 mm default).
constexpr double kMgTheta = 35.0, kMgDelta = 22.0, kMgH0 = 1.0, kMgX0 = 20.0, kMgL = 50.0, kMgT = 3.0;
constexpr double kMgGrain = 1e-6;
constexpr double kMgWindow = 17.0;
const int kMgGrids[] = {100, 200, 400, 800};

// Minimum observed L1 order between the two finest grids. The solution has the Ritter-type front
// h ~ (x_f - x)^2 on a dry bed and two kinks (rarefaction head and front), where the limited
// reconstruction falls to first order and the front lags by O(dx), so the L1 order is 1 at best
// (as for the Ritter dam break, test_dambreak.cpp); 0.8 leaves room for pre-asymptotic mixing of
// rates (measured between nx 400 and 800: 1.03 with cos2, 1.06 with cos4).
constexpr double kMgMinOrder = 0.8;

struct MangeneyError {
  int nx = 0, steps = 0;
  double l1 = 0, mass = 0;  ///< L1 error and integral of the exact h over the window [m^2]
};

MangeneyError runMangeney(int nx, bool cos4) {
  const double theta = kMgTheta * kDeg, delta = kMgDelta * kDeg;
  const double dx = kMgL / nx;
  const Grid grid = Grid::make(nx, 1, dx);
  const fl::FlowInput in = planeScene(grid, theta, delta, 0.0, kMgGrain, [](double x) { return x < kMgX0 ? kMgH0 : 0.0; });
  fl::FlowSettings s = dryGranularSettings();
  s.depthPressure = cos4 ? fl::DepthPressure::Cos4 : fl::DepthPressure::Cos2;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  MangeneyError e;
  e.nx = nx;
  e.steps = talus::test::advance(solver, talus::test::RunLimits::until(kMgT));
  EXPECT_NEAR(solver.time(), kMgT, 1e-12);
  const auto st = talus::test::readState(solver);
  const an::MangeneyDamBreak d = an::mangeneyFromSlope(kMgH0, theta, delta, 1.0, cos4, kMgX0);
  EXPECT_LT(kMgT, d.validUntil(0.0));
  EXPECT_GE(kMgWindow, d.validFrom(0.0, kMgT));
  EXPECT_LT(d.front(kMgT), kMgL - 2.0);
  for (int i = 0; i < nx; ++i) {
    const double xl = i * dx, xr = xl + dx;
    EXPECT_EQ(st.qsy[i], 0.0);
    if (xl < kMgWindow - 1e-9) continue;
    const double exact = d.integralH(xl, xr, kMgT);
    e.l1 += std::fabs(st.hs[i] * dx - exact);
    e.mass += exact;
  }
  if (talus::test::validation::enabled()) {  // the profile against exact cell averages, whole domain
    talus::test::validation::Table t({"x_m", "hs_m", "hs_exact_m", "in_window"});
    for (int i = 0; i < nx; ++i)
      t.add({cellX(grid, i), st.hs[i], d.integralH(i * dx, (i + 1) * dx, kMgT) / dx, i * dx >= kMgWindow - 1e-9 ? 1 : 0});
    t.write(std::string("mangeney_") + (cos4 ? "cos4" : "cos2") + "_profile_nx" + std::to_string(nx) + ".csv");
  }
  return e;
}

}  // namespace

TEST(Granular, MangeneyDamBreakConverges) {
  for (const bool cos4 : {false, true}) {
    const char* name = cos4 ? "cos4" : "cos2";
    const an::MangeneyDamBreak d =
        an::mangeneyFromSlope(kMgH0, kMgTheta * kDeg, kMgDelta * kDeg, 1.0, cos4, kMgX0);
    std::printf("[ Mangeney %s ] theta %.0f deg, delta %.0f deg, K 1, c0 %.4f m/s, m %.4f m/s^2, t %.1f s, "
                "window [%.1f, %.1f] m, front %.2f m\n",
                name, kMgTheta, kMgDelta, d.c0, d.m, kMgT, kMgWindow, kMgL, d.front(kMgT));
    std::vector<MangeneyError> errs;
    for (const int nx : kMgGrids) {
      errs.push_back(runMangeney(nx, cos4));
      const MangeneyError& e = errs.back();
      std::printf("  nx %4d  L1(h) %.4e m^2 (relative %.3e)", e.nx, e.l1, e.l1 / e.mass);
      if (errs.size() > 1) std::printf("  order %.3f", an::observedOrder(errs[errs.size() - 2].l1, e.l1, 2.0));
      std::printf("  %d steps\n", e.steps);
    }
    for (std::size_t k = 1; k < errs.size(); ++k)
      EXPECT_LT(errs[k].l1, errs[k - 1].l1) << name << ": L1 grew from nx " << errs[k - 1].nx << " to " << errs[k].nx;
    const double order = an::observedOrder(errs[errs.size() - 2].l1, errs.back().l1, 2.0);
    RecordProperty(std::string("mangeney_") + name + "_l1_nx800", std::to_string(errs.back().l1));
    if (talus::test::validation::enabled()) {
      talus::test::validation::Table t({"nx", "dx_m", "l1_h_m2", "relative_l1", "order", "steps"});
      for (std::size_t k = 0; k < errs.size(); ++k)
        t.add({errs[k].nx, kMgL / errs[k].nx, errs[k].l1, errs[k].l1 / errs[k].mass,
               k > 0 ? an::observedOrder(errs[k - 1].l1, errs[k].l1, 2.0) : std::nan(""), errs[k].steps});
      t.write(std::string("mangeney_") + name + "_errors.csv");
    }
    RecordProperty(std::string("mangeney_") + name + "_order", std::to_string(order));
    EXPECT_GE(order, kMgMinOrder) << name;
  }
  std::fflush(stdout);
}

namespace {

// ------------------------------------------------------------------------------------------------
// Coulomb front. The 1 cm front of the Mangeney dam break (theta = 32 deg, K = 1, cos4, t = 3 s, the
// set-up above on a steeper plane) against the exact one, in cells: the wet/dry front is first order,
// so any scheme lags by a few cells at every resolution (water's Ritter front lags about 3), and the
// lag must not grow with the bed friction. Measured (MC): delta 20 deg 2.81 / 2.86 cells at 0.5 /
// 0.25 m, delta 30 deg 2.67 / 2.57. Before friction used the stage's thickness (it used the new
// one, so a filling front cell met the friction of its new mass with the bed force of its old one):
// 4.30 / 5.37 and 5-6 cells. 3.5 cells separates the two.
constexpr double kFrontMaxLagCells = 3.5;

double frontLagCells(double deltaDeg, int nx) {
  const double theta = 32.0 * kDeg, delta = deltaDeg * kDeg, dx = kMgL / nx, level = 0.01;
  const Grid grid = Grid::make(nx, 1, dx);
  const fl::FlowInput in = planeScene(grid, theta, delta, 0.0, kMgGrain, [](double x) { return x < kMgX0 ? kMgH0 : 0.0; });
  fl::FlowSettings s = dryGranularSettings();
  s.depthPressure = fl::DepthPressure::Cos4;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  talus::test::advance(solver, talus::test::RunLimits::until(kMgT));
  const auto st = talus::test::readState(solver);
  const an::MangeneyDamBreak d = an::mangeneyFromSlope(kMgH0, theta, delta, 1.0, true, kMgX0);
  EXPECT_LT(kMgT, d.validUntil(0.0));
  EXPECT_LT(d.front(kMgT), kMgL - 2.0);
  // Numerical front: where h falls through the level, linear between the cell centres, downslope-most.
  double numerical = -1;
  for (int i = nx - 1; i > 0 && numerical < 0; --i)
    if (st.hs[i - 1] >= level && st.hs[i] < level)
      numerical = cellX(grid, i - 1) + dx * (st.hs[i - 1] - level) / (st.hs[i - 1] - st.hs[i]);
  // Exact front: h(x) = level by bisection between the dam and the tip (h falls monotonically there).
  double lo = kMgX0, hi = d.front(kMgT);
  for (int k = 0; k < 100; ++k) (d.h(0.5 * (lo + hi), kMgT) >= level ? lo : hi) = 0.5 * (lo + hi);
  std::printf("  delta %.0f deg, %d cells of %.3f m: 1 cm front %.3f m, exact %.3f m, lag %.2f cells\n", deltaDeg, nx,
              dx, numerical, lo, (lo - numerical) / dx);
  return (lo - numerical) / dx;
}

}  // namespace

TEST(Granular, CoulombFrontLagsLikeWater) {
  for (const double deltaDeg : {20.0, 30.0})
    for (const int nx : {100, 200}) {
      const double lag = frontLagCells(deltaDeg, nx);
      EXPECT_LT(lag, kFrontMaxLagCells) << "delta " << deltaDeg << ", nx " << nx;
      EXPECT_GT(lag, -1.0) << "the front ran ahead of the exact one: delta " << deltaDeg << ", nx " << nx;
    }
}

// ------------------------------------------------------------------------------------------------
// Rigid block. A block 4 m long (x in (2, 6) m, 40 cells of 0.1 m) and 0.5 m thick with cohesion
// 1e6 Pa on a plane: Bell's lateral pressure K g_p H / 2 - 2 c sqrt(K) / rho_s is at most
// 0.5 * 9.81 * 0.5 / 2 - 2 * 1e6 / 2500 < 0 and clipped to zero, so the solids feel only the bed
// slope g_n tan(theta) and Coulomb friction g_n tan(delta): a rigid body with the horizontal
// acceleration a = slidingAcceleration(theta, delta). Run to t = 2 s (4.3 to 4.6 m of travel).
//
// The film regularisation is off (see "Film" above): with a 1 cm film it sheds 1.8% of the block's
// momentum through its thin trail (measured; 1 mm: 0.18%, 0.1 mm, the default: 0.017%).
// What is exact in the scheme, and is asserted to round-off:
//  - the total momentum: interior face fluxes cancel, the bed source of every cell is
//    g_n tan(theta) h_i dt with the cell's own reconstructed bed (exact on a plane), and the
//    implicit friction removes exactly ds g_n tan(delta) h_i from every moving cell, with
//    ds = dt + dt/2 + dt/2 over the two SSP-RK2 stages; so sum q / sum h = a t. This needs every
//    cell to keep moving (tan(theta) > 1.5 tan(delta) holds for all pairs below: a freshly wetted
//    front cell gets the incoming velocity minus half a step of friction) and films thinner than
//    the dry threshold to be negligible: the solver discards the momentum of cells with
//    h_s <= hDry by design, which with the default hDry = 1e-6 m sheds 2e-6 of the momentum over
//    the run (measured) through the thin trail the block leaves behind; hDry = 1e-12 m makes that
//    loss round-off, so the exact kinematics is visible;
//  - the velocity of the block's interior (the 5 cells within L / 16 of the block's exact centre,
//    which travels a t^2 / 2) until T / 2: a t to round-off, and their thickness the initial 0.5 m
//    to round-off (measured <= 1.2e-14 both): the smearing of the block's ends has not reached them
//    yet (its tail is 3e-9 of the thickness at L / 4 from the centre by T / 2, 3e-4 by T). (Not "the cells
//    still bitwise 0.5 m": the bed differs from cell to cell, so the interior's velocities and face
//    fluxes differ in their last bits, and which cells keep exactly 0.5 m, and for how long, changed
//    with any reordering of the arithmetic: the last such cell at t = 0.95 - 1.42 s.)
// The centroid sum x h / sum h moves with the mass fluxes, which are h u of the MUSCL face values;
// at the block's ends the limiter clips the reconstruction (zero slope at the cells where the block
// meets the dry bed), so sum of face fluxes differs from sum h u by O(H0 dx u) out of O(M u): the
// centroid gains a relative error O(dx / L_block) (here dx / L = 1/40) that shrinks as the ends
// smear. Measured with first-order ends at wet/dry fronts: at most 3.9e-3 of the travelled distance
// (early, when the travel is a few millimetres), 1.2e-4 at the end; asserted <= 1e-2 over the run
// (below dx / L) and <= 1e-3 at the end. (Round-off
// exactness of the centroid would need the first-order flux h_i u_i, see
// Granular.RigidBlockFirstOrderScheme.)
// With tan(delta) > tan(theta), friction exceeds the driving force in every cell in every stage:
// the momentum is set to exactly zero, the cells stay "locked", no mass crosses their faces, and
// the block must stay bitwise unchanged for ever (here 300 steps).
// History: this failed while the solids' bed force came from the reconstructed bed (zero at the
// block's first-order ends); the bed and buoyancy forces now use cell-centre gradients.

namespace {

constexpr double kBlockH = 0.5, kBlockFrom = 2.0, kBlockTo = 6.0, kBlockDx = 0.1, kBlockT = 2.0;
constexpr double kBlockGrain = 1e-12;  // = hDry of the moving runs: no momentum removed above hDry
constexpr int kBlockNx = 160;
// Momentum: a thin fresh front cell (h_s < 1e-8 m) now and then receives a limited face velocity
// below the friction impulse of its stage and is stopped; friction never reverses motion, so the
// part of that impulse beyond its momentum is not applied: a relative momentum excess of at most a
// few 1e-10 early in the run, decaying like 1/t (measured max 4.3e-10 at t = 0.04 s, 40/25 deg;
// 3e-13 at t = 2 s). 2e-9 bounds it; a wrong force would show up as O(1e-3) or more.
constexpr double kBlockMomentumTol = 2e-9;
constexpr double kBlockInteriorTol = 1e-12;  // measured <= 2e-14
constexpr double kBlockInteriorT = 0.5 * kBlockT;  // the interior is checked until then
constexpr double kBlockInteriorH = 1e-12;    // |h - 0.5 m| / 0.5 m in the interior: measured <= 1.2e-14
constexpr double kBlockCentroidTol = 1e-2;
constexpr double kBlockCentroidEndTol = 1e-3;

struct BlockRun {
  double momentumErr = 0;  ///< max over steps of |sum q / sum h - a t| / (a t)
  double interiorErr = 0;  ///< max over steps and interior cells of |u - a t| / (a t)
  double centroidErr = 0;  ///< max over steps of |X - X0 - a t^2/2| / (a t^2/2)
  double centroidErrEnd = 0;
  double travel = 0;       ///< X(T) - X0 [m]
  double interiorHErr = 0;  ///< max over steps and interior cells of |h - H0| / H0
  int steps = 0;
  std::vector<std::vector<double>> series;  ///< t, travel, exact travel, mean velocity, exact (validation CSV only)
};

BlockRun slideBlock(double thetaDeg, double deltaDeg, fl::Limiter limiter) {
  const double theta = thetaDeg * kDeg, delta = deltaDeg * kDeg;
  const Grid grid = Grid::make(kBlockNx, 1, kBlockDx);
  const fl::FlowInput in = planeScene(grid, theta, delta, 1e6, kBlockGrain,
                                      [](double x) { return x > kBlockFrom && x < kBlockTo ? kBlockH : 0.0; });
  fl::FlowSettings s = dryGranularSettings();
  s.limiter = limiter;
  s.hDry = 1e-12;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  const auto st0 = talus::test::readState(solver);
  const double X0 = st0.solidCentroidX(grid), M = st0.volumeSolid(kBlockDx);
  const double a = an::slidingAcceleration(theta, delta);
  BlockRun r;
  r.steps = talus::test::advance(solver, talus::test::RunLimits::until(kBlockT), [&](const fl::FlowSolver& sv) {
    const auto st = talus::test::readState(sv);
    const double t = sv.time(), ut = a * t, xt = 0.5 * a * t * t;
    double P = 0;
    for (double q : st.qsx) P += q;
    P *= kBlockDx * kBlockDx;
    r.momentumErr = std::max(r.momentumErr, std::fabs(P / M - ut) / ut);
    const double centre = 0.5 * (kBlockFrom + kBlockTo) + xt, half = 0.0625 * (kBlockTo - kBlockFrom);
    for (int i = 0; i < kBlockNx && t <= kBlockInteriorT; ++i)
      if (std::fabs((i + 0.5) * kBlockDx - centre) <= half) {
        r.interiorErr = std::max(r.interiorErr, std::fabs(st.qsx[i] / st.hs[i] - ut) / ut);
        r.interiorHErr = std::max(r.interiorHErr, std::fabs(st.hs[i] - kBlockH) / kBlockH);
      }
    r.travel = st.solidCentroidX(grid) - X0;
    r.centroidErrEnd = std::fabs(r.travel - xt) / xt;
    r.centroidErr = std::max(r.centroidErr, r.centroidErrEnd);
    if (talus::test::validation::enabled()) r.series.push_back({t, r.travel, xt, P / M, ut});
    return true;
  });
  return r;
}

}  // namespace

TEST(Granular, RigidBlockSlidesWithExactAcceleration) {
  const double moving[][2] = {{35.0, 20.0}, {30.0, 15.0}, {40.0, 25.0}};
  for (const auto& pair : moving) {
    const double a = an::slidingAcceleration(pair[0] * kDeg, pair[1] * kDeg);
    const BlockRun r = slideBlock(pair[0], pair[1], fl::Limiter::VanLeer);
    std::printf("[ block theta %.0f, delta %.0f ] a %.6f m/s^2, travel %.4f m (exact %.4f), %d steps:\n"
                "  momentum error %.2e, interior velocity error %.2e, thickness error %.2e, centroid error max "
                "%.2e, at t = %.0f s %.2e\n",
                pair[0], pair[1], a, r.travel, 0.5 * a * kBlockT * kBlockT, r.steps, r.momentumErr, r.interiorErr,
                r.interiorHErr, r.centroidErr, kBlockT, r.centroidErrEnd);
    if (talus::test::validation::enabled()) {
      namespace vo = talus::test::validation;
      vo::Table t({"t_s", "travel_m", "travel_exact_m", "velocity_m_s", "velocity_exact_m_s"});
      for (const auto& row : r.series) t.add({row[0], row[1], row[2], row[3], row[4]});
      const std::string tag = std::to_string(static_cast<int>(pair[0])) + "_" + std::to_string(static_cast<int>(pair[1]));
      t.write("grid_block_series_" + tag + ".csv");
      vo::Table e({"theta_deg", "delta_deg", "a_m_s2", "travel_m", "travel_exact_m", "momentum_error", "interior_error",
                   "centroid_error_max", "centroid_error_end", "steps"});
      e.add({pair[0], pair[1], a, r.travel, 0.5 * a * kBlockT * kBlockT, r.momentumErr, r.interiorErr, r.centroidErr,
             r.centroidErrEnd, r.steps});
      e.write("grid_block_errors_" + tag + ".csv");
    }
    EXPECT_LE(r.momentumErr, kBlockMomentumTol) << pair[0] << "/" << pair[1];
    EXPECT_LE(r.interiorHErr, kBlockInteriorH) << "the block's interior should survive the smearing of its ends";
    EXPECT_LE(r.interiorErr, kBlockInteriorTol) << pair[0] << "/" << pair[1];
    EXPECT_LE(r.centroidErr, kBlockCentroidTol) << pair[0] << "/" << pair[1];
    EXPECT_LE(r.centroidErrEnd, kBlockCentroidEndTol) << pair[0] << "/" << pair[1];
  }

  const double resting[][2] = {{20.0, 30.0}, {30.0, 35.0}};
  for (const auto& pair : resting) {
    const double theta = pair[0] * kDeg, delta = pair[1] * kDeg;
    const Grid grid = Grid::make(kBlockNx, 1, kBlockDx);
    const fl::FlowInput in = planeScene(grid, theta, delta, 1e6, kBlockGrain,
                                        [](double x) { return x > kBlockFrom && x < kBlockTo ? kBlockH : 0.0; });
    const fl::FlowSettings s = dryGranularSettings();
    fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
    solver.setInput(in);
    const auto before = talus::test::readState(solver);
    const int steps = talus::test::advance(solver, talus::test::RunLimits::steps(300));
    const auto after = talus::test::readState(solver);
    int changed = 0, moving = 0;
    for (int i = 0; i < kBlockNx; ++i) {
      changed += after.hs[i] != before.hs[i];
      moving += after.qsx[i] != 0.0 || after.qsy[i] != 0.0;
    }
    std::printf("[ block theta %.0f, delta %.0f ] at rest: %d steps (t %.2f s), %d cells changed, %d cells moving, "
                "centroid %.17g -> %.17g\n",
                pair[0], pair[1], steps, solver.time(), changed, moving, before.solidCentroidX(grid),
                after.solidCentroidX(grid));
    EXPECT_EQ(steps, 300);
    EXPECT_EQ(changed, 0);
    EXPECT_EQ(moving, 0);
    EXPECT_EQ(after.solidCentroidX(grid), before.solidCentroidX(grid));
  }
  std::fflush(stdout);
}

// The first-order option (Limiter::None, "the first-order scheme, for comparisons") must be
// consistent too: the same block must accelerate with a: total momentum a t as above, and since the
// first-order mass flux through a face is h_i u_i of the upwind cell (the lateral pressure is zero
// and all velocities are >= 0, so both HLL speeds are >= 0), the sum of the mass fluxes is the
// total momentum and the SSP-RK2 update of the centroid is the trapezoidal rule of a linear
// velocity: the centroid is exact too (asserted to 1e-6). Without reconstruction the bed of
// every cell is flat, the within-cell bed source g_n h (b_hi - b_lo) of debris_stage.cl vanishes,
// and the slope force has to come from the face bed jumps of the hydrostatic reconstruction, which
// the solid face (solid_face) turns into (h - h*) Pi, the lateral pressure, instead of the weight:
// zero for this cohesive block, K g_p h tan(theta) / 2 for K = 1 without cohesion. EXPECTED TO FAIL
// until the solver is fixed (measured: the block does not move at all).
TEST(Granular, RigidBlockFirstOrderScheme) {
  const double theta = 35.0, delta = 20.0;
  const double a = an::slidingAcceleration(theta * kDeg, delta * kDeg);
  const BlockRun r = slideBlock(theta, delta, fl::Limiter::None);
  std::printf("[ block theta %.0f, delta %.0f, first order ] travel %.4f m (exact %.4f), momentum error %.3e, "
              "centroid error %.3e\n",
              theta, delta, r.travel, 0.5 * a * kBlockT * kBlockT, r.momentumErr, r.centroidErr);
  EXPECT_LE(r.momentumErr, kBlockMomentumTol);
  EXPECT_LE(r.centroidErr, 1e-6);
}

// ------------------------------------------------------------------------------------------------
// Pile at repose. A triangular pile H = max(0, 1 - |x - 4|) m (surface slope 1, i.e. 45 deg) on
// flat ground, domain [0, 8] m, delta = phi = 30 deg, no cohesion, constant K = 1, default grain
// size (1 cm: the toes thinner than that are slowed by the grain-size desingularisation, which only
// helps them stop; the slope is measured away from the toes). A pile at rest
// needs K g H |dH/dx| <= g H tan(delta), so it spreads until its flanks are no steeper than
// reposeSlope(delta, K) = tan 30 = 0.5774, and the implicit friction then sets every momentum to
// exactly zero: the run must reach a state where every cell has q_s = 0 exactly, and stay there
// bitwise (friction exceeds the discrete force imbalance in every cell, and locked cells pass no
// mass).
// Final slope: the largest centred difference |H_{i+1} - H_{i-1}| / (2 dx) over cells whose two
// neighbours are thicker than 5% of the final top (this excludes the thin toes, where the
// reconstruction is first order). It cannot exceed repose in a deposit at rest (up to the O(dx)
// difference between the centred slope and the face-pressure balance the scheme holds), and the
// flanks come to rest just at repose: the last moving material stops as soon as the slope allows.
// Grid effects: the deposit's flanks are resolved by 50-200 cells; the slope deficit is O(dx)
// (measured 4.3%, 1.9%, 1.1% for dx = 0.04, 0.02, 0.01 m, i.e. 28.9, 29.5, 29.7 deg), from the
// smearing of the slope near the top and the toe. Asserted on dx = 0.02 and 0.01 m: within 5%
// (1.5 deg) of repose, never above repose + 2%, and the deficit shrinks with dx.
namespace {

struct PileResult {
  double slope = 0, tStop = -1, top = 0, from = 0, to = 0;
  int steps = 0, stillMoving = 0, changedAfterStop = 0;
};

PileResult runPile(double dx) {
  const double phi = 30.0 * kDeg;
  const int nx = static_cast<int>(std::lround(8.0 / dx));
  const Grid grid = Grid::make(nx, 1, dx);
  talus::test::SolidMaterial mat;
  mat.phi = phi;
  mat.delta = phi;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int i = 0; i < nx; ++i) in.hs[i] = std::max(0.0, 1.0 - std::fabs(cellX(grid, i) - 4.0));
  const fl::FlowSettings s = dryGranularSettings();
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  PileResult r;
  // Until every momentum is exactly zero (at most 4 s; measured t = 1.0-1.1 s).
  r.steps = talus::test::advance(solver, talus::test::RunLimits::until(4.0), [&](const fl::FlowSolver& sv) {
    for (double q : sv.qsx())
      if (q != 0.0) return true;
    r.tStop = sv.time();
    return false;
  });
  const auto rest = talus::test::readState(solver);
  // Then 200 more steps: nothing may change.
  r.steps += talus::test::advance(solver, talus::test::RunLimits::steps(200));
  const auto st = talus::test::readState(solver);
  for (int i = 0; i < nx; ++i) {
    r.changedAfterStop += st.hs[i] != rest.hs[i];
    r.stillMoving += st.qsx[i] != 0.0 || st.qsy[i] != 0.0;
    r.top = std::max(r.top, st.hs[i]);
  }
  bool wet = false;
  for (int i = 0; i < nx; ++i)
    if (st.hs[i] > s.hDry) {
      if (!wet) r.from = cellX(grid, i);
      r.to = cellX(grid, i);
      wet = true;
    }
  if (talus::test::validation::enabled()) {
    talus::test::validation::Table t({"x_m", "hs_initial_m", "hs_final_m"});
    for (int i = 0; i < nx; ++i) t.add({cellX(grid, i), in.hs[i], st.hs[i]});
    char name[64];
    std::snprintf(name, sizeof name, "pile_profile_dx%.2f.csv", dx);
    t.write(name);
  }
  for (int i = 1; i + 1 < nx; ++i)
    if (st.hs[i - 1] > 0.05 * r.top && st.hs[i + 1] > 0.05 * r.top)
      r.slope = std::max(r.slope, std::fabs(st.hs[i + 1] - st.hs[i - 1]) / (2.0 * dx));
  return r;
}

}  // namespace

TEST(Granular, PileStopsNearReposeSlope) {
  const double repose = an::reposeSlope(30.0 * kDeg, 1.0);
  std::vector<PileResult> results;
  for (const double dx : {0.02, 0.01}) {
    const PileResult r = runPile(dx);
    results.push_back(r);
    std::printf("[ pile dx %.2f m ] at rest at t %.3f s (%d steps), deposit %.2f..%.2f m, top %.4f m, "
                "final slope %.4f = %.2f deg (repose tan(delta)/K %.4f = %.2f deg, phi 30 deg), deficit %.2f%%\n",
                dx, r.tStop, r.steps, r.from, r.to, r.top, r.slope, std::atan(r.slope) / kDeg, repose,
                std::atan(repose) / kDeg, 100.0 * (repose - r.slope) / repose);
    EXPECT_GT(r.tStop, 0.0) << "dx " << dx << ": the pile never came exactly to rest";
    EXPECT_EQ(r.stillMoving, 0) << "dx " << dx;
    EXPECT_EQ(r.changedAfterStop, 0) << "dx " << dx;
    EXPECT_NEAR(r.slope, repose, 0.05 * repose) << "dx " << dx;
    EXPECT_LE(r.slope, 1.02 * repose) << "dx " << dx;
  }
  if (talus::test::validation::enabled()) {
    talus::test::validation::Table t({"dx_m", "t_stop_s", "final_slope", "final_slope_deg", "repose_slope",
                                      "repose_deg", "deficit_percent"});
    const double dxs[] = {0.02, 0.01};
    for (std::size_t k = 0; k < results.size(); ++k)
      t.add({dxs[k], results[k].tStop, results[k].slope, std::atan(results[k].slope) / kDeg, repose,
             std::atan(repose) / kDeg, 100.0 * (repose - results[k].slope) / repose});
    t.write("pile_errors.csv");
  }
  EXPECT_LT(repose - results[1].slope, repose - results[0].slope) << "the slope deficit should shrink with dx";
  std::fflush(stdout);
}

// The energy budget's friction term (FlowDiagnostics::sourceWork, debris_stage.cl out_step row 2):
// the rigid block of RigidBlockSlidesWithExactAcceleration, theta 35 deg and delta 20 deg. The
// mechanical energy of a block that follows the plane is m u^2 / (2 cos^2 theta) (horizontal and
// vertical motion), and with u' = g cos^2(theta) (tan(theta) - tan(delta)) it changes at the rate
// m g u tan(theta) (the potential energy released) minus m g u tan(delta): the work of friction up
// to t is exactly m g tan(delta) x(t), x = a t^2 / 2 the horizontal travel. Asserted: the measured
// work within 1 % of that (the implicit friction of each stage removes, beyond the work F u, the
// O(dt) share (F dt)^2 / 2m of the kinetic energy; measured 5.6e-3), and the budget closes: the
// energy released equals the kinetic energy gained plus the friction work within 1 % of the release
// (measured 1.3e-3: the scheme's dissipation at the block's smearing ends). The work counts the
// vertical motion along the bed too: the horizontal kinetic energy alone gave 0.675 = cos^2(35 deg)
// of it.
TEST(Granular, FrictionWorkOfASlidingBlockIsTheExactWork) {
  const double theta = 35.0 * kDeg, delta = 20.0 * kDeg;
  const Grid grid = Grid::make(kBlockNx, 1, kBlockDx);
  const fl::FlowInput in = planeScene(grid, theta, delta, 1e6, kBlockGrain,
                                      [](double x) { return x > kBlockFrom && x < kBlockTo ? kBlockH : 0.0; });
  fl::FlowSettings s = dryGranularSettings();
  s.hDry = 1e-12;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  const fl::FlowDiagnostics d0 = solver.diagnostics();
  const double mass = talus::test::readState(solver).volumeSolid(kBlockDx) * talus::test::SolidMaterial{}.rhoS;
  double work = 0;
  talus::test::advance(solver, talus::test::RunLimits::until(kBlockT), [&](const fl::FlowSolver& sv) {
    work += sv.diagnostics().sourceWork;
    return true;
  });
  const double t = solver.time(), x = 0.5 * an::slidingAcceleration(theta, delta) * t * t;
  const double exact = mass * talus::kGravity * std::tan(delta) * x;
  const fl::FlowDiagnostics& d = solver.diagnostics();
  const double released = d0.potential - d.potential;
  const double gained = (d.kinetic + d.kineticVertical) - (d0.kinetic + d0.kineticVertical);
  std::printf("[ block theta 35, delta 20, t = %.3f s ] friction work %.6e J, exact %.6e J (error %.2e); released "
              "%.6e J, kinetic gained %.6e J, budget residual %.2e of the release\n",
              t, work, exact, work / exact - 1, released, gained, (released - gained - work) / released);
  EXPECT_NEAR(work / exact, 1.0, 1e-2);
  EXPECT_NEAR((released - gained - work) / released, 0.0, 1e-2);
}
