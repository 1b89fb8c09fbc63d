// Solids on a rough bed with the curvature term on (kernels/flow/terrain_curvature.cl): a real DEM's
// noise must not become speed.
//
// Scene: a 40 deg plane, cells of 1 m, every cell's bed raised or lowered by an independent uniform
// amount in [-A, A] (A = 0.5 m: a DEM whose cell-to-cell noise is of the order of the slope's own
// rise over a cell, local curvatures up to 2 A / dx^2 = 1 1/m). A block of solids 0.5 m thick, 8 x 10
// cells near the top, frictionless, with hydrostatic lateral pressure (K = 1), is released at rest
// and slides for 9 s (its front about 160 m down the plane), inside walls.
//
// References (independent of the scheme): the mechanical energy of the model, kinetic (horizontal and
// vertical, (u.grad b)^2 / 2) plus potential g m (b + h/2) (with K = 1 the shallow layer's internal
// energy is the h/2 of the potential), can only fall: nothing in the model adds energy, and the
// scheme's mixing takes it away (the turn onto each cell's tangent plane keeps the speed). And no
// material may move faster than free fall from the highest released point to the lowest bed it has
// reached plus what the release's own pressure can give its front, sqrt(2 g dz) + 2 sqrt(g h0)
// (the dam-break front speed of a layer h0 = 0.5 m: Ritter).
//
// Measured (double): the path-based turn: no energy gain, 0.906 of the speed bound (0.701 on the
// smooth plane). The centred curvature u^T H u of each cell's own velocity (the form before, issue
// 13's avaKot failure): energy 1.3e4 times the energy released, 2400 times the speed bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "core/Constants.hpp"
#include "flow/FlowSolver.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"
#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

using namespace talus;
namespace fl = talus::flow;

namespace {

constexpr double kH0 = 0.5;  // release thickness [m]

struct RoughRun {
  double gain = 0;       ///< largest (E(t) - E(0)) / (potential energy released by then)
  double speedRatio = 0;  ///< largest speed / free-fall speed from the top of the release
  double released = 0;   ///< potential energy released at the end [J]
};

constexpr int kNx = 20, kNy = 200;

/// The 40 deg plane with independent uniform noise in [-amplitude, amplitude] per cell, falling
/// towards j = ny.
std::vector<double> roughBed(const Grid& grid, double amplitude) {
  const double slope = std::tan(40.0 * 3.14159265358979323846 / 180.0);
  std::mt19937 rng(20261203u);
  std::uniform_real_distribution<double> noise(-amplitude, amplitude);
  std::vector<double> bed(grid.cells());
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) bed[grid.index(i, j)] = slope * (grid.ny - j) * grid.dx + noise(rng);
  return bed;
}

/// The release: 8 x 10 cells near the top.
bool released(int i, int j) { return i >= 6 && i < 14 && j >= 8 && j < 18; }

/// The blocks' settings: two-phase solids between walls, K = 1, the bed friction angle as given.
fl::FlowSettings blockSettings(bool curvature) {
  fl::FlowSettings s = test::granularBetweenWalls(1.0);
  s.curvature = curvature;
  return s;
}

RoughRun runRough(double amplitude, bool curvature) {
  const Grid grid = Grid::make(kNx, kNy, 1.0);
  test::SolidMaterial mat;
  mat.phi = mat.delta = 0.0;
  fl::FlowInput in = test::debrisInput(grid, mat);
  in.bed = roughBed(grid, amplitude);
  double top = -1e300;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i)
      if (released(i, j)) {
        const std::size_t k = grid.index(i, j);
        in.hs[k] = kH0;
        top = std::max(top, in.bed[k] + in.hs[k]);
      }
  fl::FlowSolver solver(test::testContext(compute::Precision::Double), grid, blockSettings(curvature));
  solver.setInput(in);
  const fl::FlowDiagnostics d0 = solver.diagnostics();
  const double e0 = d0.kinetic + d0.kineticVertical + d0.potential;
  RoughRun r;
  test::advance(solver, test::RunLimits::until(9.0), [&](const fl::FlowSolver& sv) {
    const fl::FlowDiagnostics& d = sv.diagnostics();
    const double released = d0.potential - d.potential;
    // (from the first step on: the release's first movements are round-off)
    if (released > 1e-6 * d0.potential) r.gain = std::max(r.gain, (d.kinetic + d.kineticVertical + d.potential - e0) / released);
    r.released = released;
    const std::vector<double> hs = sv.hs(), qx = sv.qsx(), qy = sv.qsy();
    double lowest = 1e300, fastest = 0;
    for (std::size_t k = 0; k < hs.size(); ++k)
      if (hs[k] > 1e-6) {
        lowest = std::min(lowest, in.bed[k]);
        fastest = std::max(fastest, std::hypot(qx[k], qy[k]) / hs[k]);
      }
    if (lowest < top)
      r.speedRatio = std::max(r.speedRatio, fastest / (std::sqrt(2.0 * kGravity * (top - lowest)) + 2.0 * std::sqrt(kGravity * kH0)));
    return true;
  });
  return r;
}

}  // namespace

// Asserted: no growth of the mechanical energy beyond 1e-3 of the energy released (the valley test's
// bound for the diagnostics' second-order sums; measured: the energy never rose above its initial
// value), and speeds below the bound.
TEST(TerrainRoughness, FrictionlessBlockOnANoisyPlaneGainsNoEnergy) {
  const RoughRun smooth = runRough(0.0, true), rough = runRough(0.5, true);
  std::printf("[ rough plane, curvature on ] smooth: energy gain %.2e of released, speed %.3f of free fall; "
              "A = 0.5 m: gain %.2e, speed %.3f of free fall (released %.3e J)\n",
              smooth.gain, smooth.speedRatio, rough.gain, rough.speedRatio, rough.released);
  EXPECT_GT(rough.released, 0.5 * smooth.released) << "the block must slide down the rough plane";
  EXPECT_LE(rough.gain, 1e-3);
  EXPECT_LE(smooth.gain, 1e-3);
  EXPECT_LT(rough.speedRatio, 1.0);
  EXPECT_LT(smooth.speedRatio, 1.0);
}

namespace {

struct CorrugatedRun {
  double speed = 0;    ///< mass-weighted mean downslope (horizontal, +y) velocity at the end [m/s]
  double liftOff = 0;  ///< largest lift-off speed w of a cell over the run [m/s]
};

/// A block of solids 0.5 m thick, 8 x 10 cells, launched at 20 m/s down a 30 deg plane corrugated
/// along the fall line (a sinusoid of amplitude `amplitude`, wavelength 8 m, on 1 m cells), after 2 s
/// (curvature term on, bed friction angle `deltaDeg`, K = 1, walls).
CorrugatedRun runCorrugated(double amplitude, double deltaDeg) {
  constexpr double kPi = 3.14159265358979323846, kV0 = 20.0, kWavelength = 8.0;
  const Grid grid = Grid::make(kNx, kNy, 1.0);
  test::SolidMaterial mat;
  mat.phi = 0.0;
  mat.delta = deltaDeg * kPi / 180.0;
  fl::FlowInput in = test::debrisInput(grid, mat);
  const double slope = std::tan(30.0 * kPi / 180.0);
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const std::size_t k = grid.index(i, j);
      in.bed[k] = slope * (kNy - j) * grid.dx + amplitude * std::sin(2.0 * kPi * j * grid.dx / kWavelength);
      if (released(i, j)) {
        in.hs[k] = kH0;
        in.qsy[k] = kH0 * kV0;
      }
    }
  fl::FlowSolver solver(test::testContext(compute::Precision::Double), grid, blockSettings(true));
  solver.setInput(in);
  CorrugatedRun r;
  test::advance(solver, test::RunLimits::until(2.0), [&](const fl::FlowSolver& sv) {
    const std::vector<double> hs = sv.hs(), hw = sv.hsLiftOff();
    for (std::size_t k = 0; k < hs.size(); ++k)
      if (hs[k] > 1e-3) r.liftOff = std::max(r.liftOff, hw[k] / hs[k]);
    return true;
  });
  const std::vector<double> hs = solver.hs(), qy = solver.qsy();
  double m = 0, q = 0;
  for (std::size_t k = 0; k < hs.size(); ++k) m += hs[k], q += qy[k];
  r.speed = q / m;
  return r;
}

}  // namespace

// Coulomb friction over a corrugated bed with the curvature term: the bed's normal force follows the
// material's path, but the bed only pushes. Where fast material runs over a convex crest (u^2 b''
// below -g) it lifts off, and the next concave trough is its landing (solid_bed.cl, point 5).
// Reference: the momentum balance normal to the mean bed. The block's vertical momentum stays
// bounded, so over many corrugations the normal force it takes from the bed averages gravity's, and
// the friction on it takes the same speed from the block as on the smooth plane: the speed lost to
// friction, (frictionless - Coulomb) mean velocity after 2 s on the same bed, is the smooth plane's.
// Clamping each cell's normal load at zero instead (no lift-off, the form before) counts the
// troughs' extra load without the crests' relief.
// 30 deg plane, delta = 20 deg, launched at 20 m/s; corrugations of 8 m and 0.1 / 0.2 m, u^2 b'' up
// to 2.5 / 4.9 g. Asserted: the ratio within 10 % of 1 (the frictionless and Coulomb runs meet the
// corrugations at other speeds and phases, and the scheme's dissipation on the corrugations differs
// between them by a few per cent). Measured: 1.031 / 1.042; the clamped load: 1.379 / 1.870.
TEST(TerrainRoughness, CoulombBlockOverCorrugationsLosesThePlanesSpeedToFriction) {
  constexpr double kDelta = 20.0;
  const double smoothLoss = runCorrugated(0.0, 0.0).speed - runCorrugated(0.0, kDelta).speed;
  EXPECT_GT(smoothLoss, 0.0);
  for (const double amplitude : {0.1, 0.2}) {
    const CorrugatedRun free = runCorrugated(amplitude, 0.0), coulomb = runCorrugated(amplitude, kDelta);
    const double ratio = (free.speed - coulomb.speed) / smoothLoss;
    std::printf("[ corrugated plane, Coulomb, curvature on ] speed lost to friction in 2 s: smooth %.3f m/s, "
                "A = %.2f m %.3f m/s (frictionless %.3f, Coulomb %.3f); ratio %.3f; largest lift-off %.2f m/s\n",
                smoothLoss, amplitude, free.speed - coulomb.speed, free.speed, coulomb.speed, ratio, coulomb.liftOff);
    EXPECT_GT(coulomb.liftOff, 0.0) << "the crests must throw the block off (the case this checks)";
    EXPECT_NEAR(ratio, 1.0, 0.1) << amplitude;
  }
}

namespace {

struct NoisyBlockRun {
  double worstParticle = 0;  ///< largest particle speed over sqrt(2 g (top of the release - lowest bed reached))
  double worstCentre = 0;    ///< largest 3-D speed of the centre of mass over sqrt(2 g (its own drop))
  double worstEnergy = 0;    ///< largest kinetic energy over (potential released + artificial stress work)
  double descended = 0;      ///< top of the release - lowest bed cell reached [m]
};

/// The stiff frictionless block of ParticleBlockOnANoisyPlaneStaysBelowFreeFall on the 40 deg plane
/// with noise amplitude `amplitude`.
NoisyBlockRun particleBlockOnNoisyPlane(double amplitude) {
  // 2 m thick: the noise's steps (up to 2 A = 1 m) are ramps to it, not walls (particle_integrate.cl).
  constexpr double kBlockH = 2.0;
  const Grid grid = Grid::make(kNx, kNy, 1.0);
  particles::ParticleTerrain terrain;
  terrain.curvature = true;
  terrain.mask.assign(grid.cells(), 1);
  terrain.bed = roughBed(grid, amplitude);
  particles::SeedInput in;
  in.mask = terrain.mask;
  in.bed = terrain.bed;
  in.thickness.assign(grid.cells(), 0.0);
  in.density.assign(grid.cells(), 2400.0);
  double top = -1e300;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i)
      if (released(i, j)) {
        in.thickness[grid.index(i, j)] = kBlockH;
        top = std::max(top, terrain.bed[grid.index(i, j)]);
      }
  const particles::SeededParticles seeded = particles::seedParticles(grid, in, particles::SeedSpacing{0, 2});
  particles::ParticleMaterial mat;
  mat.density = {2400.0};
  mat.phi = {30.0 * 3.14159265358979323846 / 180.0};
  mat.delta = {0.0};
  mat.cohesion = {1e7};
  particles::ParticleSettings ps;
  ps.edgeWalls = true;
  particles::ParticleSolver solver(test::testContext(compute::Precision::Double), grid, terrain, ps);
  solver.setParticles(seeded, mat);
  auto cellOf = [&](double x, double y) {
    const int i = std::min(kNx - 1, std::max(0, static_cast<int>(std::floor(x / grid.dx))));
    const int j = std::min(kNy - 1, std::max(0, static_cast<int>(std::floor(y / grid.dx))));
    return grid.index(i, j);
  };
  // The centre of mass's height: the mass-weighted DEM value of the cells under the particles.
  auto centreHeight = [&](const particles::ParticleState& st) {
    double mz = 0, m = 0;
    for (std::size_t q = 0; q < st.size(); ++q) mz += st.mass[q] * terrain.bed[cellOf(st.x[q], st.y[q])], m += st.mass[q];
    return mz / m;
  };
  const double tanSlope = std::tan(40.0 * 3.14159265358979323846 / 180.0), z0 = centreHeight(solver.state());
  NoisyBlockRun r;
  double lowestReached = top;
  for (int k = 0; k < 180; ++k) {
    solver.step(0.05);
    const particles::ParticleState st = solver.state();
    // Until the block's front comes within 20 m of the lower wall (the impact is another test).
    if (*std::max_element(st.y.begin(), st.y.end()) > (kNy - 20) * grid.dx) break;
    for (std::size_t q = 0; q < st.size(); ++q) {
      const int i = static_cast<int>(std::floor(st.x[q] / grid.dx)), j = static_cast<int>(std::floor(st.y[q] / grid.dx));
      if (i < 0 || j < 0 || i >= kNx || j >= kNy) continue;
      lowestReached = std::min(lowestReached, terrain.bed[grid.index(i, j)]);
    }
    // (from 10 m of descent on: before, the block's elastic settling speeds dominate a bound near 0)
    for (std::size_t q = 0; q < st.size(); ++q)
      if (top - lowestReached > 10.0)
        r.worstParticle = std::max(r.worstParticle, std::hypot(st.vx[q], st.vy[q]) / std::sqrt(2.0 * kGravity * (top - lowestReached)));
    // The centre of mass: its horizontal velocity, and its vertical one along the mean plane.
    double m = 0, px = 0, py = 0;
    for (std::size_t q = 0; q < st.size(); ++q) m += st.mass[q], px += st.mass[q] * st.vx[q], py += st.mass[q] * st.vy[q];
    const double ux = px / m, uy = py / m, drop = z0 - centreHeight(st);
    if (drop > 10.0)
      r.worstCentre = std::max(r.worstCentre, std::sqrt(ux * ux + uy * uy * (1 + tanSlope * tanSlope)) / std::sqrt(2.0 * kGravity * drop));
    // The whole block: its kinetic energy on the bed against what the bed surface released along the
    // particles' own paths (both from particle_integrate.cl's exact bilinear bed), plus the artificial
    // stress's work where it is on.
    const particles::ParticleDiagnostics& d = solver.diagnostics();
    if (top - lowestReached > 10.0)
      r.worstEnergy = std::max(r.worstEnergy, d.kinetic / (d.potentialReleased + d.artificialStressWork));
  }
  r.descended = top - lowestReached;
  return r;
}

}  // namespace

// The particles on a rough plane (particle_integrate.cl): a stiff frictionless block, 2 m thick,
// 8 x 10 cells, slides down the 40 deg plane with A = 0, 0.1, 0.25 and 0.5 m of noise (a lidar DEM's
// to the roughness of test FrictionlessBlockOnANoisyPlaneGainsNoEnergy) until its front is 20 m from
// the lower wall, with the default numerical terms (artificial viscosity alpha_Pi = 0.1, no
// artificial stress). Two references, checked from 10 m of descent on (before, the block's elastic
// settling speeds dominate bounds near zero):
// - the whole block's energy: the bed does no work on a frictionless block, the artificial viscosity
//   only dissipates and the elastic energy is never negative, so the block's kinetic energy on the bed,
//   sum m (|v|^2 + (v . grad b)^2) / 2, is at most the potential energy the bed surface released along
//   the particles' own paths (plus the artificial stress's work, zero here). Tolerance 0.5 %: the
//   symplectic step's energy oscillation (measured 0.9997 on the smooth plane, where the bound holds
//   with equality up to the viscosity);
// - the centre of mass: the block's kinetic energy is at least that of its centre of mass,
//   M |V_c|^2 / 2 (Cauchy-Schwarz), with V_c the 3-D velocity (the mean horizontal velocity, the
//   vertical one along the mean 40 deg plane). So |V_c| <= sqrt(2 g dz_c), with dz_c from the DEM
//   values of the cells under the particles. Tolerance 0.5 %: on the smooth plane the measure gives
//   1.0003 (the particles' positions inside their cells, averaged over 320 of them); with noise,
//   sampling the noise under the particles adds at most A / sqrt(320) / 10 m = 0.3 % to the drop at
//   10 m, half that to the speed.
// Measured (largest values from 10 m of descent on): energy 0.9997 / 0.996 / 0.983 / 0.930 (at the
// end 0.23 at A = 0.5: the rough bed takes energy, a block thrown off a crest lands inelastically and
// rings); centre of mass 1.0000 / 0.989 / 0.926 / 0.765.
// The largest single-particle speed over free fall from the top of the release to the lowest bed
// reached is printed, not bounded: an elastic body need not share its energy evenly, and with the
// literature's weak viscosity the block ringing on the 0.25 and 0.5 m bumps throws edge particles to
// 1.11 and 1.59 times that speed (0.74 and 0.98 at A = 0 and 0.1) while the whole block holds less
// than what it released (the paper's
// alpha_Pi = beta_Pi = 1, the default until 2026-12-07, damped the ringing: 0.76 / 0.87 / 0.85 / 0.89).
// Before the bed was one surface (particle_common.cl, bed_gradient; the force sampled a blend
// of the cells' centred differences, which is not the gradient of any surface): the centre of mass
// 1.0003 / 1.031 / (not run) / 1.120 at A = 0 / 0.1 / 0.25 / 0.5, faster than its own free fall by 3
// and 12 %, which the particle bound (0.832 / 0.908 / 0.977) did not catch. Before the internal forces took the bed's metric, the particle
// bound was 0.863 / 1.019 / 1.859: the bonds exchanged horizontal kinetic energy while the turn keeps
// the 3-D speed; the centred curvature v^T H v before the turn gave 1.051 at A = 0.1 (2.96 / 16.4 at
// 0.25 / 0.5).
TEST(TerrainRoughness, ParticleBlockOnANoisyPlaneStaysBelowFreeFall) {
  for (const double amplitude : {0.0, 0.1, 0.25, 0.5}) {
    const NoisyBlockRun r = particleBlockOnNoisyPlane(amplitude);
    std::printf("[ rough plane A = %.2f m, particles, curvature on ] kinetic energy %.4f of the released, centre of mass "
                "%.4f of its free fall, largest particle speed %.3f of free fall, %.1f m descended\n",
                amplitude, r.worstEnergy, r.worstCentre, r.worstParticle, r.descended);
    EXPECT_GT(r.descended, 50.0) << "the block must slide down the plane, A = " << amplitude;
    EXPECT_LT(r.worstEnergy, 1.005) << "A = " << amplitude;
    EXPECT_LT(r.worstCentre, 1.005) << "A = " << amplitude;
  }
}

namespace {

/// Mean downslope velocity, averaged over the second second, of a loose particle block (2 m thick,
/// 8 x 10 cells, phi 30 deg, no cohesion) launched at 20 m/s down the corrugated 30 deg plane of
/// runCorrugated (amplitude `amplitude`), with bed friction angle `deltaDeg` (curvature term on).
double particleBlockSpeed(double amplitude, double deltaDeg) {
  constexpr double kPi = 3.14159265358979323846, kV0 = 20.0, kWavelength = 8.0;
  const Grid grid = Grid::make(kNx, kNy, 1.0);
  particles::ParticleTerrain terrain;
  terrain.curvature = true;
  terrain.mask.assign(grid.cells(), 1);
  terrain.bed.assign(grid.cells(), 0.0);
  const double slope = std::tan(30.0 * kPi / 180.0);
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i)
      terrain.bed[grid.index(i, j)] = slope * (kNy - j) * grid.dx + amplitude * std::sin(2.0 * kPi * j * grid.dx / kWavelength);
  particles::SeedInput in;
  in.mask = terrain.mask;
  in.bed = terrain.bed;
  in.thickness.assign(grid.cells(), 0.0);
  in.density.assign(grid.cells(), 2400.0);
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i)
      if (released(i, j)) in.thickness[grid.index(i, j)] = 2.0;
  const particles::SeededParticles seeded = particles::seedParticles(grid, in, particles::SeedSpacing{0, 2});
  particles::ParticleMaterial mat;
  mat.density = {2400.0};
  mat.phi = {30.0 * kPi / 180.0};
  mat.delta = {deltaDeg * kPi / 180.0};
  mat.cohesion = {0.0};
  particles::ParticleSettings ps;
  ps.edgeWalls = true;
  particles::ParticleSolver solver(test::testContext(compute::Precision::Double), grid, terrain, ps);
  solver.setParticles(seeded, mat);
  solver.setVelocities(std::vector<double>(seeded.x.size(), 0.0), std::vector<double>(seeded.x.size(), kV0));
  double mean = 0;
  for (int k = 0; k < 40; ++k) {
    solver.step(0.05);
    if (k < 20) continue;
    const particles::ParticleState st = solver.state();
    double m = 0, p = 0;
    for (std::size_t q = 0; q < st.size(); ++q) m += st.mass[q], p += st.mass[q] * st.vy[q];
    mean += p / m / 20;
  }
  return mean;
}

}  // namespace

// The particles' form of CoulombBlockOverCorrugationsLosesThePlanesSpeedToFriction: each particle
// carries its lift-off speed (particle_integrate.cl), so a loose block launched at 20 m/s over the
// 0.2 m corrugations loses to friction about the smooth plane's speed. The particle kernel's rules for
// one particle (the turn, the lift-off, the cells' centred gradients interpolated, as written out in
// a 60-line script) give a mean normal load of 1.06 g_n there (the clamped load 1.87); the block's
// particles, bound by their elasto-plastic stresses, take up the corrugations' kicks differently with
// and without friction, and the block's ratio is 1.18 (1.21 before its internal forces took the bed's
// metric; clamped load: 1.91). Asserted: within 25 % of 1, which the clamped form misses by a factor
// 3.6; the block's extra 12 % is an open finding.
TEST(TerrainRoughness, ParticleBlockOverCorrugationsLosesThePlanesSpeedToFriction) {
  constexpr double kDelta = 20.0, kA = 0.2;
  const double smoothLoss = particleBlockSpeed(0.0, 0.0) - particleBlockSpeed(0.0, kDelta);
  const double roughFree = particleBlockSpeed(kA, 0.0), roughCoulomb = particleBlockSpeed(kA, kDelta);
  const double ratio = (roughFree - roughCoulomb) / smoothLoss;
  std::printf("[ corrugated plane, particles, Coulomb ] speed lost to friction (mean over 1-2 s): smooth %.3f m/s, A = %.2f m "
              "%.3f m/s (frictionless %.3f, Coulomb %.3f); ratio %.3f\n",
              smoothLoss, kA, roughFree - roughCoulomb, roughFree, roughCoulomb, ratio);
  EXPECT_GT(smoothLoss, 0.0);
  EXPECT_NEAR(ratio, 1.0, 0.25);
}
