// Tests of the viewer's device-side packing (kernels/view/view_pack.cl through sim::ViewPacker),
// which both interop paths use: every packing mode against a CPU reference of the same formula,
// in float and double runs, and the particle positions against the formula of ParticleRun.
//
// Tolerances. The reference computes in the run's precision from the values the device holds (the
// inputs are read back from the device), then rounds to float like the kernel.
// - Copies, sums, max, the arrival test and the mask involve at most one correctly rounded IEEE
//   operation: the result must be bitwise equal (NaN where the reference is NaN).
// - Double runs: hypot and the division may differ from the host's by a few double ulps; after the
//   rounding to float that is at most one float ulp (float round-off of the double -> float step).
// - Float runs: OpenCL allows hypot and division in single precision to be a few ulps off (they are
//   not required to be correctly rounded); we allow 8 float ulps for the modes using them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "core/Grid.hpp"
#include "flow/FlowSolver.hpp"
#include "sim/Scene.hpp"
#include "sim/ViewFields.hpp"
#include "support/FlowScene.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus;
using compute::Precision;
using sim::PackMode;

/// Distance in float ulps (NaN equals NaN only).
long long ulpDistance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : std::numeric_limits<long long>::max();
  auto key = [](float f) {
    int32_t i;
    std::memcpy(&i, &f, sizeof i);
    return i < 0 ? static_cast<long long>(INT32_MIN) - i : static_cast<long long>(i);
  };
  return std::llabs(key(a) - key(b));
}

/// The kernel's formula in precision R, rounded to float (the reference).
template <class R>
float reference(PackMode mode, const R in[6], R hDry) {
  const R a = in[0], b = in[1], c = in[2], d = in[3], e = in[4], f = in[5];
  auto speed = [&](R qx, R qy, R h) { return h > hDry ? R(std::hypot(qx, qy) / h) : R(0); };
  R v = 0;
  switch (mode) {
    case PackMode::Copy: v = a; break;
    case PackMode::Sum: v = a + b; break;
    case PackMode::Speed: v = speed(b, c, a); break;
    case PackMode::SpeedSum: v = speed(R(b + e), R(c + f), R(a + d)); break;
    case PackMode::Fraction: v = (a + b) > hDry ? R(b / (a + b)) : R(0); break;
    case PackMode::Max2: v = std::fmax(a, b); break;
    case PackMode::Arrival: v = a < 0 ? std::numeric_limits<R>::quiet_NaN() : a; break;
    case PackMode::Norm: v = std::hypot(a, b); break;
  }
  const float packed = static_cast<float>(v);
  return std::isfinite(packed) ? packed : std::numeric_limits<float>::quiet_NaN();
}

bool exactMode(PackMode m) {
  return m == PackMode::Copy || m == PackMode::Sum || m == PackMode::Max2 || m == PackMode::Arrival;
}

/// Six random input fields: thicknesses with dry (0, below the threshold) and wet cells, signed
/// discharges, arrival times with "not arrived" (-1).
std::vector<std::vector<double>> randomInputs(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<std::vector<double>> in(6, std::vector<double>(n));
  for (std::size_t k = 0; k < n; ++k) {
    const double r = uni(rng);
    in[0][k] = r < 0.2 ? 0.0 : r < 0.3 ? 1e-5 * uni(rng) : r < 0.35 ? -1.0 : std::ldexp(uni(rng), -int(8 * uni(rng)));
    in[3][k] = r < 0.4 ? 0.0 : 3.0 * uni(rng);
    for (int c : {1, 2, 4, 5}) in[c][k] = 4.0 * (uni(rng) - 0.5);
  }
  return in;
}

void checkModes(Precision precision) {
  compute::Context& ctx = test::testContext(precision);
  const std::size_t n = 10007;  // not a multiple of the work-group size
  const double hDry = 1e-4;
  const auto host = randomInputs(n, 42 + static_cast<unsigned>(precision));
  std::vector<compute::RealBuffer> dev;
  std::vector<std::vector<double>> held;  // what the device holds (rounded to `real`)
  for (const auto& v : host) {
    dev.emplace_back(ctx, n, "pack input");
    dev.back().upload(v);
    held.push_back(dev.back().download());
  }
  std::vector<uint8_t> valid(n);
  for (std::size_t k = 0; k < n; ++k) valid[k] = (k % 17) != 3;
  compute::Buffer<uint8_t> mask(ctx, n, "pack mask");
  mask.write(valid);
  compute::Buffer<float> out(ctx, n, "packed");
  sim::ViewPacker packer(ctx);

  for (int m = 0; m <= static_cast<int>(PackMode::Norm); ++m) {
    const auto mode = static_cast<PackMode>(m);
    for (int variant = 0; variant < 3; ++variant) {
      // 0: no mask; 1: mask, NaN marks "no value"; 2: mask, the shaders' marker -1e30 does.
      const bool useMask = variant > 0;
      const float noValue = variant == 2 ? -1e30f : std::numeric_limits<float>::quiet_NaN();
      out.fill(-7.0f);
      const sim::PackInputs in{dev[0].mem(), dev[1].mem(), dev[2].mem(), dev[3].mem(),
                               dev[4].mem(), dev[5].mem(), useMask ? mask.mem() : nullptr};
      packer.packValues(mode, n, in, hDry, out.mem(), nullptr, noValue);
      const std::vector<float> got = out.read();
      const long long tol = exactMode(mode) ? 0 : precision == Precision::Double ? 1 : 8;
      long long worst = 0;
      for (std::size_t k = 0; k < n; ++k) {
        float want;
        if (useMask && !valid[k]) {
          want = std::numeric_limits<float>::quiet_NaN();
        } else if (precision == Precision::Double) {
          const double r[6] = {held[0][k], held[1][k], held[2][k], held[3][k], held[4][k], held[5][k]};
          want = reference<double>(mode, r, hDry);
        } else {
          const float r[6] = {float(held[0][k]), float(held[1][k]), float(held[2][k]),
                              float(held[3][k]), float(held[4][k]), float(held[5][k])};
          want = reference<float>(mode, r, float(hDry));
        }
        if (std::isnan(want)) want = noValue;
        const long long dist = ulpDistance(got[k], want);
        worst = std::max(worst, dist);
        ASSERT_LE(dist, tol) << "mode " << m << " mask " << useMask << " element " << k << ": got " << got[k]
                             << ", want " << want;
      }
      ::testing::Test::RecordProperty("worst_ulps_mode_" + std::to_string(m), static_cast<int>(worst));
    }
  }
}

TEST(ViewPack, ValuesMatchCpuReferenceFloat) { checkModes(Precision::Float); }

TEST(ViewPack, ValuesMatchCpuReferenceDouble) {
  checkModes(Precision::Double);
}

/// ParticleRun::positions' formula in precision R (removed particles give NaN triples here).
template <class R>
void referencePositions(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& H,
                        const std::vector<double>& bed, const Grid& g, std::vector<float>& out) {
  const auto& t = g.geoTransform;
  out.assign(3 * x.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t q = 0; q < x.size(); ++q) {
    if (!std::isfinite(x[q])) continue;
    const R u = R(x[q]) / R(g.dx), v = R(y[q]) / R(g.dx);
    const int i = std::min(std::max(static_cast<int>(u), 0), g.nx - 1);
    const int j = std::min(std::max(static_cast<int>(v), 0), g.ny - 1);
    out[3 * q] = static_cast<float>(R(R(R(t[0]) + R(u * R(t[1]))) + R(v * R(t[2]))));
    out[3 * q + 1] = static_cast<float>(R(R(R(t[3]) + R(u * R(t[4]))) + R(v * R(t[5]))));
    out[3 * q + 2] = static_cast<float>(R(bed[g.index(i, j)]) + R(H[q]));
  }
}

void checkPositions(Precision precision) {
  compute::Context& ctx = test::testContext(precision);
  Grid g;
  g.nx = 37;
  g.ny = 23;
  g.dx = 2.5;
  g.geoTransform = {1000.0, 2.5, 0.0, 5000.0, 0.0, -2.5};
  const std::size_t n = 1001;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<double> x(n), y(n), H(n), bed(g.cells());
  for (double& b : bed) b = 100.0 + 50.0 * uni(rng);
  for (std::size_t q = 0; q < n; ++q) {
    x[q] = q % 13 == 5 ? std::numeric_limits<double>::quiet_NaN() : (uni(rng) * 1.1 - 0.05) * g.nx * g.dx;
    y[q] = (uni(rng) * 1.1 - 0.05) * g.ny * g.dx;
    H[q] = 3.0 * uni(rng);
  }
  auto upload = [&](const std::vector<double>& v) {
    compute::RealBuffer b(ctx, v.size(), "positions input");
    b.upload(v);
    return b;
  };
  compute::RealBuffer dx = upload(x), dy = upload(y), dH = upload(H), dbed = upload(bed);
  compute::Buffer<float> out(ctx, 3 * n, "packed positions");
  sim::ViewPacker packer(ctx);
  packer.packPositions(n, dx.mem(), dy.mem(), dH.mem(), dbed.mem(), g, out.mem());
  const std::vector<float> got = out.read();
  std::vector<float> want;
  if (precision == Precision::Double)
    referencePositions<double>(dx.download(), dy.download(), dH.download(), dbed.download(), g, want);
  else
    referencePositions<float>(dx.download(), dy.download(), dH.download(), dbed.download(), g, want);
  // Double: exact arithmetic order and correctly rounded operations, then one rounding to float;
  // float: the division x / dx may be off by a few ulps in OpenCL single precision.
  const long long tol = precision == Precision::Double ? 1 : 8;
  for (std::size_t k = 0; k < 3 * n; ++k)
    ASSERT_LE(ulpDistance(got[k], want[k]), tol) << "value " << k << ": got " << got[k] << ", want " << want[k];
}

TEST(ViewPack, PositionsMatchCpuReferenceFloat) { checkPositions(Precision::Float); }

TEST(ViewPack, PositionsMatchCpuReferenceDouble) {
  checkPositions(Precision::Double);
}

/// ViewFields packs on the device what its host path computes: a dam break run for a few steps in
/// double, the solver's fields registered as device fields (copies, since the solver keeps its own
/// buffers private), every layer compared with the host snapshot (the float of the same double
/// formula: exact, or one float ulp where hypot and a division are involved).
TEST(ViewPack, ViewFieldsDevicePackingEqualsHostSnapshot) {
  compute::Context& ctx = test::testContext(Precision::Double);
  const Grid grid = Grid::make(48, 40, 2.0, 0.0, 0.0);
  sim::Scene scene;
  scene.dem = Raster(grid, 0.0);
  scene.flow = test::makeInput(grid, [](double x, double) { return 0.01 * x; },
                               [](double x, double y) { return x < 30 && y < 50 ? 1.5 : 0.0; });
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      scene.dem.values[k] = scene.flow.bed[k];
      if (i + j < 4) scene.dem.valid[k] = scene.flow.mask[k] = 0;  // a nodata corner
    }
  flow::FlowSolver solver(ctx, grid, scene.settings);
  solver.setInput(scene.flow);
  for (int n = 0; n < 20; ++n) solver.step(std::min(solver.stableDt(), 0.05));
  sim::ViewFields view(scene, solver);
  const sim::ViewSnapshot host = view.snapshot();

  std::map<std::string, compute::RealBuffer> copies;
  std::map<std::string, cl_mem> fields;
  const std::pair<const char*, std::vector<double>> sources[] = {
      {"h", solver.h()},       {"qx", solver.qx()},     {"qy", solver.qy()},
      {"hMax", solver.hMax()}, {"vMax", solver.vMax()}, {"arrival", solver.arrival()}};
  for (const auto& [name, values] : sources) {
    compute::RealBuffer b(ctx, values.size(), name);
    b.upload(values);
    fields[name] = b.mem();
    copies.emplace(name, std::move(b));
  }
  view.setDeviceFields(ctx, fields);
  const sim::ViewSnapshot device = view.snapshot({}, true, -1e30f);
  ASSERT_EQ(device.layerNames, host.layerNames);
  int wet = 0;
  for (const sim::GridLayerInfo& info : view.gridLayers()) {
    ASSERT_TRUE(view.canPackOnDevice(info.name)) << info.name;
    ASSERT_NE(device.deviceLayer(info.name), nullptr) << info.name;
    const std::vector<float>& a = *host.layer(info.name);
    const std::vector<float>& b = *device.layer(info.name);
    const long long tol = info.name == "velocity" ? 1 : 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_LE(ulpDistance(a[k], b[k]), tol) << info.name << " cell " << k << ": host " << a[k] << ", device " << b[k];
      if (info.name == "h" && a[k] > 0.01f) ++wet;
    }
  }
  EXPECT_GT(wet, 100);
  // The device copy marks cells without a value with the shaders' marker.
  std::vector<float> arrival(grid.cells());
  clEnqueueReadBuffer(ctx.queue(), device.deviceLayer("arrival"), CL_TRUE, 0, arrival.size() * sizeof(float),
                      arrival.data(), 0, nullptr, nullptr);
  EXPECT_EQ(arrival[0], -1e30f);
}

}  // namespace
