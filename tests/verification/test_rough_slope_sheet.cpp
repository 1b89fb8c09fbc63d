// A water sheet on a steep slope whose DEM is rough at the scale of its cells: the map at practical
// cell sizes must be the resolved one, not a sheet the grid holds back (issue 21).
//
// Scene (solver frame, flow towards +y): a 200 m x 400 m plane falling 0.7 m per m (35 degrees),
// plus DEM noise given on a 5 m lattice (uniform in [-0.85, 0.85] m: standard deviation 0.49 m, a
// sixth of the plane's fall over one 5 m cell) and interpolated bilinearly between the lattice's
// cell centres, so every grid samples the same continuous bed (the 5 m grid takes the lattice values
// themselves). 2 m of water over 40 m x 40 m near the top, at rest; Manning n = 0.05, slope
// correction off (the classical equations), open edges, 30 s, double.
//
// Reference (independent of the cell size): the same scene on cells four times finer (1.25 m), whose
// depths averaged over each 5 m cell are compared with the 5 m run: the distance
// sum|h5 - H| / sum H, and the distance the sheet's centre of mass has travelled.
//
// Measured (2026-12-06, MC and van Leer alike): the 5 m sheet travels 0.94 of the resolved distance
// and its map lies 0.28 (relative L1) from the resolved map. Before the face thicknesses were held to
// their neighbours' range (flow_common.cl, reconstruct_surface) it travelled 0.63 of it and lay
// 1.03-1.05 from it (this test fails on those kernels). GeoClaw 5.14 at 5 m lies 0.38 from its own 1.25 m map on the Python version of this
// scene (bench/peers/rough_slope.py, docs/numerics.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "flow/FlowSolver.hpp"
#include "support/FlowScene.hpp"
#include "support/TestDevice.hpp"

namespace fl = talus::flow;
using talus::test::cellX;
using talus::test::cellY;

namespace {

constexpr int kLatticeX = 40, kLatticeY = 80;  // the 5 m lattice of the DEM noise
constexpr double kLattice = 5.0, kSlope = 0.7, kT = 30.0;

/// The noise values on the lattice (fixed seed, so every run of the suite sees the same bed).
std::vector<double> latticeNoise() {
  std::mt19937 rng(20261206u);
  std::uniform_real_distribution<double> uniform(-0.85, 0.85);
  std::vector<double> v(kLatticeX * kLatticeY);
  for (double& x : v) x = uniform(rng);
  return v;
}

/// Bilinear interpolation of the lattice noise at (x, y), the lattice values at its cell centres,
/// constant beyond the outermost centres.
double noiseAt(const std::vector<double>& lat, double x, double y) {
  const double fx = std::clamp(x / kLattice - 0.5, 0.0, kLatticeX - 1.0);
  const double fy = std::clamp(y / kLattice - 0.5, 0.0, kLatticeY - 1.0);
  const int i = std::min(static_cast<int>(fx), kLatticeX - 2), j = std::min(static_cast<int>(fy), kLatticeY - 2);
  const double a = fx - i, b = fy - j;
  auto at = [&](int ii, int jj) { return lat[jj * kLatticeX + ii]; };
  return (1 - a) * (1 - b) * at(i, j) + a * (1 - b) * at(i + 1, j) + (1 - a) * b * at(i, j + 1) + a * b * at(i + 1, j + 1);
}

/// Final depths on cells of kLattice / refine.
std::vector<double> runSheet(int refine, fl::Limiter limiter) {
  const std::vector<double> lat = latticeNoise();
  const talus::Grid grid = talus::Grid::make(kLatticeX * refine, kLatticeY * refine, kLattice / refine);
  const fl::FlowInput in = talus::test::makeInput(
      grid, [&](double x, double y) { return kSlope * (kLatticeY * kLattice - y) + noiseAt(lat, x, y); },
      [](double x, double y) { return (x > 80 && x < 120 && y > 20 && y < 60) ? 2.0 : 0.0; }, {}, {}, 0.05);
  fl::FlowSettings s;
  s.limiter = limiter;
  s.slopeCorrection = false;
  s.edge = fl::Boundary::Open;
  return talus::test::runFlow(grid, in, s, talus::test::RunLimits::until(kT)).h;
}

/// Centre of mass of the sheet along y [m] on a grid of nx x ny cells of dx.
double centroidY(const std::vector<double>& h, int nx, int ny, double dx) {
  double m = 0, my = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m += h[j * nx + i];
      my += h[j * nx + i] * (j + 0.5) * dx;
    }
  return my / m;
}

}  // namespace

TEST(RoughSlopeSheet, FiveMetreMapMatchesTheResolvedOne) {
  const struct { fl::Limiter limiter; const char* name; } cases[] = {{fl::Limiter::MC, "mc"}, {fl::Limiter::VanLeer, "vanleer"}};
  for (const auto& c : cases) {
    const std::vector<double> coarse = runSheet(1, c.limiter), fine = runSheet(4, c.limiter);
    // The fine depths averaged over each 5 m cell (cells are stored row by row, i fastest).
    std::vector<double> avg(coarse.size(), 0.0);
    const int fnx = kLatticeX * 4;
    for (int j = 0; j < kLatticeY * 4; ++j)
      for (int i = 0; i < fnx; ++i) avg[(j / 4) * kLatticeX + i / 4] += fine[j * fnx + i] / 16.0;
    double diff = 0, sum = 0;
    for (std::size_t k = 0; k < avg.size(); ++k) {
      diff += std::fabs(coarse[k] - avg[k]);
      sum += avg[k];
    }
    const double start = 40.0;  // centre of the release
    const double travel5 = centroidY(coarse, kLatticeX, kLatticeY, kLattice) - start;
    const double travelRef = centroidY(avg, kLatticeX, kLatticeY, kLattice) - start;
    std::printf("[ rough 35 deg slope, %-7s ] travel 5 m %.1f m, 1.25 m %.1f m (ratio %.3f); L1 5 m vs 1.25 m %.3f\n",
                c.name, travel5, travelRef, travel5 / travelRef, diff / sum);
    // The sheet travels as far as the resolved one within 10 % (measured 0.94; 0.63 before): the
    // remaining difference is the first-order wet/dry margins and films.
    EXPECT_GT(travel5 / travelRef, 0.9) << c.name;
    EXPECT_LT(travel5 / travelRef, 1.1) << c.name;
    // Its map lies closer to the resolved map than GeoClaw's 5 m map to its own (0.38 on the Python
    // version of the scene): within 0.35 (measured 0.28; 1.03-1.05 before). The 5 m margins alone make a
    // difference of this order, as GeoClaw's shows.
    EXPECT_LT(diff / sum, 0.35) << c.name;
  }
}
