#include "render/ClGlInterop.hpp"

#include <CL/cl_gl.h>
#include <GL/glx.h>

#include <vector>

namespace talus::gui {

namespace {

/// True when `ctx` was created with CL_GL_CONTEXT_KHR naming the GL context current on this thread.
bool createdForCurrentGlContext(cl_context ctx) {
  const GLXContext current = glXGetCurrentContext();
  if (!ctx || !current) return false;
  std::size_t bytes = 0;
  if (clGetContextInfo(ctx, CL_CONTEXT_PROPERTIES, 0, nullptr, &bytes) != CL_SUCCESS || bytes == 0) return false;
  std::vector<cl_context_properties> props(bytes / sizeof(cl_context_properties));
  if (clGetContextInfo(ctx, CL_CONTEXT_PROPERTIES, bytes, props.data(), nullptr) != CL_SUCCESS) return false;
  for (std::size_t k = 0; k + 1 < props.size() && props[k] != 0; k += 2)
    if (props[k] == CL_GL_CONTEXT_KHR && props[k + 1] == reinterpret_cast<cl_context_properties>(current)) return true;
  return false;
}

}  // namespace

QString interopPathName(InteropPath path) {
  return path == InteropPath::Shared ? "OpenCL/OpenGL sharing (cl_khr_gl_sharing)" : "copy through host memory";
}

compute::GlShareHandles glShareHandlesOfCurrentContext() {
  compute::GlShareHandles h;
  h.glContext = reinterpret_cast<void*>(glXGetCurrentContext());
  h.display = reinterpret_cast<void*>(glXGetCurrentDisplay());
  return h;
}

QString interopLogLine(const InteropChoice& choice) {
  return QString("interop: %1 (%2)").arg(interopPathName(choice.path), choice.reason);
}

InteropChoice chooseInteropPath(const compute::DeviceInfo* device, cl_context dataContext, cl_command_queue queue,
                                const QString& contextNote) {
  InteropChoice c;
  if (!device) {
    c.reason = "no OpenCL device holds the data";
  } else if (!device->hasGlSharing) {
    c.reason = QString("device '%1' does not report cl_khr_gl_sharing").arg(QString::fromStdString(device->name));
  } else if (!createdForCurrentGlContext(dataContext)) {
    c.reason = QString("device '%1' offers cl_khr_gl_sharing, but the run's OpenCL context was not created "
                       "for this OpenGL context")
                   .arg(QString::fromStdString(device->name));
    if (!contextNote.isEmpty()) c.reason += ": " + contextNote;
  } else {
    c.path = InteropPath::Shared;
    c.context = dataContext;
    c.queue = queue;
    c.deviceId = device->id;
    c.reason = QString("device '%1' shares buffers with OpenGL").arg(QString::fromStdString(device->name));
  }
  return c;
}

ClGlInterop::ClGlInterop(QOpenGLFunctions_3_3_Core& gl, InteropChoice choice) : gl_(gl), choice_(std::move(choice)) {
  if (choice_.path == InteropPath::Shared && choice_.context && choice_.deviceId) {
    // Uploads run on the GUI thread while the worker keeps the run's queue busy with steps: a
    // queue of their own keeps them from waiting for (or interleaving with) the simulation.
    cl_int err = CL_SUCCESS;
    ownQueue_ = clCreateCommandQueue(choice_.context, choice_.deviceId, 0, &err);
    if (err != CL_SUCCESS) ownQueue_ = nullptr;
    if (ownQueue_) choice_.queue = ownQueue_;
  }
}

ClGlInterop::~ClGlInterop() {
  for (auto& [buffer, mem] : shared_) clReleaseMemObject(mem);
  if (ownQueue_) clReleaseCommandQueue(ownQueue_);
}

void ClGlInterop::release(GLuint glBuffer) {
  auto it = shared_.find(glBuffer);
  if (it == shared_.end()) return;
  clReleaseMemObject(it->second);
  shared_.erase(it);
}

void ClGlInterop::upload(GLuint glBuffer, std::size_t count, const float* host, cl_mem device) {
  if (choice_.path == InteropPath::Shared && device) {
    cl_mem& image = shared_[glBuffer];
    cl_int err = CL_SUCCESS;
    if (!image) image = clCreateFromGLBuffer(choice_.context, CL_MEM_WRITE_ONLY, glBuffer, &err);
    if (err == CL_SUCCESS && image) {
      gl_.glFinish();  // GL must be done with the buffer before OpenCL takes it
      err = clEnqueueAcquireGLObjects(choice_.queue, 1, &image, 0, nullptr, nullptr);
      if (err == CL_SUCCESS)
        err = clEnqueueCopyBuffer(choice_.queue, device, image, 0, 0, count * sizeof(float), 0, nullptr, nullptr);
      clEnqueueReleaseGLObjects(choice_.queue, 1, &image, 0, nullptr, nullptr);
      clFinish(choice_.queue);
      if (err == CL_SUCCESS) {
        ++sharedUploads_;
        return;
      }
    }
    // A failed shared upload falls back to the host copy from now on.
    choice_.path = InteropPath::HostCopy;
    choice_.reason = QString("OpenCL/OpenGL sharing failed (OpenCL error %1); copying through host memory").arg(err);
  }
  if (!host) return;
  gl_.glBindBuffer(GL_TEXTURE_BUFFER, glBuffer);
  gl_.glBufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(float)), host);
  gl_.glBindBuffer(GL_TEXTURE_BUFFER, 0);
  ++hostUploads_;
}

}  // namespace talus::gui
