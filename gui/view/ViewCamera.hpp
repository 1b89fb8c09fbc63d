// The viewer's camera over model coordinates (x east, y north, z up, metres from the grid centre):
// a top-down map view (orthographic, pan and zoom) or a tilted 3D view (perspective orbit).
#pragma once
#include <QMatrix4x4>
#include <QPointF>
#include <QVector3D>

namespace talus::gui {

class ViewCamera {
 public:
  enum class Mode { Map, Tilted };

  Mode mode() const { return mode_; }
  void setMode(Mode m) { mode_ = m; }
  /// Frames a scene of width x height metres in a viewport of w x h pixels.
  void fit(double width, double height, int w, int h);
  /// The model-view-projection matrix for a viewport of w x h pixels.
  QMatrix4x4 matrix(int w, int h) const;
  /// Map view: the model point (x, y) under the pixel.
  QPointF mapPoint(QPointF pixel, int w, int h) const;
  /// Map view: the pixel showing the model point (x, y).
  QPointF mapPixel(QPointF point, int w, int h) const;

  /// Moves the view by a drag of (dx, dy) pixels.
  void pan(double dx, double dy, int w, int h);
  /// Zooms by `factor` (> 1: closer) keeping the point under `pixel` fixed (map view).
  void zoom(double factor, QPointF pixel, int w, int h);
  /// Tilted view: turns by a drag of (dx, dy) pixels.
  void orbit(double dx, double dy);

 private:
  Mode mode_ = Mode::Map;
  // Map view: centre [m] and scale [m per pixel].
  QPointF centre_{0, 0};
  double metresPerPixel_ = 1;
  // Tilted view: orbit around target_.
  QVector3D target_{0, 0, 0};
  double distance_ = 1000, azimuthDeg_ = 20, elevationDeg_ = 50, sceneSize_ = 1000;
};

}  // namespace talus::gui
