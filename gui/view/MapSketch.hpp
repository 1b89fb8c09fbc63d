// What the user draws on the map view, and how it is drawn over it: a polygon (a release area), a
// polyline (a profile) or a point (a time series), in model coordinates (metres from the grid's
// centre, y north, as ViewCamera). A transparent child of the viewer: the viewer feeds it clicks
// and keys while a tool is active, and it paints the vertices, the edges and the rubber band to the
// cursor.
#pragma once
#include <QPointF>
#include <QWidget>
#include <functional>
#include <vector>

namespace talus::gui {

class MapSketch : public QWidget {
  Q_OBJECT

 public:
  enum class Tool { None, Polygon, Profile, Point };

  /// `toPixel` maps a model point to the viewer's pixel (the current camera).
  MapSketch(std::function<QPointF(QPointF)> toPixel, QWidget* parent);

  /// Starts drawing with `tool` (None: stops); forgets an unfinished sketch.
  void start(Tool tool);
  Tool tool() const { return tool_; }
  bool active() const { return tool_ != Tool::None; }
  const std::vector<QPointF>& vertices() const { return vertices_; }
  /// Fewest vertices the tool needs to finish (polygon 3, profile 2, point 1).
  int verticesNeeded() const;

  /// A click at a model point: a new vertex (a point tool finishes at once).
  void addVertex(QPointF model);
  /// The cursor moved to a model point (the rubber band follows it).
  void moveCursor(QPointF model);
  void removeLastVertex();
  /// Finishes when there are enough vertices (emits finished and stops); false otherwise.
  bool finish();
  /// Abandons the sketch (emits cancelled).
  void cancel();

 signals:
  /// A finished sketch: its tool and vertices (model coordinates).
  void finished(talus::gui::MapSketch::Tool tool, const std::vector<QPointF>& vertices);
  void cancelled();
  /// Something to tell the user (how to go on, why it cannot finish yet).
  void hint(const QString& text);

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  std::function<QPointF(QPointF)> toPixel_;
  Tool tool_ = Tool::None;
  std::vector<QPointF> vertices_;
  QPointF cursor_;
  bool hasCursor_ = false;
};

}  // namespace talus::gui
