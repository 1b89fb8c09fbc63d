// Water falling over a cliff resolved by one cell, with every limiter: the energy the shallow-water
// equations allow, E_kin(t) <= E_kin(0) + g (P(0) - P(t)) with P = sum h (b + h/2) dx^2 (friction,
// shocks and the open edge only remove energy), must hold step by step.
//
// Scene (issue 13, after the stress suite's cliff failures): a 1D channel of 40 cells of 5 m on a
// gentle 1 % slope with a 50 m cliff between cells 19 and 20, 2 m of still water in cells 5-14,
// Manning 0.03, open edges, 90 s. Before the subcell face bed of Chen & Noelle (riemann.cl) and the
// minmod face bed (flow_common.cl, reconstruct_surface) the limiters disagreed on this scene: peak
// speeds 4.11 m/s (none), 4.69 (minmod), 24.17 (van Leer), 4.20 (MC). The face at the cliff edge
// passed only a dam-break flux (the drop's bed force was lost), and van Leer's false face-bed rises
// accelerated water that they held (on the 2D version MC reached 41.8 m/s where the fall allows
// 34.3). Measured now (double): the excess of E_kin over E_kin(0) + g dP is never positive (energy is
// only lost) and the peak speeds are 17.92, 21.80, 24.42, 24.40 m/s. The peak is reached by the thin
// sheet below the cliff and grows with resolution for every limiter (first order 17.9, 20.3, 22.1,
// 23.3 m/s at 5, 2.5, 1.25, 0.625 m cells; van Leer 24.4, 25.4, 26.7, 27.9), so the reference for the
// limiters' peaks is the first-order scheme on cells 8 times finer. (With face thicknesses that were
// allowed outside their neighbours' range, before 2026-12-06, every limiter held the sheet back:
// 17.46, 18.54, 18.73, 18.82 m/s.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/Constants.hpp"
#include "flow/FlowSolver.hpp"
#include "support/FlowScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;

namespace {

struct Energy {
  double kinetic = 0, potential = 0;  // per unit density: sum h u^2 / 2 dx^2, g sum h (b + h/2) dx^2
};

Energy energyOf(const std::vector<double>& h, const std::vector<double>& qx, const std::vector<double>& bed,
                double dx, double hDry) {
  Energy e;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (h[k] > hDry) e.kinetic += 0.5 * qx[k] * qx[k] / h[k] * dx * dx;
    e.potential += talus::kGravity * h[k] * (bed[k] + 0.5 * h[k]) * dx * dx;
  }
  return e;
}

struct CliffRun {
  double worstExcess = 0;  // max over steps of (E_kin - E_kin(0) - g dP) / (g |dP| + tiny)
  double peakSpeed = 0;    // max over steps and cells of |u| [m/s]
};

/// The scene on cells of 5 / refine m (the cliff and the water at the same places).
CliffRun runCliff(fl::Limiter limiter, int refine = 1) {
  const int nx = 40 * refine;
  const double dx = 5.0 / refine;
  const talus::Grid grid = talus::Grid::make(nx, 1, dx);
  fl::FlowInput in;
  in.mask.assign(nx, 1);
  in.bed.resize(nx);
  in.manning.assign(nx, 0.03);
  in.h.assign(nx, 0.0);
  for (int i = 0; i < nx; ++i) {
    in.bed[i] = 0.01 * dx * (nx - i) + (i < 20 * refine ? 50.0 : 0.0);
    if (i >= 5 * refine && i < 15 * refine) in.h[i] = 2.0;
  }
  fl::FlowSettings s;
  s.limiter = limiter;
  s.slopeCorrection = false;
  s.edge = fl::Boundary::Open;
  fl::FlowSolver solver(talus::test::testContext(talus::compute::Precision::Double), grid, s);
  solver.setInput(in);
  const Energy e0 = energyOf(solver.h(), solver.qx(), in.bed, dx, s.hDry);
  CliffRun r;
  while (solver.time() < 90.0) {
    solver.step(std::min(solver.stableDt(), 90.0 - solver.time()));
    const std::vector<double> h = solver.h(), qx = solver.qx();
    const Energy e = energyOf(h, qx, in.bed, dx, s.hDry);
    const double released = e0.potential - e.potential;
    r.worstExcess = std::max(r.worstExcess, (e.kinetic - e0.kinetic - released) / (std::fabs(released) + 1e-9));
    for (int i = 0; i < nx; ++i)
      if (h[i] > s.hDry) r.peakSpeed = std::max(r.peakSpeed, std::fabs(qx[i] / h[i]));
  }
  return r;
}

}  // namespace

TEST(CliffEnergy, WaterOverACliffGainsNoEnergyWithAnyLimiter) {
  const struct { fl::Limiter limiter; const char* name; } cases[] = {
      {fl::Limiter::None, "none"}, {fl::Limiter::Minmod, "minmod"}, {fl::Limiter::VanLeer, "vanleer"}, {fl::Limiter::MC, "mc"}};
  std::vector<double> peaks;
  for (const auto& c : cases) {
    const CliffRun r = runCliff(c.limiter);
    std::printf("[ cliff 50 m, 5 m cells, %-7s ] worst (E_kin - E_kin0 - g dP) / g|dP| %+.3e, peak speed %.2f m/s\n", c.name,
                r.worstExcess, r.peakSpeed);
    // Rounding of the sums is ~1e-15 of the energies; 1e-6 of the released energy is far below the
    // old excess (the MC speed 41.8 m/s against 34.3 is a 50 % energy excess in that cell).
    EXPECT_LE(r.worstExcess, 1e-6) << c.name;
    peaks.push_back(r.peakSpeed);
  }
  // The limiters change the reconstruction, not the energy of the fall: their peak speeds lie within
  // 25 % of the resolved peak (the first-order scheme on 0.625 m cells, 23.3 m/s; the 5 m peaks are
  // 0.77-1.05 of it, van Leer's false rises once made it 5.9 times the first-order 5 m peak), and
  // below what the fall can give: free fall over the relief plus the release's dam-break front
  // speed 2 sqrt(g h0) (Ritter).
  const double resolved = runCliff(fl::Limiter::None, 8).peakSpeed;
  const double fall = std::sqrt(2.0 * talus::kGravity * (50.0 + 0.01 * 200.0)) + 2.0 * std::sqrt(talus::kGravity * 2.0);
  std::printf("[ cliff 50 m, 0.625 m cells, none ] peak speed %.2f m/s; bound of the fall %.2f m/s\n", resolved, fall);
  for (const double v : peaks) {
    EXPECT_NEAR(v, resolved, 0.25 * resolved);
    EXPECT_LT(v, fall);
  }
}
