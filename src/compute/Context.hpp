// The compute runtime of one run: device, context, in-order profiling queue, program cache, profiler.
#pragma once
#include <CL/cl.h>

#include <map>
#include <memory>
#include <string>

#include "compute/Device.hpp"
#include "compute/Precision.hpp"
#include "compute/Profiler.hpp"

namespace talus::compute {

class Program;

class Context {
 public:
  /// Opens `device` for kernels of the given precision. Throws ComputeError when the device cannot
  /// run double precision and Precision::Double was requested.
  Context(const DeviceInfo& device, Precision precision);
  /// Convenience: selectDevice(selector) then the constructor above.
  static std::unique_ptr<Context> create(const std::string& selector, Precision precision);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  cl_context context() const { return context_; }
  cl_command_queue queue() const { return queue_; }
  const DeviceInfo& device() const { return device_; }
  Precision precision() const { return precision_; }
  Profiler& profiler() { return profiler_; }

  /// The program built from kernels/<file> with `options` (plus the precision options), built once
  /// and cached in memory and on disk (binary cache keyed by source, device, driver and options).
  /// A failed build throws ComputeError with the file, the options and the build log.
  Program& program(const std::string& file, const std::string& options = "");

  /// Blocks until every queued command has finished.
  void finish();

 private:
  DeviceInfo device_;
  Precision precision_;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  Profiler profiler_;
  std::map<std::string, std::unique_ptr<Program>> programs_;
};

}  // namespace talus::compute
