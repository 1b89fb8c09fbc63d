#include "plots/PlotPanel.hpp"

#include <QGridLayout>
#include <algorithm>

namespace talus::gui {

PlotPanel::PlotPanel(QWidget* parent) : QWidget(parent) {
  volume_ = new TimeSeriesPlot("volume", "m³");
  outflow_ = new TimeSeriesPlot("outflow (cumulative)", "m³");
  kinetic_ = new TimeSeriesPlot("energy", "J");
  front_ = new TimeSeriesPlot("front distance from the release", "m");
  total_ = volume_->addSeries("total", QColor(60, 60, 60));
  fluid_ = volume_->addSeries("fluid", QColor(30, 110, 220));
  solid_ = volume_->addSeries("solid", QColor(160, 90, 30));
  out_ = outflow_->addSeries("outflow", QColor(200, 60, 40));
  energy_ = kinetic_->addSeries("kinetic", QColor(220, 140, 20));
  released_ = kinetic_->addSeries("released", QColor(60, 60, 60));
  work_ = kinetic_->addSeries("friction and drag", QColor(160, 90, 30));
  distance_ = front_->addSeries("front", QColor(120, 60, 200));
  mass_ = new TimeSeriesPlot("particle mass", "kg");
  particles_ = mass_->addSeries("particles", QColor(160, 90, 30));
  auto* grid = new QGridLayout(this);
  grid->addWidget(volume_, 0, 0);
  grid->addWidget(outflow_, 0, 1);
  grid->addWidget(kinetic_, 1, 0);
  grid->addWidget(front_, 1, 1);
  grid->addWidget(mass_, 2, 0);
}

void PlotPanel::addProgress(const RunProgress& p, bool twoPhase) {
  volume_->append(total_, p.time, p.fluidVolume + p.solidVolume);
  if (twoPhase) {
    volume_->append(fluid_, p.time, p.fluidVolume);
    volume_->append(solid_, p.time, p.solidVolume);
  }
  outflow_->append(out_, p.time, p.cumulativeOutflow);
  kinetic_->append(energy_, p.time, p.kineticEnergy);
  if (twoPhase) {
    kinetic_->append(released_, p.time, p.energyReleased);
    kinetic_->append(work_, p.time, p.frictionWork);
  }
  if (p.particleMass > 0) mass_->append(particles_, p.time, p.particleMass);
}

void PlotPanel::addSnapshot(const sim::ViewSnapshot& s) { front_->append(distance_, s.time, s.frontDistance); }

void PlotPanel::setDiagnostics(const DiagnosticsTable& table) {
  clear();
  const std::vector<double>* t = table.column("time_s");
  if (!t) return;
  const std::vector<double>* fluid = table.column("fluid_volume_m3");
  const std::vector<double>* solid = table.column("solid_volume_m3");
  const std::vector<double>* water = table.column("volume_m3");
  const std::vector<double>* out = table.column("cumulative_outflow_m3");
  const std::vector<double>* energy = table.column("kinetic_energy_J");
  const std::vector<double>* released = table.column("energy_released_J");
  const std::vector<double>* work = table.column("friction_drag_work_J");
  const std::vector<double>* mass = table.column("particle_mass_kg");
  const bool twoPhase = solid && std::any_of(solid->begin(), solid->end(), [](double v) { return v != 0; });
  for (std::size_t r = 0; r < t->size(); ++r) {
    const double time = (*t)[r];
    if (fluid && solid) volume_->append(total_, time, (*fluid)[r] + (*solid)[r]);
    else if (water) volume_->append(total_, time, (*water)[r]);
    if (twoPhase && fluid) {
      volume_->append(fluid_, time, (*fluid)[r]);
      volume_->append(solid_, time, (*solid)[r]);
    }
    if (out) outflow_->append(out_, time, (*out)[r]);
    if (energy) kinetic_->append(energy_, time, (*energy)[r]);
    if (twoPhase && released) kinetic_->append(released_, time, (*released)[r]);
    if (twoPhase && work) kinetic_->append(work_, time, (*work)[r]);
    if (mass && (*mass)[r] > 0) mass_->append(particles_, time, (*mass)[r]);
  }
}

void PlotPanel::clear() {
  for (TimeSeriesPlot* p : {volume_, outflow_, kinetic_, front_, mass_}) p->clear();
}

}  // namespace talus::gui
