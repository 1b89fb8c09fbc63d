// The run's time series, drawn live: volume per phase, cumulative outflow, the energy (kinetic; in
// the two-phase model also the potential energy released and the work of friction and drag), the
// position of the flow front and, in runs with particles, the particles' mass.
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
  /// The particles' mass (runs with particles only; their material is not in the grid's volumes).
  const TimeSeriesPlot& massPlot() const { return *mass_; }

 private:
  TimeSeriesPlot *volume_, *outflow_, *kinetic_, *front_, *mass_;
  int fluid_, solid_, total_, out_, energy_, released_, work_, distance_, particles_;
};

}  // namespace talus::gui
