// How device data reach OpenGL buffers: through OpenCL/OpenGL sharing (cl_khr_gl_sharing: the GL
// buffer is an OpenCL memory object and device data are copied device to device) when the device
// offers it and the OpenCL context holding the data was created for the current GL context, or
// through host memory otherwise (PoCL's CPU device). The choice is automatic and says why. The
// run's OpenCL context is created for the viewer's GL context when the viewer hands its handles to
// the engine first (glShareHandlesOfCurrentContext + compute::setGlShareForNewContexts).
#pragma once
#include <CL/cl.h>

#include <QOpenGLFunctions_3_3_Core>
#include <QString>
#include <cstddef>
#include <map>

#include "compute/Device.hpp"
#include "compute/GlShare.hpp"

namespace talus::gui {

enum class InteropPath {
  Shared,    ///< cl_khr_gl_sharing: clEnqueueCopyBuffer into the GL buffer
  HostCopy,  ///< device -> host vector -> glBufferSubData
};

/// The path chosen for a device and context, and why (for the log).
struct InteropChoice {
  InteropPath path = InteropPath::HostCopy;
  QString reason;
  cl_context context = nullptr;      ///< the sharing context (Shared only)
  cl_command_queue queue = nullptr;  ///< a queue of that context (Shared only)
  cl_device_id deviceId = nullptr;   ///< the device of that context (Shared only)
};

/// The path for data living in `dataContext` (may be nullptr: no device data, host copies only) on
/// `device`, given the GL context current on this thread. `contextNote`, when given, says why the
/// data context does or does not share with OpenGL (compute::Context::glShareReason) and is used
/// when the context turns out not to be shared with this GL context.
InteropChoice chooseInteropPath(const compute::DeviceInfo* device, cl_context dataContext, cl_command_queue queue,
                                const QString& contextNote = {});

/// The GL context and display current on this thread (GLX), as opaque handles for the engine.
compute::GlShareHandles glShareHandlesOfCurrentContext();

/// The log line for a choice: "interop: <path> (<reason>)".
QString interopLogLine(const InteropChoice& choice);

/// Name of a path for messages ("OpenCL/OpenGL sharing", "copy through host memory").
QString interopPathName(InteropPath path);

/// Fills GL buffers from device buffers or host values. Needs the GL context current.
class ClGlInterop {
 public:
  ClGlInterop(QOpenGLFunctions_3_3_Core& gl, InteropChoice choice);
  ~ClGlInterop();
  ClGlInterop(const ClGlInterop&) = delete;
  ClGlInterop& operator=(const ClGlInterop&) = delete;

  const InteropChoice& choice() const { return choice_; }
  /// Writes `count` floats into the GL buffer object `glBuffer` (at least that large): device to
  /// device from `device` on the shared path when it is given, else from `host`.
  void upload(GLuint glBuffer, std::size_t count, const float* host, cl_mem device = nullptr);
  /// Forgets the OpenCL image of a GL buffer that is about to be deleted or reallocated.
  void release(GLuint glBuffer);
  /// Uploads done on each path since construction (for tests and the log).
  int sharedUploads() const { return sharedUploads_; }
  int hostUploads() const { return hostUploads_; }

 private:
  QOpenGLFunctions_3_3_Core& gl_;
  InteropChoice choice_;
  cl_command_queue ownQueue_ = nullptr;  // GUI-thread queue for shared uploads (the run's is busy)
  std::map<GLuint, cl_mem> shared_;  // GL buffer -> its OpenCL memory object
  int sharedUploads_ = 0, hostUploads_ = 0;
};

}  // namespace talus::gui
