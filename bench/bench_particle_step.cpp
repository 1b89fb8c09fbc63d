// Benchmark of the particle solver's sub-step (spec §5): particle-updates per second at 1e5 and 1e6
// particles, and the share of each phase (sort and tables, reordering, density, stress, forces,
// terrain update) from the device profiler. Scene: a cohesive block on a 30-degree slope with 20-degree
// bed friction (it slides, so the sort sees moving particles), 4 particles per cell.
//   bench_particle_step [--sizes 100000,1000000] [--substeps N] [--precision float|double] [--device SEL]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "compute/Context.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"

using namespace talus;
using talus::bench::split;

namespace {

void benchStep(compute::Context& ctx, std::size_t particles, int substeps) {
  const int side = static_cast<int>(std::ceil(std::sqrt(particles / 4.0)));
  const int n = side + 40;
  const double dx = 1.0;
  const Grid g = Grid::make(n, n, dx);
  particles::ParticleTerrain terrain;
  terrain.mask.assign(g.cells(), 1);
  terrain.bed.assign(g.cells(), 0.0);
  particles::SeedInput in;
  in.mask = terrain.mask;
  in.thickness.assign(g.cells(), 0.0);
  in.density.assign(g.cells(), 2000.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      terrain.bed[g.index(i, j)] = -std::tan(30 * M_PI / 180) * i * dx;
      if (i >= 20 && i < 20 + side && j >= 20 && j < 20 + side) in.thickness[g.index(i, j)] = 5.0;
    }
  in.bed = terrain.bed;
  const particles::SeededParticles seeded = particles::seedParticles(g, in, particles::SeedSpacing{0, 4});
  particles::ParticleMaterial mat;
  mat.density = {2000.0};
  mat.phi = {0.5};
  mat.delta = {20 * M_PI / 180};
  mat.cohesion = {1e6};
  particles::ParticleSettings ps;
  particles::ParticleSolver solver(ctx, g, terrain, ps);
  solver.setParticles(seeded, mat);
  const double sub = solver.stableSubStep();
  solver.step(2 * sub);  // warm-up: kernel builds
  ctx.finish();
  ctx.profiler().clear();
  const auto t0 = std::chrono::steady_clock::now();
  solver.step(substeps * sub * 0.999);
  ctx.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int done = solver.diagnostics().subSteps;
  std::printf("particles %8zu  %3d sub-steps  %8.3f s  %10.4g particle-updates/s  (%s)\n", seeded.size(), done, seconds,
              static_cast<double>(seeded.size()) * done / seconds, compute::precisionName(ctx.precision()));
  std::printf("%s\n", ctx.profiler().report().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sizes = {"100000", "1000000"};
  std::string device, precision = "float";
  int substeps = 10;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool more = a + 1 < argc;
    if (arg == "--sizes" && more) sizes = split(argv[++a]);
    else if (arg == "--substeps" && more) substeps = std::max(1, std::atoi(argv[++a]));
    else if (arg == "--precision" && more) precision = argv[++a];
    else if (arg == "--device" && more) device = argv[++a];
    else {
      std::fprintf(stderr, "usage: bench_particle_step [--sizes 100000,1000000] [--substeps N] "
                           "[--precision float|double] [--device SEL]\n");
      return 1;
    }
  }
  try {
    auto ctx = compute::Context::create(device, compute::parsePrecision(precision));
    std::printf("device: %s\n\n", ctx->device().describe().c_str());
    for (const std::string& s : sizes) benchStep(*ctx, std::strtoull(s.c_str(), nullptr, 10), substeps);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_particle_step: %s\n", e.what());
    return 1;
  }
  return 0;
}
