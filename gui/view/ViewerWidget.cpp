#include "view/ViewerWidget.hpp"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include "render/ParticleRenderer.hpp"

namespace talus::gui {

ViewerWidget::ViewerWidget(QWidget* parent) : QOpenGLWidget(parent) {
  setMouseTracking(true);
  setMinimumSize(320, 240);
  setFocusPolicy(Qt::StrongFocus);  // Enter, Backspace and Esc for the sketch tools
  sketch_ = new MapSketch([this](QPointF model) { return camera_.mapPixel(model, width(), height()); }, this);
}

ViewerWidget::~ViewerWidget() {
  // GL objects are released with the context current.
  makeCurrent();
  particles_.reset();
  terrain_.reset();
  interop_.reset();
  doneCurrent();
  // Contexts made from now on must not name the GL context about to go away.
  const compute::GlShareHandles now = compute::glShareForNewContexts();
  if (offered_.valid() && now.glContext == offered_.glContext && now.display == offered_.display)
    compute::setGlShareForNewContexts({});
}

void ViewerWidget::setTerrain(const Grid& grid, std::vector<float> elevation) {
  // The same terrain again (the scene re-read after an edit, such as a drawn release area) keeps
  // the view the user chose; another one (or one after clearScene) is framed whole.
  const bool same = grid_.nx > 0 && sameGrid(grid_, grid);
  grid_ = grid;
  elevation_ = std::move(elevation);
  snapshot_.reset();
  terrainDirty_ = true;
  if (same) update();
  else resetView();
}

void ViewerWidget::clearScene() {
  grid_ = Grid{};
  elevation_.clear();
  snapshot_.reset();
  terrainDirty_ = true;
  // The interop chosen for the old run stays until the next run's setDataSource chooses again;
  // without a snapshot nothing reaches it meanwhile.
  device_ = nullptr;
  clContext_ = nullptr;
  clQueue_ = nullptr;
  update();
}

void ViewerWidget::setDataSource(const compute::DeviceInfo* device, cl_context context, cl_command_queue queue,
                                 const QString& contextNote) {
  device_ = device;
  clContext_ = context;
  clQueue_ = queue;
  contextNote_ = contextNote;
  if (glReady_) {
    makeCurrent();
    chooseInterop();
    doneCurrent();
  }
}

void ViewerWidget::setSnapshot(std::shared_ptr<const sim::ViewSnapshot> snapshot) {
  snapshot_ = std::move(snapshot);
  layerDirty_ = particlesDirty_ = true;
  update();
}

void ViewerWidget::setLayer(const QString& name, const LayerStyle& style) {
  if (name != layer_) layerDirty_ = true;
  layer_ = name;
  layerStyle_ = style;
  layerStyle_.visible = style.visible && !name.isEmpty();
  update();
}

void ViewerWidget::setLayerRamp(const QString& ramp) {
  layerRamp_ = ramp;
  rampDirty_ = true;
  update();
}

void ViewerWidget::setParticleStyle(const ParticleStyle& style) {
  if (style.attribute != particleStyle_.attribute) particlesDirty_ = true;
  particleStyle_ = style;
  update();
}

void ViewerWidget::setParticleRamp(const QString& ramp) {
  particleRamp_ = ramp;
  rampDirty_ = true;
  update();
}

void ViewerWidget::setMode(ViewCamera::Mode mode) {
  camera_.setMode(mode);
  update();
}

void ViewerWidget::resetView() {
  camera_.fit(grid_.nx * grid_.dx, grid_.ny * grid_.dx, width(), height());
  update();
}

const InteropChoice* ViewerWidget::interopChoice() const { return interop_ ? &interop_->choice() : nullptr; }

void ViewerWidget::initializeGL() {
  initializeOpenGLFunctions();
  terrain_ = std::make_unique<TerrainRenderer>(gl());
  particles_ = std::make_unique<ParticleRenderer>(gl());
  glReady_ = true;
  // Offer this GL context to the OpenCL contexts runs create from now on (compute::Context::create):
  // a device with cl_khr_gl_sharing then shares buffers with it. Runs started before the viewer
  // was first shown get no sharing (their log says so).
  offered_ = glShareHandlesOfCurrentContext();
  if (offered_.valid()) compute::setGlShareForNewContexts(offered_);
  chooseInterop();
}

void ViewerWidget::chooseInterop() {
  interop_ = std::make_unique<ClGlInterop>(gl(), chooseInteropPath(device_, clContext_, clQueue_, contextNote_));
  if (device_) {
    emit interopChosen(interopLogLine(interop_->choice()));
    emit sharedPathChosen(interop_->choice().path == InteropPath::Shared);
  }
}

void ViewerWidget::resizeGL(int w, int h) {
  sketch_->setGeometry(0, 0, width(), height());
  if (frames_ == 0) camera_.fit(grid_.nx * grid_.dx, grid_.ny * grid_.dx, w, h);
}

QVector3D ViewerWidget::worldOrigin() const {
  const QPointF centre = worldOf(QPointF(0, 0));
  return QVector3D(float(centre.x()), float(centre.y()), terrain_ ? terrain_->elevationMid() : 0.0f);
}

float ViewerWidget::exaggeration() const {
  return camera_.mode() == ViewCamera::Mode::Tilted ? float(verticalExaggeration_) : 0.0f;
}

void ViewerWidget::setVerticalExaggeration(double factor) {
  verticalExaggeration_ = std::clamp(factor, 0.1, 50.0);
  update();
}

void ViewerWidget::uploadPending() {
  if (terrainDirty_ && grid_.nx == 0) {
    terrain_->clear();
    terrainDirty_ = false;
  }
  if (terrainDirty_) {
    terrain_->setTerrain(grid_, elevation_);
    terrainDirty_ = false;
    layerDirty_ = true;
  }
  if (rampDirty_) {
    terrain_->setRamp(ColorRamp::byName(layerRamp_));
    particles_->setRamp(ColorRamp::byName(particleRamp_));
    rampDirty_ = false;
  }
  if (layerDirty_ && snapshot_ && terrain_->hasTerrain()) {
    // On the shared path the snapshot's device copy (if it has one) goes device to device.
    const std::string name = layer_.toStdString();
    if (const std::vector<float>* v = snapshot_->layer(name))
      terrain_->setLayer(*v, *interop_, interop_->choice().path == InteropPath::Shared ? snapshot_->deviceLayer(name) : nullptr);
    layerDirty_ = false;
  }
  if (particlesDirty_ && snapshot_) {
    const std::string name = particleStyle_.attribute.isEmpty() && !snapshot_->particleAttributeNames.empty()
                                 ? snapshot_->particleAttributeNames.front()
                                 : particleStyle_.attribute.toStdString();
    const std::vector<float>* values = snapshot_->particleAttribute(name);
    particles_->setParticles(snapshot_->particlePositions, values ? *values : std::vector<float>{}, *interop_);
    particlesDirty_ = false;
  }
}

void ViewerWidget::paintGL() {
  uploadPending();
  glClearColor(0.16f, 0.17f, 0.19f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const bool tilted = camera_.mode() == ViewCamera::Mode::Tilted;
  if (tilted) glEnable(GL_DEPTH_TEST);
  else glDisable(GL_DEPTH_TEST);
  const QMatrix4x4 mvp = camera_.matrix(width(), height());
  terrain_->draw(mvp, exaggeration(), layerStyle_);
  if (particleStyle_.visible && snapshot_ && snapshot_->particleCount > 0) {
    // In the map view (no depth test) particles are drawn over the terrain; tilted, hills hide them.
    particles_->draw(mvp, worldOrigin(), exaggeration(), particleStyle_.pointSize, particleStyle_.min,
                     particleStyle_.max);
  }
  ++frames_;
  if (sketch_->active()) sketch_->update();  // the camera may have moved under it
}

bool ViewerWidget::cellAt(QPoint pixel, int& i, int& j) {
  if (grid_.nx == 0) return false;
  QPointF model;
  if (camera_.mode() == ViewCamera::Mode::Map) {
    model = camera_.mapPoint(pixel, width(), height());
  } else {
    // Unproject the depth under the cursor.
    makeCurrent();
    const double ratio = devicePixelRatioF();
    const int px = int(pixel.x() * ratio), py = int((height() - 1 - pixel.y()) * ratio);
    float depth = 1.0f;
    glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
    glReadPixels(px, py, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
    doneCurrent();
    if (depth >= 1.0f) return false;
    const QVector4D ndc(2.0f * pixel.x() / width() - 1.0f, 1.0f - 2.0f * pixel.y() / height(), 2.0f * depth - 1.0f, 1);
    const QVector4D p = camera_.matrix(width(), height()).inverted() * ndc;
    model = QPointF(p.x() / p.w(), p.y() / p.w());
  }
  i = int(std::floor(model.x() / grid_.dx + grid_.nx / 2.0));
  j = int(std::floor(grid_.ny / 2.0 - model.y() / grid_.dx));
  return i >= 0 && j >= 0 && i < grid_.nx && j < grid_.ny;
}

QPointF ViewerWidget::pixelOfCell(int i, int j) const {
  const QPointF model((i + 0.5 - grid_.nx / 2.0) * grid_.dx, (grid_.ny / 2.0 - j - 0.5) * grid_.dx);
  return camera_.mapPixel(model, width(), height());
}

QPointF ViewerWidget::worldOf(QPointF model) const {
  // The model origin is the grid's centre (in double: the sketch needs the georeference in full).
  const auto& gt = grid_.geoTransform;
  return {gt[0] + gt[1] * grid_.nx / 2.0 + model.x(), gt[3] + gt[5] * grid_.ny / 2.0 + model.y()};
}

QPointF ViewerWidget::modelOf(QPointF world) const { return world - worldOf(QPointF(0, 0)); }

void ViewerWidget::mousePressEvent(QMouseEvent* e) {
  lastMouse_ = e->pos();
  const bool sketching = sketch_->active() && camera_.mode() == ViewCamera::Mode::Map && grid_.nx > 0;
  if (sketching && e->button() == Qt::LeftButton && !(e->modifiers() & Qt::ShiftModifier))
    sketch_->addVertex(camera_.mapPoint(e->pos(), width(), height()));
}

void ViewerWidget::mouseDoubleClickEvent(QMouseEvent* e) {
  // The double click's first press added the last vertex.
  if (sketch_->active() && e->button() == Qt::LeftButton) sketch_->finish();
}

void ViewerWidget::keyPressEvent(QKeyEvent* e) {
  if (!sketch_->active()) {
    QOpenGLWidget::keyPressEvent(e);
    return;
  }
  switch (e->key()) {
    case Qt::Key_Return:
    case Qt::Key_Enter: sketch_->finish(); break;
    case Qt::Key_Escape: sketch_->cancel(); break;
    case Qt::Key_Backspace: sketch_->removeLastVertex(); break;
    default: QOpenGLWidget::keyPressEvent(e);
  }
}

void ViewerWidget::mouseMoveEvent(QMouseEvent* e) {
  const QPoint d = e->pos() - lastMouse_;
  lastMouse_ = e->pos();
  const bool sketching = sketch_->active() && camera_.mode() == ViewCamera::Mode::Map;
  if (sketching) sketch_->moveCursor(camera_.mapPoint(e->pos(), width(), height()));
  const bool panning = (e->buttons() & Qt::LeftButton && camera_.mode() == ViewCamera::Mode::Map && !sketching) ||
                       e->buttons() & Qt::MiddleButton || e->buttons() & Qt::RightButton ||
                       (e->buttons() & Qt::LeftButton && e->modifiers() & Qt::ShiftModifier);
  if (panning) {
    camera_.pan(d.x(), d.y(), width(), height());
    update();
  } else if (e->buttons() & Qt::LeftButton) {
    camera_.orbit(d.x(), d.y());
    update();
  }
  int i = 0, j = 0;
  const bool inside = cellAt(e->pos(), i, j);
  emit hovered(i, j, inside);
}

void ViewerWidget::wheelEvent(QWheelEvent* e) {
  const double factor = std::pow(1.0015, e->angleDelta().y());
  camera_.zoom(factor, e->position(), width(), height());
  update();
}

void ViewerWidget::leaveEvent(QEvent*) { emit hovered(0, 0, false); }

}  // namespace talus::gui
