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
