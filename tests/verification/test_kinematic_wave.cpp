// Rain on a tilted plane (docs/sources.md): the outflow hydrograph at the open lower edge against
// the kinematic-wave solution for Manning friction. On a plane of length L, slope S, Manning n
// under rain i from t = 0 on a dry bed, the kinematic wave (q = alpha h^(5/3), alpha = sqrt(S)/n)
// gives at the outlet (e.g. Singh 1996, Kinematic Wave Modeling in Water Resources, ch. 4)
//   q(L, t) = alpha (i t)^(5/3)                    for t < t_c,
//   q(L, t) = i L                                  for t >= t_c,
//   t_c = (L / (alpha i^(2/3)))^(3/5) = (n L / (sqrt(S) i^(2/3)))^(3/5).
// The shallow-water model keeps the pressure and inertia terms the kinematic wave drops; with the
// kinematic-wave number k = S L / (h_e F_e^2) about 275 here (h_e = 7.3 mm, F_e = 0.70 at the
// outlet in equilibrium) they change the hydrograph by O(1/k) except near t_c, where the kinematic
// wave has a corner that the pressure term rounds off. Hydrographs are compared as means over 5 s
// windows (t_c/100), which smooths the step-to-step variation of the boundary flux.
// TALUS_KW_CELLS=N runs the plane with N cells (default 50) to measure the grid's share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "flow/FlowSolver.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;

namespace {

struct Plane {
  double length = 100.0;                          // L [m]
  double slope = 0.01;                            // S
  double manning = 0.02;                          // n [s m^-1/3]
  double rain = 50.0 / (3600.0 * 1000.0);         // i [m/s] (50 mm/h)
  double alpha() const { return std::sqrt(slope) / manning; }
  double concentration() const { return std::pow(length / (alpha() * std::pow(rain, 2.0 / 3.0)), 0.6); }
  double outflow(double t) const {  // kinematic wave q(L, t) [m^2/s]
    return t < concentration() ? alpha() * std::pow(rain * t, 5.0 / 3.0) : rain * length;
  }
  double cumulative(double t) const {  // its integral from 0 to t [m^2]
    const double tc = concentration(), T = std::min(t, tc);
    return 3.0 / 8.0 * alpha() * std::pow(rain, 5.0 / 3.0) * std::pow(T, 8.0 / 3.0) + rain * length * std::max(0.0, t - tc);
  }
};

struct Hydrograph {
  std::vector<double> t, out;  // step end times and the cumulative outflow per unit width [m^2]
  double rainVolume = 0, outVolume = 0, finalVolume = 0;
};

/// One row of cells i = 1..N (dx = L / N) between nodata walls; the raster's right edge, at the foot
/// of the plane, is `edge` (open or level: outflow only).
Hydrograph runPlane(const Plane& p, int cells, double endTime, fl::Boundary edge = fl::Boundary::Open) {
  auto& ctx = talus::test::testContext(Precision::Double);
  const double dx = p.length / cells;
  const Grid g = Grid::make(cells + 1, 3, dx, 0.0, 0.0);
  fl::FlowInput in;
  in.mask.assign(g.cells(), 0);
  in.bed.assign(g.cells(), 0.0);
  in.manning.assign(g.cells(), p.manning);
  in.h.assign(g.cells(), 0.0);
  for (int i = 1; i <= cells; ++i) {
    const std::size_t k = g.index(i, 1);
    in.mask[k] = 1;
    in.bed[k] = p.slope * (p.length - (i - 0.5) * dx);
  }
  fl::FlowSettings s;
  s.slopeCorrection = false;  // the classical equations the kinematic wave approximates
  s.edge = edge;
  fl::FlowSolver solver(ctx, g, s);
  solver.setInput(in);
  Hydrograph h;
  h.t.push_back(0.0);
  h.out.push_back(0.0);
  double t = 0;
  while (t < endTime) {
    const double dt = std::min({solver.stableDt(), 1.0, endTime - t});
    solver.step(dt, p.rain * dt);
    t += dt;
    h.t.push_back(t);
    h.out.push_back(h.out.back() + solver.diagnostics().outflow / dx);
    h.rainVolume += solver.diagnostics().rain;
    h.outVolume += solver.diagnostics().outflow;
  }
  h.finalVolume = solver.diagnostics().volume;
  return h;
}

/// Cumulative outflow at time t, linear between step ends [m^2].
double cumulative(const Hydrograph& h, double t) {
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(h.t.begin(), h.t.end(), t) - h.t.begin());
  if (k >= h.t.size()) return h.out.back();
  const double w = (t - h.t[k - 1]) / (h.t[k] - h.t[k - 1]);
  return h.out[k - 1] + w * (h.out[k] - h.out[k - 1]);
}

/// The model's outflow per unit width at time t: the mean over [t - window, t] [m^2/s], which
/// smooths the step-to-step variation of the boundary flux.
double at(const Hydrograph& h, double t, double window) {
  return (cumulative(h, t) - cumulative(h, t - window)) / window;
}

}  // namespace

/// Runs the plane with the foot's `edge` and checks the hydrograph against the kinematic wave.
static void checkHydrograph(fl::Boundary edge, double risingBound, double cornerBound) {
  const Plane p;
  const double tc = p.concentration(), qe = p.rain * p.length, window = 5.0;
  const int cells = std::getenv("TALUS_KW_CELLS") ? std::atoi(std::getenv("TALUS_KW_CELLS")) : 50;
  const Hydrograph h = runPlane(p, cells, 3.0 * tc, edge);
  std::printf("plane L = %.0f m, S = %.3f, n = %.3f, i = 50 mm/h, %d cells: t_c = %.1f s, q_e = %.4e m^2/s\n",
              p.length, p.slope, p.manning, cells, tc, qe);
  double worstRising = 0, worstCorner = 0;
  for (double f : {0.2, 0.4, 0.6, 0.8, 0.9, 1.0, 1.1, 1.25, 1.5, 2.0, 2.5, 3.0}) {
    const double t = f * tc;
    const double model = at(h, t, window), exact = (p.cumulative(t) - p.cumulative(t - window)) / window;
    const double err = (model - exact) / qe;
    std::printf("  t/t_c = %.2f  q = %.5e  kinematic %.5e  (q - q_kw)/q_e = %+.4f\n", f, model, exact, err);
    if (f <= 0.8 || f >= 1.5)
      worstRising = std::max(worstRising, std::fabs(err));
    else
      worstCorner = std::max(worstCorner, std::fabs(err));
  }
  std::printf("  max error away from t_c %.4f, near t_c %.4f (of q_e)\n", worstRising, worstCorner);
  // Away from the corner at t_c the difference is the scheme's: measured 0.032 of q_e at 50 cells
  // and 0.018 at 100 (TALUS_KW_CELLS=100), largest early on, when the film at the foot is 1-3 mm
  // thick over cells of 2 m and the open boundary's first-order cell sets the outflow. The bound
  // keeps a quarter of margin over the 50-cell figure.
  EXPECT_LT(worstRising, risingBound);
  // Near t_c the kinematic wave has a corner that the shallow-water pressure term rounds off:
  // measured 0.030 at 50 cells and 0.028 at 100 (the physics, not the grid); same margin.
  EXPECT_LT(worstCorner, cornerBound);
  // Equilibrium: after 3 t_c the outflow equals the rain on the plane.
  EXPECT_NEAR(at(h, 3.0 * tc, 60.0), qe, 0.002 * qe);
  // Volume: rain = stored + outflow, to round-off.
  EXPECT_NEAR(h.finalVolume + h.outVolume, h.rainVolume, 1e-12 * h.rainVolume);
}

TEST(KinematicWave, RainOnTiltedPlaneHydrograph) { checkHydrograph(fl::Boundary::Open, 0.04, 0.04); }

// The same plane whose foot is a level edge: the plane starts dry, so the outside is dry and the
// foot a free overfall (the film leaves at up to the critical speed the characteristics allow
// instead of the copied inside state). Measured at 50 cells: 0.018 away from t_c, 0.026 near it
// (open, measured in the same build: 0.030, 0.035); same bounds.
TEST(KinematicWave, RainOnTiltedPlaneLevelEdge) { checkHydrograph(fl::Boundary::Level, 0.04, 0.04); }
