#include "render/GlSetup.hpp"
#include "render/ParticleRenderer.hpp"

#include "render/ShaderResources.hpp"

namespace talus::gui {

ParticleRenderer::ParticleRenderer(QOpenGLFunctions_3_3_Core& gl) : gl_(gl) {
  program_ = loadShaderProgram("particles");
  gl_.glGenVertexArrays(1, &vao_);
  gl_.glGenBuffers(1, &positionBuffer_);
  gl_.glGenBuffers(1, &valueBuffer_);
  gl_.glGenTextures(1, &rampTexture_);
  gl_.glBindVertexArray(vao_);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, positionBuffer_);
  gl_.glEnableVertexAttribArray(0);
  gl_.glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, valueBuffer_);
  gl_.glEnableVertexAttribArray(1);
  gl_.glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl_.glBindVertexArray(0);
  setRamp(ColorRamp::byName("heat"));
}

ParticleRenderer::~ParticleRenderer() {
  gl_.glDeleteBuffers(1, &positionBuffer_);
  gl_.glDeleteBuffers(1, &valueBuffer_);
  gl_.glDeleteTextures(1, &rampTexture_);
  gl_.glDeleteVertexArrays(1, &vao_);
}

void ParticleRenderer::reserve(std::size_t n) {
  if (n <= capacity_) return;
  capacity_ = n;
  gl_.glBindBuffer(GL_ARRAY_BUFFER, positionBuffer_);
  gl_.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(3 * n * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, valueBuffer_);
  gl_.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(n * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void ParticleRenderer::setParticles(const std::vector<float>& positions, const std::vector<float>& values,
                                    ClGlInterop& interop) {
  count_ = positions.size() / 3;
  if (count_ == 0) return;
  // Reallocating the GL buffers invalidates their OpenCL images.
  if (count_ > capacity_) {
    interop.release(positionBuffer_);
    interop.release(valueBuffer_);
  }
  reserve(count_);
  interop.upload(positionBuffer_, 3 * count_, positions.data());
  std::vector<float> zeros;
  const float* v = values.data();
  if (values.size() < count_) {
    zeros.assign(count_, 0.0f);
    v = zeros.data();
  }
  interop.upload(valueBuffer_, count_, v);
}

void ParticleRenderer::setRamp(const ColorRamp& ramp) {
  uploadRampTexture(gl_, rampTexture_, ramp);
}

void ParticleRenderer::draw(const QMatrix4x4& mvp, const QVector3D& origin, float exaggeration, float pointSize,
                            float min, float max) {
  if (count_ == 0) return;
  program_->bind();
  gl_.glEnable(GL_PROGRAM_POINT_SIZE);
  gl_.glActiveTexture(GL_TEXTURE0);
  gl_.glBindTexture(GL_TEXTURE_2D, rampTexture_);
  program_->setUniformValue("uRamp", 0);
  program_->setUniformValue("uMvp", mvp);
  program_->setUniformValue("uOrigin", origin);
  program_->setUniformValue("uExaggeration", exaggeration);
  program_->setUniformValue("uPointSize", pointSize);
  program_->setUniformValue("uRange", QVector2D(min, max));
  gl_.glBindVertexArray(vao_);
  gl_.glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(count_));
  gl_.glBindVertexArray(0);
  program_->release();
}

}  // namespace talus::gui
