// The CL/GL interop layer on PoCL: the automatic choice takes the copy path (and says why), and the
// copy path puts exactly the given values into the OpenGL buffer.
#include <gtest/gtest.h>

#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFunctions_3_3_Core>

#include "compute/Context.hpp"
#include "render/ClGlInterop.hpp"

using namespace talus;

TEST(ClGlInterop, PoclTakesTheCopyPathAndCopiesExactly) {
  QOpenGLContext gl;
  ASSERT_TRUE(gl.create());
  QOffscreenSurface surface;
  surface.setFormat(gl.format());
  surface.create();
  ASSERT_TRUE(gl.makeCurrent(&surface));
  auto* f = gl.versionFunctions<QOpenGLFunctions_3_3_Core>();
  ASSERT_NE(f, nullptr) << "no OpenGL 3.3 core context";
  ASSERT_TRUE(f->initializeOpenGLFunctions());

  const auto ctx = compute::Context::create("", compute::Precision::Float);
  const gui::InteropChoice choice = gui::chooseInteropPath(&ctx->device(), ctx->context(), ctx->queue());
  EXPECT_EQ(choice.path, gui::InteropPath::HostCopy);
  if (!ctx->device().hasGlSharing)
    EXPECT_TRUE(choice.reason.contains("does not report cl_khr_gl_sharing")) << choice.reason.toStdString();
  else
    EXPECT_TRUE(choice.reason.contains("not created for this OpenGL context")) << choice.reason.toStdString();

  const std::size_t n = 10007;
  std::vector<float> values(n);
  for (std::size_t k = 0; k < n; ++k) values[k] = 0.25f * float(k) - 3.0f;
  GLuint buffer = 0;
  f->glGenBuffers(1, &buffer);
  f->glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  f->glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(n * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  gui::ClGlInterop interop(*f, choice);
  interop.upload(buffer, n, values.data());
  std::vector<float> back(n, -1.0f);
  f->glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  f->glGetBufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(n * sizeof(float)), back.data());
  EXPECT_EQ(back, values);
  EXPECT_EQ(interop.hostUploads(), 1);
  EXPECT_EQ(interop.sharedUploads(), 0);
  f->glDeleteBuffers(1, &buffer);
  gl.doneCurrent();
}

TEST(ClGlInterop, NoDeviceMeansHostCopies) {
  const gui::InteropChoice choice = gui::chooseInteropPath(nullptr, nullptr, nullptr);
  EXPECT_EQ(choice.path, gui::InteropPath::HostCopy);
  EXPECT_FALSE(choice.reason.isEmpty());
}

namespace {

/// An offscreen OpenGL 3.3 context made current for the lifetime of the object.
struct CurrentGl {
  QOpenGLContext gl;
  QOffscreenSurface surface;
  bool ok = false;
  CurrentGl() {
    if (!gl.create()) return;
    surface.setFormat(gl.format());
    surface.create();
    ok = gl.makeCurrent(&surface);
  }
  ~CurrentGl() {
    if (ok) gl.doneCurrent();
  }
};

}  // namespace

TEST(ClGlInterop, ContextOfferedTheGlContextRecordsWhySharingIsOff) {
  CurrentGl gl;
  ASSERT_TRUE(gl.ok);
  const compute::GlShareHandles handles = gui::glShareHandlesOfCurrentContext();
  ASSERT_TRUE(handles.valid()) << "no GLX context current (the tests run under xvfb-run)";
  const compute::DeviceInfo device = compute::selectDevice("");
  compute::Context ctx(device, compute::Precision::Float, handles);
  const QString note = QString::fromStdString(ctx.glShareReason());
  if (!device.hasGlSharing) {
    // PoCL: an ordinary context, and the reason names the missing extension.
    EXPECT_FALSE(ctx.glShared());
    EXPECT_TRUE(note.contains("does not report cl_khr_gl_sharing")) << note.toStdString();
    const gui::InteropChoice choice = gui::chooseInteropPath(&ctx.device(), ctx.context(), ctx.queue(), note);
    EXPECT_EQ(choice.path, gui::InteropPath::HostCopy);
    const QString line = gui::interopLogLine(choice);
    EXPECT_TRUE(line.startsWith("interop: copy through host memory (device '")) << line.toStdString();
    EXPECT_TRUE(line.contains("cl_khr_gl_sharing")) << line.toStdString();
  } else {
    // A device with the extension: either the context is shared with this GL context and the shared
    // path is chosen, or the reason says why not.
    const gui::InteropChoice choice = gui::chooseInteropPath(&ctx.device(), ctx.context(), ctx.queue(), note);
    EXPECT_EQ(choice.path == gui::InteropPath::Shared, ctx.glShared()) << choice.reason.toStdString();
    EXPECT_FALSE(note.isEmpty());
  }
}

TEST(ClGlInterop, ContextWithoutGlHandlesSaysNoneWasOffered) {
  const compute::DeviceInfo device = compute::selectDevice("");
  compute::Context ctx(device, compute::Precision::Float, compute::GlShareHandles{});
  EXPECT_FALSE(ctx.glShared());
  EXPECT_EQ(ctx.glShareReason(), "no OpenGL context was offered for sharing");
}

TEST(ClGlInterop, CreateUsesTheHandlesOfferedForNewContexts) {
  CurrentGl gl;
  ASSERT_TRUE(gl.ok);
  compute::setGlShareForNewContexts(gui::glShareHandlesOfCurrentContext());
  const auto ctx = compute::Context::create("", compute::Precision::Float);
  compute::setGlShareForNewContexts({});
  const std::string note = ctx->glShareReason();
  // The handles reached the context: the reason is about the device, not about missing handles.
  EXPECT_NE(note, "no OpenGL context was offered for sharing");
  if (!ctx->device().hasGlSharing) {
    EXPECT_NE(note.find("cl_khr_gl_sharing"), std::string::npos) << note;
  }
  EXPECT_FALSE(compute::glShareForNewContexts().valid());
}
