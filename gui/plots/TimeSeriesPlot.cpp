#include "plots/TimeSeriesPlot.hpp"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

namespace talus::gui {

namespace {
constexpr std::size_t kMaxPoints = 4000;  ///< beyond this a series keeps every second point
}

TimeSeriesPlot::TimeSeriesPlot(const QString& title, const QString& unit, QWidget* parent)
    : QWidget(parent), title_(title), unit_(unit) {
  setMinimumSize(200, 120);
}

int TimeSeriesPlot::addSeries(const QString& name, const QColor& color) {
  series_.push_back({name, color, {}});
  return static_cast<int>(series_.size()) - 1;
}

void TimeSeriesPlot::append(int series, double t, double value) {
  if (!std::isfinite(t) || !std::isfinite(value)) return;
  auto& pts = series_[static_cast<std::size_t>(series)].points;
  if (!pts.empty() && t < pts.back().x()) pts.clear();  // time went back: a new run
  pts.emplace_back(t, value);
  if (pts.size() > kMaxPoints) {
    std::vector<QPointF> thinned;
    for (std::size_t k = 0; k < pts.size(); k += 2) thinned.push_back(pts[k]);
    if (thinned.back() != pts.back()) thinned.push_back(pts.back());
    pts.swap(thinned);
  }
  update();
}

void TimeSeriesPlot::clear() {
  for (auto& s : series_) s.points.clear();
  update();
}

void TimeSeriesPlot::setTitle(const QString& title, const QString& unit) {
  title_ = title;
  unit_ = unit;
  update();
}

void TimeSeriesPlot::setXUnit(const QString& unit) {
  xUnit_ = unit;
  update();
}

void TimeSeriesPlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), palette().color(QPalette::Base));
  const QFontMetrics fm = p.fontMetrics();
  const int left = fm.horizontalAdvance("-0.000e+00") + 8, top = fm.height() + 6, bottom = fm.height() + 8, right = 10;
  const QRectF area(left, top, width() - left - right, height() - top - bottom);
  p.setPen(palette().color(QPalette::Text));
  p.drawText(QRect(left, 2, width() - left, fm.height()), Qt::AlignLeft, title_ + " [" + unit_ + "]");
  double t0 = HUGE_VAL, t1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (const auto& s : series_)
    for (const QPointF& q : s.points) {
      t0 = std::min(t0, q.x());
      t1 = std::max(t1, q.x());
      y0 = std::min(y0, q.y());
      y1 = std::max(y1, q.y());
    }
  p.drawRect(area);
  if (!(t0 <= t1)) return;
  if (y0 > 0 && y0 < 0.5 * y1) y0 = 0;  // show amounts from zero unless they vary little
  if (t1 <= t0) t1 = t0 + 1;
  // A nearly constant series (a conserved volume) is drawn flat, not as magnified rounding noise.
  const double minSpan = std::max(1e-4 * std::max(std::fabs(y0), std::fabs(y1)), 1e-12);
  if (y1 - y0 < minSpan) {
    const double mid = 0.5 * (y0 + y1);
    y0 = mid - minSpan;
    y1 = mid + minSpan;
  }
  auto map = [&](const QPointF& q) {
    return QPointF(area.left() + (q.x() - t0) / (t1 - t0) * area.width(),
                   area.bottom() - (q.y() - y0) / (y1 - y0) * area.height());
  };
  p.drawText(QRectF(0, area.top() - fm.height() / 2.0, left - 4, fm.height()), Qt::AlignRight, QString::number(y1, 'g', 4));
  p.drawText(QRectF(0, area.bottom() - fm.height() / 2.0, left - 4, fm.height()), Qt::AlignRight, QString::number(y0, 'g', 4));
  p.drawText(QRectF(area.left(), area.bottom() + 2, area.width(), fm.height()), Qt::AlignLeft, QString::number(t0, 'g', 4) + " " + xUnit_);
  p.drawText(QRectF(area.left(), area.bottom() + 2, area.width(), fm.height()), Qt::AlignRight, QString::number(t1, 'g', 4) + " " + xUnit_);
  int legendX = int(area.right()) - 4;
  for (auto it = series_.rbegin(); it != series_.rend(); ++it) {
    if (it->points.empty()) continue;
    QPainterPath path(map(it->points.front()));
    for (const QPointF& q : it->points) path.lineTo(map(q));
    p.setPen(QPen(it->color, 1.5));
    p.drawPath(path);
    const int w = fm.horizontalAdvance(it->name);
    legendX -= w;
    p.drawText(legendX, top + fm.ascent() + 2, it->name);
    legendX -= 10;
  }
}

}  // namespace talus::gui
