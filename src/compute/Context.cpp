#include "compute/Context.hpp"

#include "compute/ClError.hpp"
#include "compute/KernelSources.hpp"
#include "compute/Program.hpp"
#include "core/Error.hpp"

namespace talus::compute {

Context::Context(const DeviceInfo& device, Precision precision) : Context(device, precision, GlShareHandles{}) {}

Context::Context(const DeviceInfo& device, Precision precision, const GlShareHandles& gl)
    : device_(device), precision_(precision) {
  if (precision == Precision::Double && !device.hasDouble)
    throw ComputeError("device '" + device.name + "' has no double precision (cl_khr_fp64); use --precision float");
  cl_int status = CL_SUCCESS;
  if (gl.valid()) {
    GlSharePlan plan = planGlSharing(device, gl);
    glShareReason_ = plan.reason;
    if (plan.shared) {
      context_ = clCreateContext(plan.properties.data(), 1, &device_.id, nullptr, nullptr, &status);
      if (status == CL_SUCCESS) {
        glShared_ = true;
      } else {
        // The driver refused the GL properties: run without sharing rather than not at all.
        context_ = nullptr;
        glShareReason_ = "creating an OpenCL context shared with OpenGL on '" + device.name + "' failed (" +
                         clErrorText(status) + ")";
      }
    }
  }
  if (!context_) {
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(device.platform), 0};
    context_ = clCreateContext(props, 1, &device_.id, nullptr, nullptr, &status);
    clCheck(status, "creating an OpenCL context on '" + device.name + "'");
  }
  queue_ = clCreateCommandQueue(context_, device_.id, CL_QUEUE_PROFILING_ENABLE, &status);
  clCheck(status, "creating a command queue on '" + device.name + "'");
}

std::unique_ptr<Context> Context::create(const std::string& selector, Precision precision) {
  return std::make_unique<Context>(selectDevice(selector), precision, glShareForNewContexts());
}

Context::~Context() {
  if (queue_) {
    clFinish(queue_);
    profiler_.flush();
  }
  programs_.clear();
  if (queue_) clReleaseCommandQueue(queue_);
  if (context_) clReleaseContext(context_);
}

Program& Context::program(const std::string& file, const std::string& options) {
  const std::string fullOptions = precisionBuildOptions(precision_) + (options.empty() ? "" : " " + options);
  const std::string key = file + "\n" + fullOptions;
  auto it = programs_.find(key);
  if (it != programs_.end()) return *it->second;
  auto program = std::make_unique<Program>(*this, file, loadKernelSource(file), fullOptions);
  Program& ref = *program;
  programs_.emplace(key, std::move(program));
  return ref;
}

void Context::finish() { clCheck(clFinish(queue_), "waiting for the device"); }

}  // namespace talus::compute
