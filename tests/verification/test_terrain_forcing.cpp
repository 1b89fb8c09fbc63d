// Solids on curved terrain (kernels/flow/solid_bed.cl, point 1: gravity with the bed's curvature).
//
// Valley. A slope of alpha_1 turns smoothly into a counter-slope of alpha_2: b'(x) runs linearly
// from -tan(alpha_1) to +tan(alpha_2) over a transition of W = 60 m (constant curvature there), with
// cells of 1 m, in a 1-cell-wide channel with walls. A block of solids 5 m long and 1 m thick is
// released at rest with its centroid Z0 = 50 m above the valley floor; no lateral pressure (K = 0)
// and no cohesion: every material point moves as a bead on the bed.
//
// Reference: a bead on z = b(x) in horizontal coordinates obeys x'' = -lambda (b' + mu sign(x')),
// lambda = (g + b'' x'^2) / (1 + b'^2) (the normal reaction; the friction's vertical part cancels
// from lambda, see solid_bed.cl), integrated here by RK4 with a step of 1e-4 s from the block's
// release centroid and the analytic b', b''. Without friction it conserves
// (x'^2 (1 + b'^2)) / 2 + g b, so it climbs back to its release height exactly.
//
// Measured: the highest elevation of the block's centroid on the counter-slope, above the floor,
// against the bead's. The block is not a point (5 m long, so its points start up to 1.6 m
// (40 deg) apart in elevation) and the finite-volume scheme mixes their momenta where the block
// compresses in the valley, an inelastic loss; both are first order in the block length and the
// cell size. Before the curvature term the mass climbed to 0.65 of its release height (40 -> 20
// deg, issue 13), the error growing with the difference of the slopes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/Constants.hpp"
#include "flow/FlowSolver.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"
#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"
#include "support/ValleyBead.hpp"

using namespace talus;
namespace fl = talus::flow;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kW = 60.0, kZ0 = 50.0, kBlockL = 5.0, kBlockH = 1.0;

/// The valley of the header: W = 60 m, release Z0 = 50 m above the floor, 10 m of bed above it.
test::Valley valley(double a1, double a2) { return test::Valley(a1, a2, kW, kZ0, 10.0); }

/// Domain length: room for the climb up the counter-slope.
double valleyLength(const test::Valley& v) { return v.xa + kW + 1.3 * kZ0 / v.s2 + 10.0; }

/// Highest elevation above the floor that a bead released at rest at x0 reaches on the
/// counter-slope (its first turning point), with friction coefficient mu.
double beadRunUp(const test::Valley& v, double x0, double mu) { return v.bed(test::beadTurningPoint(v, x0, mu)); }

struct RunUp {
  double release = 0;  ///< centroid elevation of the release above the floor [m]
  double highest = 0;  ///< highest centroid elevation on the counter-slope [m]
  double bead = 0;     ///< the bead's run-up from the release centroid [m]
  double gain = 0;     ///< max over steps of (E(t) - E(0)) / (largest potential energy released)
  double low = 0;      ///< share of the volume on bed below Z0 / 5 when the centroid is highest
};

RunUp runValley(double a1, double a2, double mu, double kDx, bool curvature = true) {
  const test::Valley v = valley(a1, a2);
  const int nx = static_cast<int>(std::ceil(valleyLength(v) / kDx));
  const Grid grid = Grid::make(nx, 1, kDx);
  test::SolidMaterial mat;
  mat.phi = mat.delta = std::atan(mu);
  fl::FlowInput in = test::debrisInput(grid, mat);
  // Find the cell centre whose bed is kZ0 and put the block around it.
  int ic = 0;
  for (int i = 0; i < nx; ++i)
    if (v.bed(test::cellX(grid, i)) >= kZ0 && test::cellX(grid, i) < v.xf) ic = i;
  const int half = static_cast<int>(kBlockL / kDx) / 2;
  for (int i = 0; i < nx; ++i) {
    in.bed[i] = v.bed(test::cellX(grid, i));
    if (i >= ic - half && i <= ic + half) in.hs[i] = kBlockH;
  }
  fl::FlowSettings s = test::granularBetweenWalls(0.0);
  s.debris.filmThickness = 0.0;
  s.curvature = curvature;
  fl::FlowSolver solver(test::testContext(compute::Precision::Double), grid, s);
  solver.setInput(in);
  auto centroid = [&](const std::vector<double>& hs) {
    double m0 = 0, m1 = 0, mx = 0;
    for (int i = 0; i < nx; ++i) {
      m0 += hs[i];
      m1 += hs[i] * in.bed[i];
      mx += hs[i] * test::cellX(grid, i);
    }
    return std::pair<double, double>{m1 / m0, mx / m0};
  };
  RunUp r;
  const auto [z0, x0] = centroid(in.hs);
  r.release = z0;
  r.bead = beadRunUp(v, x0, mu);
  double best = -1e9, maxReleased = 0, maxGain = -1e300;
  bool climbing = false;
  // The model's energy: without lateral pressure (K = 0) a column's own centroid height h/2 is not
  // part of it (nothing resists piling up), so g rho_s sum h^2/2 dx^2 is taken off the diagnostics'
  // potential energy g sum m (b + h/2).
  auto selfPotential = [&](const std::vector<double>& hs) {
    double e = 0;
    for (double h : hs) e += 0.5 * kGravity * mat.rhoS * h * h * grid.dx * grid.dx;
    return e;
  };
  const fl::FlowDiagnostics d0 = solver.diagnostics();
  const double pot0 = d0.potential - selfPotential(in.hs), e0 = d0.kinetic + d0.kineticVertical + pot0;
  test::advance(solver, test::RunLimits::until(60.0), [&](const fl::FlowSolver& sv) {
    const fl::FlowDiagnostics& d = sv.diagnostics();
    const std::vector<double> hsNow = sv.hs();
    const double pot = d.potential - selfPotential(hsNow);
    maxReleased = std::max(maxReleased, pot0 - pot);
    maxGain = std::max(maxGain, d.kinetic + d.kineticVertical + pot - e0);
    const auto [z, x] = centroid(hsNow);
    if (x > v.xf) climbing = true;
    if (!climbing) return true;
    if (z > best) {
      best = z;
      double below = 0, all = 0;
      for (int i = 0; i < nx; ++i) {
        all += hsNow[i];
        if (in.bed[i] < 0.2 * kZ0) below += hsNow[i];
      }
      r.low = below / all;
      return true;
    }
    return z > best - 0.5;  // stop once the centroid is well on its way back down
  });
  r.highest = best;
  r.gain = maxGain / maxReleased;
  return r;
}

}  // namespace

// Frictionless: the block climbs back to its release height, and all of it leaves the valley.
// Measured deficits (1, 0.5, 0.25 m cells): 40 -> 20 deg 1.1 / 0.53 / 0.28 %, 20 -> 40 deg 4.0 / 3.0 /
// 2.0 %, 30 -> 30 deg 2.0 / 1.4 / 1.0 %, 35 -> 10 deg 0.86 / 0.40 / 0.20 %. What remains is the
// numerical mixing of the block's momenta where the pressureless block (K = 0) compresses, most at
// the apex of the steep counter-slope, where it piles into one or two cells (a delta shock of the
// K = 0 equations); it falls with the cell but slower than first order. Asserted: within 2 % (issue
// 13) at 0.25 m cells (20 cells per block), a deficit that falls by at least a fifth with each
// halving of the cell, and no gain at any resolution (the scheme cannot create energy; 1e-3 for
// round-off and the mass's finite extent).
// Left behind: every bead has the energy to climb out of the valley, so when the centroid is highest
// nothing may lie below Z0 / 5. Before the moving solids climbed the reconstruction's rises with
// their energy (solid_bed.cl, point 3a) a film as thick as those rises stayed in the concave half
// of the valley, holding its speed without moving: 3.6 / 0.83 / 0.22 % of the volume (40 -> 20 deg)
// and 6.3 / 1.4 / 0.38 % (20 -> 40 deg) at 1 / 0.5 / 0.25 m, while the deficits above read
// 4.6 / 1.2 / 0.4 % and 9.4 / 2.8 / 1.2 %. Now 1.1e-5 to 1.9e-5: films at the solver's dry threshold
// (10^-6 m over the valley's 60 m is about 1.2e-5 of the block); asserted below 1e-4.
TEST(TerrainForcing, FrictionlessMassClimbsBackToItsReleaseHeight) {
  const double pairs[][2] = {{40.0, 20.0}, {20.0, 40.0}, {30.0, 30.0}, {35.0, 10.0}};
  for (const auto& p : pairs) {
    double deficit[3] = {0, 0, 0};
    const double cells[3] = {1.0, 0.5, 0.25};
    for (int c = 0; c < 3; ++c) {
      const RunUp r = runValley(p[0], p[1], 0.0, cells[c]);
      const double ratio = r.highest / r.release;
      deficit[c] = 1.0 - ratio;
      std::printf("[ valley %2.0f -> %2.0f deg, frictionless, dx %.2f m ] release %.2f m above the floor, run-up %.2f m: "
                  "ratio %.4f (bead %.6f); largest mechanical-energy gain %.2e of the energy released; "
                  "left below %.0f m: %.2e of the volume\n",
                  p[0], p[1], cells[c], r.release, r.highest, ratio, r.bead / r.release, r.gain, 0.2 * kZ0, r.low);
      // The mechanical energy of the diagnostics (kinetic, vertical kinetic from the cell's bed slope,
      // potential) grows by at most a second-order discretisation error of those sums (measured
      // 1.0e-3, 2.3e-4, 6e-5 of the released energy at 1, 0.5, 0.25 m for 40 -> 20 deg): 2e-3.
      EXPECT_LE(r.gain, 2e-3) << "the mechanical energy may not grow";
      EXPECT_NEAR(r.bead / r.release, 1.0, 1e-4) << "the reference bead conserves energy";
      EXPECT_LE(ratio, 1.0 + 1e-3) << "no energy may be created";
      EXPECT_LT(r.low, 1e-4) << "material left in the valley although it has the energy to climb out";
    }
    EXPECT_LE(deficit[2], 0.02) << p[0] << " -> " << p[1] << " deg";
    if (p[0] == 40.0) {
      // Without the curvature term (Curvature Acceleration=0, the default) the mass conserves the
      // wrong energy: about 0.65 of the run-up (issue 13).
      const RunUp off = runValley(p[0], p[1], 0.0, 0.5, false);
      std::printf("[ valley 40 -> 20 deg, frictionless, dx 0.50 m, curvature off ] ratio %.4f\n", off.highest / off.release);
      EXPECT_LT(off.highest / off.release, 0.8);
    }
    EXPECT_LE(deficit[1], 0.8 * deficit[0]) << "the deficit falls with the cell";
    EXPECT_LE(deficit[2], 0.8 * deficit[1]) << "the deficit falls with the cell";
  }
}

// Coulomb friction mu = tan(10 deg): the block turns where the bead does (the bead's friction
// includes the centripetal normal stress in the bend). Measured at 1 m cells -2.5 % / -3.1 % of the
// release height (the same first-order loss as above); asserted within 1.5 % at 0.25 m.
TEST(TerrainForcing, CoulombMassTurnsWhereTheBeadDoes) {
  const double mu = std::tan(10.0 * kDeg);
  const double pairs[][2] = {{40.0, 20.0}, {25.0, 35.0}};
  for (const auto& p : pairs) {
    const RunUp r = runValley(p[0], p[1], mu, 0.25);
    std::printf("[ valley %2.0f -> %2.0f deg, mu tan 10, dx 0.25 m ] release %.2f m, run-up %.2f m, bead %.2f m "
                "(%+.4f of release)\n",
                p[0], p[1], r.release, r.highest, r.bead, (r.highest - r.bead) / r.release);
    EXPECT_LT(r.bead, 0.9 * r.release) << "friction must take a visible share";
    EXPECT_NEAR(r.highest, r.bead, 0.015 * r.release) << p[0] << " -> " << p[1] << " deg";
  }
}

// Particle mode: a small strong block (3 m x 3 m, 1 m thick, cohesion 10 MPa: elastic, far from
// yield; 4 particles per cell) over the same valleys, cells of 1 m, 5 cells wide, bed friction 0.
// Its particles follow the bilinear field of the sampled bed gradient (particle_integrate.cl), and at
// every step the bed turns each particle from the tangent plane it moved along into the one where it
// now is, its speed kept; the block's centroid elevation climbs back to the release height. The
// block is stiff, so it neither spreads nor mixes. What remains is first order in the cell size:
// the sampled gradient is bilinear between cell centres while the valley's is piecewise linear, so
// the two differ next to the kinks of b' at the ends of the transition (measured +0.23 % / -0.26 % at
// 1 m cells; +0.47 % / -0.57 % with the centred curvature used before). Before the curvature term
// the particles climbed to 0.68 (40 -> 20 deg, issue 13). Asserted within 2 % (issue 13).
TEST(TerrainForcing, ParticleBlockClimbsBackToItsReleaseHeight) {
  const double pairs[][2] = {{40.0, 20.0}, {20.0, 40.0}};
  for (const auto& pr : pairs) {
    const test::Valley v = valley(pr[0], pr[1]);
    const double dx = 1.0;
    const int nx = static_cast<int>(std::ceil(valleyLength(v) / dx)), ny = 5;
    const Grid grid = Grid::make(nx, ny, dx);
    particles::ParticleTerrain terrain;
    terrain.curvature = true;
    terrain.mask.assign(grid.cells(), 1);
    terrain.bed.assign(grid.cells(), 0.0);
    particles::SeedInput in;
    in.mask = terrain.mask;
    in.thickness.assign(grid.cells(), 0.0);
    in.density.assign(grid.cells(), 2400.0);
    int ic = 0;
    for (int i = 0; i < nx; ++i)
      if (v.bed((i + 0.5) * dx) >= kZ0 && (i + 0.5) * dx < v.xf) ic = i;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        terrain.bed[grid.index(i, j)] = v.bed((i + 0.5) * dx);
        if (i >= ic - 1 && i <= ic + 1 && j >= 1 && j <= 3) in.thickness[grid.index(i, j)] = 1.0;
      }
    in.bed = terrain.bed;
    const particles::SeededParticles seeded = particles::seedParticles(grid, in, particles::SeedSpacing{0, 4});
    particles::ParticleMaterial mat;
    mat.density = {2400.0};
    mat.phi = {30 * kDeg};
    mat.delta = {0.0};
    mat.cohesion = {1e7};
    particles::ParticleSettings ps;
    particles::ParticleSolver solver(test::testContext(compute::Precision::Double), grid, terrain, ps);
    solver.setParticles(seeded, mat);
    // Centroid elevation of the particles on the sampled bed (bilinear, as the kernels see it).
    auto centroid = [&](const particles::ParticleState& st) {
      double m = 0, z = 0, x = 0;
      for (std::size_t q = 0; q < st.size(); ++q) {
        m += st.mass[q];
        z += st.mass[q] * v.bed(st.x[q]);
        x += st.mass[q] * st.x[q];
      }
      return std::pair<double, double>{z / m, x / m};
    };
    const double z0 = centroid(solver.state()).first;
    double best = -1e9;
    bool climbing = false;
    for (int k = 0; k < 800; ++k) {
      solver.step(0.05);
      const auto [z, x] = centroid(solver.state());
      if (x > v.xf) climbing = true;
      if (!climbing) continue;
      if (z > best) best = z;
      else if (z < best - 0.5) break;
    }
    const double ratio = best / z0;
    std::printf("[ particle block, valley %2.0f -> %2.0f deg, frictionless ] release %.2f m, run-up %.2f m: ratio %.4f\n",
                pr[0], pr[1], z0, best, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.02);
  }
}
