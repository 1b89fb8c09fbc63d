// Scene builder and run loop for the shallow-water verification tests; see FlowScene.hpp.
#include "support/FlowScene.hpp"

#include "support/TestDevice.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace talus::test {

flow::FlowInput makeInput(const Grid& grid, const Field& bed, const Field& h, const Field& qx, const Field& qy,
                          double manning) {
  const std::size_t n = grid.cells();
  flow::FlowInput in;
  in.mask.assign(n, 1);
  in.manning.assign(n, manning);
  in.bed.resize(n);
  in.h.resize(n);
  if (qx) in.qx.resize(n);
  if (qy) in.qy.resize(n);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      const double x = cellX(grid, i), y = cellY(grid, j);
      in.bed[k] = bed(x, y);
      in.h[k] = h(x, y);
      if (qx) in.qx[k] = qx(x, y);
      if (qy) in.qy[k] = qy(x, y);
    }
  return in;
}

std::vector<double> roughDem(const Grid& g, unsigned seed, double noise) {
  constexpr double kPi = 3.14159265358979323846;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-noise, noise);
  std::vector<double> b(g.cells());
  const double lx = g.nx * g.dx, ly = g.ny * g.dx;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double x = cellX(g, i), y = cellY(g, j);
      b[g.index(i, j)] = 0.8 * std::sin(3 * kPi * x / lx) * std::cos(2 * kPi * y / ly) +
                         0.4 * std::cos(5 * kPi * x / lx + 1.0) * std::sin(3 * kPi * y / ly) + uniform(rng);
    }
  return b;
}

namespace {

std::vector<double> velocity(const std::vector<double>& h, const std::vector<double>& q, double hDry) {
  std::vector<double> u(h.size(), 0.0);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (h[k] > hDry) u[k] = q[k] / h[k];
  return u;
}

}  // namespace

std::vector<double> FlowRun::velocityX(double hDry) const { return velocity(h, qx, hDry); }
std::vector<double> FlowRun::velocityY(double hDry) const { return velocity(h, qy, hDry); }

FlowRun runFlow(const Grid& grid, const flow::FlowInput& input, const flow::FlowSettings& settings,
                const RunLimits& limits, compute::Precision precision,
                const std::function<void(const flow::FlowSolver&)>& onStep) {
  flow::FlowSolver solver(testContext(precision), grid, settings);
  solver.setInput(input);
  FlowRun run;
  run.grid = grid;
  run.bed = input.bed;
  run.volume0 = solver.diagnostics().volume;
  const auto start = std::chrono::steady_clock::now();
  // Stop when the remaining time is a round-off sliver of the end time, so no step of ~1e-16 s
  // is taken after the last full one.
  const double tEnd = limits.endTime;
  const double sliver = std::isfinite(tEnd) ? 1e-12 * std::max(1.0, std::fabs(tEnd)) : 0.0;
  double t = 0.0;
  while (run.steps < limits.maxSteps && t < tEnd - sliver) {
    const double stable = solver.stableDt();
    if (!std::isfinite(stable) || !(stable > 0))
      throw std::runtime_error("runFlow: no finite stable time step at t = " + std::to_string(t) + " (dt " +
                               std::to_string(stable) + ")");
    const double dt = std::min(stable, tEnd - t);
    solver.step(dt);
    t += dt;
    ++run.steps;
    run.outflow += solver.diagnostics().outflow;
    if (onStep) onStep(solver);
  }
  run.h = solver.h();
  run.qx = solver.qx();
  run.qy = solver.qy();
  run.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.time = t;
  run.volume = solver.diagnostics().volume;
  return run;
}

}  // namespace talus::test
