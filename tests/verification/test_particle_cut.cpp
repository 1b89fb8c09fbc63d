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

using namespace talus;
using namespace talus::particles;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct CutResult {
  double maxSpeed = 0, spread = 0, minCohesionFraction = 1, massError = 0;
  std::size_t particles = 0;
};

/// A square column (8 x 8 cells of 0.5 m) of height H, c = 10 kPa, phi = 30 degrees, K = K_a, run
/// for 2 s. spread: growth of the largest distance of a particle from the column's centre line.
CutResult runColumn(double H) {
  const double dx = 0.5, c = 1e4, phi = 30 * kDeg, rho = 2000.0;
  const Grid g = Grid::make(40, 40, dx);
  ParticleTerrain terrain;
  terrain.mask.assign(g.cells(), 1);
  terrain.bed.assign(g.cells(), 0.0);
  SeedInput in;
  in.mask = terrain.mask;
  in.bed = terrain.bed;
  in.thickness.assign(g.cells(), 0.0);
  in.density.assign(g.cells(), rho);
  for (int j = 16; j < 24; ++j)
    for (int i = 16; i < 24; ++i) in.thickness[g.index(i, j)] = H;
  const SeededParticles seeded = seedParticles(g, in, SeedSpacing{0, 4});
  ParticleMaterial mat;
  mat.density = {rho};
  mat.phi = {phi};
  mat.delta = {phi};
  mat.cohesion = {c};
  ParticleSettings ps;
  ps.youngModulus = 1e7;
  ps.earthPressure = ParticleEarthPressure::Constant;
  ps.kConst = (1 - std::sin(phi)) / (1 + std::sin(phi));
  ParticleSolver solver(test::testContext(compute::Precision::Double), g, terrain, ps);
  solver.setParticles(seeded, mat);
  const double centre = 20 * dx;
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
  const double dx = 0.5, c = 1e4, phi = 30 * kDeg, rho = 2000.0, rhoF = 1000.0;
  const double Ka = (1 - std::sin(phi)) / (1 + std::sin(phi));
  const double H = 2 * 4 * c / (rho * kGravity * std::sqrt(Ka));
  const Grid g = Grid::make(60, 60, dx);
  ParticleTerrain terrain;
  terrain.mask.assign(g.cells(), 1);
  terrain.bed.assign(g.cells(), 0.0);
  SeedInput in;
  in.mask = terrain.mask;
  in.bed = terrain.bed;
  in.thickness.assign(g.cells(), 0.0);
  in.density.assign(g.cells(), rho);
  for (int j = 26; j < 34; ++j)
    for (int i = 26; i < 34; ++i) in.thickness[g.index(i, j)] = H;
  const SeededParticles seeded = seedParticles(g, in, SeedSpacing{0, 4});
  ParticleMaterial mat;
  mat.density = {rho};
  mat.phi = {phi};
  mat.delta = {phi};
  mat.cohesion = {c};
  mat.fluidVolume = seeded.volume;
  for (double& v : mat.fluidVolume) v *= 0.5;
  ParticleSettings ps;
  ps.youngModulus = 1e7;
  ps.earthPressure = ParticleEarthPressure::Constant;
  ps.kConst = Ka;
  ps.fluidDensity = rhoF;
  compute::Context& ctx = test::testContext(compute::Precision::Double);
  ParticleSolver particles(ctx, g, terrain, ps);
  particles.setParticles(seeded, mat);
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
