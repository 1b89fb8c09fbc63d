#include "sim/RunMemory.hpp"

#include <algorithm>

#include "core/Error.hpp"
#include "core/Memory.hpp"

namespace talus::sim {
namespace {

// Per-cell buffers of flow::FlowSolver, in reals (see its member list and FlowSolverDebris.cpp).
constexpr int kWaterArrays = 19;     // bed, g_p, g_n, Manning, slope speed, bed slope (2), h/qx/qy and
                                     // their stage copies, outflow, h max, v max, arrival, infiltration
                                     // capacity and infiltrated depth
constexpr int kTwoPhaseArrays = 26;  // solid state at two stages (2 x 8), delta, maxima (7),
                                     // outflow of the solids, the sources' work per step
constexpr int kParticleBedArrays = 5;  // particle bed (3) and its impulse (2)
constexpr int kParticleGridArrays = 24;  // particles::ParticleSolver's per-cell buffers: bed, bed-surface
                                         // patches (3), limited slope (2), released fluid and its
                                         // discharge (3), peak maps (2) and their P2G (4), the fluid
                                         // exchange's cell fields (6, 8 with PIC), the transfer's scratch
constexpr int kHostOutputMaps = 4;     // h, qx, qy and the speed of a report, in double

}  // namespace

RunMemory estimateRunMemory(const Scene& scene) {
  const double cells = static_cast<double>(scene.dem.grid.cells());
  const double real = scene.precision == "double" ? 8.0 : 4.0;
  RunMemory m;
  m.deviceArrays = kWaterArrays + (scene.settings.twoPhase ? kTwoPhaseArrays : 0) +
                   (scene.settings.particleBed ? kParticleBedArrays : 0) +
                   (scene.particles.enabled ? kParticleGridArrays : 0);
  const double maskBytes = scene.settings.twoPhase ? 3.0 : 1.0;  // domain mask, static-solid flags
  m.deviceBytes = cells * (m.deviceArrays * real + maskBytes);
  m.hostBytes = cells * kHostOutputMaps * 8.0;
  return m;
}

void requireMemoryForRun(const Scene& scene, const std::string& demPath) {
  const double available = static_cast<double>(availableMemoryBytes());
  const RunMemory m = estimateRunMemory(scene);
  if (available <= 0 || m.total() <= available) return;
  const Grid& g = scene.dem.grid;
  throw InputError("the grid of DEM '" + demPath + "' (" + std::to_string(g.nx) + "x" + std::to_string(g.ny) +
                   " cells) needs about " + formatBytes(m.total()) + " for the run (" +
                   std::to_string(m.deviceArrays) + " arrays of " + scene.precision + " a cell on the device, " +
                   formatBytes(m.deviceBytes) + ", and " + formatBytes(m.hostBytes) +
                   " of output maps), but only " + formatBytes(available) +
                   " of memory is available; use a coarser DEM or a smaller extent");
}

double bytesPerParticle(const std::string& precision) {
  const double real = precision == "double" ? 8.0 : 4.0;
  // Device: the solver's 32 per-particle fields, 5 sub-step tallies, 5 totals, 3 gradient-correction
  // and 3 artificial-stress components (particles/ParticleSolver.cpp, setParticles), the neighbour
  // sort's keys, values and scratch (4 words), and the neighbour list: 80 indices and 80 kernel-gradient
  // factors with a count at 4 particles per cell and h = dx (allocateNeighbourLists; more with more
  // neighbours).
  const double device = 48 * real + 16 + 81 * 4 + 80 * real;
  // Host, at the peak of a report: the seeding and material arrays (12 doubles), the downloaded
  // state (30 doubles), a checkpoint's copy (24 reals) and a layer's attribute columns (15 doubles).
  const double host = (12 + 30 + 15) * 8.0 + 24 * real;
  return device + host;
}

std::size_t particleLimit(const std::string& precision) {
  const double available = static_cast<double>(availableMemoryBytes());
  if (!(available > 0)) return std::size_t{1} << 28;
  return static_cast<std::size_t>(std::max(1.0, available / bytesPerParticle(precision)));
}

}  // namespace talus::sim
