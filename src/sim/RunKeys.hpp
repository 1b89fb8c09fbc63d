// The run-file keys Talus understands, each declared once with default, unit, valid range, section
// and help. To add a key, add one line to the matching section function in RunKeys.cpp.
#pragma once
#include "io/KeyRegistry.hpp"

namespace talus::sim {

/// The registry of every run-file key (built once, on first use; thread-safe).
const talus::io::KeyRegistry& talusRunKeys();

}  // namespace talus::sim

namespace talus {
using sim::talusRunKeys;
}  // namespace talus
