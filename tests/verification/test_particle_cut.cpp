// Vertical cut stability in the particle mode (spec §10): a cohesive column with vertical sides on
// flat ground stands when its height H <= H_c / 2 and collapses when H >= 2 H_c, with the critical
// height of a vertical cut H_c = 4 c / (gamma sqrt(K_a)) (Rankine with Bell's cohesion term, which
// is exactly where the model's lateral stress -max(0, K_a p_zz - 2 c sqrt(K_a)) becomes non-zero:
// p_zz = gamma H / 2). The factor-2 margins cover the Drucker-Prager fit to Mohr-Coulomb: the fit
// yields a column under its own weight at about 0.7 H_c already (vertical stress -gamma H / 2,
// in-plane zero). Double precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/Constants.hpp"
#include "flow/FlowSolver.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"
#include "support/TestDevice.hpp"
#include "verification/ValidationOut.hpp"

using namespace talus;
using namespace talus::particles;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct CutResult {
  double maxSpeed = 0, spread = 0, minCohesionFraction = 1, massError = 0;
  std::size_t particles = 0;
};

constexpr double kCutDx = 0.5, kCutC = 1e4, kCutPhi = 30 * kDeg, kCutRho = 2000.0;

/// A square column of 8 x 8 cells of 0.5 m and height H in the middle of an n x n flat grid: c = 10
/// kPa, phi = delta = 30 degrees, rho 2000, K = K_a (constant), E = 10 MPa.
struct ColumnScene {
  Grid grid;
  ParticleTerrain terrain;
  SeededParticles seeded;
  ParticleMaterial material;
  ParticleSettings settings;
};

ColumnScene columnScene(int n, double H) {
  ColumnScene c;
  c.grid = Grid::make(n, n, kCutDx);
  c.terrain.mask.assign(c.grid.cells(), 1);
  c.terrain.bed.assign(c.grid.cells(), 0.0);
  SeedInput in;
  in.mask = c.terrain.mask;
  in.bed = c.terrain.bed;
  in.thickness.assign(c.grid.cells(), 0.0);
  in.density.assign(c.grid.cells(), kCutRho);
  for (int j = n / 2 - 4; j < n / 2 + 4; ++j)
    for (int i = n / 2 - 4; i < n / 2 + 4; ++i) in.thickness[c.grid.index(i, j)] = H;
  c.seeded = seedParticles(c.grid, in, SeedSpacing{0, 4});
  c.material.density = {kCutRho};
  c.material.phi = {kCutPhi};
  c.material.delta = {kCutPhi};
  c.material.cohesion = {kCutC};
  c.settings.youngModulus = 1e7;
  c.settings.earthPressure = ParticleEarthPressure::Constant;
  c.settings.kConst = (1 - std::sin(kCutPhi)) / (1 + std::sin(kCutPhi));
  return c;
}

/// The column of columnScene(40, H), run for 2 s. spread: growth of the largest distance of a
/// particle from the column's centre line.
CutResult runColumn(double H) {
  const ColumnScene c = columnScene(40, H);
  ParticleSolver solver(test::testContext(compute::Precision::Double), c.grid, c.terrain, c.settings);
  solver.setParticles(c.seeded, c.material);
  const double centre = 20 * kCutDx;
  auto extent = [&](const ParticleState& s) {
    double e = 0;
    for (std::size_t q = 0; q < s.size(); ++q) e = std::max({e, std::fabs(s.x[q] - centre), std::fabs(s.y[q] - centre)});
    return e;
  };
  const double e0 = extent(solver.state());
  const double m0 = solver.diagnostics().mass;
  CutResult r;
  double outflow = 0;
  for (int k = 0; k < 20; ++k) {
    solver.step(0.1);
    r.maxSpeed = std::max(r.maxSpeed, solver.diagnostics().maxSpeed);
    outflow += solver.diagnostics().outflowMass;
  }
  const ParticleState s = solver.state();
  r.spread = extent(s) - e0;
  for (std::size_t q = 0; q < s.size(); ++q) r.minCohesionFraction = std::min(r.minCohesionFraction, s.cohesion[q] / s.cohesion0[q]);
  r.massError = std::fabs(solver.diagnostics().mass + outflow - m0) / m0;  // particles may leave the raster
  r.particles = s.size();
  if (talus::test::validation::enabled()) {  // the particles at 2 s: deposit and cohesion fraction
    talus::test::validation::Table t({"x_m", "y_m", "cohesion_fraction", "thickness_m"});
    for (std::size_t q = 0; q < s.size(); ++q) t.add({s.x[q], s.y[q], s.cohesion[q] / s.cohesion0[q], s.H[q]});
    char name[64];
    std::snprintf(name, sizeof name, "cut_particles_H%.3f.csv", H);
    t.write(name);
  }
  return r;
}

}  // namespace

TEST(ParticleCut, ShortColumnStandsTallColumnCollapses) {
  const double c = 1e4, phi = 30 * kDeg, gamma = 2000.0 * kGravity;
  const double Ka = (1 - std::sin(phi)) / (1 + std::sin(phi));
  const double Hc = 4 * c / (gamma * std::sqrt(Ka));
  const CutResult shortCol = runColumn(0.5 * Hc);
  const CutResult tallCol = runColumn(2.0 * Hc);
  std::printf("vertical cut, H_c = %.3f m: H = H_c/2: max speed %.3g m/s, spread %.3g m, min c/c0 %.3f; "
              "H = 2 H_c: max speed %.3g m/s, spread %.3f m, min c/c0 %.3f (%zu particles, mass error %.1e)\n",
              Hc, shortCol.maxSpeed, shortCol.spread, shortCol.minCohesionFraction, tallCol.maxSpeed, tallCol.spread,
              tallCol.minCohesionFraction, tallCol.particles, tallCol.massError);
  {
    talus::test::validation::Table t({"case", "H_m", "Hc_m", "H_over_Hc", "max_speed_m_s", "spread_m",
                                      "min_cohesion_fraction", "particles", "mass_error", "file"});
    char f1[64], f2[64];
    std::snprintf(f1, sizeof f1, "cut_particles_H%.3f.csv", 0.5 * Hc);
    std::snprintf(f2, sizeof f2, "cut_particles_H%.3f.csv", 2.0 * Hc);
    t.add({"stands", 0.5 * Hc, Hc, 0.5, shortCol.maxSpeed, shortCol.spread, shortCol.minCohesionFraction,
           shortCol.particles, shortCol.massError, f1});
    t.add({"collapses", 2.0 * Hc, Hc, 2.0, tallCol.maxSpeed, tallCol.spread, tallCol.minCohesionFraction,
           tallCol.particles, tallCol.massError, f2});
    t.write("cut_errors.csv");
  }
  // Standing: nothing drives it (no lateral push, inside the yield surface): exactly at rest.
  EXPECT_EQ(shortCol.maxSpeed, 0.0);
  EXPECT_EQ(shortCol.minCohesionFraction, 1.0);
  // Collapsing: the sides move out by more than a metre in 2 s and bonds break where it yields.
  EXPECT_GT(tallCol.spread, 1.0);
  EXPECT_LT(tallCol.minCohesionFraction, 0.5);
  EXPECT_LT(tallCol.massError, 1e-12);  // mass + tallied outflow: a sum of equal masses, round-off only
}

// Water release (OpenLISEM Hazard P.27-P.28): the tall column of the test above, holding confined
// water (half of each particle's volume), collapses; where bonds break the water leaves the particles
// (V_f = V_f0 c / c0) and ParticleSolver::releaseToGrid moves it onto the grid's free fluid
// (FlowSolver::addFluid), where it flows. Fluid volume: grid water + water still held by the
// particles + released but not yet moved = the initial confined water, after every grid step, to
// round-off (double: sums of ~10^3 terms, 1e-12 relative); and mass: particles + rho_f x grid water
// = the initial mass. Walls and a 30 m domain: nothing leaves.
TEST(ParticleCut, ReleasedWaterReachesTheGridConserved) {
  const double rhoF = 1000.0;
  const double Ka = (1 - std::sin(kCutPhi)) / (1 + std::sin(kCutPhi));
  ColumnScene c = columnScene(60, 2 * 4 * kCutC / (kCutRho * kGravity * std::sqrt(Ka)));
  const Grid& g = c.grid;
  const ParticleTerrain& terrain = c.terrain;
  const double dx = kCutDx;
  c.material.fluidVolume = c.seeded.volume;
  for (double& v : c.material.fluidVolume) v *= 0.5;
  c.settings.fluidDensity = rhoF;
  compute::Context& ctx = test::testContext(compute::Precision::Double);
  ParticleSolver particles(ctx, g, terrain, c.settings);
  particles.setParticles(c.seeded, c.material);
  flow::FlowSettings fs;
  fs.edge = flow::Boundary::Wall;
  flow::FlowSolver fluid(ctx, g, fs);
  flow::FlowInput fin;
  fin.mask = terrain.mask;
  fin.bed = terrain.bed;
  fin.manning.assign(g.cells(), 0.0);
  fin.h.assign(g.cells(), 0.0);
  fluid.setInput(fin);
  const double water0 = particles.diagnostics().confinedFluid, mass0 = particles.diagnostics().mass;
  double worstVolume = 0, worstMass = 0, released = 0;
  for (int k = 0; k < 20; ++k) {
    double dt = std::min(0.1, fluid.stableDt());
    fluid.step(dt);
    particles.step(dt);
    fluid.addFluid([&](compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy) {
      released += particles.releaseToGrid(h, qx, qy);
    });
    const ParticleDiagnostics& d = particles.diagnostics();
    const double water = fluid.diagnostics().volume + d.confinedFluid + d.pendingRelease;
    worstVolume = std::max(worstVolume, std::fabs(water - water0) / water0);
    worstMass = std::max(worstMass, std::fabs(d.mass + rhoF * fluid.diagnostics().volume - mass0) / mass0);
  }
  std::printf("water release: %.3f of %.3f m^3 released to the grid; fluid volume balance %.2e, mass balance %.2e\n",
              released, water0, worstVolume, worstMass);
  EXPECT_GT(released, 0.1 * water0) << "the collapsing column must release water";
  // The released-fluid map holds what was moved, cell by cell (same P2G weights).
  const std::vector<double> map = particles.gridFields().releasedFluid;
  double mapped = 0;
  for (double v : map) mapped += v * dx * dx;
  EXPECT_NEAR(mapped, released, 1e-12 * released);
  EXPECT_LT(worstVolume, 1e-12);
  EXPECT_LT(worstMass, 1e-12);
}
