// The run's time series, drawn live: volume per phase, cumulative outflow, the energy (kinetic; in
// the two-phase model also the potential energy released and the work of friction and drag) and the
// position of the flow front.
#pragma once
#include <QWidget>

#include "plots/TimeSeriesPlot.hpp"
#include "results/DiagnosticsTable.hpp"
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
  /// Replaces the series by the rows of a finished run's diagnostics.csv (volumes, cumulative
  /// outflow, energies; the front distance is not in the file and stays empty).
  void setDiagnostics(const DiagnosticsTable& table);
  void clear();
  const TimeSeriesPlot& volumePlot() const { return *volume_; }
  const TimeSeriesPlot& outflowPlot() const { return *outflow_; }
  const TimeSeriesPlot& energyPlot() const { return *kinetic_; }

 private:
  TimeSeriesPlot *volume_, *outflow_, *kinetic_, *front_;
  int fluid_, solid_, total_, out_, energy_, released_, work_, distance_;
};

}  // namespace talus::gui
