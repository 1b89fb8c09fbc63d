// Benchmark of the shallow-water step (not a test): cell-updates per second on fully wet grids for
// float and double, the kernels' shares of a step, an effective memory bandwidth, and the effect of
// skipping dry tiles on a mostly dry scene.
//
//   bench_flow [--sizes 1000,4000] [--precision float,double] [--steps N] [--device SEL]
//
// Effective bandwidth uses a model of the minimum traffic of one step (kRealsPerCellUpdate reals per
// cell: two fused stages, friction, maxima and diagnostics, every field read or written once per
// kernel), so it is a lower bound of the traffic the device really served.
#include "bench_args.hpp"
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "compute/Context.hpp"
#include "core/Error.hpp"
#include "flow/FlowSolver.hpp"

using namespace talus;

namespace {

using talus::bench::split;

/// Reals moved per cell per step in the traffic model (see docs/performance.md): each fused stage
/// reads the tile with its two-cell halo (20^2 / 16^2 = 1.5625 times) of h, qx, qy, b, g_p (and a
/// byte of mask), g_n and the RK base state (3), and writes 3 fields and the outflow (16 in all);
/// friction moves 6, maxima 9, diagnostics 5.
constexpr double kRealsPerCellUpdate = 2 * 16 + 6 + 9 + 5;

flow::FlowInput wetScene(const Grid& g) {
  flow::FlowInput in;
  const std::size_t n = g.cells();
  in.mask.assign(n, 1);
  in.bed.resize(n);
  in.h.resize(n);
  in.manning.assign(n, 0.03);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double x = (i + 0.5) / g.nx, y = (j + 0.5) / g.ny;
      in.bed[g.index(i, j)] = 0.5 * std::sin(6.0 * x) * std::cos(5.0 * y);
      in.h[g.index(i, j)] = 2.0 + 0.3 * std::exp(-50.0 * ((x - 0.4) * (x - 0.4) + (y - 0.5) * (y - 0.5)));
    }
  return in;
}

flow::FlowInput dryScene(const Grid& g, double radiusCells) {
  flow::FlowInput in;
  const std::size_t n = g.cells();
  in.mask.assign(n, 1);
  in.bed.assign(n, 0.0);
  in.h.assign(n, 0.0);
  in.manning.assign(n, 0.03);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double r = std::hypot(i - 0.5 * g.nx, j - 0.5 * g.ny);
      if (r < radiusCells) in.h[g.index(i, j)] = 5.0;
    }
  return in;
}

/// Runs `steps` steps after one warm-up step; returns wall seconds of the timed steps.
double timeSteps(compute::Context& ctx, flow::FlowSolver& solver, int steps) {
  solver.step(solver.stableDt());
  ctx.finish();
  ctx.profiler().clear();
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < steps; ++s) solver.step(solver.stableDt());
  ctx.finish();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The wet grid with one time scheme (unsplit at CFL 0.5; the split and MUSCL-Hancock sweeps at
/// 0.9, where they are used). A step is one step of the scheme: two RK stages over both directions,
/// two RK stages per direction, or one MUSCL-Hancock stage per direction; the steps per simulated
/// second differ (docs/performance.md), so compare rates of one scheme only across devices.
void benchWet(const std::string& device, compute::Precision prec, int size, int steps, flow::TimeScheme scheme) {
  auto ctx = compute::Context::create(device, prec);
  const Grid g = Grid::make(size, size, 1.0);
  flow::FlowSettings settings;
  settings.edge = flow::Boundary::Wall;
  settings.scheme = scheme;
  if (scheme != flow::TimeScheme::Unsplit) settings.cfl = 0.9;
  flow::FlowSolver solver(*ctx, g, settings);
  solver.setInput(wetScene(g));
  const double seconds = timeSteps(*ctx, solver, steps);
  const double rate = static_cast<double>(g.cells()) * steps / seconds;
  const double gbs = rate * kRealsPerCellUpdate * compute::realSize(prec) / 1e9;
  const char* name = scheme == flow::TimeScheme::Unsplit ? "" : scheme == flow::TimeScheme::Split ? " split" : " hancock";
  std::printf("wet %5dx%-5d %-6s%s  %3d steps  %8.3f s  %10.4g cell-updates/s  %7.2f GB/s effective\n", size, size,
              compute::precisionName(prec), name, steps, seconds, rate, gbs);
  std::printf("%s\n", ctx->profiler().report().c_str());
}

/// The two-phase step on a fully wet grid (solids and fluid everywhere), with the optional exchange
/// terms switched one by one, so each term's cost shows.
void benchTwoPhase(const std::string& device, compute::Precision prec, int size, int steps) {
  auto ctx = compute::Context::create(device, prec);
  const Grid g = Grid::make(size, size, 1.0);
  flow::FlowInput in = wetScene(g);
  in.hs.resize(g.cells());
  for (std::size_t k = 0; k < g.cells(); ++k) {
    in.hs[k] = 0.5 * in.h[k];
    in.h[k] *= 0.5;
  }
  struct Variant {
    const char* name;
    flow::DragLaw drag;
    bool virtualMass;
    bool viscous = false;
    flow::Rheology rheology = flow::Rheology::Coulomb;
    std::array<double, 4> rheo{};
    bool entrainment = false;
    bool curvature = false;
  };
  const double kTan21 = 0.3839, kTan31 = 0.5938;
  const Variant variants[] = {{"drag off", flow::DragLaw::Off, false},
                              {"linear drag", flow::DragLaw::Linear, false},
                              {"linear drag + virtual mass", flow::DragLaw::Linear, true},
                              {"quadratic drag + virtual mass", flow::DragLaw::Quadratic, true},
                              {"quadratic + vm + viscous P.30", flow::DragLaw::Quadratic, true, true},
                              // The basal laws (kernels/flow/basal_rheology.cl) and entrainment, drag off.
                              {"drag off, voellmy", flow::DragLaw::Off, false, false, flow::Rheology::Voellmy,
                               {0.155, 9.81 / 4000}},
                              {"drag off, mu(I)", flow::DragLaw::Off, false, false, flow::Rheology::MuI,
                               {kTan21, kTan31, 0.136, 6.5e-4}},
                              {"drag off, bingham", flow::DragLaw::Off, false, false, flow::Rheology::HerschelBulkley,
                               {1000, 100, 1, 0}},
                              {"drag off, herschel-bulkley n 1/3", flow::DragLaw::Off, false, false,
                               flow::Rheology::HerschelBulkley, {1000, 100, 1.0 / 3.0, 0}},
                              {"drag off, coulomb + entrainment", flow::DragLaw::Off, false, false,
                               flow::Rheology::Coulomb, {}, true},
                              // The bed's curvature along the solids' path (kernels/flow/solid_bed.cl, point 1).
                              {"drag off, curvature", flow::DragLaw::Off, false, false, flow::Rheology::Coulomb, {},
                               false, true}};
  for (const Variant& v : variants) {
    flow::FlowSettings settings;
    settings.edge = flow::Boundary::Wall;
    settings.twoPhase = true;
    settings.debris.drag = v.drag;
    settings.debris.virtualMass = v.virtualMass;
    if (v.viscous) {  // the paper's values (OpenLISEM Hazard 2.0a, numerical tests)
      settings.debris.reynolds = 15000;
      settings.debris.reynoldsInterfacial = 30;
    }
    settings.debris.rheology = v.rheology;
    settings.debris.rheologyParams = v.rheo;
    settings.entrainment.enabled = v.entrainment;
    settings.entrainment.growthRate = 0.01;
    settings.curvature = v.curvature;
    flow::FlowInput input = in;
    if (v.entrainment) input.erodible.assign(g.cells(), 1.0);
    flow::FlowSolver solver(*ctx, g, settings);
    solver.setInput(input);
    const double seconds = timeSteps(*ctx, solver, steps);
    const double rate = static_cast<double>(g.cells()) * steps / seconds;
    std::printf("two-phase %4dx%-4d %-6s %-34s %3d steps  %8.3f s  %10.4g cell-updates/s\n", size, size,
                compute::precisionName(prec), v.name, steps, seconds, rate);
  }
  std::printf("\n");
}

void benchDryTiles(const std::string& device, int size, int steps) {
  auto ctx = compute::Context::create(device, compute::Precision::Float);
  const Grid g = Grid::make(size, size, 1.0);
  double rates[2];
  int active = 0;
  for (int skip = 0; skip < 2; ++skip) {
    flow::FlowSettings settings;
    settings.skipDryTiles = skip == 1;
    flow::FlowSolver solver(*ctx, g, settings);
    solver.setInput(dryScene(g, 0.03 * size));
    const double seconds = timeSteps(*ctx, solver, steps);
    rates[skip] = static_cast<double>(g.cells()) * steps / seconds;
    if (skip) active = solver.activeTiles();
    std::printf("mostly dry %dx%d float, skip dry tiles %-3s  %3d steps  %8.3f s  %10.4g cell-updates/s\n", size, size,
                skip ? "on" : "off", steps, seconds, rates[skip]);
    if (skip) std::printf("  active tiles %d of %d\n", active, solver.tileCount());
  }
  std::printf("  speed-up from skipping dry tiles: %.1fx\n\n", rates[1] / rates[0]);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sizes = {"1000", "4000"}, precisions = {"float", "double"}, schemes = {"unsplit"};
  std::string device;
  int steps = 10;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool more = a + 1 < argc;
    if (arg == "--sizes" && more) sizes = split(argv[++a]);
    else if (arg == "--precision" && more) precisions = split(argv[++a]);
    else if (arg == "--steps" && more) steps = std::atoi(argv[++a]);
    else if (arg == "--device" && more) device = argv[++a];
    else if (arg == "--schemes" && more) schemes = split(argv[++a]);
    else {
      std::fprintf(stderr, "usage: bench_flow [--sizes 1000,4000] [--precision float,double] [--steps N] [--device SEL] "
                           "[--schemes unsplit,split,hancock]\n");
      return 1;
    }
  }
  try {
    std::printf("device: %s\n\n", compute::selectDevice(device).describe().c_str());
    for (const std::string& sc : schemes)
      for (const std::string& p : precisions)
        for (const std::string& s : sizes) {
          const int size = std::atoi(s.c_str());
          try {
            benchWet(device, compute::parsePrecision(p), size, size >= 4000 ? std::max(2, steps / 4) : steps,
                     flow::parseTimeScheme(sc));
          } catch (const ComputeError& e) {
            std::printf("wet %dx%d %s: not run: %s\n\n", size, size, p.c_str(), e.what());
          }
        }
    benchDryTiles(device, 2000, steps);
    for (const std::string& p : precisions) benchTwoPhase(device, compute::parsePrecision(p), 500, std::max(2, steps / 2));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_flow: %s\n", e.what());
    return 1;
  }
  return 0;
}
