// The compute runtime of one run: device, context, in-order profiling queue, program cache, profiler.
#pragma once
#include <CL/cl.h>

#include <map>
#include <memory>
#include <string>

#include "compute/Device.hpp"
#include "compute/GlShare.hpp"
#include "compute/Precision.hpp"
#include "compute/Profiler.hpp"

namespace talus::compute {

class Program;

class Context {
 public:
  /// Opens `device` for kernels of the given precision. Throws ComputeError when the device cannot
  /// run double precision and Precision::Double was requested.
  Context(const DeviceInfo& device, Precision precision);
  /// As above, and shares buffers with the OpenGL context `gl` when the device can (planGlSharing);
  /// otherwise an ordinary context, with glShareReason() saying why sharing is off.
  Context(const DeviceInfo& device, Precision precision, const GlShareHandles& gl);
  /// Convenience: selectDevice(selector) then the constructor above, with the handles of
  /// setGlShareForNewContexts() (none unless a viewer set them).
  static std::unique_ptr<Context> create(const std::string& selector, Precision precision);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  cl_context context() const { return context_; }
  cl_command_queue queue() const { return queue_; }
  const DeviceInfo& device() const { return device_; }
  Precision precision() const { return precision_; }
  Profiler& profiler() { return profiler_; }
  /// True when the context was created for an OpenGL context (cl_khr_gl_sharing properties).
  bool glShared() const { return glShared_; }
  /// Why the context does or does not share buffers with OpenGL (one clause, for the log).
  const std::string& glShareReason() const { return glShareReason_; }

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
  bool glShared_ = false;
  std::string glShareReason_ = "no OpenGL context was offered for sharing";
  Profiler profiler_;
  std::map<std::string, std::unique_ptr<Program>> programs_;
};

}  // namespace talus::compute
