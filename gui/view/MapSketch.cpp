#include "view/MapSketch.hpp"

#include <QPainter>
#include <QPainterPath>

namespace talus::gui {

MapSketch::MapSketch(std::function<QPointF(QPointF)> toPixel, QWidget* parent)
    : QWidget(parent), toPixel_(std::move(toPixel)) {
  setAttribute(Qt::WA_TransparentForMouseEvents);
  setAttribute(Qt::WA_NoSystemBackground);
  hide();
}

int MapSketch::verticesNeeded() const {
  switch (tool_) {
    case Tool::Polygon: return 3;
    case Tool::Profile: return 2;
    case Tool::Point: return 1;
    case Tool::None: break;
  }
  return 0;
}

void MapSketch::start(Tool tool) {
  tool_ = tool;
  vertices_.clear();
  hasCursor_ = false;
  setVisible(active());
  update();
  switch (tool) {
    case Tool::Polygon:
      emit hint("release area: click the corners on the map; double-click or Enter closes it, Backspace removes "
                "the last corner, Esc cancels");
      break;
    case Tool::Profile:
      emit hint("profile: click the line's points on the map; double-click or Enter ends it, Esc cancels");
      break;
    case Tool::Point: emit hint("time series: click a cell on the map, Esc cancels"); break;
    case Tool::None: break;
  }
}

void MapSketch::addVertex(QPointF model) {
  if (!active()) return;
  vertices_.push_back(model);
  update();
  if (tool_ == Tool::Point) finish();
}

void MapSketch::moveCursor(QPointF model) {
  cursor_ = model;
  hasCursor_ = true;
  if (active()) update();
}

void MapSketch::removeLastVertex() {
  if (!vertices_.empty()) vertices_.pop_back();
  update();
}

bool MapSketch::finish() {
  if (!active()) return false;
  if (int(vertices_.size()) < verticesNeeded()) {
    emit hint(QString("needs at least %1 points on the map (has %2)").arg(verticesNeeded()).arg(vertices_.size()));
    return false;
  }
  const Tool tool = tool_;
  const std::vector<QPointF> done = vertices_;
  start(Tool::None);
  emit finished(tool, done);
  return true;
}

void MapSketch::cancel() {
  if (!active()) return;
  start(Tool::None);
  emit cancelled();
}

void MapSketch::paintEvent(QPaintEvent*) {
  if (!active() || vertices_.empty()) return;
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  QPainterPath path(toPixel_(vertices_.front()));
  for (std::size_t k = 1; k < vertices_.size(); ++k) path.lineTo(toPixel_(vertices_[k]));
  if (hasCursor_) path.lineTo(toPixel_(cursor_));
  if (tool_ == Tool::Polygon && vertices_.size() + (hasCursor_ ? 1 : 0) >= 3) {
    path.closeSubpath();
    p.fillPath(path, QColor(255, 200, 40, 70));
  }
  // A dark casing under a bright line: visible over any hillshade and colour ramp.
  p.setPen(QPen(QColor(0, 0, 0, 200), 4));
  p.drawPath(path);
  p.setPen(QPen(QColor(255, 210, 60), 2));
  p.drawPath(path);
  p.setBrush(QColor(255, 210, 60));
  p.setPen(QPen(Qt::black, 1));
  for (const QPointF& v : vertices_) p.drawEllipse(toPixel_(v), 3.5, 3.5);
}

}  // namespace talus::gui
