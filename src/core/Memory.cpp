#include "core/Memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace talus {
namespace {

constexpr std::uint64_t kUnknown = std::numeric_limits<std::uint64_t>::max();

/// MemAvailable of /proc/meminfo (the kernel's estimate of what can be allocated without swapping),
/// else the free physical pages.
std::uint64_t systemAvailable() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kb = 0;
  std::string unit;
  while (in >> key >> kb) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kb * 1024;
  }
  const long pages = ::sysconf(_SC_AVPHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && pageSize > 0) return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize);
  return kUnknown;
}

/// Reads one unsigned number from a file ("max" or an unreadable file: unknown).
std::uint64_t readNumber(const char* path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return kUnknown;
  return std::stoull(text);
}

/// Room left under a cgroup v2 memory limit: inside a container MemAvailable shows the host's memory.
std::uint64_t cgroupAvailable() {
  const std::uint64_t limit = readNumber("/sys/fs/cgroup/memory.max");
  if (limit == kUnknown) return kUnknown;
  const std::uint64_t used = readNumber("/sys/fs/cgroup/memory.current");
  if (used == kUnknown) return limit;
  return limit > used ? limit - used : 0;
}

/// Room left under the soft address-space limit (ulimit -v): the mapped size of this process is the
/// VmSize line of /proc/self/status.
std::uint64_t addressSpaceAvailable() {
  rlimit lim{};
  if (::getrlimit(RLIMIT_AS, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return kUnknown;
  std::ifstream in("/proc/self/status");
  std::string line;
  std::uint64_t mappedKb = 0;
  while (std::getline(in, line))
    if (line.rfind("VmSize:", 0) == 0) {
      std::istringstream(line.substr(7)) >> mappedKb;
      break;
    }
  const std::uint64_t cap = static_cast<std::uint64_t>(lim.rlim_cur), mapped = mappedKb * 1024;
  return cap > mapped ? cap - mapped : 0;
}

}  // namespace

std::uint64_t availableMemoryBytes() {
  const std::uint64_t m = std::min({systemAvailable(), cgroupAvailable(), addressSpaceAvailable()});
  return m == kUnknown ? 0 : m;
}

std::string formatBytes(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 5) {
    bytes /= 1000.0;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return buf;
}

}  // namespace talus
