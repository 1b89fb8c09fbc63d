// Per-kernel timing from OpenCL profiling events, accumulated by launch label.
#pragma once
#include <CL/cl.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace talus::compute {

class Profiler {
 public:
  struct Entry {
    long long launches = 0;
    double seconds = 0.0;
  };

  /// Takes ownership of `event` (a completed or pending launch) under `label`.
  void record(const std::string& label, cl_event event);
  /// Waits for pending events and adds their device time to the totals.
  void flush();
  /// Totals per label (flushes first).
  const std::map<std::string, Entry>& totals();
  void clear();
  /// A table: label, launches, total ms, mean us, share of the total.
  std::string report();
  bool enabled = true;

 private:
  std::vector<std::pair<std::string, cl_event>> pending_;
  std::map<std::string, Entry> totals_;
};

}  // namespace talus::compute
