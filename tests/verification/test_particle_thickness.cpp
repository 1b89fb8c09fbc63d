// The particles' own thickness H_i (particle_density.cl: H_i = sum V_j W_ij / sum A_j W_ij with the
// areas A_i = a_i / S_i of the number density) against two independent references (issue 18, item 2):
// the exact thickness of a uniformly expanding layer, and the thickness P2G gives the grid
// (particle_grid.cl), which distributes each particle's volume with a partition of unity and so holds
// the particles' volume exactly, whatever their spacing. Double precision.
//
// The two agree where the layer is resolved, to the quadrature error of the number density (the sum
// S_i = sum_j W_ij over a layout of spacing dp approximates 1/dp^2 less well as dp approaches h: on an
// unbounded layout of the R2 sequence S dp^2 - 1 is 0.6 % at h/dp = 2 (the seeding), 1.0 % at 1.67,
// 1.7 % at 1.33 and 4.7 % at 1.0; the anchor a_i removes its value at the seeding, not its growth).
// They part at a thin front whose particles stand farther apart than h: there the fixed h leaves a
// particle with only itself and a few neighbours in its support, S_i tends to W(0) and H_i to
// V_i W(0) / a_i, independent of how far the neighbours are. The dam-break test prints that front;
// docs/particles.md ("Not yet done") gives the figures and the fix (a smoothing length that follows the
// spacing). The quadrature figures: tools/validation/sph_number_density_quadrature.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "particles/ParticleSolver.hpp"
#include "support/FlatParticleBlock.hpp"
#include "support/ParticleDamBreakScene.hpp"
#include "support/TestDevice.hpp"

using namespace talus;
using namespace talus::particles;

namespace {

/// Means over the interior of an expanding block of the particles' H / exact - 1 and the grid's.
struct ExpansionErrors {
  double particles = 0, particlesMax = 0, grid = 0;
};

}  // namespace

// An 8 m square layer, 1 m thick, 4 particles per 0.5 m cell (h = dx = 2 dp), on a flat frictionless
// bed with no lateral pressure, no artificial terms and a negligible stiffness (E = 1e-3 Pa), is given
// the uniform expansion v = 0.1/s (x - x_c): its particles move on straight lines, x(t) = x_c +
// lambda(t) (x_0 - x_c), lambda = 1 + 0.1 t, and the exact thickness is H_0 / lambda^2 everywhere.
// Compared where the kernel and the B-spline see only the layer (more than 2h from its current edge):
// - the grid's thickness, the mean over those cells: P2G is volume-exact, so its mean is exact up to
//   the sampling of 4 / lambda^2 particles per cell over 144-256 cells (per-cell scatter 5-10 %;
//   measured -0.03 % and +0.29 %); tolerance 2 %;
// - the particles' own H, the mean over those particles: the number density's quadrature error
//   (header; the seeded per-cell R2 layout is less even than the unbounded sequence): measured
//   +1.5 % at lambda = 1.2 (area 1.44 times, h/dp = 1.67) and +3.0 % at 1.5 (2.25 times, h/dp = 1.33);
//   tolerance 2.5 % and 5 %, the unbounded layout's error plus the seeded layout's scatter at the
//   seeding (2.7 %, the sd of S dp^2 at h/dp = 2), rounded up;
// - the particles' largest interior H: within 10 % and 20 % (measured +4.6 % and +12 %).
// A particle thickness that followed its own continuity integral instead of the positions, an anchor
// lost on a sort, or a P2G that dropped or doubled weights would each fail one of these.
TEST(ParticleThickness, FollowsAUniformExpansionAsTheGridDoesWhileTheLayerIsResolved) {
  const double rho = 2000.0, rate = 0.1, dx = 0.5, xc = 16.0, half0 = 4.0;
  const test::FlatParticleBlock s = test::flatParticleBlock(64, dx, 24, 40, rho, 4);
  ParticleSettings ps;
  ps.youngModulus = 1e-3;
  ps.soundSpeed = 5.0;  // sets the sub-step only (no artificial viscosity)
  ps.alphaPi = 0;
  ps.betaPi = 0;
  ps.earthPressure = ParticleEarthPressure::Constant;
  ps.kConst = 0.0;
  ParticleSolver solver(test::testContext(compute::Precision::Double), s.grid, s.terrain, ps);
  solver.setParticles(s.seeded, s.material);
  test::setRadialVelocity(solver, s.seeded, rate, xc);
  auto measure = [&](double lambda) {
    const double exact = 1.0 / (lambda * lambda), inner = lambda * half0 - 2 * dx;
    const ParticleState st = solver.state();
    ExpansionErrors e;
    int n = 0;
    for (std::size_t q = 0; q < st.size(); ++q) {
      if (std::max(std::fabs(st.x[q] - xc), std::fabs(st.y[q] - xc)) > inner) continue;
      e.particles += st.H[q] / exact - 1;
      e.particlesMax = std::max(e.particlesMax, std::fabs(st.H[q] / exact - 1));
      ++n;
    }
    e.particles /= n;
    const ParticleGridFields gf = solver.gridFields();
    int cells = 0;
    for (int j = 0; j < s.grid.ny; ++j)
      for (int i = 0; i < s.grid.nx; ++i)
        if (std::max(std::fabs((i + 0.5) * dx - xc), std::fabs((j + 0.5) * dx - xc)) <= inner - 2 * dx) {
          e.grid += gf.thickness[s.grid.index(i, j)] / exact - 1;
          ++cells;
        }
    e.grid /= cells;
    std::printf("layer expanded %.2f times in area: interior particles' H %+.4f (largest |error| %.4f), grid %+.4f "
                "of the exact %.4f m\n",
                lambda * lambda, e.particles, e.particlesMax, e.grid, exact);
    return e;
  };
  for (int k = 0; k < 4; ++k) solver.step(0.5);  // t = 2 s
  const ExpansionErrors a = measure(1.0 + rate * 2.0);
  for (int k = 0; k < 6; ++k) solver.step(0.5);  // t = 5 s
  const ExpansionErrors b = measure(1.0 + rate * 5.0);
  EXPECT_LT(std::fabs(a.grid), 0.02);
  EXPECT_LT(std::fabs(b.grid), 0.02);
  EXPECT_LT(std::fabs(a.particles), 0.025);
  EXPECT_LT(std::fabs(b.particles), 0.05);
  EXPECT_LT(a.particlesMax, 0.10);
  EXPECT_LT(b.particlesMax, 0.20);
}

// A real flow: the cohesionless particle dam break of test_particle_dambreak.cpp (Mangeney's setup,
// 35 degrees, 4 particles per 1 m cell) at t = 3 s, where the layer has spread from 1 m to a fan thinning
// to nothing over 20 m. In the middle band (6 m, no side effects), per 1 m column: the particles' mean
// H against the grid's mean thickness (P2G), over the columns where the grid holds at least 0.4 m
// (1.6 particles per cell or more, spacing up to 0.8 m against h = 1 m: h/dp >= 1.26). Measured: mean
// |difference| 1.2 %, largest 3.1 % (the B-spline smooths over 4 cells, the kernel over 2h = 2 m, and
// the fan is curved on that scale). Tolerances 3 % (mean) and 6 % (largest), about twice the measured:
// the two are different smoothings of the same positions. (At 0.36 m, the reservoir's thinning rear,
// the difference is 6 %, at 0.1 m and less, the front, 1.6-3.8 times: header.) The thin ends (grid
// < 0.15 m) are printed.
TEST(ParticleThickness, AgreesWithTheGridInADamBreakWhereTheLayerIsResolved) {
  const test::ParticleDamBreakScene scene = test::makeParticleDamBreak(4);
  const double T = 3.0, dx = scene.dx, yc = 0.5 * scene.ny * dx, band = 3.0;
  const int nx = scene.nx;
  ParticleSettings ps;
  ps.youngModulus = 1e6;
  ps.earthPressure = ParticleEarthPressure::Constant;
  ps.kConst = 1.0;
  ParticleSolver solver(test::testContext(compute::Precision::Double), scene.grid, scene.terrain, ps);
  solver.setParticles(scene.seeded, scene.material);
  for (int k = 0; k < 30; ++k) solver.step(T / 30);
  const ParticleState s = solver.state();
  const ParticleGridFields gf = solver.gridFields();
  std::vector<double> hSum(nx, 0.0), hCount(nx, 0.0), gSum(nx, 0.0), gCount(nx, 0.0);
  for (std::size_t q = 0; q < s.size(); ++q) {
    if (std::fabs(s.y[q] - yc) > band || !(s.x[q] >= 0) || s.x[q] >= nx * dx) continue;
    const int i = static_cast<int>(s.x[q] / dx);
    hSum[i] += s.H[q];
    hCount[i] += 1;
  }
  for (int j = 0; j < scene.ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (std::fabs((j + 0.5) * dx - yc) <= band) {
        gSum[i] += gf.thickness[scene.grid.index(i, j)];
        gCount[i] += 1;
      }
  double meanDiff = 0, maxDiff = 0;
  int resolved = 0;
  for (int i = 0; i < nx; ++i) {
    if (hCount[i] == 0) continue;
    const double hp = hSum[i] / hCount[i], hg = gSum[i] / gCount[i];
    if (hg >= 0.4) {
      meanDiff += std::fabs(hp / hg - 1);
      maxDiff = std::max(maxDiff, std::fabs(hp / hg - 1));
      ++resolved;
    } else if (hg < 0.15) {
      std::printf("  front column x = %4.1f m: particles' H %.3f m, grid %.3f m (%.2f times), %.0f particles\n",
                  (i + 0.5) * dx, hp, hg, hp / hg, hCount[i]);
    }
  }
  meanDiff /= resolved;
  std::printf("dam break, %d columns with >= 0.4 m: particles' H against the grid's thickness: mean |difference| "
              "%.4f, largest %.4f\n",
              resolved, meanDiff, maxDiff);
  EXPECT_GE(resolved, 15);  // the fan's body: x from about 8 to 30 m
  EXPECT_LT(meanDiff, 0.03);
  EXPECT_LT(maxDiff, 0.06);
}
