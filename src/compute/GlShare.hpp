// OpenCL/OpenGL sharing (cl_khr_gl_sharing) at context creation, without GL headers: the GL side
// hands over its context and display as opaque handles, and this file turns them into the context
// properties OpenCL needs, or says why sharing is off. The engine never includes Qt or GL headers;
// the desktop application fills GlShareHandles from glXGetCurrentContext()/glXGetCurrentDisplay().
#pragma once
#include <CL/cl.h>

#include <string>
#include <vector>

#include "compute/Device.hpp"

namespace talus::compute {

/// The OpenGL context an OpenCL context should share buffers with (Linux/GLX). Both null: none.
struct GlShareHandles {
  void* glContext = nullptr;  ///< GLXContext
  void* display = nullptr;    ///< Display*
  bool valid() const { return glContext != nullptr && display != nullptr; }
};

/// The outcome of asking for a GL-shared context on a device.
struct GlSharePlan {
  bool shared = false;                            ///< create the context with `properties`
  std::vector<cl_context_properties> properties;  ///< zero-terminated, CL_CONTEXT_PLATFORM included
  std::string reason;                             ///< why sharing is on or off (for the log)
};

/// Decides whether a context on `device` can share buffers with the GL context `gl`: the device must
/// report cl_khr_gl_sharing and, where the platform offers clGetGLContextInfoKHR, be among the
/// devices that can drive that GL context. Never throws; `reason` says what decided.
GlSharePlan planGlSharing(const DeviceInfo& device, const GlShareHandles& gl);

/// Handles for contexts made by Context::create() (the engine's own code paths, e.g. Simulation)
/// from now on in this process; invalid handles switch sharing off again. Thread-safe.
void setGlShareForNewContexts(const GlShareHandles& gl);
GlShareHandles glShareForNewContexts();

}  // namespace talus::compute
