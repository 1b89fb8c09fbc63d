// Cohesionless granular dam break in the particle mode against Mangeney et al. (2000) (spec §10):
// theta = 35 deg, delta = 22 deg, K = 1, H0 = 1 m reservoir from x = 0 to the dam at x0 = 20 m, t = 3 s,
// the solution of support/GranularAnalytic.hpp with the cos^4 depth pressure of the slope-aligned
// model: the particles' p_zz uses g_n = g cos^2(theta), and the bed's metric takes cos^2(theta) of
// the internal force along the fall line (particle_integrate.cl).
// Particles have no side walls, so the strip is 30 m wide and only its middle 6 m are compared: a
// lateral rarefaction from each free side travels at most c0 t + (front acceleration 0 across) =
// 7.7 m in 3 s, leaving the middle 15 +- 7 m untouched. The material is a frictionless-inside,
// cohesionless solid (phi = 1 deg, c = 0): the Drucker-Prager return removes any deviator, so the
// stress is the Bell-Rankine pressure K rho g_n H / 2 and the particles solve Savage-Hutter with
// K = 1, the grid mode's equations. Thickness profile: particle volumes in the middle band binned
// into 1 m columns, against exact column averages, over the window [17, 50] m where the solution
// holds (test_granular.cpp explains the window). Double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"
#include "support/GranularAnalytic.hpp"
#include "support/ParticleDamBreakScene.hpp"
#include "support/TestDevice.hpp"
#include "verification/ValidationOut.hpp"

using namespace talus;
using namespace talus::particles;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

TEST(ParticleDamBreak, MatchesMangeneyInTheMiddleOfAWideStrip) {
  const test::ParticleDamBreakScene scene = test::makeParticleDamBreak(4);
  const double theta = scene.theta, delta = scene.delta, H0 = scene.H0, x0 = scene.x0, T = 3.0, dx = scene.dx;
  const int nx = scene.nx, ny = scene.ny;
  const Grid& g = scene.grid;
  ParticleSettings ps;
  ps.youngModulus = 1e6;
  ps.earthPressure = ParticleEarthPressure::Constant;
  ps.kConst = 1.0;
  ParticleSolver solver(test::testContext(compute::Precision::Double), g, scene.terrain, ps);
  solver.setParticles(scene.seeded, scene.material);
  for (int k = 0; k < 30; ++k) solver.step(T / 30);
  const ParticleState s = solver.state();
  const double yc = 0.5 * ny * dx, band = 3.0;
  std::vector<double> column(nx, 0.0);
  for (std::size_t q = 0; q < s.size(); ++q) {
    if (std::fabs(s.y[q] - yc) > band || !(s.x[q] >= 0)) continue;
    const int i = static_cast<int>(s.x[q] / dx);
    if (i < nx) column[i] += s.mass[q] / 2000.0;  // volume
  }
  const analytic::MangeneyDamBreak exact = analytic::mangeneyFromSlope(H0, theta, delta, 1.0, true, x0);
  double l1 = 0, mass = 0;
  for (int i = 17; i < nx; ++i) {
    const double h = column[i] / (2 * band * dx);
    const double hbar = exact.integralH(i * dx, (i + 1) * dx, T) / dx;
    l1 += std::fabs(h - hbar) * dx;
    mass += hbar * dx;
  }
  std::printf("particle dam break: %zu particles, L1(h) over [17, 50] m = %.4f m^2 (%.2f %% of the exact %.3f m^2); "
              "front %.2f m (exact %.2f m)\n",
              s.size(), l1, 100 * l1 / mass, mass, [&] {
                double f = 0;
                for (std::size_t q = 0; q < s.size(); ++q)
                  if (std::fabs(s.y[q] - yc) <= band) f = std::max(f, s.x[q]);
                return f;
              }(), exact.front(T));
  if (talus::test::validation::enabled()) {  // 1 m columns of the middle band against exact column averages
    namespace vo = talus::test::validation;
    vo::Table t({"x_m", "h_particles_m", "h_exact_m", "in_window"});
    for (int i = 0; i < nx; ++i)
      t.add({(i + 0.5) * dx, column[i] / (2 * band * dx), exact.integralH(i * dx, (i + 1) * dx, T) / dx, i >= 17 ? 1 : 0});
    t.write("particle_dambreak_profile.csv");
    double front = 0;
    for (std::size_t q = 0; q < s.size(); ++q)
      if (std::fabs(s.y[q] - yc) <= band) front = std::max(front, s.x[q]);
    vo::Table e({"particles", "l1_h_m2", "relative_l1", "front_m", "front_exact_m", "dx_m"});
    e.add({s.size(), l1, l1 / mass, front, exact.front(T), dx});
    e.write("particle_dambreak_errors.csv");
  }
  // Measured: L1 = 7.9 % of the mass in the window (8.9 % with the plane-strain law), the front
  // 2.4 m (about the kernel support 2h) behind the exact one (before the metric: 8.3 % and 2.3 m against the cos^2 solution, which it
  // then solved; 8.7 % against this one, with its front 0.5 m ahead); the grid mode gives 2.1 % at dx = 0.5 m
  // (test_granular.cpp). SPH with 2 x 2 particles per cell smooths the thin front over the support
  // 2h = 2 m, where the exact h ~ (x_f - x)^2 is tiny: most of the error sits there. Tolerance
  // 15 % of the mass: a wrong pressure (K off by 2) or friction (tan(delta) off by 20 %) moves the
  // fan by more than that.
  EXPECT_LT(l1, 0.15 * mass);
}
