#include "compute/GlShare.hpp"

#include <CL/cl_gl.h>

#include <mutex>

namespace talus::compute {
namespace {

std::mutex gMutex;
GlShareHandles gHandles;

/// Asks the platform which devices can drive the GL context (clGetGLContextInfoKHR, an extension
/// function looked up per platform). Returns 1 when `device` is among them, 0 when it is not, -1 when
/// the platform cannot tell (no such function, or the query failed).
int deviceDrivesGlContext(const DeviceInfo& device, const std::vector<cl_context_properties>& props) {
  auto fn = reinterpret_cast<clGetGLContextInfoKHR_fn>(
      clGetExtensionFunctionAddressForPlatform(device.platform, "clGetGLContextInfoKHR"));
  if (!fn) return -1;
  std::size_t bytes = 0;
  if (fn(props.data(), CL_DEVICES_FOR_GL_CONTEXT_KHR, 0, nullptr, &bytes) != CL_SUCCESS) return -1;
  std::vector<cl_device_id> devices(bytes / sizeof(cl_device_id));
  if (devices.empty()) return 0;
  if (fn(props.data(), CL_DEVICES_FOR_GL_CONTEXT_KHR, bytes, devices.data(), nullptr) != CL_SUCCESS) return -1;
  for (cl_device_id d : devices)
    if (d == device.id) return 1;
  return 0;
}

}  // namespace

GlSharePlan planGlSharing(const DeviceInfo& device, const GlShareHandles& gl) {
  GlSharePlan plan;
  const std::string who = "device '" + device.name + "'";
  if (!gl.valid()) {
    plan.reason = "no OpenGL context was offered for sharing";
    return plan;
  }
  if (!device.hasGlSharing) {
    plan.reason = who + " does not report cl_khr_gl_sharing";
    return plan;
  }
  plan.properties = {CL_GL_CONTEXT_KHR,   reinterpret_cast<cl_context_properties>(gl.glContext),
                     CL_GLX_DISPLAY_KHR,  reinterpret_cast<cl_context_properties>(gl.display),
                     CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(device.platform),
                     0};
  const int drives = deviceDrivesGlContext(device, plan.properties);
  if (drives == 0) {
    plan.properties.clear();
    plan.reason = who + " offers cl_khr_gl_sharing but does not drive the OpenGL context";
    return plan;
  }
  plan.shared = true;
  plan.reason = who + " shares buffers with the OpenGL context (cl_khr_gl_sharing" +
                (drives == 1 ? ", confirmed by clGetGLContextInfoKHR)" : ")");
  return plan;
}

void setGlShareForNewContexts(const GlShareHandles& gl) {
  std::lock_guard<std::mutex> lock(gMutex);
  gHandles = gl;
}

GlShareHandles glShareForNewContexts() {
  std::lock_guard<std::mutex> lock(gMutex);
  return gHandles;
}

}  // namespace talus::compute
