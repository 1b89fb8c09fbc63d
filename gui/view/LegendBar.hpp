// A colour-ramp legend: the ramp as a horizontal bar with its range and unit.
#pragma once
#include <QString>
#include <QWidget>

namespace talus::gui {

class LegendBar : public QWidget {
  Q_OBJECT

 public:
  explicit LegendBar(QWidget* parent = nullptr);
  /// Shows `ramp` from min to max, labelled "title [unit]".
  void setLegend(const QString& title, const QString& unit, const QString& ramp, double min, double max);
  QSize sizeHint() const override { return {220, 48}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  QString title_, unit_, ramp_ = "water";
  double min_ = 0, max_ = 1;
};

}  // namespace talus::gui
