// Work-group size of the per-particle kernels.
#pragma once
#include "compute/Kernel.hpp"

namespace talus::particles {

/// Fixed rather than left to the driver: with a driver-chosen size, PoCL builds a new work-group
/// function for almost every global size, and the particle count changes as particles leave (a
/// dam break spent minutes compiling on a cold cache). Kernels check their index against the count,
/// so the rounded-up global range is safe.
inline const compute::Range kParticleGroup{64};

}  // namespace talus::particles
