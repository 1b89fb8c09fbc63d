#include "render/GlSetup.hpp"
#include "render/TerrainRenderer.hpp"

#include <algorithm>
#include <cmath>

#include "render/ShaderResources.hpp"

namespace talus::gui {

namespace {
/// The 3D mesh has at most this many vertices along each side (one per `step` cells).
constexpr int kMeshSide = 384;
}  // namespace

TerrainRenderer::TerrainRenderer(QOpenGLFunctions_3_3_Core& gl) : gl_(gl) {
  program_ = loadShaderProgram("terrain");
  gl_.glGenVertexArrays(1, &vao_);
  gl_.glGenBuffers(1, &vbo_);
  gl_.glGenBuffers(1, &ibo_);
  gl_.glGenBuffers(1, &layerBuffer_);
  GLuint tex[3];
  gl_.glGenTextures(3, tex);
  demTexture_ = tex[0];
  rampTexture_ = tex[1];
  layerTexture_ = tex[2];
  setRamp(ColorRamp::byName("water"));
}

TerrainRenderer::~TerrainRenderer() {
  const GLuint tex[3] = {demTexture_, rampTexture_, layerTexture_};
  gl_.glDeleteTextures(3, tex);
  gl_.glDeleteBuffers(1, &vbo_);
  gl_.glDeleteBuffers(1, &ibo_);
  gl_.glDeleteBuffers(1, &layerBuffer_);
  gl_.glDeleteVertexArrays(1, &vao_);
}

void TerrainRenderer::setTerrain(const Grid& grid, const std::vector<float>& elevation) {
  nx_ = grid.nx;
  ny_ = grid.ny;
  dx_ = static_cast<float>(grid.dx);
  zMin_ = HUGE_VALF;
  zMax_ = -HUGE_VALF;
  scratch_.resize(elevation.size());
  for (std::size_t k = 0; k < elevation.size(); ++k) {
    const float z = elevation[k];
    scratch_[k] = std::isfinite(z) ? z : kGlNoData;
    if (std::isfinite(z)) {
      zMin_ = std::min(zMin_, z);
      zMax_ = std::max(zMax_, z);
    }
  }
  if (!(zMin_ <= zMax_)) zMin_ = zMax_ = 0;
  gl_.glBindTexture(GL_TEXTURE_2D, demTexture_);
  gl_.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl_.glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, nx_, ny_, 0, GL_RED, GL_FLOAT, scratch_.data());
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.glBindTexture(GL_TEXTURE_2D, 0);
  // The layer buffer: one float per cell, empty until the first layer arrives.
  std::fill(scratch_.begin(), scratch_.end(), kGlNoData);
  gl_.glBindBuffer(GL_TEXTURE_BUFFER, layerBuffer_);
  gl_.glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(scratch_.size() * sizeof(float)), scratch_.data(),
                   GL_DYNAMIC_DRAW);
  gl_.glBindBuffer(GL_TEXTURE_BUFFER, 0);
  gl_.glBindTexture(GL_TEXTURE_BUFFER, layerTexture_);
  gl_.glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, layerBuffer_);
  gl_.glBindTexture(GL_TEXTURE_BUFFER, 0);
  buildMesh(std::max(1, (std::max(nx_, ny_) + kMeshSide - 1) / kMeshSide));
}

void TerrainRenderer::buildMesh(int step) {
  // Vertices at cell corners in cell units: the four corners of the flat quad, then the 3D mesh.
  std::vector<float> v = {0, 0, float(nx_), 0, float(nx_), float(ny_), 0, float(ny_)};
  std::vector<GLuint> idx = {0, 1, 2, 0, 2, 3};
  std::vector<int> xs, ys;
  for (int i = 0; i < nx_; i += step) xs.push_back(i);
  xs.push_back(nx_);
  for (int j = 0; j < ny_; j += step) ys.push_back(j);
  ys.push_back(ny_);
  const GLuint base = 4, w = static_cast<GLuint>(xs.size());
  for (int j : ys)
    for (int i : xs) {
      v.push_back(float(i));
      v.push_back(float(j));
    }
  for (GLuint r = 0; r + 1 < ys.size(); ++r)
    for (GLuint c = 0; c + 1 < w; ++c) {
      const GLuint a = base + r * w + c, b = a + 1, d = a + w, e = d + 1;
      idx.insert(idx.end(), {a, b, e, a, e, d});
    }
  flatIndices_ = 6;
  meshIndices_ = static_cast<GLsizei>(idx.size()) - 6;
  gl_.glBindVertexArray(vao_);
  gl_.glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
  gl_.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo_);
  gl_.glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(GLuint)), idx.data(),
                   GL_STATIC_DRAW);
  gl_.glEnableVertexAttribArray(0);
  gl_.glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl_.glBindVertexArray(0);
}

void TerrainRenderer::setLayer(const std::vector<float>& values, ClGlInterop& interop, cl_mem device) {
  if (values.size() != static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_)) return;
  scratch_.resize(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) scratch_[k] = std::isfinite(values[k]) ? values[k] : kGlNoData;
  interop.upload(layerBuffer_, scratch_.size(), scratch_.data(), device);
}

void TerrainRenderer::setRamp(const ColorRamp& ramp) {
  uploadRampTexture(gl_, rampTexture_, ramp);
}

void TerrainRenderer::draw(const QMatrix4x4& mvp, float exaggeration, const LayerStyle& style) {
  if (!hasTerrain()) return;
  program_->bind();
  gl_.glActiveTexture(GL_TEXTURE0);
  gl_.glBindTexture(GL_TEXTURE_2D, demTexture_);
  gl_.glActiveTexture(GL_TEXTURE1);
  gl_.glBindTexture(GL_TEXTURE_BUFFER, layerTexture_);
  gl_.glActiveTexture(GL_TEXTURE2);
  gl_.glBindTexture(GL_TEXTURE_2D, rampTexture_);
  program_->setUniformValue("uElevation", 0);
  program_->setUniformValue("uLayer", 1);
  program_->setUniformValue("uRamp", 2);
  program_->setUniformValue("uGridSize", QVector2D(float(nx_), float(ny_)));
  program_->setUniformValue("uCellSize", dx_);
  program_->setUniformValue("uElevationMid", elevationMid());
  program_->setUniformValue("uElevationRange", QVector2D(zMin_, zMax_));
  program_->setUniformValue("uExaggeration", exaggeration);
  program_->setUniformValue("uMvp", mvp);
  // Light from azimuth 315 degrees (north-west), 45 degrees above the horizon.
  program_->setUniformValue("uLight", QVector3D(-0.5f, 0.5f, 0.70710678f));
  program_->setUniformValue("uLayerOn", style.visible);
  program_->setUniformValue("uRange", QVector2D(style.min, style.max));
  program_->setUniformValue("uEmptyBelow", style.emptyBelow);
  program_->setUniformValue("uOpacity", style.opacity);
  gl_.glBindVertexArray(vao_);
  if (exaggeration > 0)
    gl_.glDrawElements(GL_TRIANGLES, meshIndices_, GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(static_cast<std::uintptr_t>(flatIndices_) * sizeof(GLuint)));
  else
    gl_.glDrawElements(GL_TRIANGLES, flatIndices_, GL_UNSIGNED_INT, nullptr);
  gl_.glBindVertexArray(0);
  gl_.glActiveTexture(GL_TEXTURE0);
  program_->release();
}

}  // namespace talus::gui
