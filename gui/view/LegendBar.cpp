#include "view/LegendBar.hpp"

#include <QLinearGradient>
#include <QPainter>

#include "render/ColorRamp.hpp"

namespace talus::gui {

LegendBar::LegendBar(QWidget* parent) : QWidget(parent) { setMinimumHeight(48); }

void LegendBar::setLegend(const QString& title, const QString& unit, const QString& ramp, double min, double max) {
  title_ = title;
  unit_ = unit;
  ramp_ = ramp;
  min_ = min;
  max_ = max;
  update();
}

void LegendBar::paintEvent(QPaintEvent*) {
  QPainter p(this);
  const ColorRamp ramp = ColorRamp::byName(ramp_);
  const QFontMetrics fm = p.fontMetrics();
  const int textH = fm.height();
  const QRect bar(4, textH + 4, width() - 8, std::max(8, height() - 2 * textH - 10));
  QLinearGradient g(bar.topLeft(), bar.topRight());
  for (int k = 0; k <= 16; ++k) g.setColorAt(k / 16.0, ramp.at(k / 16.0));
  p.fillRect(bar, g);
  p.setPen(palette().color(QPalette::WindowText));
  p.drawRect(bar.adjusted(0, 0, -1, -1));
  const QString unit = unit_.isEmpty() || unit_ == "-" ? QString() : " " + unit_;
  p.drawText(QRect(4, 0, width() - 8, textH + 2), Qt::AlignLeft, title_ + (unit.isEmpty() ? "" : " [" + unit_ + "]"));
  const QRect labels(4, bar.bottom() + 2, width() - 8, textH + 2);
  p.drawText(labels, Qt::AlignLeft, QString::number(min_, 'g', 4) + unit);
  p.drawText(labels, Qt::AlignRight, QString::number(max_, 'g', 4) + unit);
}

}  // namespace talus::gui
