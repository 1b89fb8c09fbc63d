// A small live line plot of one or more time series against simulated time, with axes, a unit and
// a legend, painted with QPainter. Long series are thinned to keep drawing cheap.
#pragma once
#include <QColor>
#include <QPointF>
#include <QString>
#include <QWidget>
#include <vector>

namespace talus::gui {

class TimeSeriesPlot : public QWidget {
  Q_OBJECT

 public:
  TimeSeriesPlot(const QString& title, const QString& unit, QWidget* parent = nullptr);
  /// Adds a series; returns its index for append().
  int addSeries(const QString& name, const QColor& color);
  /// Appends a point (t [s], value) to a series.
  void append(int series, double t, double value);
  void clear();
  /// Replaces the title and the value unit (the legend's series stay).
  void setTitle(const QString& title, const QString& unit);
  /// The unit of the horizontal axis ("s" unless set: a profile plots against distance in "m").
  void setXUnit(const QString& unit);
  /// The points of a series (x, value).
  const std::vector<QPointF>& points(int series) const { return series_[static_cast<std::size_t>(series)].points; }
  /// Number of points held by a series.
  std::size_t size(int series) const { return series_[static_cast<std::size_t>(series)].points.size(); }
  /// The last point of a series (t, value); (0, 0) while it has none.
  QPointF last(int series) const {
    const auto& p = series_[static_cast<std::size_t>(series)].points;
    return p.empty() ? QPointF() : p.back();
  }
  QSize sizeHint() const override { return {320, 180}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  struct Series {
    QString name;
    QColor color;
    std::vector<QPointF> points;
  };
  QString title_, unit_, xUnit_ = "s";
  std::vector<Series> series_;
};

}  // namespace talus::gui
