#include "plots/PlotPanel.hpp"

#include <QGridLayout>

namespace talus::gui {

PlotPanel::PlotPanel(QWidget* parent) : QWidget(parent) {
  volume_ = new TimeSeriesPlot("volume", "m³");
  outflow_ = new TimeSeriesPlot("outflow (cumulative)", "m³");
  kinetic_ = new TimeSeriesPlot("kinetic energy", "J");
  front_ = new TimeSeriesPlot("front distance from the release", "m");
  total_ = volume_->addSeries("total", QColor(60, 60, 60));
  fluid_ = volume_->addSeries("fluid", QColor(30, 110, 220));
  solid_ = volume_->addSeries("solid", QColor(160, 90, 30));
  out_ = outflow_->addSeries("outflow", QColor(200, 60, 40));
  energy_ = kinetic_->addSeries("kinetic", QColor(220, 140, 20));
  distance_ = front_->addSeries("front", QColor(120, 60, 200));
  auto* grid = new QGridLayout(this);
  grid->addWidget(volume_, 0, 0);
  grid->addWidget(outflow_, 0, 1);
  grid->addWidget(kinetic_, 1, 0);
  grid->addWidget(front_, 1, 1);
}

void PlotPanel::addProgress(const RunProgress& p, bool twoPhase) {
  volume_->append(total_, p.time, p.fluidVolume + p.solidVolume);
  if (twoPhase) {
    volume_->append(fluid_, p.time, p.fluidVolume);
    volume_->append(solid_, p.time, p.solidVolume);
  }
  outflow_->append(out_, p.time, p.cumulativeOutflow);
  kinetic_->append(energy_, p.time, p.kineticEnergy);
}

void PlotPanel::addSnapshot(const sim::ViewSnapshot& s) { front_->append(distance_, s.time, s.frontDistance); }

void PlotPanel::clear() {
  for (TimeSeriesPlot* p : {volume_, outflow_, kinetic_, front_}) p->clear();
}

}  // namespace talus::gui
