// Draws the terrain (hillshaded DEM) with one grid layer over it: owns the DEM texture, the layer's
// buffer texture (filled through ClGlInterop), the colour-ramp texture and the mesh. Needs the GL
// context current in every call.
#pragma once
#include <QMatrix4x4>
#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLShaderProgram>
#include <memory>
#include <vector>

#include "core/Grid.hpp"
#include "render/ClGlInterop.hpp"
#include "render/ColorRamp.hpp"

namespace talus::gui {

/// How the layer is drawn.
struct LayerStyle {
  bool visible = false;
  float min = 0, max = 1;        ///< values mapped to the ends of the ramp
  float emptyBelow = 0;          ///< values at or below are not drawn (dry cells)
  float opacity = 0.85f;
};

/// The value the shaders read as "no data" (NaN is replaced by it on upload).
constexpr float kGlNoData = -1e30f;

class TerrainRenderer {
 public:
  explicit TerrainRenderer(QOpenGLFunctions_3_3_Core& gl);
  ~TerrainRenderer();

  /// Uploads the DEM (NaN outside the domain) and builds the meshes.
  void setTerrain(const Grid& grid, const std::vector<float>& elevation);
  /// Forgets the terrain: draw() draws nothing until the next setTerrain (its buffers are reused).
  void clear() { nx_ = ny_ = 0; }
  /// Uploads one layer value per cell (NaN: no value), through `interop`.
  void setLayer(const std::vector<float>& values, ClGlInterop& interop, cl_mem device = nullptr);
  void setRamp(const ColorRamp& ramp);
  /// Draws with the model-view-projection `mvp`; exaggeration 0 draws the flat map.
  void draw(const QMatrix4x4& mvp, float exaggeration, const LayerStyle& style);

  bool hasTerrain() const { return nx_ > 0; }
  float elevationMid() const { return 0.5f * (zMin_ + zMax_); }
  float elevationMin() const { return zMin_; }
  float elevationMax() const { return zMax_; }

 private:
  void buildMesh(int step);

  QOpenGLFunctions_3_3_Core& gl_;
  std::unique_ptr<QOpenGLShaderProgram> program_;
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
  GLuint demTexture_ = 0, rampTexture_ = 0, layerBuffer_ = 0, layerTexture_ = 0;
  GLsizei flatIndices_ = 0, meshIndices_ = 0;  ///< the flat quad first, then the 3D mesh
  int nx_ = 0, ny_ = 0;
  float dx_ = 1, zMin_ = 0, zMax_ = 1;
  std::vector<float> scratch_;
};

}  // namespace talus::gui
