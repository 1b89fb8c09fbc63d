// The live viewer: a thin QOpenGLWidget adapter that owns the camera and the renderers, turns mouse
// input into camera moves and hover positions, and uploads the latest ViewSnapshot when it draws.
// Draws as often as Qt repaints it, independent of how fast the simulation steps.
#pragma once
#include <QOpenGLFunctions_3_3_Core>
#include <QOpenGLWidget>
#include <QPoint>
#include <memory>
#include <vector>

#include "compute/Device.hpp"
#include "core/Grid.hpp"
#include "render/ClGlInterop.hpp"
#include "render/TerrainRenderer.hpp"
#include "sim/ViewFields.hpp"
#include "view/MapSketch.hpp"
#include "view/ViewCamera.hpp"

namespace talus::gui {

class ParticleRenderer;

/// How particles are drawn.
struct ParticleStyle {
  QString attribute;          ///< the attribute colouring them ("" = first listed)
  float min = 0, max = 1;
  float pointSize = 4;        ///< [pixels]
  bool visible = true;
};

class ViewerWidget : public QOpenGLWidget, protected QOpenGLFunctions_3_3_Core {
  Q_OBJECT

 public:
  explicit ViewerWidget(QWidget* parent = nullptr);
  ~ViewerWidget() override;

  /// The terrain of a scene: grid and elevation (NaN outside the domain). Frames it whole unless
  /// it lies on the grid already shown (then the view stays).
  void setTerrain(const Grid& grid, std::vector<float> elevation);
  /// Where device data live, for the choice of the interop path (nullptrs: host data only).
  /// `contextNote` says why that context does or does not share with OpenGL (for the log).
  void setDataSource(const compute::DeviceInfo* device, cl_context context, cl_command_queue queue,
                     const QString& contextNote = {});
  /// The data to draw from now on (null: terrain only).
  void setSnapshot(std::shared_ptr<const sim::ViewSnapshot> snapshot);
  /// Forgets the scene: terrain, snapshot and the run's OpenCL queue (which goes with its run), so
  /// that nothing of a previous run-file stays on screen.
  void clearScene();
  std::shared_ptr<const sim::ViewSnapshot> snapshot() const { return snapshot_; }

  /// The grid layer drawn over the terrain ("" = none) and its style.
  void setLayer(const QString& name, const LayerStyle& style);
  void setLayerRamp(const QString& ramp);
  void setParticleStyle(const ParticleStyle& style);
  void setParticleRamp(const QString& ramp);
  void setMode(ViewCamera::Mode mode);
  /// Vertical exaggeration of the tilted 3D view (terrain and particles; 1 = true heights; clamped
  /// to 0.1..50). The map view is flat whatever it is.
  void setVerticalExaggeration(double factor);
  double verticalExaggeration() const { return verticalExaggeration_; }
  ViewCamera::Mode mode() const { return camera_.mode(); }
  /// Frames the whole terrain.
  void resetView();

  /// The cell (i, j) under a widget pixel: exact in the map view, from the depth buffer in the
  /// tilted view. False outside the terrain.
  bool cellAt(QPoint pixel, int& i, int& j);
  /// Map view: the widget pixel at the centre of cell (i, j).
  QPointF pixelOfCell(int i, int j) const;
  /// World coordinates (the grid's georeference) of a model point, and back.
  QPointF worldOf(QPointF model) const;
  QPointF modelOf(QPointF world) const;
  /// Map view: the widget pixel showing a world point.
  QPointF pixelOfWorld(QPointF world) const { return camera_.mapPixel(modelOf(world), width(), height()); }
  /// What is being drawn on the map (release area, profile, point). While a tool is active, left
  /// clicks in the map view add its vertices instead of panning (Shift+drag still pans).
  MapSketch& sketch() { return *sketch_; }
  /// The chosen interop path (valid once the widget has been shown).
  const InteropChoice* interopChoice() const;
  ClGlInterop* interop() { return interop_.get(); }
  long long framesDrawn() const { return frames_; }

 signals:
  /// The mouse is over cell (i, j) (inside false: over no cell).
  void hovered(int i, int j, bool inside);
  /// The interop path was chosen (sentence for the log: "interop: <path> (<reason>)").
  void interopChosen(const QString& report);
  /// The interop path was chosen: true when device data reach OpenGL by sharing, so snapshots
  /// should keep their device copies.
  void sharedPathChosen(bool shared);

 protected:
  void initializeGL() override;
  void resizeGL(int w, int h) override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void leaveEvent(QEvent* e) override;
  void mouseDoubleClickEvent(QMouseEvent* e) override;
  void keyPressEvent(QKeyEvent* e) override;

 private:
  QOpenGLFunctions_3_3_Core& gl() { return *this; }
  void chooseInterop();
  void uploadPending();
  QVector3D worldOrigin() const;
  float exaggeration() const;

  ViewCamera camera_;
  std::unique_ptr<TerrainRenderer> terrain_;
  std::unique_ptr<ParticleRenderer> particles_;
  std::unique_ptr<ClGlInterop> interop_;
  bool glReady_ = false;
  // Data waiting for the next paint.
  Grid grid_;
  std::vector<float> elevation_;
  bool terrainDirty_ = false, layerDirty_ = false, particlesDirty_ = false, rampDirty_ = true;
  std::shared_ptr<const sim::ViewSnapshot> snapshot_;
  QString layer_, layerRamp_ = "water", particleRamp_ = "heat";
  LayerStyle layerStyle_;
  ParticleStyle particleStyle_;
  const compute::DeviceInfo* device_ = nullptr;
  cl_context clContext_ = nullptr;
  cl_command_queue clQueue_ = nullptr;
  QString contextNote_;
  compute::GlShareHandles offered_;  // what initializeGL offered the engine for GL-shared contexts
  QPoint lastMouse_;
  long long frames_ = 0;
  MapSketch* sketch_;
  double verticalExaggeration_ = 1;
};

}  // namespace talus::gui
