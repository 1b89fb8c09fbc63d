// Benchmark of the particle neighbour search (not a test): throughput of the bitonic sort of
// (key, index) pairs in keys/s, for several work-group sizes, and the time of a full neighbour-grid
// build (cell keys, sort, start/end tables) plus the reordering of the two position arrays, with the
// kernels' shares from the profiler; then the particle-grid transfers (P2G of the confined phase by
// gather, G2P of the velocity) at 4 particles per terrain cell.
//
//   bench_particles [--sizes 100000,1000000] [--repeat N] [--local 64,256,1024] [--precision float|double]
//                   [--per-cell P] [--device SEL]
//
// Sort keys are uniform random 32-bit values; the particle clouds are uniform over a square domain
// with P particles per cell on average (cell edge = search radius), as an SPH run with h = dx has.
#include "bench_args.hpp"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "compute/Context.hpp"
#include "core/Error.hpp"
#include "core/Grid.hpp"
#include "particles/NeighbourGrid.hpp"
#include "particles/ParticleGridTransfer.hpp"
#include "particles/ParticleSort.hpp"

using namespace talus;

namespace {

using talus::bench::split;

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Global passes of the network for n pairs at work-group size L (the rest run in local memory).
int globalPasses(std::size_t n, std::size_t local) {
  const std::size_t padded = particles::ParticleSort::paddedSize(n);
  const std::size_t tile = std::min(4 * local, padded);
  int passes = 0;
  for (std::size_t k = 2 * tile; k <= padded; k *= 2) {
    std::size_t j = k / 2;
    for (; j >= 2 * tile; j /= 4) ++passes;  // two strides per pass
    if (j == tile) ++passes;
  }
  return passes;
}

void benchSort(compute::Context& ctx, std::size_t n, std::size_t local, int repeat) {
  particles::ParticleSort sorter(ctx, local);
  std::mt19937 rng(1);
  std::vector<cl_uint> keys(n);
  for (auto& k : keys) k = rng();
  compute::Buffer<cl_uint> in(ctx, n, "keys"), sortedKeys(ctx, n, "sorted keys"), order(ctx, n, "order");
  in.write(keys);
  sorter.sortWithIndex(in, n, sortedKeys, order);  // warm-up: allocates scratch, builds kernels
  ctx.finish();
  ctx.profiler().clear();
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeat; ++r) sorter.sortWithIndex(in, n, sortedKeys, order);
  ctx.finish();
  const double s = seconds(t0) / repeat;
  std::printf("sort %8zu pairs  local %4zu  %3d global passes  %9.3f ms  %10.4g keys/s\n", n, sorter.localSize(),
              globalPasses(n, sorter.localSize()), 1e3 * s, static_cast<double>(n) / s);
}

void benchGrid(compute::Context& ctx, std::size_t n, double perCell, int repeat) {
  // A square domain of n / perCell cells of edge 1 m.
  const double side = std::sqrt(static_cast<double>(n) / perCell);
  const particles::DomainBox box{0.0, 0.0, side, side};
  particles::NeighbourGrid grid(ctx, box, 1.0, n);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0.0, side);
  std::vector<double> xs(n), ys(n);
  for (std::size_t i = 0; i < n; ++i) xs[i] = u(rng), ys[i] = u(rng);
  compute::RealBuffer x(ctx, n, "x"), y(ctx, n, "y"), x2(ctx, n, "x sorted"), y2(ctx, n, "y sorted");
  x.upload(xs);
  y.upload(ys);
  grid.build(x, y, n);  // warm-up
  ctx.finish();
  ctx.profiler().clear();
  double buildSeconds = 0, gatherSeconds = 0;
  for (int r = 0; r < repeat; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    grid.build(x, y, n);
    ctx.finish();
    buildSeconds += seconds(t0);
    t0 = std::chrono::steady_clock::now();
    grid.gather(x, x2);
    grid.gather(y, y2);
    ctx.finish();
    gatherSeconds += seconds(t0);
  }
  buildSeconds /= repeat;
  gatherSeconds /= repeat;
  std::printf("grid %8zu particles  %5dx%-5d cells  %-6s  build %9.3f ms (%10.4g particles/s)"
              "  reorder x,y %7.3f ms\n", n,
              grid.cellsX(), grid.cellsY(), compute::precisionName(ctx.precision()), 1e3 * buildSeconds,
              static_cast<double>(n) / buildSeconds, 1e3 * gatherSeconds);
  std::printf("%s\n", ctx.profiler().report().c_str());
}

/// P2G (confined phase: thickness, mass, momentum) and G2P (PIC/FLIP velocity) of n particles,
/// uniform over a square raster of 1 m cells with 4 particles per cell, h = dx (neighbour cell 2 dx).
void benchTransfer(compute::Context& ctx, std::size_t n, int repeat) {
  const int side = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(n) / 4.0))));
  const Grid g = Grid::make(side, side, 1.0);
  const double r = 2.0;  // support 2h, h = dx
  particles::NeighbourGrid grid(ctx, particles::DomainBox{-r, -r, side + r, side + r}, r, n);
  particles::ParticleGridTransfer transfer(ctx, g);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, side), v(-1.0, 1.0);
  std::vector<double> xs(n), ys(n), vs(n), ones(n, 0.25);
  for (std::size_t i = 0; i < n; ++i) xs[i] = u(rng), ys[i] = u(rng), vs[i] = v(rng);
  compute::RealBuffer x(ctx, n, "x"), y(ctx, n, "y"), vx(ctx, n, "vx"), vy(ctx, n, "vy"), vol(ctx, n, "volume");
  x.upload(xs), y.upload(ys), vx.upload(vs), vy.upload(vs), vol.upload(ones);
  grid.build(x, y, n);
  for (compute::RealBuffer* f : {&x, &y, &vx, &vy, &vol}) grid.reorder(*f);
  const std::size_t cells = g.cells();
  compute::RealBuffer H(ctx, cells, "H"), M(ctx, cells, "M"), Px(ctx, cells, "Px"), Py(ctx, cells, "Py");
  transfer.confinedToGrid(grid, x, y, vol, vol, vx, vy, H, M, Px, Py);  // warm-up
  transfer.gridVelocityToParticles(Px, Py, H, M, 0.05, x, y, n, vx, vy);
  ctx.finish();
  auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < repeat; ++k) transfer.confinedToGrid(grid, x, y, vol, vol, vx, vy, H, M, Px, Py);
  ctx.finish();
  const double p2g = seconds(t0) / repeat;
  t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < repeat; ++k) transfer.gridVelocityToParticles(Px, Py, H, M, 0.05, x, y, n, vx, vy);
  ctx.finish();
  const double g2p = seconds(t0) / repeat;
  std::printf("transfer %8zu particles  %5dx%-5d cells  P2G %9.3f ms (%10.4g particles/s)  G2P %8.3f ms (%10.4g "
              "particles/s)\n", n, side, side, 1e3 * p2g, static_cast<double>(n) / p2g, 1e3 * g2p,
              static_cast<double>(n) / g2p);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sizes = {"100000", "1000000"}, locals = {"64", "256", "1024"};
  std::string device, precision = "float";
  int repeat = 5;
  double perCell = 8.0;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool more = a + 1 < argc;
    if (arg == "--sizes" && more) sizes = split(argv[++a]);
    else if (arg == "--local" && more) locals = split(argv[++a]);
    else if (arg == "--repeat" && more) repeat = std::max(1, std::atoi(argv[++a]));
    else if (arg == "--precision" && more) precision = argv[++a];
    else if (arg == "--per-cell" && more) perCell = std::atof(argv[++a]);
    else if (arg == "--device" && more) device = argv[++a];
    else {
      std::fprintf(stderr,
                   "usage: bench_particles [--sizes 100000,1000000] [--repeat N] [--local 64,256,1024] "
                   "[--precision float|double] [--per-cell P] [--device SEL]\n");
      return 1;
    }
  }
  try {
    auto ctx = compute::Context::create(device, compute::parsePrecision(precision));
    std::printf("device: %s\n\n", ctx->device().describe().c_str());
    for (const std::string& s : sizes)
      for (const std::string& l : locals)
        benchSort(*ctx, std::strtoull(s.c_str(), nullptr, 10), std::strtoull(l.c_str(), nullptr, 10), repeat);
    std::printf("\n");
    for (const std::string& s : sizes) benchGrid(*ctx, std::strtoull(s.c_str(), nullptr, 10), perCell, repeat);
    for (const std::string& s : sizes) benchTransfer(*ctx, std::strtoull(s.c_str(), nullptr, 10), repeat);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_particles: %s\n", e.what());
    return 1;
  }
  return 0;
}
