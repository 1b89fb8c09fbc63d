#include "compute/Profiler.hpp"

#include <cstdio>
#include <sstream>

namespace talus::compute {

void Profiler::record(const std::string& label, cl_event event) {
  if (!event) return;
  pending_.emplace_back(label, event);
  if (pending_.size() >= 4096) flush();
}

void Profiler::flush() {
  for (auto& [label, event] : pending_) {
    cl_ulong start = 0, end = 0;
    clWaitForEvents(1, &event);
    if (clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_START, sizeof(start), &start, nullptr) == CL_SUCCESS &&
        clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_END, sizeof(end), &end, nullptr) == CL_SUCCESS) {
      Entry& e = totals_[label];
      e.launches += 1;
      e.seconds += 1e-9 * static_cast<double>(end - start);
    }
    clReleaseEvent(event);
  }
  pending_.clear();
}

const std::map<std::string, Profiler::Entry>& Profiler::totals() {
  flush();
  return totals_;
}

void Profiler::clear() {
  flush();
  totals_.clear();
}

std::string Profiler::report() {
  flush();
  double all = 0.0;
  for (const auto& [label, e] : totals_) all += e.seconds;
  std::ostringstream o;
  char line[200];
  std::snprintf(line, sizeof line, "%-28s %10s %12s %12s %7s\n", "kernel", "launches", "total ms", "mean us", "share");
  o << line;
  for (const auto& [label, e] : totals_) {
    std::snprintf(line, sizeof line, "%-28s %10lld %12.3f %12.2f %6.1f%%\n", label.c_str(), e.launches,
                  1e3 * e.seconds, e.launches ? 1e6 * e.seconds / e.launches : 0.0,
                  all > 0 ? 100.0 * e.seconds / all : 0.0);
    o << line;
  }
  return o.str();
}

}  // namespace talus::compute
