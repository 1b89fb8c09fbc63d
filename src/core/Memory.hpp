// How much memory this process may still take, and a readable size, for the checks that refuse an
// input before allocating what it merely declares (a raster header, the run's grids).
#pragma once
#include <cstdint>
#include <string>

namespace talus {

/// Bytes this process can still allocate: the smallest of the system's available memory
/// (/proc/meminfo MemAvailable, else the free physical pages), the room left under the cgroup's
/// memory limit (containers), and the room left under the address-space limit (RLIMIT_AS). 0 when
/// none of them can be read, which the callers treat as "unknown" and do not refuse on.
std::uint64_t availableMemoryBytes();

/// "3.58 GB", "512 MB", "12 kB" (decimal units, three significant digits).
std::string formatBytes(double bytes);

}  // namespace talus
