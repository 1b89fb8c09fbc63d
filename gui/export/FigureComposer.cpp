#include "export/FigureComposer.hpp"

#include <QPainter>
#include <QPainterPath>
#include <cmath>

#include "render/ColorRamp.hpp"

namespace talus::gui {

namespace {
constexpr int kLeft = 90, kTop = 40, kRight = 190, kBottom = 50;

/// A round step (1, 2 or 5 times a power of ten) near `approx`.
double niceStep(double approx) {
  const double p = std::pow(10.0, std::floor(std::log10(approx)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= approx) return m * p;
  return 10 * p;
}

void drawTicks(QPainter& p, const FigureLayout& l, const FigureContent& c) {
  const QRect v = l.view;
  const double w = v.width() * c.metresPerPixel, h = v.height() * c.metresPerPixel;
  p.setPen(Qt::black);
  p.drawRect(v.adjusted(0, 0, -1, -1));
  const double sx = niceStep(w / 5), sy = niceStep(h / 5);
  for (double x = std::ceil(c.x0 / sx) * sx; x <= c.x0 + w; x += sx) {
    const int px = v.left() + int(std::lround((x - c.x0) / c.metresPerPixel));
    p.drawLine(px, v.bottom(), px, v.bottom() + 6);
    p.drawText(QRect(px - 60, v.bottom() + 8, 120, 16), Qt::AlignHCenter, QString::number(x, 'f', 0));
  }
  for (double y = std::ceil((c.y0 - h) / sy) * sy; y <= c.y0; y += sy) {
    const int py = v.top() + int(std::lround((c.y0 - y) / c.metresPerPixel));
    p.drawLine(v.left() - 6, py, v.left(), py);
    p.drawText(QRect(0, py - 8, v.left() - 8, 16), Qt::AlignRight | Qt::AlignVCenter, QString::number(y, 'f', 0));
  }
}

void drawScaleBar(QPainter& p, const FigureLayout& l, const FigureContent& c) {
  const QRect r = l.scaleBar;
  p.fillRect(r, QColor(255, 255, 255, 220));
  const double metres = niceStep(0.8 * (r.width() - 20) * c.metresPerPixel / 2);
  const int px = int(std::lround(metres / c.metresPerPixel));
  const QRect bar(r.left() + 10, r.bottom() - 14, px, 6);
  p.fillRect(bar, Qt::black);
  p.setPen(Qt::black);
  p.drawText(QRect(r.left() + 10, r.top() + 2, r.width() - 20, 16), Qt::AlignLeft,
             metres >= 1000 ? QString("%1 km").arg(metres / 1000) : QString("%1 m").arg(metres));
}

void drawNorthArrow(QPainter& p, const FigureLayout& l) {
  const QRect r = l.northArrow;
  p.fillRect(r, QColor(255, 255, 255, 220));
  QPainterPath arrow;
  const double cx = r.center().x();
  arrow.moveTo(cx, r.top() + 18);
  arrow.lineTo(cx + 10, r.bottom() - 6);
  arrow.lineTo(cx, r.bottom() - 14);
  arrow.lineTo(cx - 10, r.bottom() - 6);
  arrow.closeSubpath();
  p.fillPath(arrow, Qt::black);
  p.setPen(Qt::black);
  p.drawText(QRect(r.left(), r.top() + 2, r.width(), 16), Qt::AlignHCenter, "N");
}

void drawLegend(QPainter& p, const FigureLayout& l, const FigureContent& c) {
  const QRect bar = l.colourBar;
  const ColorRamp ramp = ColorRamp::byName(c.ramp);
  for (int y = bar.top(); y <= bar.bottom(); ++y)
    p.fillRect(QRect(bar.left(), y, bar.width(), 1), ramp.at(double(bar.bottom() - y) / std::max(1, bar.height() - 1)));
  p.setPen(Qt::black);
  p.drawRect(bar.adjusted(-1, -1, 0, 0));
  p.drawText(QRect(bar.left() - 10, bar.top() - 36, kRight - 10, 32), Qt::AlignLeft | Qt::AlignBottom | Qt::TextWordWrap,
             c.layer + (c.unit.isEmpty() ? QString() : " [" + c.unit + "]"));
  for (int k = 0; k <= 4; ++k) {
    const int y = bar.bottom() - k * (bar.height() - 1) / 4;
    p.drawLine(bar.right() + 1, y, bar.right() + 5, y);
    p.drawText(QRect(bar.right() + 8, y - 8, 100, 16), Qt::AlignLeft | Qt::AlignVCenter,
               QString::number(c.min + k * (c.max - c.min) / 4, 'g', 4));
  }
}
}  // namespace

FigureLayout FigureLayout::of(QSize viewSize) {
  FigureLayout l;
  l.size = QSize(kLeft + viewSize.width() + kRight, kTop + viewSize.height() + kBottom);
  l.view = QRect(QPoint(kLeft, kTop), viewSize);
  const int barHeight = std::max(60, viewSize.height() / 2);
  l.colourBar = QRect(l.view.right() + 30, l.view.top() + 50, 24, barHeight);
  l.scaleBar = QRect(l.view.left() + 10, l.view.bottom() - 50, std::min(220, viewSize.width() / 2), 40);
  l.northArrow = QRect(l.view.right() - 50, l.view.top() + 10, 40, 56);
  return l;
}

QImage composeFigure(const FigureContent& c) {
  const FigureLayout l = FigureLayout::of(c.view.size());
  QImage figure(l.size, QImage::Format_RGB32);
  figure.fill(Qt::white);
  QPainter p(&figure);
  p.setRenderHint(QPainter::Antialiasing, false);
  p.drawImage(l.view.topLeft(), c.view);
  drawTicks(p, l, c);
  drawScaleBar(p, l, c);
  drawNorthArrow(p, l);
  if (!c.layer.isEmpty()) drawLegend(p, l, c);
  p.setPen(Qt::black);
  p.drawText(QRect(l.view.left(), 8, l.view.width(), 24), Qt::AlignLeft | Qt::AlignVCenter,
             QString("t = %1 s").arg(c.time, 0, 'f', 2));
  p.end();
  return figure;
}

}  // namespace talus::gui
