#include "view/ViewCamera.hpp"

#include <algorithm>
#include <cmath>

namespace talus::gui {

void ViewCamera::fit(double width, double height, int w, int h) {
  w = std::max(w, 1);
  h = std::max(h, 1);
  centre_ = {0, 0};
  metresPerPixel_ = 1.05 * std::max(width / w, height / h);
  if (!(metresPerPixel_ > 0)) metresPerPixel_ = 1;
  sceneSize_ = std::max(width, height);
  target_ = {0, 0, 0};
  distance_ = 2.0 * sceneSize_;
}

QMatrix4x4 ViewCamera::matrix(int w, int h) const {
  w = std::max(w, 1);
  h = std::max(h, 1);
  QMatrix4x4 m;
  if (mode_ == Mode::Map) {
    const double hw = 0.5 * w * metresPerPixel_, hh = 0.5 * h * metresPerPixel_;
    m.ortho(float(centre_.x() - hw), float(centre_.x() + hw), float(centre_.y() - hh), float(centre_.y() + hh), -1e6f,
            1e6f);
    return m;
  }
  const double az = azimuthDeg_ * M_PI / 180, el = elevationDeg_ * M_PI / 180;
  const QVector3D dir(float(std::sin(az) * std::cos(el)), float(-std::cos(az) * std::cos(el)), float(std::sin(el)));
  m.perspective(40.0f, float(w) / float(h), float(distance_ * 0.01), float(distance_ + 4 * sceneSize_));
  m.lookAt(target_ + dir * float(distance_), target_, QVector3D(0, 0, 1));
  return m;
}

QPointF ViewCamera::mapPoint(QPointF pixel, int w, int h) const {
  return {centre_.x() + (pixel.x() - 0.5 * w) * metresPerPixel_, centre_.y() - (pixel.y() - 0.5 * h) * metresPerPixel_};
}

QPointF ViewCamera::mapPixel(QPointF point, int w, int h) const {
  return {0.5 * w + (point.x() - centre_.x()) / metresPerPixel_, 0.5 * h - (point.y() - centre_.y()) / metresPerPixel_};
}

void ViewCamera::pan(double dx, double dy, int, int h) {
  if (mode_ == Mode::Map) {
    centre_ -= QPointF(dx * metresPerPixel_, -dy * metresPerPixel_);
    return;
  }
  // Move the target in the ground plane, scaled so the terrain follows the cursor roughly.
  const double az = azimuthDeg_ * M_PI / 180;
  const double s = distance_ / std::max(h, 1);
  const QVector3D right(float(std::cos(az)), float(std::sin(az)), 0), forward(float(-std::sin(az)), float(std::cos(az)), 0);
  target_ -= right * float(dx * s) - forward * float(dy * s);
}

void ViewCamera::zoom(double factor, QPointF pixel, int w, int h) {
  if (mode_ == Mode::Map) {
    const QPointF before = mapPoint(pixel, w, h);
    metresPerPixel_ /= factor;
    centre_ += before - mapPoint(pixel, w, h);
    return;
  }
  distance_ = std::clamp(distance_ / factor, 0.02 * sceneSize_, 20 * sceneSize_);
}

void ViewCamera::orbit(double dx, double dy) {
  azimuthDeg_ = std::fmod(azimuthDeg_ - 0.3 * dx, 360.0);
  elevationDeg_ = std::clamp(elevationDeg_ + 0.3 * dy, 5.0, 89.0);
}

}  // namespace talus::gui
