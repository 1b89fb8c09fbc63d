// The bed surface the particles move on (kernels/particles/particle_walls.cl, walled_bed_gradient;
// particle_common.cl, bed_gradient), evaluated on the device through a probe kernel, against its host
// implementation (src/particles/ParticleBedSurface) and against what the surface must be:
//  - on a rough random DEM with raised blocks (steps of 0.5-6 m), nodata holes, and the raster edge
//    and nodata faces as walls or open, at random points and columns: device and host agree. Both
//    evaluate the same expressions in the same order in double; the comparisons of a rise with a
//    column are then decided alike except within round-off of equality (none in a random sample),
//    so we allow 1e-12 relative to the largest gradient (measured: 0);
//  - where no corner of a point's patch lies behind a wall for its column, the walled gradient is
//    the bilinear one bit for bit (the surface away from walls is unchanged);
//  - on flat ground in front of a step higher than the column the walled gradient is exactly 0 (the
//    bilinear surface ramps the step over the half cell: gradient step / dx); on a plane rising
//    towards such a step the plane's own gradient (the ghost continues the plane), to round-off; on a
//    plane falling towards it 0 (the cell's limited slope, the minmod of the plane's fall and the
//    step's rise, is 0 there, as the grid's solids reconstruct it);
//  - a step lower than the column is no wall: the surface there is the bilinear one;
//  - the walled gradient is the gradient of the walled elevation (bilinear elevation plus the offset
//    that walled_bed_offset gives): central differences of +-1e-6 dx inside one cell's part of a
//    patch (the surface is bilinear there: the difference is exact up to round-off, 1e-16 x 1000 m /
//    1e-6 m ~ 1e-7; we allow 1e-6 of the largest gradient), on the rough DEM's wall points.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Kernel.hpp"
#include "compute/Program.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/SlopeGravity.hpp"
#include "particles/ParticleBedSurface.hpp"
#include "particles/ParticleParams.hpp"
#include "support/TestDevice.hpp"

using namespace talus;
using namespace talus::particles;

namespace {

struct Terrain {
  Grid grid;
  std::vector<double> bed;
  std::vector<uint8_t> mask;
};

struct Points {
  std::vector<double> x, y, column;
};

/// (plain x, plain y, walled x, walled y, walled offset) per point, from the device in double, and the host surface.
struct Sampled {
  std::vector<double> out;
  ParticleBedSurface host;
};

Sampled sample(const Terrain& t, const Points& pts, bool edgeWalls, bool nodataWalls) {
  const flow::SlopeGravity sg = flow::computeSlopeGravity(t.grid, t.bed, t.mask, flow::FlowSettings{});
  ParticleBedSurface host(t.grid, t.bed, t.mask, sg.slopeX, sg.slopeY, edgeWalls, nodataWalls);
  compute::Context& ctx = test::testContext(compute::Precision::Double);
  ParticleParamsT<double> p{};
  p.nx = t.grid.nx;
  p.ny = t.grid.ny;
  p.edgeWall = edgeWalls ? 1 : 0;
  p.nodataWall = nodataWalls ? 1 : 0;
  p.dx = t.grid.dx;
  compute::RawBuffer params(ctx, sizeof p);
  params.writeBytes(&p, sizeof p);
  const std::size_t n = t.grid.cells(), m = pts.x.size();
  compute::Buffer<uint8_t> mask(ctx, n);
  mask.write(t.mask);
  compute::RealBuffer patch(ctx, 3 * n), bed(ctx, n), slope(ctx, 2 * n), x(ctx, m), y(ctx, m), column(ctx, m),
      out(ctx, 5 * m);
  patch.upload(host.patches());
  bed.upload(host.cellBed());
  slope.upload(host.limitedSlopes());
  x.upload(pts.x);
  y.upload(pts.y);
  column.upload(pts.column);
  compute::Kernel k(ctx.program("particles/particle_walls_probe.cl"), "particle_walls_probe");
  k.bind(params, patch, mask, bed, slope, x, y, column, static_cast<int>(m), out);
  k.launch(compute::Range{m});
  return {out.download(), std::move(host)};
}

/// A 17 x 13 DEM of 0.7 m cells: a plane with noise, six raised blocks of 0.5-6 m, and nodata cells.
Terrain roughTerrain(std::mt19937& rng) {
  Terrain t{Grid::make(17, 13, 0.7), {}, {}};
  const Grid& g = t.grid;
  std::uniform_real_distribution<double> noise(-0.2, 0.2), u(0.0, 1.0);
  t.bed.resize(g.cells());
  t.mask.assign(g.cells(), 1);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) t.bed[g.index(i, j)] = 1000.0 - 0.3 * i * g.dx + 0.1 * j * g.dx + noise(rng);
  for (int b = 0; b < 6; ++b) {
    const int i = static_cast<int>(u(rng) * (g.nx - 2)), j = static_cast<int>(u(rng) * (g.ny - 2));
    const double rise = 0.5 + 5.5 * u(rng);
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 1 + b % 2; ++di) t.bed[g.index(i + di, j + dj)] += rise;
  }
  for (int q = 0; q < 5; ++q) t.mask[g.index(static_cast<int>(u(rng) * g.nx), static_cast<int>(u(rng) * g.ny))] = 0;
  return t;
}

Points randomPoints(const Grid& g, std::mt19937& rng, std::size_t count) {
  std::uniform_real_distribution<double> ux(0.0, g.nx * g.dx), uy(0.0, g.ny * g.dx), uc(0.05, 4.0);
  Points p;
  for (std::size_t q = 0; q < count; ++q) {
    p.x.push_back(ux(rng));
    p.y.push_back(uy(rng));
    p.column.push_back(uc(rng));
  }
  return p;
}

/// Flat or planar (b = slope x) ground of 10 x 6 cells of 1 m, raised by `step` for i >= 6.
Terrain stepTerrain(double slope, double step) {
  Terrain t{Grid::make(10, 6, 1.0), {}, {}};
  t.mask.assign(t.grid.cells(), 1);
  t.bed.resize(t.grid.cells());
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 10; ++i) t.bed[t.grid.index(i, j)] = slope * (i + 0.5) + (i >= 6 ? step : 0.0);
  return t;
}

/// Points in the half cell in front of the step (x in (5.5, 6)), away from the raster's rows of edge.
Points frontOfStep(double column) {
  Points p;
  for (double x : {5.51, 5.7, 5.99})
    for (double y : {1.2, 2.5, 3.9}) {
      p.x.push_back(x);
      p.y.push_back(y);
      p.column.push_back(column);
    }
  return p;
}

}  // namespace

TEST(ParticleBedSurface, DeviceAgreesWithTheHostOnARoughDemWithStepsAndNodata) {
  std::mt19937 rng(20261207);
  for (int variant = 0; variant < 4; ++variant) {
    const Terrain t = roughTerrain(rng);
    const Points pts = randomPoints(t.grid, rng, 3000);
    const bool edgeWalls = variant & 1, nodataWalls = variant & 2;
    const Sampled s = sample(t, pts, edgeWalls, nodataWalls);
    double scale = 0, worst = 0;
    std::size_t walledPoints = 0, unchanged = 0;
    for (std::size_t q = 0; q < pts.x.size(); ++q) {
      const std::array<double, 2> plain = s.host.gradient(pts.x[q], pts.y[q]);
      const std::array<double, 2> walled = s.host.walledGradient(pts.x[q], pts.y[q], pts.column[q]);
      const bool changed = walled != plain;
      walledPoints += changed;
      scale = std::max({scale, std::fabs(plain[0]), std::fabs(plain[1]), std::fabs(walled[0]), std::fabs(walled[1])});
      worst = std::max({worst, std::fabs(s.out[5 * q] - plain[0]), std::fabs(s.out[5 * q + 1] - plain[1]),
                        std::fabs(s.out[5 * q + 2] - walled[0]), std::fabs(s.out[5 * q + 3] - walled[1]),
                        std::fabs(s.out[5 * q + 4] - s.host.walledOffset(pts.x[q], pts.y[q], pts.column[q])) / t.grid.dx});
      if (!changed) {
        // Away from walls the device's walled surface is its bilinear one, bit for bit.
        unchanged += s.out[5 * q + 2] == s.out[5 * q] && s.out[5 * q + 3] == s.out[5 * q + 1];
        EXPECT_EQ(s.out[5 * q + 2], s.out[5 * q]) << "point " << q;
        EXPECT_EQ(s.out[5 * q + 3], s.out[5 * q + 1]) << "point " << q;
      }
    }
    std::printf("variant %d (edge walls %d, nodata walls %d): %zu of %zu points see a wall; device - host %.3g of "
                "%.3g\n",
                variant, edgeWalls, nodataWalls, walledPoints, pts.x.size(), worst, scale);
    EXPECT_LE(worst, 1e-12 * scale);
    EXPECT_GT(walledPoints, 100u) << "the sample must exercise the walls";
    EXPECT_EQ(unchanged, pts.x.size() - walledPoints);
  }
}

TEST(ParticleBedSurface, WalledGradientIsTheGradientOfTheWalledElevation) {
  std::mt19937 rng(7);
  const Terrain t = roughTerrain(rng);
  const flow::SlopeGravity sg = flow::computeSlopeGravity(t.grid, t.bed, t.mask, flow::FlowSettings{});
  const ParticleBedSurface host(t.grid, t.bed, t.mask, sg.slopeX, sg.slopeY, true, true);
  const Points pts = randomPoints(t.grid, rng, 3000);
  const double e = 1e-6 * t.grid.dx;
  auto z = [&](double x, double y, double c) { return host.elevation(x, y) + host.walledOffset(x, y, c); };
  double worst = 0, scale = 0;
  std::size_t checked = 0;
  for (std::size_t q = 0; q < pts.x.size(); ++q) {
    const double x = pts.x[q], y = pts.y[q], c = pts.column[q];
    const double fx = x / t.grid.dx, fy = y / t.grid.dx;
    auto nearLine = [](double f) { return std::fabs(f * 2 - std::round(f * 2)) < 1e-3; };  // a cell face or centre line
    if (nearLine(fx) || nearLine(fy) || host.walledOffset(x, y, c) == 0.0) continue;
    const std::array<double, 2> g = host.walledGradient(x, y, c);
    const double gx = (z(x + e, y, c) - z(x - e, y, c)) / (2 * e), gy = (z(x, y + e, c) - z(x, y - e, c)) / (2 * e);
    worst = std::max({worst, std::fabs(gx - g[0]), std::fabs(gy - g[1])});
    scale = std::max({scale, std::fabs(g[0]), std::fabs(g[1])});
    ++checked;
  }
  std::printf("%zu wall points: walled gradient against differences of the walled elevation %.3g of %.3g\n", checked,
              worst, scale);
  EXPECT_GT(checked, 100u);
  EXPECT_LE(worst, 1e-6 * scale);
}

TEST(ParticleBedSurface, GroundInFrontOfAWallIsTheGroundNotARampUpTheWall) {
  for (double slope : {0.0, 0.25, -0.4}) {
    const Terrain t = stepTerrain(slope, 2.0);
    const Points pts = frontOfStep(0.5);  // the 2 m step is a wall for a 0.5 m column
    const Sampled s = sample(t, pts, false, true);
    for (std::size_t q = 0; q < pts.x.size(); ++q) {
      // bilinear: the plane plus the step over the dual cell from x = 5.5 to 6.5
      EXPECT_NEAR(s.out[5 * q], slope + 2.0, 1e-12) << "x " << pts.x[q];
      EXPECT_NEAR(s.out[5 * q + 2], std::max(slope, 0.0), 1e-12) << "x " << pts.x[q];
      EXPECT_NEAR(s.out[5 * q + 3], 0.0, 1e-12) << "x " << pts.x[q];
      if (slope == 0.0) EXPECT_EQ(s.out[5 * q + 2], 0.0);
    }
  }
}

TEST(ParticleBedSurface, AStepLowerThanTheColumnStaysPartOfTheSurface) {
  const Terrain t = stepTerrain(0.0, 0.3);
  const Points pts = frontOfStep(0.5);  // 0.3 m below the 0.5 m column: climbed, not a wall
  const Sampled s = sample(t, pts, false, true);
  for (std::size_t q = 0; q < pts.x.size(); ++q) {
    EXPECT_EQ(s.out[5 * q + 2], s.out[5 * q]);
    EXPECT_NEAR(s.out[5 * q + 2], 0.3, 1e-12);
  }
}
