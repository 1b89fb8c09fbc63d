// The memory a run's grids will take, estimated from the scene before the solver allocates them,
// so that a grid too large for the machine is refused with the numbers instead of ending in
// std::bad_alloc (or the kernel's OOM killer) after minutes of loading.
#pragma once
#include <cstddef>
#include <string>

#include "sim/Scene.hpp"

namespace talus::sim {

/// Bytes the run still has to allocate for its grids once the scene is loaded.
struct RunMemory {
  double deviceBytes = 0;  ///< the flow solver's per-cell buffers (host memory on a CPU device)
  double hostBytes = 0;    ///< host copies made for the outputs (report and final maps)
  int deviceArrays = 0;    ///< per-cell arrays of the solver (counted in reals)
  double total() const { return deviceBytes + hostBytes; }
};

/// The estimate for a scene: the solver's buffer list (flow/FlowSolver.hpp: 15 reals a cell for
/// water, 27 more for the two-phase model, 5 for the particle bed) times the cells times the
/// precision's size, plus four double maps for the outputs.
RunMemory estimateRunMemory(const Scene& scene);

/// Throws talus::InputError when the estimate exceeds the memory this process can still take
/// (core/Memory.hpp), naming the grid, the estimate and what is available. Does nothing when the
/// available memory cannot be read.
void requireMemoryForRun(const Scene& scene, const std::string& demPath);

/// Bytes one MPM particle takes over a run, device and host together (see the definition).
double bytesPerParticle(const std::string& precision);
/// The most particles the memory this process can still take holds (the seeding refuses more, by
/// count, before allocating them); a fixed 2^28 when the available memory cannot be read.
std::size_t particleLimit(const std::string& precision);

}  // namespace talus::sim
