// Draws particles as point sprites coloured by one attribute through a colour ramp. Positions and
// values come from a ViewSnapshot (through ClGlInterop). Needs the GL context current in every call.
#pragma once
#include <QMatrix4x4>
#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLShaderProgram>
#include <QVector3D>
#include <memory>
#include <vector>

#include "render/ClGlInterop.hpp"
#include "render/ColorRamp.hpp"

namespace talus::gui {

class ParticleRenderer {
 public:
  explicit ParticleRenderer(QOpenGLFunctions_3_3_Core& gl);
  ~ParticleRenderer();

  /// Uploads x, y, z per particle (world coordinates [m]) and one value each (empty: all zero).
  void setParticles(const std::vector<float>& positions, const std::vector<float>& values, ClGlInterop& interop);
  void setRamp(const ColorRamp& ramp);
  /// Draws; `origin` is the world point drawn at the model origin (grid centre, mid elevation).
  void draw(const QMatrix4x4& mvp, const QVector3D& origin, float exaggeration, float pointSize, float min, float max);
  std::size_t count() const { return count_; }

 private:
  void reserve(std::size_t n);

  QOpenGLFunctions_3_3_Core& gl_;
  std::unique_ptr<QOpenGLShaderProgram> program_;
  GLuint vao_ = 0, positionBuffer_ = 0, valueBuffer_ = 0, rampTexture_ = 0;
  std::size_t count_ = 0, capacity_ = 0;
};

}  // namespace talus::gui
