// Values of a layer where the user asks: its time series at a chosen cell (over the frames of
// opened results, or as a live run's snapshots arrive) and its profile along a drawn line, with the
// terrain's elevation along the same line.
#pragma once
#include <QLabel>
#include <QPointF>
#include <QWidget>
#include <vector>

#include "plots/TimeSeriesPlot.hpp"

namespace talus::gui {

class ProbePanel : public QWidget {
  Q_OBJECT

 public:
  explicit ProbePanel(QWidget* parent = nullptr);

  /// Replaces the time series: `where` names the cell, `points` are (time [s], value).
  void setPointSeries(const QString& where, const QString& layer, const QString& unit,
                      const std::vector<QPointF>& points);
  /// Adds one (time, value) to the time series (a live run's new snapshot).
  void appendPoint(double time, double value);
  /// Replaces the profile: (distance [m], value) of the layer and (distance, elevation).
  void setProfile(const QString& layer, const QString& unit, const std::vector<QPointF>& values,
                  const std::vector<QPointF>& elevation);
  void clear();

  const TimeSeriesPlot& pointPlot() const { return *point_; }
  const TimeSeriesPlot& profilePlot() const { return *profile_; }
  const TimeSeriesPlot& elevationPlot() const { return *elevation_; }
  QString pointCaption() const { return caption_->text(); }

 private:
  QLabel* caption_;
  TimeSeriesPlot *point_, *profile_, *elevation_;
  int pointSeries_, profileSeries_, elevationSeries_;
};

}  // namespace talus::gui
