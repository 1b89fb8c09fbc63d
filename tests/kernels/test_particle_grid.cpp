// Tests of the particle-grid transfers (src/particles/ParticleGridTransfer,
// kernels/particles/particle_grid.cl) against the host reference of tests/support/ParticleGridReference,
// in float and double, on a 23 x 17 raster of 2 m cells with the neighbour grid the particle solver
// uses (box = raster plus one support 2h, cell 2h):
// 1. P2G of random clouds (particles near and on the edges and corners, slightly outside the raster,
//    clustered, outside the neighbour box, at NaN) equals the reference (double: 1e-12 of the field's
//    scale), for smoothing lengths h = dx/2 .. 5dx/2 (2 x 2 to 6 x 6 neighbour cells per stencil);
// 2. total volume, mass and momentum are conserved by P2G to round-off (edge weights are folded
//    onto the edge cells);
// 3. P2G is bitwise reproducible run to run (after rebuilds), and a permuted input gives the same
//    fields to round-off;
// 4. G2P of a linear field is exact where the stencil lies inside; PIC, FLIP and blends;
// 5. partition of unity: G2P of 1 is 1 everywhere, each single particle's P2G sums to its volume;
// 6. released fluid: added volume and discharge summed over cells equal the particles' sums, and
//    accumulate adds onto existing fields;
// plus the field transfer (sum and weighted mean), P2G/G2P adjointness, G2P against the reference,
// a one-cell raster, no particles and invalid arguments.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "core/Error.hpp"
#include "core/Grid.hpp"
#include "particles/NeighbourGrid.hpp"
#include "particles/ParticleGridTransfer.hpp"
#include "support/NeighbourReference.hpp"
#include "support/ParticleGridReference.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus;
using compute::Precision;
using compute::RealBuffer;
using particles::DomainBox;
using particles::FieldTransfer;
using particles::NeighbourGrid;
using particles::ParticleGridTransfer;

/// Particles on the host (values as the device holds them, see Cloud::rounded).
struct Cloud {
  std::vector<double> x, y, volume, mass, vx, vy, released;
  std::size_t size() const { return x.size(); }
  void add(double px, double py, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0), s(-1.0, 1.0);
    x.push_back(px);
    y.push_back(py);
    volume.push_back(0.2 + u(rng));
    mass.push_back(1500.0 * (0.5 + u(rng)));
    vx.push_back(3.0 * s(rng));
    vy.push_back(2.0 * s(rng) - 1.0);
    released.push_back(u(rng) < 0.3 ? 0.0 : 0.05 * u(rng));
  }
  /// Every value rounded to the device's real.
  Cloud rounded(bool isDouble) const {
    Cloud c = *this;
    for (auto* v : {&c.x, &c.y, &c.volume, &c.mass, &c.vx, &c.vy, &c.released})
      for (double& e : *v) e = test::toDeviceReal(e, isDouble);
    return c;
  }
  /// The same particles in another order.
  Cloud permuted(const std::vector<std::size_t>& perm) const {
    Cloud c;
    for (std::size_t k : perm) {
      c.x.push_back(x[k]), c.y.push_back(y[k]), c.volume.push_back(volume[k]), c.mass.push_back(mass[k]);
      c.vx.push_back(vx[k]), c.vy.push_back(vy[k]), c.released.push_back(released[k]);
    }
    return c;
  }
};

/// Device side of one test: the neighbour grid, the transfer and the particle arrays in sorted order.
struct Scene {
  Grid grid;
  double h = 0;
  std::unique_ptr<NeighbourGrid> ng;
  std::unique_ptr<ParticleGridTransfer> transfer;
  RealBuffer x, y, volume, mass, vx, vy, released;  // sorted
  std::size_t n = 0;
};

/// Cell fields read back from the device.
struct Fields {
  std::vector<double> thickness, mass, momentumX, momentumY;
};

class ParticleGridTest : public ::testing::TestWithParam<Precision> {
 protected:
  bool isDouble() const { return GetParam() == Precision::Double; }
  compute::Context& ctx() const { return test::testContext(GetParam()); }
  /// Relative tolerance of a comparison with the reference.
  double tol() const { return isDouble() ? 1e-12 : 2e-5; }
  /// Relative tolerance of a conservation check (sums of many terms).
  double sumTol() const { return isDouble() ? 1e-13 : 2e-6; }

  static Grid testGrid() { return Grid::make(23, 17, 2.0); }

  /// The neighbour grid of the particle solver for smoothing length h = factor * dx.
  std::unique_ptr<Scene> makeScene(const Grid& g, double factor) {
    auto s = std::make_unique<Scene>();
    s->grid = g;
    s->h = factor * g.dx;
    const double r = 2 * s->h;
    s->ng = std::make_unique<NeighbourGrid>(ctx(), DomainBox{-r, -r, g.nx * g.dx + r, g.ny * g.dx + r}, r);
    s->transfer = std::make_unique<ParticleGridTransfer>(ctx(), g);
    return s;
  }

  /// Uploads `c`, builds the neighbour grid from it and reorders every array into the sorted order.
  void load(Scene& s, const Cloud& c) {
    const std::size_t n = c.size(), cap = std::max<std::size_t>(n, 1);
    s.n = n;
    auto upload = [&](const std::vector<double>& v) {
      RealBuffer raw(ctx(), cap, "particle field");
      if (n > 0) raw.upload(v);
      return raw;
    };
    const RealBuffer rx = upload(c.x), ry = upload(c.y);
    s.ng->build(rx, ry, n);
    for (auto [dst, v] : {std::pair{&s.x, &c.x}, {&s.y, &c.y}, {&s.volume, &c.volume}, {&s.mass, &c.mass},
                          {&s.vx, &c.vx}, {&s.vy, &c.vy}, {&s.released, &c.released}}) {
      const RealBuffer raw = upload(*v);
      *dst = RealBuffer(ctx(), cap, "sorted particle field");
      if (n > 0) s.ng->gather(raw, *dst);
    }
  }

  Fields confined(Scene& s) {
    const std::size_t cells = s.grid.cells();
    RealBuffer H(ctx(), cells, "H"), M(ctx(), cells, "M"), Px(ctx(), cells, "Px"), Py(ctx(), cells, "Py");
    s.transfer->confinedToGrid(*s.ng, s.x, s.y, s.volume, s.mass, s.vx, s.vy, H, M, Px, Py);
    return {H.download(), M.download(), Px.download(), Py.download()};
  }

  /// Particles inside the neighbour grid's box (compared in real, as the device keys them).
  std::vector<char> insideBox(const Scene& s, const Cloud& c) const {
    const test::ReferenceGrid rg = test::ReferenceGrid::of(*s.ng);
    std::vector<char> use(c.size());
    for (std::size_t p = 0; p < c.size(); ++p)
      use[p] = test::referenceCellKey(rg, c.x[p], c.y[p], isDouble()) != NeighbourGrid::kCellKeyOutside;
    return use;
  }

  /// A random cloud over the raster and one support around it, with the awkward cases added.
  static Cloud randomCloud(const Grid& g, double h, std::size_t n, unsigned seed, bool withOutside) {
    std::mt19937_64 rng(seed);
    const double W = g.nx * g.dx, Hh = g.ny * g.dx;
    std::uniform_real_distribution<double> ux(-1.5 * h, W + 1.5 * h), uy(-1.5 * h, Hh + 1.5 * h), cl(0.0, 1.0);
    Cloud c;
    for (std::size_t k = 0; k < n; ++k) c.add(ux(rng), uy(rng), rng);
    // Corners, edges, cell faces and centres, the raster's far edge (outside the raster, inside the box).
    const double e = 1e-9 * g.dx;
    for (double px : {0.0, e, 0.5 * g.dx, g.dx, 1.5 * g.dx, W - 1.5 * g.dx, W - g.dx, W - e, W})
      for (double py : {0.0, e, 0.5 * g.dx, Hh - 0.5 * g.dx, Hh - e, Hh}) c.add(px, py, rng);
    // A cluster in one cell, and particles just outside the raster.
    for (int k = 0; k < 40; ++k) c.add(7.0 * g.dx + cl(rng) * g.dx, 5.0 * g.dx + cl(rng) * g.dx, rng);
    for (int k = 0; k < 10; ++k) c.add(-0.3 * g.dx * cl(rng), Hh * cl(rng), rng);
    if (withOutside) {
      c.add(-3 * h - 1.0, 3.0, rng);
      c.add(5.0, Hh + 3 * h + 1.0, rng);
      c.add(std::numeric_limits<double>::quiet_NaN(), 4.0, rng);
    }
    return c;
  }

  static double maxAbs(const std::vector<double>& v) {
    double m = 0;
    for (double e : v) m = std::max(m, std::fabs(e));
    return m;
  }

  /// max_c |a - b| relative to `scale`.
  static double maxRelDiff(const std::vector<double>& a, const std::vector<double>& b, double scale, std::size_t n) {
    double m = 0;
    for (std::size_t k = 0; k < n; ++k) m = std::max(m, std::fabs(a[k] - b[k]) / scale);
    return m;
  }
};

TEST_P(ParticleGridTest, ConfinedP2GEqualsReferenceForSeveralSmoothingLengths) {
  const Grid g = testGrid();
  for (double factor : {0.5, 1.0, 1.5, 2.5}) {
    SCOPED_TRACE("h = " + std::to_string(factor) + " dx");
    auto s = makeScene(g, factor);
    const Cloud c = randomCloud(g, s->h, 1500, 11, true).rounded(isDouble());
    load(*s, c);
    const Fields f = confined(*s);
    const std::vector<char> use = insideBox(*s, c);
    EXPECT_EQ(s->ng->readInsideCount(), static_cast<std::size_t>(std::count(use.begin(), use.end(), 1)));
    const test::ReferenceConfined r = test::referenceConfinedToGrid(g, c.x, c.y, c.volume, c.mass, c.vx, c.vy, use);
    // Scales: the fields' magnitudes (momentum: the sum of |m v| w).
    std::vector<double> avx(c.vx), avy(c.vy);
    for (double& v : avx) v = std::fabs(v);
    for (double& v : avy) v = std::fabs(v);
    const test::ReferenceConfined a = test::referenceConfinedToGrid(g, c.x, c.y, c.volume, c.mass, avx, avy, use);
    const std::size_t n = g.cells();
    const double eH = maxRelDiff(f.thickness, r.thickness, maxAbs(r.thickness), n);
    const double eM = maxRelDiff(f.mass, r.mass, maxAbs(r.mass), n);
    const double ePx = maxRelDiff(f.momentumX, r.momentumX, maxAbs(a.momentumX), n);
    const double ePy = maxRelDiff(f.momentumY, r.momentumY, maxAbs(a.momentumY), n);
    EXPECT_LE(eH, tol());
    EXPECT_LE(eM, tol());
    EXPECT_LE(ePx, tol());
    EXPECT_LE(ePy, tol());
    std::printf("[ P2G vs reference %s, h = %.1f dx (%d x %d neighbour cells): H %.1e, mass %.1e, momentum %.1e %.1e ]\n",
                isDouble() ? "double" : "float", factor, s->ng->cellsX(), s->ng->cellsY(), eH, eM, ePx, ePy);
    // Every cell of this dense cloud receives mass, corners included.
    EXPECT_GT(*std::min_element(f.mass.begin(), f.mass.begin() + n), 0.0);
  }
}

TEST_P(ParticleGridTest, P2GConservesVolumeMassAndMomentum) {
  const Grid g = testGrid();
  auto s = makeScene(g, 1.0);
  for (unsigned seed : {1u, 2u, 3u}) {
    const Cloud c = randomCloud(g, s->h, 2000, seed, true).rounded(isDouble());
    load(*s, c);
    const Fields f = confined(*s);
    const std::vector<char> use = insideBox(*s, c);
    long double V = 0, M = 0, Px = 0, Py = 0, Pabs = 0;
    for (std::size_t p = 0; p < c.size(); ++p) {
      if (!use[p]) continue;
      V += c.volume[p], M += c.mass[p];
      Px += static_cast<long double>(c.mass[p]) * c.vx[p];
      Py += static_cast<long double>(c.mass[p]) * c.vy[p];
      Pabs += c.mass[p] * (std::fabs(c.vx[p]) + std::fabs(c.vy[p]));
    }
    long double gV = 0, gM = 0, gPx = 0, gPy = 0;
    for (std::size_t k = 0; k < g.cells(); ++k) {
      gV += static_cast<long double>(f.thickness[k]) * g.dx * g.dx;
      gM += f.mass[k], gPx += f.momentumX[k], gPy += f.momentumY[k];
    }
    const double eV = static_cast<double>(std::fabs(gV - V) / V), eM = static_cast<double>(std::fabs(gM - M) / M);
    const double ePx = static_cast<double>(std::fabs(gPx - Px) / Pabs);
    const double ePy = static_cast<double>(std::fabs(gPy - Py) / Pabs);
    EXPECT_LE(eV, sumTol()) << "seed " << seed;
    EXPECT_LE(eM, sumTol()) << "seed " << seed;
    EXPECT_LE(ePx, sumTol()) << "seed " << seed;
    EXPECT_LE(ePy, sumTol()) << "seed " << seed;
    if (seed == 1)
      std::printf("[ P2G conservation %s: volume %.2e, mass %.2e, momentum %.2e %.2e (relative) ]\n",
                  isDouble() ? "double" : "float", eV, eM, ePx, ePy);
  }
}

TEST_P(ParticleGridTest, P2GBitwiseReproducibleAndOrderIndependentToRoundOff) {
  const Grid g = testGrid();
  auto s = makeScene(g, 1.0);
  const Cloud c = randomCloud(g, s->h, 3000, 5, false).rounded(isDouble());
  load(*s, c);
  const Fields a = confined(*s);
  // Another cloud in between (the tables are cleared and refilled), then the first again.
  load(*s, randomCloud(g, s->h, 700, 6, true).rounded(isDouble()));
  (void)confined(*s);
  load(*s, c);
  const Fields b = confined(*s);
  const std::size_t bytes = g.cells() * sizeof(double);
  EXPECT_EQ(std::memcmp(a.thickness.data(), b.thickness.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(a.mass.data(), b.mass.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(a.momentumX.data(), b.momentumX.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(a.momentumY.data(), b.momentumY.data(), bytes), 0);

  // The same particles in reverse and in random order: the neighbour-cell contents are summed in
  // another order (ties of the sort follow the input index), so the fields agree to round-off.
  std::vector<std::size_t> perm(c.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::reverse(perm.begin(), perm.end());
  std::vector<std::size_t> shuffled = perm;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(9));
  for (const auto& pm : {perm, shuffled}) {
    load(*s, c.permuted(pm));
    const Fields p = confined(*s);
    const std::size_t n = g.cells();
    const double t = isDouble() ? 1e-14 : 1e-6;
    const double e = std::max({maxRelDiff(p.thickness, a.thickness, maxAbs(a.thickness), n),
                               maxRelDiff(p.mass, a.mass, maxAbs(a.mass), n),
                               maxRelDiff(p.momentumX, a.momentumX, maxAbs(a.mass) * 3, n),
                               maxRelDiff(p.momentumY, a.momentumY, maxAbs(a.mass) * 3, n)});
    EXPECT_LE(e, t);
    std::printf("[ P2G of a permuted input %s: largest relative difference %.1e ]\n", isDouble() ? "double" : "float", e);
  }
}

TEST_P(ParticleGridTest, G2PReproducesLinearFieldsAndBlendsPicFlip) {
  const Grid g = testGrid();
  auto s = makeScene(g, 1.0);
  // Particles whose 4 x 4 stencil lies inside the raster: 1.5 dx <= x <= (n - 1.5) dx.
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> ux(1.5 * g.dx, (g.nx - 1.5) * g.dx), uy(1.5 * g.dx, (g.ny - 1.5) * g.dx);
  Cloud c;
  for (int k = 0; k < 800; ++k) c.add(ux(rng), uy(rng), rng);
  c = c.rounded(isDouble());
  const std::size_t n = c.size(), cells = g.cells();
  auto linear = [&](double a, double b, double d) {
    std::vector<double> f(cells);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) f[g.index(i, j)] = a + b * (i + 0.5) * g.dx + d * (j + 0.5) * g.dx;
    return f;
  };
  RealBuffer x(ctx(), n, "x"), y(ctx(), n, "y"), out(ctx(), n, "out"), field(ctx(), cells, "field");
  x.upload(c.x), y.upload(c.y);
  field.upload(linear(3.0, 0.7, -1.3));
  s->transfer->gridToParticles(field, x, y, n, out);
  const std::vector<double> got = out.download();
  double worst = 0;
  for (std::size_t p = 0; p < n; ++p)
    worst = std::max(worst, std::fabs(got[p] - (3.0 + 0.7 * c.x[p] - 1.3 * c.y[p])) / 50.0);
  EXPECT_LE(worst, isDouble() ? 1e-14 : 1e-6) << "linear field not reproduced";
  std::printf("[ G2P of a linear field %s: largest error %.1e of its range ]\n", isDouble() ? "double" : "float", worst);

  // Velocities: u = linear, du = another linear field. PIC (a = 1) gives u(x_p); FLIP (a = 0) adds
  // du(x_p) to the particle's velocity; a blend is the stated combination.
  const std::vector<double> U = linear(1.0, 0.1, 0.05), V = linear(-0.5, -0.02, 0.08), dU = linear(0.01, 0.002, 0.0),
                            dV = linear(-0.02, 0.0, 0.001);
  RealBuffer u(ctx(), cells, "u"), v(ctx(), cells, "v"), du(ctx(), cells, "du"), dv(ctx(), cells, "dv");
  u.upload(U), v.upload(V), du.upload(dU), dv.upload(dV);
  auto at = [&](const std::vector<double>& f, double px, double py) {
    // The linear field's value at a point, from its coefficients (the cell values are exact samples).
    const double f00 = f[g.index(0, 0)], fx = (f[g.index(1, 0)] - f00) / g.dx, fy = (f[g.index(0, 1)] - f00) / g.dx;
    return f00 + fx * (px - 0.5 * g.dx) + fy * (py - 0.5 * g.dx);
  };
  for (double a : {1.0, 0.0, 0.3}) {
    RealBuffer vx(ctx(), n, "vx"), vy(ctx(), n, "vy");
    vx.upload(c.vx), vy.upload(c.vy);
    s->transfer->gridVelocityToParticles(u, v, du, dv, a, x, y, n, vx, vy);
    const std::vector<double> gx = vx.download(), gy = vy.download();
    double err = 0;
    for (std::size_t p = 0; p < n; ++p) {
      const double ex = (1 - a) * (c.vx[p] + at(dU, c.x[p], c.y[p])) + a * at(U, c.x[p], c.y[p]);
      const double ey = (1 - a) * (c.vy[p] + at(dV, c.x[p], c.y[p])) + a * at(V, c.x[p], c.y[p]);
      err = std::max({err, std::fabs(gx[p] - ex), std::fabs(gy[p] - ey)});
    }
    EXPECT_LE(err, isDouble() ? 1e-13 : 1e-5) << "PIC fraction " << a;
  }
}

TEST_P(ParticleGridTest, PartitionOfUnity) {
  const Grid g = testGrid();
  auto s = makeScene(g, 1.0);
  const Cloud c = randomCloud(g, s->h, 1000, 31, false).rounded(isDouble());
  const std::size_t n = c.size(), cells = g.cells();
  // The reference's weights themselves (folded at the edges) sum to 1.
  for (std::size_t p = 0; p < n; ++p) {
    double sum = 0;
    for (const auto& cw : test::referenceCellWeights(g, c.x[p], c.y[p])) sum += cw.second;
    ASSERT_NEAR(sum, 1.0, 1e-14) << "reference weights of particle " << p;
  }
  // G2P of a constant is that constant for every particle, on the edges and beyond them too.
  RealBuffer x(ctx(), n, "x"), y(ctx(), n, "y"), out(ctx(), n, "out"), ones(ctx(), cells, "ones");
  x.upload(c.x), y.upload(c.y);
  ones.fill(1.0);
  s->transfer->gridToParticles(ones, x, y, n, out);
  const std::vector<double> got = out.download();
  double worst = 0;
  for (double v : got) worst = std::max(worst, std::fabs(v - 1.0));
  EXPECT_LE(worst, isDouble() ? 1e-15 : 5e-7);  // a few units of round-off
  // One particle at a time (corners, edges, faces, centres, outside the raster): P2G puts exactly
  // its volume, mass and momentum on the raster.
  std::mt19937_64 rng(3);
  const double W = g.nx * g.dx, Hh = g.ny * g.dx;
  for (double px : {-1.9 * g.dx, -0.5 * g.dx, 0.0, 0.3 * g.dx, 1.0 * g.dx, 2.5 * g.dx, 11.25 * g.dx, W - 1e-7, W + g.dx})
    for (double py : {-0.1 * g.dx, 0.0, 0.75 * g.dx, 8.5 * g.dx, Hh - 0.5 * g.dx, Hh + 1.9 * g.dx}) {
      Cloud one;
      one.add(px, py, rng);
      one = one.rounded(isDouble());
      load(*s, one);
      const Fields f = confined(*s);
      long double V = 0, M = 0;
      int touched = 0;
      for (std::size_t k = 0; k < cells; ++k) {
        V += static_cast<long double>(f.thickness[k]) * g.dx * g.dx, M += f.mass[k];
        touched += f.mass[k] != 0;
      }
      EXPECT_NEAR(static_cast<double>(V / one.volume[0]), 1.0, isDouble() ? 1e-15 : 5e-7) << px << ", " << py;
      EXPECT_NEAR(static_cast<double>(M / one.mass[0]), 1.0, isDouble() ? 1e-15 : 5e-7) << px << ", " << py;
      EXPECT_LE(touched, 16);
    }
}

TEST_P(ParticleGridTest, ReleasedFluidConservedAndAccumulated) {
  const Grid g = testGrid();
  auto s = makeScene(g, 1.0);
  const Cloud c = randomCloud(g, s->h, 2000, 41, true).rounded(isDouble());
  load(*s, c);
  const std::size_t cells = g.cells();
  RealBuffer h(ctx(), cells, "h"), qx(ctx(), cells, "qx"), qy(ctx(), cells, "qy");
  s->transfer->releasedToGrid(*s->ng, s->x, s->y, s->released, s->vx, s->vy, h, qx, qy);
  const std::vector<double> H = h.download(), Qx = qx.download(), Qy = qy.download();
  const std::vector<char> use = insideBox(*s, c);
  long double V = 0, Px = 0, Py = 0, Pabs = 0, gV = 0, gPx = 0, gPy = 0;
  for (std::size_t p = 0; p < c.size(); ++p) {
    if (!use[p]) continue;
    V += c.released[p];
    Px += static_cast<long double>(c.released[p]) * c.vx[p];
    Py += static_cast<long double>(c.released[p]) * c.vy[p];
    Pabs += c.released[p] * (std::fabs(c.vx[p]) + std::fabs(c.vy[p]));
  }
  const double area = g.dx * g.dx;
  for (std::size_t k = 0; k < cells; ++k) gV += H[k] * area, gPx += Qx[k] * area, gPy += Qy[k] * area;
  EXPECT_LE(static_cast<double>(std::fabs(gV - V) / V), sumTol());
  EXPECT_LE(static_cast<double>(std::fabs(gPx - Px) / Pabs), sumTol());
  EXPECT_LE(static_cast<double>(std::fabs(gPy - Py) / Pabs), sumTol());
  // Against the reference: thickness = sum w dV / dx^2, discharge = sum w dV v / dx^2.
  const std::vector<double> ones(c.size(), 1.0);
  std::vector<double> rH = test::referenceFieldToGrid(g, c.x, c.y, c.released, ones, false, use);
  std::vector<double> rQx = test::referenceFieldToGrid(g, c.x, c.y, c.released, c.vx, false, use);
  for (double& v : rH) v /= area;
  for (double& v : rQx) v /= area;
  EXPECT_LE(maxRelDiff(H, rH, maxAbs(rH), cells), tol());
  EXPECT_LE(maxRelDiff(Qx, rQx, maxAbs(rH) * 3, cells), tol());
  // Accumulate: the increments are added to the fields already there.
  std::vector<double> h0(cells), q0(cells);
  for (std::size_t k = 0; k < cells; ++k) h0[k] = 0.01 * static_cast<double>(k % 7), q0[k] = -0.2;
  h.upload(h0), qx.upload(q0), qy.upload(q0);
  s->transfer->releasedToGrid(*s->ng, s->x, s->y, s->released, s->vx, s->vy, h, qx, qy, true);
  const std::vector<double> H2 = h.download(), Qx2 = qx.download();
  for (std::size_t k = 0; k < cells; ++k) {
    const double hk = test::toDeviceReal(h0[k], isDouble()), qk = test::toDeviceReal(q0[k], isDouble());
    ASSERT_EQ(H2[k], test::toDeviceReal(hk + H[k], isDouble())) << "cell " << k;
    ASSERT_EQ(Qx2[k], test::toDeviceReal(qk + Qx[k], isDouble())) << "cell " << k;
  }
}

TEST_P(ParticleGridTest, FieldToGridSumMeanAndAdjointness) {
  const Grid g = testGrid();
  auto s = makeScene(g, 1.0);
  // A sparse cloud, so some cells receive nothing (mean 0 there).
  Cloud c;
  std::mt19937_64 rng(51);
  std::uniform_real_distribution<double> ux(4 * g.dx, 12 * g.dx), uy(0.0, 6 * g.dx);
  for (int k = 0; k < 300; ++k) c.add(ux(rng), uy(rng), rng);
  c.add(0.0, g.ny * g.dx - 1e-6, rng);  // a corner
  c = c.rounded(isDouble());
  load(*s, c);
  const std::size_t cells = g.cells();
  RealBuffer out(ctx(), cells, "out"), constant(ctx(), c.size(), "constant");
  const std::vector<char> use = insideBox(*s, c);
  for (FieldTransfer mode : {FieldTransfer::Sum, FieldTransfer::WeightedMean}) {
    const bool mean = mode == FieldTransfer::WeightedMean;
    s->transfer->fieldToGrid(*s->ng, s->x, s->y, s->mass, s->vx, mode, out);
    const std::vector<double> got = out.download();
    const std::vector<double> ref = test::referenceFieldToGrid(g, c.x, c.y, c.mass, c.vx, mean, use);
    std::vector<double> avx(c.vx);
    for (double& v : avx) v = std::fabs(v);
    const double scale = maxAbs(test::referenceFieldToGrid(g, c.x, c.y, c.mass, avx, false, use));
    EXPECT_LE(maxRelDiff(got, ref, mean ? 3.0 : scale, cells), mean ? 1e3 * tol() : tol()) << "mean " << mean;
  }
  // The weighted mean of a constant is that constant wherever a particle reaches, 0 elsewhere.
  constant.fill(0.625);
  s->transfer->fieldToGrid(*s->ng, s->x, s->y, s->volume, constant, FieldTransfer::WeightedMean, out);
  const std::vector<double> m = out.download();
  const std::vector<double> reach = test::referenceFieldToGrid(g, c.x, c.y, c.volume, std::vector<double>(c.size(), 1.0),
                                                               false, use);
  int empty = 0;
  for (std::size_t k = 0; k < cells; ++k) {
    if (reach[k] == 0) {
      ++empty;
      EXPECT_EQ(m[k], 0.0) << "cell " << k;
    } else {
      EXPECT_NEAR(m[k], 0.625, isDouble() ? 1e-15 : 1e-6) << "cell " << k;
    }
  }
  EXPECT_GT(empty, 100);
  // Adjointness: sum_c f_c (P2G V)_c = sum_p V_p (G2P f)_p, the same weights both ways.
  std::vector<double> f(cells);
  for (std::size_t k = 0; k < cells; ++k) f[k] = std::sin(0.37 * static_cast<double>(k)) + 2.0;
  RealBuffer field(ctx(), cells, "field"), fp(ctx(), c.size(), "f at particles");
  field.upload(f);
  s->transfer->gridToParticles(field, s->x, s->y, c.size(), fp);
  const Fields p2g = confined(*s);
  const std::vector<double> fAt = fp.download(), vSorted = s->volume.download();
  long double lhs = 0, rhs = 0;
  for (std::size_t k = 0; k < cells; ++k) lhs += static_cast<long double>(test::toDeviceReal(f[k], isDouble())) *
                                                p2g.thickness[k] * g.dx * g.dx;
  for (std::size_t p = 0; p < c.size(); ++p) rhs += static_cast<long double>(vSorted[p]) * fAt[p];
  EXPECT_LE(static_cast<double>(std::fabs(lhs - rhs) / rhs), isDouble() ? 1e-14 : 2e-6);
}

TEST_P(ParticleGridTest, G2PEqualsReferenceEverywhere) {
  const Grid g = testGrid();
  auto s = makeScene(g, 1.0);
  const Cloud c = randomCloud(g, s->h, 1500, 61, false).rounded(isDouble());
  const std::size_t n = c.size(), cells = g.cells();
  std::vector<double> f(cells);
  std::mt19937_64 rng(62);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  for (double& v : f) v = test::toDeviceReal(u(rng), isDouble());
  RealBuffer x(ctx(), n, "x"), y(ctx(), n, "y"), out(ctx(), n, "out"), field(ctx(), cells, "field");
  x.upload(c.x), y.upload(c.y), field.upload(f);
  s->transfer->gridToParticles(field, x, y, n, out);
  const std::vector<double> got = out.download(), ref = test::referenceGridToParticles(g, f, c.x, c.y);
  EXPECT_LE(maxRelDiff(got, ref, 5.0, n), tol());
}

TEST_P(ParticleGridTest, OneCellRasterNoParticlesAndInvalidArguments) {
  // A 1 x 1 raster: every particle's whole weight lands on the one cell.
  const Grid one = Grid::make(1, 1, 3.0);
  auto s = makeScene(one, 1.0);
  std::mt19937_64 rng(71);
  Cloud c;
  for (double p : {-2.0, 0.0, 1.5, 2.999, 3.0, 5.0}) c.add(p, 3.0 - p, rng);
  c = c.rounded(isDouble());
  load(*s, c);
  Fields f = confined(*s);
  double M = 0;
  for (double m : c.mass) M += m;
  EXPECT_NEAR(f.mass[0] / M, 1.0, isDouble() ? 1e-15 : 5e-7);

  // No particles: zero fields, no launch on the empty tables.
  const Grid g = testGrid();
  auto e = makeScene(g, 1.0);
  load(*e, Cloud{});
  f = confined(*e);
  EXPECT_EQ(maxAbs(f.thickness) + maxAbs(f.mass) + maxAbs(f.momentumX) + maxAbs(f.momentumY), 0.0);
  RealBuffer small(ctx(), 3, "small"), cellsBuf(ctx(), g.cells(), "cells"), px(ctx(), 4, "p");
  e->transfer->gridToParticles(cellsBuf, px, px, 0, px);  // n = 0 is a no-op

  // Buffers too small, a bad PIC fraction, a bad grid.
  load(*e, randomCloud(g, e->h, 50, 72, false));
  EXPECT_THROW(e->transfer->confinedToGrid(*e->ng, e->x, e->y, e->volume, e->mass, e->vx, e->vy, small, cellsBuf,
                                           cellsBuf, cellsBuf),
               ComputeError);
  EXPECT_THROW(e->transfer->confinedToGrid(*e->ng, small, e->y, e->volume, e->mass, e->vx, e->vy, cellsBuf, cellsBuf,
                                           cellsBuf, cellsBuf),
               ComputeError);
  EXPECT_THROW(e->transfer->gridToParticles(small, px, px, 4, px), ComputeError);
  EXPECT_THROW(e->transfer->gridVelocityToParticles(cellsBuf, cellsBuf, cellsBuf, cellsBuf, 1.5, px, px, 4, px, px),
               InputError);
  EXPECT_THROW(ParticleGridTransfer(ctx(), Grid::make(0, 4, 1.0)), InputError);
  EXPECT_THROW(ParticleGridTransfer(ctx(), Grid::make(4, 4, 0.0)), InputError);
}

INSTANTIATE_TEST_SUITE_P(Precisions, ParticleGridTest, ::testing::Values(Precision::Float, Precision::Double),
                         [](const auto& info) { return info.param == Precision::Double ? "Double" : "Float"; });

}  // namespace
