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
// With a fixed h they parted where the particles stand farther apart than h: a particle with only
// itself in its support has S_i = W(0, h) and H_i = V_i W(0, h) / a_i, whatever the distance to its
// neighbours. The thickness sums now take a smoothing length that follows the spacing, h_i = h
// sqrt(A_i / A_0) up to 3 h (particle_density.cl), so the expanding layer below is tested to 9 times
// its area and the dam-break test prints its thin ends (figures before and after: docs/particles.md,
// "Verification"). The quadrature figures: tools/validation/sph_number_density_quadrature.py.
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
  double edge = 0, edgeMax = 0;  // the particles within 2 h_i of the layer's edge
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
// - the particles' own H at lambda = 1.2, 1.5, 2 and 3 (area 1.44, 2.25, 4 and 9 times): the thickness
//   sums' smoothing length follows the spacing (h_i = h lambda, up to 3 h), so h_i / dp stays the
//   seeding's 2 and the number density's quadrature error stays the one the anchor a_i took away at
//   the seeding. What is left is the change of that error as the layout stretches. Measured: mean
//   +0.60 / +0.48 / +0.36 / +0.24 %, largest 0.63 / 0.50 / 0.38 / 0.25 %. Tolerance 1.5 % (mean) and
//   2 % (largest): under the seeded layout's scatter of S dp^2 (2.7 %), which a particle whose anchor
//   was not kept, or whose sums did not follow the spacing, would show. With a fixed h the same
//   layer gave +1.5 / +3.0 / +7.2 / +33 % (largest 4.6 / 12 / 31 / 121 %): the floor of the header.
// - the same for the particles within 2 h_i of the layer's edge (448 of them), the free edge of a
//   spreading layer being where a front's particles stand apart: the Shepard form is exact at a
//   free edge of a uniform layer and the anchor took the kernel's deficiency there away at the
//   seeding. Measured +0.63 / +0.51 / +0.38 / +0.26 % (largest 0.73 / 0.58 / 0.44 / 0.32 %); same
//   tolerances. With a fixed h: +4.1 / +8.7 / +17 / +51 % (largest 13 / 32 / 66 / 184 %).
// A particle thickness that followed its own continuity integral instead of the positions, an anchor
// lost on a sort, or a P2G that dropped or doubled weights would each fail one of these.
TEST(ParticleThickness, FollowsAUniformExpansionToItsEdgesAsTheGridDoes) {
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
    // Inside the edge by the thickness sums' support 2 h_i = 2 h min(lambda, 3) (h = dx).
    const double exact = 1.0 / (lambda * lambda), inner = lambda * half0 - 2 * dx * std::min(lambda, 3.0);
    const ParticleState st = solver.state();
    ExpansionErrors e;
    int n = 0, m = 0;
    for (std::size_t q = 0; q < st.size(); ++q) {
      const double err = st.H[q] / exact - 1;
      if (std::max(std::fabs(st.x[q] - xc), std::fabs(st.y[q] - xc)) > inner) {
        e.edge += err;
        e.edgeMax = std::max(e.edgeMax, std::fabs(err));
        ++m;
        continue;
      }
      e.particles += err;
      e.particlesMax = std::max(e.particlesMax, std::fabs(err));
      ++n;
    }
    e.particles /= n;
    e.edge /= m;
    const ParticleGridFields gf = solver.gridFields();
    int cells = 0;
    for (int j = 0; j < s.grid.ny; ++j)
      for (int i = 0; i < s.grid.nx; ++i)
        if (std::max(std::fabs((i + 0.5) * dx - xc), std::fabs((j + 0.5) * dx - xc)) <= inner - 2 * dx) {
          e.grid += gf.thickness[s.grid.index(i, j)] / exact - 1;
          ++cells;
        }
    e.grid /= cells;
    std::printf("layer expanded %.2f times in area: interior particles' H %+.4f (largest |error| %.4f), edge "
                "particles' %+.4f (%.4f), grid %+.4f of the exact %.4f m\n",
                lambda * lambda, e.particles, e.particlesMax, e.edge, e.edgeMax, e.grid, exact);
    return e;
  };
  for (int k = 0; k < 4; ++k) solver.step(0.5);  // t = 2 s
  const ExpansionErrors a = measure(1.0 + rate * 2.0);
  for (int k = 0; k < 6; ++k) solver.step(0.5);  // t = 5 s
  const ExpansionErrors b = measure(1.0 + rate * 5.0);
  for (int k = 0; k < 10; ++k) solver.step(0.5);  // t = 10 s
  const ExpansionErrors c = measure(1.0 + rate * 10.0);
  for (int k = 0; k < 20; ++k) solver.step(0.5);  // t = 20 s
  const ExpansionErrors d = measure(1.0 + rate * 20.0);
  EXPECT_LT(std::fabs(a.grid), 0.02);
  EXPECT_LT(std::fabs(b.grid), 0.02);
  EXPECT_LT(std::fabs(c.grid), 0.02);
  EXPECT_LT(std::fabs(d.grid), 0.02);
  for (const ExpansionErrors& e : {a, b, c, d}) {
    EXPECT_LT(std::fabs(e.particles), 0.015);
    EXPECT_LT(e.particlesMax, 0.02);
    EXPECT_LT(std::fabs(e.edge), 0.015);
    EXPECT_LT(e.edgeMax, 0.02);
  }
}

// A real flow: the cohesionless particle dam break of test_particle_dambreak.cpp (Mangeney's setup,
// 35 degrees, 4 particles per 1 m cell) at t = 3 s, where the layer has spread from 1 m to a fan thinning
// to nothing over 20 m. In the middle band (6 m, no side effects), per 1 m column: the particles' mean
// H against the grid's mean thickness (P2G), over the columns where the grid holds at least 0.4 m
// (1.6 particles per cell or more, spacing up to 0.8 m against h = 1 m: h/dp >= 1.26). Measured: mean
// |difference| 1.3 %, largest 3.7 % (3.1 % with a fixed h; the B-spline smooths over 4 cells, the
// kernel over 2h_i >= 2 m, and the fan is curved on that scale). Tolerances 3 % (mean) and 6 %
// (largest), 1.6 to 2.3 times the measured:
// the two are different smoothings of the same positions. The thin ends (grid < 0.15 m; one to three
// particles per column of the band) are printed, not checked: there the particles' H is a kernel
// average over 2 h_i (up to 6 m), the grid's a B-spline over 1.5 cells, so their ratio (1.0-3.0 with
// the adaptive h_i, 1.6-3.8 with a fixed h) measures the two smoothings of a steep front as much as
// either thickness; the expanding layer above is the check of the particles' thickness where they
// stand apart.
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
