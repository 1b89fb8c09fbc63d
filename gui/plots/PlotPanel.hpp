// The run's time series, drawn live: volume per phase, cumulative outflow, kinetic energy and the
// position of the flow front.
#pragma once
#include <QWidget>

#include "plots/TimeSeriesPlot.hpp"
#include "run/RunController.hpp"
#include "sim/ViewFields.hpp"

namespace talus::gui {

class PlotPanel : public QWidget {
  Q_OBJECT

 public:
  explicit PlotPanel(QWidget* parent = nullptr);
  /// Adds the values of a progress report (volumes, outflow, kinetic energy).
  void addProgress(const RunProgress& p, bool twoPhase);
  /// Adds the front position of a snapshot.
  void addSnapshot(const sim::ViewSnapshot& s);
  void clear();
  const TimeSeriesPlot& volumePlot() const { return *volume_; }

 private:
  TimeSeriesPlot *volume_, *outflow_, *kinetic_, *front_;
  int fluid_, solid_, total_, out_, energy_, distance_;
};

}  // namespace talus::gui
