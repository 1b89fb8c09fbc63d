// Verification of the energy of submerged solids at a cliff (solid_bed.cl, point 7): the solids'
// bed force and their buoyancy, discretised so that material falling from a ledge into a pool gains
// no more kinetic energy than the mixture releases.
//
// Reference (a conservation law, independent of the kernels): the potential energy of the columns
// with the fluid above the solids, the form the model's forces derive from (spec section 4: the
// fluid sees the mixture surface, the solids their weight less the fluid's share plus the fluid's
// pressure gradient):
//   P = sum_cells A g (rho_s h_s (b + h_s / 2) + rho_f h_f (b + h_s + h_f / 2)).
// Moving solids from a ledge into a pool releases their submerged weight over the fall, less the
// lift of the pool's fluid above what arrives. From rest, with forces that derive from P, the first
// steps turn released energy into kinetic energy at a ratio -> 1 as dt -> 0 (the SSP-RK2 step of a
// body at rest under a constant force gives it exactly the work done), and friction only lowers it.
//
// Scene: a strip of 16 cells of 5 m between walls; a ledge 20 m high (cells 0-7) and a pool floor
// (cells 8-15). The solids (rho_s 2000, cohesion 1 MPa, so no lateral pressure, and a bed friction
// angle of 2 degrees so that the ledge's edge cell is not held) lie 0.3 m thick on the ledge and
// 2 m in the pool. Two cases: (a) the lake's surface 1 m above the ledge's solids (all submerged,
// a lake at rest); (b) the surface level with the ledge's solids, which are dry (a bank at the
// shore). Before point 7 the edge cell gained 1.40 (a) and 1.93 (b) times the released energy, and
// (b) still 1.93 with the submerged weight and the surface-gradient buoyancy alone (without g_sub).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::Grid;
using talus::compute::Precision;

namespace {

constexpr int kNx = 16, kEdge = 8;
constexpr double kDx = 5.0, kLedge = 20.0, kRhoS = 2000.0, kRhoF = 1000.0, kG = 9.81;

double potential(const Grid& g, const std::vector<double>& bed, const talus::test::DebrisState& s) {
  double p = 0;
  for (std::size_t k = 0; k < g.cells(); ++k)
    p += g.dx * g.dx * kG *
         (kRhoS * s.hs[k] * (bed[k] + 0.5 * s.hs[k]) + kRhoF * s.hf[k] * (bed[k] + s.hs[k] + 0.5 * s.hf[k]));
  return p;
}

double kinetic(const Grid& g, const talus::test::DebrisState& s) {
  double e = 0;
  for (std::size_t k = 0; k < g.cells(); ++k) {
    if (s.hs[k] > 0) e += 0.5 * kRhoS * (s.qsx[k] * s.qsx[k] + s.qsy[k] * s.qsy[k]) / s.hs[k];
    if (s.hf[k] > 0) e += 0.5 * kRhoF * (s.qfx[k] * s.qfx[k] + s.qfy[k] * s.qfy[k]) / s.hf[k];
  }
  return e * g.dx * g.dx;
}

struct Budget {
  double kinetic, released;
};

/// Kinetic energy and released potential energy after `steps` steps of dt = fraction * stableDt,
/// the lake's surface `surface` [m] (cells whose solids reach above it hold no fluid).
Budget firstSteps(double surface, double fraction, int steps) {
  const Grid grid = Grid::make(kNx, 1, kDx);
  talus::test::SolidMaterial mat;
  mat.rhoS = kRhoS;
  mat.delta = 2.0 * M_PI / 180.0;
  mat.cohesion = 1e6;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int i = 0; i < kNx; ++i) {
    in.bed[i] = i < kEdge ? kLedge : 0.0;
    in.hs[i] = i < kEdge ? 0.3 : 2.0;
    in.h[i] = std::max(0.0, surface - in.bed[i] - in.hs[i]);
  }
  fl::FlowSettings s = talus::test::granularBetweenWalls(1.0);
  s.debris.fluidDensity = kRhoF;
  s.debris.drag = fl::DragLaw::Off;
  fl::FlowSolver solver(talus::test::testContext(Precision::Double), grid, s);
  solver.setInput(in);
  const double p0 = potential(grid, in.bed, talus::test::readState(solver));
  for (int n = 0; n < steps; ++n) solver.step(fraction * solver.stableDt());
  const talus::test::DebrisState st = talus::test::readState(solver);
  return {kinetic(grid, st), p0 - potential(grid, in.bed, st)};
}

}  // namespace

// Tolerance: for forces that derive from P the ratio kinetic / released is 1 in the limit dt -> 0
// and the basal friction only lowers it (header); over 3 steps at half the stable step it is
// 0.970 (a) and 0.960 (b). 5 % above 1 is left for the terms that are not exact derivatives of P
// (the limited reconstruction, the HLL diffusion of the falling mass); the forms before point 7
// gave 1.40 and 1.93.
TEST(SubmergedCliff, SolidsFallingIntoAPoolGainNoMoreThanTheMixtureReleases) {
  for (const double surface : {kLedge + 0.3 + 1.0, kLedge + 0.3}) {
    const Budget b = firstSteps(surface, 0.5, 3);
    std::printf("surface %.1f m: kinetic %.6g J, released %.6g J, ratio %.4f\n", surface, b.kinetic, b.released,
                b.kinetic / b.released);
    ASSERT_GT(b.released, 0.0) << "the ledge's edge did not move";
    EXPECT_LE(b.kinetic, 1.05 * b.released) << "surface " << surface;
  }
}
