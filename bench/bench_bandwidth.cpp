// Benchmark (not a test): the device's achievable memory bandwidth, the reference against which
// docs/performance.md reads the solvers' effective bandwidth. The STREAM triad a = b + s c
// (kernels/bench/stream_triad.cl) over arrays far larger than any cache, best of several runs,
// counting 3 reals per element (2 read, 1 written).
//
//   bench_bandwidth [--mib 256] [--repeat 10] [--precision float,double] [--device SEL]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "compute/Program.hpp"

using namespace talus;

namespace {

/// Best triad bandwidth [GB/s] over `repeat` launches on arrays of `mib` MiB each.
double triad(const std::string& device, compute::Precision prec, int mib, int repeat) {
  auto ctx = compute::Context::create(device, prec);
  const std::size_t n = static_cast<std::size_t>(mib) * 1024 * 1024 / compute::realSize(prec);
  compute::RealBuffer a(*ctx, n, "triad a"), b(*ctx, n, "triad b"), c(*ctx, n, "triad c");
  b.fill(1.0);
  c.fill(2.0);
  compute::Kernel k(ctx->program("bench/stream_triad.cl"), "stream_triad");
  k.bind(static_cast<int>(n), a, b, c, compute::RealArg{3.0});
  const compute::Range global{compute::roundUp(n, 256)}, local{256};
  k.launch(global, local);  // warm-up (and first touch of the pages)
  ctx->finish();
  double best = 0;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    k.launch(global, local);
    ctx->finish();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::max(best, 3.0 * static_cast<double>(n) * compute::realSize(prec) / s / 1e9);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> precisions = {"float", "double"};
  std::string device;
  int mib = 256, repeat = 10;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool more = a + 1 < argc;
    if (arg == "--mib" && more) mib = std::atoi(argv[++a]);
    else if (arg == "--repeat" && more) repeat = std::atoi(argv[++a]);
    else if (arg == "--precision" && more) precisions = talus::bench::split(argv[++a]);
    else if (arg == "--device" && more) device = argv[++a];
    else {
      std::fprintf(stderr, "usage: bench_bandwidth [--mib 256] [--repeat 10] [--precision float,double] [--device SEL]\n");
      return 1;
    }
  }
  if (mib < 1 || repeat < 1) {
    std::fprintf(stderr, "bench_bandwidth: --mib and --repeat must be positive\n");
    return 1;
  }
  try {
    std::printf("device: %s\n", compute::selectDevice(device).describe().c_str());
    for (const std::string& p : precisions)
      std::printf("stream triad %-6s %4d MiB per array: %7.2f GB/s (best of %d)\n", p.c_str(), mib,
                  triad(device, compute::parsePrecision(p), mib, repeat), repeat);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_bandwidth: %s\n", e.what());
    return 1;
  }
  return 0;
}
