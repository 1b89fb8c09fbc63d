// Small OpenGL helpers shared by the renderers and the executables.
#pragma once
#include <QOpenGLFunctions_3_3_Core>
#include <QSurfaceFormat>

#include "render/ColorRamp.hpp"

namespace talus::gui {

/// Asks for OpenGL 3.3 core (with a depth buffer) for every GL widget; call before QApplication.
inline void requestCoreProfile33() {
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);
}

/// Loads a colour ramp into the 256 x 1 RGBA texture `tex` (linear filtering, clamped).
inline void uploadRampTexture(QOpenGLFunctions_3_3_Core& gl, GLuint tex, const ColorRamp& ramp) {
  const std::vector<uint8_t> rgba = ramp.table();
  gl.glBindTexture(GL_TEXTURE_2D, tex);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 256, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace talus::gui
