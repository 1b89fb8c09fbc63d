// Tests of the OpenCL layer (src/compute): device discovery and selection, kernel source loading
// with #include expansion, build errors, the on-disk binary cache, typed buffers, launches whose
// global size is not a multiple of the local size, and the profiler. Runs on the test device
// (support/TestDevice.hpp); fails, never skips, when there is no OpenCL device.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Device.hpp"
#include "compute/Kernel.hpp"
#include "compute/KernelSources.hpp"
#include "compute/Program.hpp"
#include "compute/Reducer.hpp"
#include "core/Error.hpp"
#include "support/TestDevice.hpp"

namespace {

namespace fs = std::filesystem;
using talus::ComputeError;
using namespace talus::compute;

/// Sets an environment variable for the lifetime of the object and restores the old value (or its
/// absence) afterwards, also when the test fails by exception.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) had_ = true, old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (had_) ::setenv(name_, old_.c_str(), 1);
    else ::unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  bool had_ = false;
  std::string old_;
};

/// A fresh, empty temporary folder, removed with its contents at the end of the scope.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "talus-test-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  void write(const std::string& relative, const std::string& text) const {
    const fs::path p = path_ / relative;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
  }

 private:
  fs::path path_;
};

/// A kernel folder for TALUS_KERNEL_DIR with the real common/real.cl and small probe kernels that
/// check their bounds (global sizes are rounded up to the local size).
void writeProbeKernels(const TempDir& dir) {
  dir.write("common/real.cl", loadKernelSource("common/real.cl"));
  dir.write("probe.cl", R"CL(#include "common/real.cl"
__kernel void write_index(__global int* out, const int n, const int scale) {
  const int i = get_global_id(0);
  if (i < n) out[i] = scale * i + 1;
}
__kernel void write_index_2d(__global int* out, const int nx, const int ny) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i < nx && j < ny) out[j * nx + i] = 1000 * j + i;
}
__kernel void axpy(__global real* y, __global const real* x, const real a, const uint n) {
  const uint i = get_global_id(0);
  if (i < n) y[i] = a * x[i] + y[i];
}
)CL");
}

TEST(Compute, ListsDevicesAndDescribesThem) {
  const std::vector<DeviceInfo> devices = listDevices();
  ASSERT_FALSE(devices.empty()) << "no OpenCL device: the kernel tests need one (install pocl-opencl-icd)";
  for (std::size_t k = 0; k < devices.size(); ++k) {
    EXPECT_EQ(devices[k].index, static_cast<int>(k));
    EXPECT_FALSE(devices[k].name.empty());
    const std::string d = devices[k].describe();
    EXPECT_NE(d.find(devices[k].name), std::string::npos) << d;
    EXPECT_EQ(d.rfind("[" + std::to_string(k) + "] ", 0), 0u) << d;
    EXPECT_GT(devices[k].maxWorkGroupSize, 0u);
  }
}

TEST(Compute, BogusSelectorThrowsAndListsDevices) {
  const std::vector<DeviceInfo> devices = listDevices();
  ASSERT_FALSE(devices.empty());
  try {
    selectDevice("no-such-device-zz9");
    FAIL() << "selectDevice accepted a bogus selector";
  } catch (const ComputeError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("no-such-device-zz9"), std::string::npos) << msg;
    for (const DeviceInfo& d : devices) EXPECT_NE(msg.find(d.describe()), std::string::npos) << msg;
  }
  // An index past the end is no better than a bogus name.
  EXPECT_THROW(selectDevice(std::to_string(devices.size())), ComputeError);
}

TEST(Compute, NumericSelectorPicksThatIndex) {
  const std::vector<DeviceInfo> devices = listDevices();
  ASSERT_FALSE(devices.empty());
  const DeviceInfo d = selectDevice("0");
  EXPECT_EQ(d.index, 0);
  EXPECT_EQ(d.id, devices[0].id);
  EXPECT_EQ(d.name, devices[0].name);
}

TEST(Compute, KernelSourceExpandsIncludes) {
  const std::string src = loadKernelSource("flow/stage.cl");
  // real.cl (included by flow_common.cl, included by riemann.cl, included by stage.cl) is pasted in,
  // once, although two files include it.
  EXPECT_NE(src.find("typedef double real;"), std::string::npos);
  EXPECT_NE(src.find("typedef float real;"), std::string::npos);
  EXPECT_EQ(src.find("typedef double real;"), src.rfind("typedef double real;"));
  EXPECT_NE(src.find("#line 1 \"common/real.cl\""), std::string::npos);
  EXPECT_NE(src.find("#line 1 \"flow/stage.cl\""), std::string::npos);
  EXPECT_NE(src.find("#line 1 \"flow/riemann.cl\""), std::string::npos);
  EXPECT_NE(src.find("flow_stage"), std::string::npos);
  EXPECT_EQ(src.find("#include \""), std::string::npos) << "an #include line was left unexpanded";
}

TEST(Compute, MissingKernelSourceThrowsNamingIt) {
  try {
    loadKernelSource("flow/no_such_kernel.cl");
    FAIL() << "loading a missing kernel source did not throw";
  } catch (const ComputeError& e) {
    EXPECT_NE(std::string(e.what()).find("flow/no_such_kernel.cl"), std::string::npos) << e.what();
  }
  // A missing file reached through #include is named too.
  TempDir dir;
  dir.write("top.cl", "#include \"nowhere/missing_include.cl\"\n__kernel void k() {}\n");
  ScopedEnv env("TALUS_KERNEL_DIR", dir.path().string());
  try {
    loadKernelSource("top.cl");
    FAIL() << "a missing #include did not throw";
  } catch (const ComputeError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere/missing_include.cl"), std::string::npos) << e.what();
  }
}

TEST(Compute, BuildFailureReportsFileOptionsAndLog) {
  TempDir dir;
  dir.write("broken.cl", "__kernel void broken(__global float* x) {\n  x[0] = talus_undeclared_symbol;\n}\n");
  ScopedEnv kernels("TALUS_KERNEL_DIR", dir.path().string());
  ScopedEnv cache("TALUS_CACHE_DIR", "off");
  Context ctx(talus::test::testDevice(), Precision::Float);
  try {
    ctx.program("broken.cl", "-DTALUS_MARKER_OPTION=42");
    FAIL() << "a kernel with an undeclared identifier built";
  } catch (const ComputeError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("broken.cl"), std::string::npos) << msg;
    EXPECT_NE(msg.find("-DTALUS_MARKER_OPTION=42"), std::string::npos) << msg;
    EXPECT_NE(msg.find(precisionBuildOptions(Precision::Float)), std::string::npos) << msg;
    // The compiler's own diagnostic (a build-log line) names the offending identifier.
    EXPECT_NE(msg.find("talus_undeclared_symbol"), std::string::npos) << msg;
  }
}

TEST(Compute, ProgramBinaryCacheReloadsAndGivesIdenticalResults) {
  TempDir cacheDir;
  ScopedEnv cache("TALUS_CACHE_DIR", cacheDir.path().string());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<double> data(5000);
  for (double& x : data) x = uni(rng);

  auto run = [&](bool expectCached) {
    Context ctx(talus::test::testDevice(), Precision::Double);
    EXPECT_EQ(ctx.program("common/reduce.cl").fromCache(), expectCached);
    RealBuffer buf(ctx, data.size());
    buf.upload(data);
    Reducer reducer(ctx);
    return std::vector<double>{reducer.sum(buf, data.size()), reducer.min(buf, data.size()),
                               reducer.max(buf, data.size())};
  };
  const std::vector<double> built = run(false);
  std::size_t binaries = 0;
  for (const auto& entry : fs::directory_iterator(cacheDir.path())) binaries += entry.path().extension() == ".clbin";
  EXPECT_EQ(binaries, 1u) << "the build was not written to TALUS_CACHE_DIR";
  const std::vector<double> cached = run(true);
  EXPECT_EQ(built, cached) << "the cached binary computes something else";  // same code: bitwise equal
}

TEST(Compute, RealBufferRoundTripsDouble) {
  Context& ctx = talus::test::testContext(Precision::Double);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uni(-1e3, 1e3);
  std::vector<double> v(1031);
  for (double& x : v) x = uni(rng);
  v[0] = 1e-300, v[1] = -0.0, v[2] = std::numeric_limits<double>::max();
  RealBuffer buf(ctx, v.size());
  EXPECT_EQ(buf.precision(), Precision::Double);
  buf.upload(v);
  EXPECT_EQ(buf.download(), v);  // bit-exact: no conversion in double precision
  buf.fill(0.1);
  for (double x : buf.download()) ASSERT_EQ(x, 0.1);
  EXPECT_THROW(buf.upload(std::vector<double>(v.size() + 1)), ComputeError);
}

TEST(Compute, RealBufferRoundTripsFloat) {
  Context& ctx = talus::test::testContext(Precision::Float);
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<float> uni(-1e3f, 1e3f);
  std::vector<double> v(1031);
  for (double& x : v) x = static_cast<double>(uni(rng));  // representable in float: exact both ways
  v[0] = 0.25, v[1] = -0.0, v[2] = static_cast<double>(std::numeric_limits<float>::max());
  RealBuffer buf(ctx, v.size());
  EXPECT_EQ(buf.precision(), Precision::Float);
  buf.upload(v);
  EXPECT_EQ(buf.download(), v);
  // A double that float cannot hold comes back rounded to the nearest float.
  buf.fill(0.1);
  for (double x : buf.download()) ASSERT_EQ(x, static_cast<double>(0.1f));
}

TEST(Compute, IntBufferFillWriteRead) {
  Context& ctx = talus::test::testContext(Precision::Float);
  Buffer<int> buf(ctx, 777);
  EXPECT_EQ(buf.size(), 777u);
  buf.fill(-7);
  for (int x : buf.read()) ASSERT_EQ(x, -7);
  std::vector<int> v(777);
  for (int k = 0; k < 777; ++k) v[k] = k * k - 300;
  buf.write(v);
  EXPECT_EQ(buf.read(), v);
  Buffer<int> copy(ctx, 777);
  copy.raw().copyFrom(buf.raw());
  EXPECT_EQ(copy.read(), v);
  Buffer<int> empty(ctx, 0);  // zero-sized buffers are valid (reads and writes do nothing)
  EXPECT_TRUE(empty.read().empty());
}

TEST(Compute, LaunchRoundsGlobalSizeUpAndKernelsCheckBounds) {
  TempDir dir;
  writeProbeKernels(dir);
  ScopedEnv kernels("TALUS_KERNEL_DIR", dir.path().string());
  ScopedEnv cache("TALUS_CACHE_DIR", "off");
  Context ctx(talus::test::testDevice(), Precision::Double);
  Program& program = ctx.program("probe.cl");

  // 1D: 1000 items in groups of 64 run as 1024; the 24 extra must not write. The buffer has a
  // guard region past n that has to stay untouched.
  const int n = 1000;
  Buffer<int> out(ctx, n + 100);
  out.fill(-1);
  Kernel k1(program, "write_index");
  k1.bind(out, n, 3).launch({static_cast<std::size_t>(n)}, {64});
  std::vector<int> got = out.read();
  for (int i = 0; i < n + 100; ++i) ASSERT_EQ(got[i], i < n ? 3 * i + 1 : -1) << "index " << i;

  // 2D: 37 x 23 with 16 x 16 groups (48 x 32 launched).
  const int nx = 37, ny = 23;
  Buffer<int> grid(ctx, nx * ny + 64);
  grid.fill(-1);
  Kernel k2(program, "write_index_2d");
  k2.bind(grid, nx, ny).launch({nx, ny}, {16, 16});
  got = grid.read();
  for (int k = 0; k < nx * ny + 64; ++k) ASSERT_EQ(got[k], k < nx * ny ? 1000 * (k / nx) + k % nx : -1) << k;

  // `real` scalar and unsigned arguments.
  RealBuffer x(ctx, 300), y(ctx, 300);
  std::vector<double> xs(300), ys(300);
  for (int i = 0; i < 300; ++i) xs[i] = 0.5 * i, ys[i] = 1.0 - i;
  x.upload(xs);
  y.upload(ys);
  Kernel k3(program, "axpy");
  k3.bind(y, x, RealArg{0.25}, 300u).launch({300}, {128});
  const std::vector<double> r = y.download();
  for (int i = 0; i < 300; ++i) ASSERT_EQ(r[i], 0.25 * xs[i] + ys[i]);  // exact in binary

  EXPECT_THROW(Kernel(program, "no_such_kernel"), ComputeError);
}

TEST(Compute, ProfilerCountsLaunchesPerLabel) {
  TempDir dir;
  writeProbeKernels(dir);
  ScopedEnv kernels("TALUS_KERNEL_DIR", dir.path().string());
  ScopedEnv cache("TALUS_CACHE_DIR", "off");
  Context ctx(talus::test::testDevice(), Precision::Float);
  Buffer<int> out(ctx, 256);
  Kernel k(ctx.program("probe.cl"), "write_index");
  k.bind(out, 256, 1);
  for (int r = 0; r < 3; ++r) k.launch({256}, {64}, "probe_label");
  for (int r = 0; r < 2; ++r) k.launch({256}, {64});  // labelled by the kernel's name
  ctx.finish();
  const auto& totals = ctx.profiler().totals();
  ASSERT_EQ(totals.count("probe_label"), 1u);
  ASSERT_EQ(totals.count("write_index"), 1u);
  EXPECT_EQ(totals.at("probe_label").launches, 3);
  EXPECT_EQ(totals.at("write_index").launches, 2);
  EXPECT_GE(totals.at("probe_label").seconds, 0.0);
  const std::string report = ctx.profiler().report();
  EXPECT_NE(report.find("probe_label"), std::string::npos) << report;
  EXPECT_NE(report.find("write_index"), std::string::npos) << report;

  ctx.profiler().enabled = false;  // disabled: launches run but are not recorded
  k.launch({256}, {64}, "untimed");
  ctx.finish();
  EXPECT_EQ(ctx.profiler().totals().count("untimed"), 0u);
  ctx.profiler().clear();
  EXPECT_TRUE(ctx.profiler().totals().empty());
}

TEST(Compute, DoublePrecisionNeedsFp64) {
  // Every device that has cl_khr_fp64 opens in both precisions.
  EXPECT_NO_THROW(talus::test::testContext(Precision::Float));
  if (talus::test::testDevice().hasDouble) {
    EXPECT_NO_THROW(talus::test::testContext(Precision::Double));
  }
  // A device without cl_khr_fp64 must refuse Precision::Double with a ComputeError. This can only
  // be checked where such a device is installed (PoCL has fp64, so CI usually has none); the loop
  // below is then empty, and we do not fake a device to pretend otherwise.
  for (const DeviceInfo& d : listDevices()) {
    if (d.hasDouble) continue;
    EXPECT_THROW(Context(d, Precision::Double), ComputeError) << d.describe();
  }
}

}  // namespace
