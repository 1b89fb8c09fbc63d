#include "sim/Simulation.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "core/Error.hpp"
#include "sim/Checkpoint.hpp"

namespace talus::sim {
namespace {

constexpr const char* kCsvHeader =
    "step,time_s,dt_s,volume_m3,outflow_m3,cumulative_outflow_m3,balance_error,kinetic_energy_J,max_wave_speed_m_s,"
    "fluid_volume_m3,solid_volume_m3,fluid_outflow_m3,solid_outflow_m3,"
    "potential_energy_J,vertical_kinetic_J,energy_released_J,energy_lost_J,friction_drag_work_J,"
    "particles,particle_mass_kg,particle_outflow_kg,particle_kinetic_J,particle_viscous_dissipation_J,"
    "particle_art_stress_work_J,particle_friction_work_J,particle_potential_released_J,cumulative_rain_m3,"
    "cumulative_infiltrated_m3,wall_s";

/// Total volume (both phases) and total outflow of the last step.
double totalVolume(const flow::FlowDiagnostics& d) { return d.volume + d.volumeSolid; }
double totalOutflow(const flow::FlowDiagnostics& d) { return d.outflow + d.outflowSolid; }

/// The scene as the health check's energy bound must see it: everything that can join the flow
/// during the run counted as if it were there at the start.
flow::FlowInput energyBoundInput(const Scene& scene) {
  flow::FlowInput bound = scene.flow;
  const double area = scene.dem.grid.dx * scene.dem.grid.dx;
  // The particles' confined water may be released onto the grid and fall from where they stand.
  if (scene.particles.enabled)
    for (std::size_t q = 0; q < scene.particles.seeded.size(); ++q)
      bound.h[scene.particles.seeded.cell[q]] += scene.particles.seeded.volume[q] / area;
  // The rain of the whole run can fall over the whole relief and drive fronts as deep as it is.
  if (!scene.rainfall.empty()) {
    const double rain = scene.rainfall.depth(scene.startTime, scene.endTime);
    for (double& h : bound.h) h += rain;
  }
  // Entrainment lowers the bed by at most the erodible depth and thickens the flow by as much (the
  // surface b + h_s stays).
  if (scene.settings.entrainment.enabled && !scene.flow.erodible.empty()) {
    if (bound.hs.empty()) bound.hs.assign(bound.bed.size(), 0.0);
    for (std::size_t k = 0; k < bound.bed.size(); ++k) {
      bound.bed[k] -= scene.flow.erodible[k];
      bound.hs[k] += scene.flow.erodible[k];
    }
  }
  return bound;
}

}  // namespace

Simulation::Simulation(const Scene& scene, const io::RunConfig& config, const std::string& outDir, OutputMode mode)
    : scene_(scene), config_(config) {
  out_ = std::make_unique<OutputWriter>(outDir.empty() ? scene.outputDir : outDir, scene.dem, scene.format,
                                        mode == OutputMode::Overwrite, mode == OutputMode::Resume);
  ctx_ = compute::Context::create(scene.device, compute::parsePrecision(scene.precision));
  solver_ = std::make_unique<flow::FlowSolver>(*ctx_, scene.dem.grid, scene.settings);
  solver_->setInput(scene.flow, scene.startTime);
  solver_->setInfiltration(scene.infiltration);
  health_ = std::make_unique<HealthCheck>(scene.dem, energyBoundInput(scene), scene.settings);
  for (uint8_t v : scene.dem.valid) domainCells_ += v;
  initialVolume_ = totalVolume(solver_->diagnostics());
  initialErodible_ = solver_->diagnostics().erodible;
  {
    double fluid = 0;
    for (double h : scene.flow.h) fluid += std::max(h, 0.0);
    fluidSeries_ = !solver_->twoPhase() || fluid > 0 || (scene.particles.enabled && !scene.particles.seeded.x.empty());
  }
  {
    // Energy accounting of the grid phases (two-phase model): at the initial state, also on resume
    // (the solver holds the scene's initial state until the checkpoint is restored).
    const flow::FlowDiagnostics& d0 = solver_->diagnostics();
    initialPotential_ = d0.potential;
    initialMechanical_ = d0.kinetic + d0.kineticVertical + d0.potential;
  }
  if (scene.particles.enabled && !scene.particles.seeded.x.empty())
    particles_ = std::make_unique<ParticleRun>(*ctx_, scene.dem, scene.particles, *solver_);
  if (mode != OutputMode::Resume) {
    // Everything is in place: only now is the previous run's folder content replaced.
    out_->prepare();
    out_->writeText("run.resolved.run", config.echo());
    return;
  }
  // Resuming: every check comes before anything in the folder changes, so a resume that fails
  // (another precision or grid, a truncated checkpoint, an End Time already passed) leaves the
  // completed or interrupted run as it was.
  const std::string path = out_->path("checkpoint.bin");
  const Checkpoint c = readCheckpoint(path);
  const Grid& g = scene.dem.grid;
  if (c.precision != compute::precisionName(ctx_->precision()) || c.nx != g.nx || c.ny != g.ny)
    throw InputError("checkpoint '" + path + "' was written for a " + std::to_string(c.nx) + "x" +
                     std::to_string(c.ny) + " grid in " + c.precision + " precision; this run is " +
                     std::to_string(g.nx) + "x" + std::to_string(g.ny) + " in " +
                     compute::precisionName(ctx_->precision()));
  solver_->restoreState(c.state, c.time);
  if (particles_ && c.particleState.empty())
    throw InputError("checkpoint '" + path + "' holds no particles, but this run has particles");
  if (particles_) particles_->restoreState(c.particleState);
  if (scene.endTime < c.time * (1 - 1e-12) - 1e-12)
    throw InputError("cannot resume: the End Time of " + std::to_string(scene.endTime) + " s lies before the time of " +
                     "checkpoint '" + path + "' (" + std::to_string(c.time) + " s); give a later End Time with --set");
  out_->checkDiagnostics(kCsvHeader, c.steps);
  steps_ = c.steps;
  reportIndex_ = c.reportIndex;
  initialVolume_ = c.initialVolume;
  totalOutflow_ = c.totalOutflow;
  totalRain_ = c.totalRain;
  totalInfiltrated_ = c.totalInfiltrated;
  totalSourceWork_ = c.totalSourceWork;
  if (solver_->entrainment()) {  // what was left at the checkpoint plus what the bed lost before it
    double eroded = 0;
    for (double d : solver_->bedChange()) eroded -= d;
    const double area = scene.dem.grid.dx * scene.dem.grid.dx;
    initialErodible_ = solver_->diagnostics().erodible + eroded * area;
  }
  wallBefore_ = c.elapsedWall;
  seriesIndex_ = c.seriesIndex;
  out_->prepare();
  out_->truncateDiagnostics(kCsvHeader, steps_);
}

void Simulation::writeCheckpoint(double wallSeconds) {
  Checkpoint c;
  c.precision = compute::precisionName(ctx_->precision());
  c.nx = scene_.dem.grid.nx;
  c.ny = scene_.dem.grid.ny;
  c.time = solver_->time();
  c.steps = steps_;
  c.reportIndex = reportIndex_;
  c.initialVolume = initialVolume_;
  c.totalOutflow = totalOutflow_;
  c.totalRain = totalRain_;
  c.totalInfiltrated = totalInfiltrated_;
  c.totalSourceWork = totalSourceWork_;
  c.elapsedWall = wallSeconds;
  c.seriesIndex = seriesIndex_;
  c.state = solver_->saveState();
  if (particles_) c.particleState = particles_->saveState();
  sim::writeCheckpoint(out_->claim("checkpoint.bin"), c);
  ++checkpoints_;
}

std::string Simulation::particleCost() {
  if (!particles_) return "";
  particles::ParticleSolver& p = particles_->solver();
  const double sub = p.stableSubStep();
  const double count = static_cast<double>(particles_->count());
  std::ostringstream o;
  o.precision(3);
  // Neighbours within the kernel's support (radius 2h) at the seeding's spacing: the cost of each
  // particle-update grows with them.
  const double support = 2 * p.smoothingLength() / p.meanSpacing();
  o << particles_->count() << " particles with about " << 3.14159 * support * support << " neighbours each, sub-step "
    << sub << " s: about " << (sub > 0 ? count / sub : 0.0) << " particle-updates per simulated second ("
    << (sub > 0 ? (scene_.endTime - solver_->time()) / sub : 0.0) << " sub-steps to the end time)";
  return o.str();
}

double Simulation::wall() const {
  return wallBefore_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double Simulation::totalEntrained() const {
  return solver_->entrainment() ? initialErodible_ - solver_->diagnostics().erodible : 0.0;
}

double Simulation::volumeBalance(double volume) const {
  // Sources and sinks: V_0 + rain + entrained = V + outflow + infiltrated when volume is conserved.
  const double supplied = initialVolume_ + totalRain_ + totalEntrained();
  return supplied > 0 ? (volume + totalOutflow_ + totalInfiltrated_ - supplied) / supplied : 0.0;
}

RunSummary Simulation::run(const std::function<void(const Progress&)>& onProgress) {
  begin();
  while (!atEnd()) {
    const Progress p = stepOnce();
    if (onProgress) onProgress(p);
  }
  return finish();
}

void Simulation::begin() {
  if (begun_) throw std::logic_error("Simulation::begin called twice");
  begun_ = true;
  start_ = std::chrono::steady_clock::now();
  const double t0 = scene_.startTime;
  if (steps_ == 0) writeReport();
  nextReport_ = t0 + reportIndex_ * scene_.reportInterval;
  const double ckInterval = scene_.checkpointInterval;
  nextCheckpoint_ = ckInterval > 0 ? t0 + (std::floor((solver_->time() - t0) / ckInterval) + 1) * ckInterval
                                   : HUGE_VAL;
  lastCheckpointWall_ = wall();
}

bool Simulation::atEnd() const { return atRest_ || !(solver_->time() < scene_.endTime * (1 - 1e-15)); }

Progress Simulation::stepOnce() {
  if (!begun_ || finished_) throw std::logic_error("Simulation::stepOnce outside begin() .. finish()");
  const double t0 = scene_.startTime, tEnd = scene_.endTime, interval = scene_.reportInterval;
  const double t = solver_->time();
  // Land exactly on report and end times (spec §4: dt clipped to output times). Checkpoints are
  // taken at the first step end after they are due, so they never change the time steps.
  const double target = std::min(nextReport_, tEnd);
  double dt = solver_->stableDt();
  if (particles_) dt = std::min(dt, particles_->maxStep());
  // Rain wets dry ground everywhere at once: the step that does so keeps within the time step the
  // wetted state will need (FlowSolver::filmStableDt), or the first rain would lie still for a
  // whole report interval on a dry slope.
  if (!scene_.rainfall.empty() && scene_.rainfall.depth(t, t + std::min(dt, target - t)) > 0)
    dt = std::min(dt, solver_->filmStableDt());
  if (!(dt < target - t)) dt = target - t;
  // The rain of the step is the integral of the step-wise constant intensity over [t, t + dt]
  // (docs/sources.md), so the volume it adds is exact whatever the steps.
  solver_->step(dt, scene_.rainfall.depth(t, t + dt));
  if (std::fabs(solver_->time() - target) <= 1e-12 * std::max(1.0, std::fabs(target))) solver_->setTime(target);
  ++steps_;
  std::string problem = health_->check(*solver_, dt);
  if (problem.empty() && particles_) {
    problem = particles_->step(dt, solver_->time());
    initialVolume_ += particles_->releasedLastStep();  // released fluid is a source of the grid's volume
  }
  if (!problem.empty()) {
    std::ostringstream o;
    o << "simulation unstable at t = " << solver_->time() << " s (step " << steps_ << ", dt = " << dt
      << " s): " << problem;
    failure_ = o.str();
    finalize(Ending::Failed);
    throw SimulationError(failure_);
  }
  const flow::FlowDiagnostics& d = solver_->diagnostics();
  totalOutflow_ += totalOutflow(d);
  totalRain_ += d.rain;
  totalInfiltrated_ += d.infiltrated;
  totalSourceWork_ += d.sourceWork;
  const double volume = totalVolume(d);
  const double balance = volumeBalance(volume);
  // The single-phase diagnostics give kinetic energy per unit density; the two-phase ones joules.
  const double kinetic = solver_->twoPhase() ? d.kinetic : scene_.settings.debris.fluidDensity * d.kinetic;
  // Energy (two-phase; zeros for water alone): potential energy, kinetic energy of the motion along
  // the bed's slope, potential energy released since the start, the mechanical energy lost (to
  // friction, drag, impacts on walls, numerical dissipation and through open boundaries) and, of
  // that, the work of friction and drag (the stiff sources' kinetic-energy change, summed).
  const double released = solver_->twoPhase() ? initialPotential_ - d.potential : 0.0;
  const double lost = solver_->twoPhase() ? initialMechanical_ - (d.kinetic + d.kineticVertical + d.potential) : 0.0;
  lastReleased_ = released;
  lastLost_ = lost;
  char line[640];
  std::snprintf(line, sizeof line,
                "%lld,%.9g,%.6g,%.12g,%.6g,%.12g,%.3e,%.6g,%.6g,%.12g,%.12g,%.6g,%.6g,%.12g,%.6g,%.9g,%.9g,%.9g,", steps_,
                solver_->time(), dt, volume, totalOutflow(d), totalOutflow_, balance, kinetic, d.maxSpeed, d.volume,
                d.volumeSolid, d.outflow, d.outflowSolid, d.potential, d.kineticVertical, released, lost, totalSourceWork_);
  char wallText[32];
  std::snprintf(wallText, sizeof wallText, ",%.4f", wall());  // wall time last: the one column that differs run to run
  char sourcesText[64];
  std::snprintf(sourcesText, sizeof sourcesText, ",%.12g,%.12g", totalRain_, totalInfiltrated_);
  guardedWrite([&] {
    out_->appendDiagnostics(kCsvHeader, std::string(line) + (particles_ ? particles_->csvRow() : "0,0,0,0,0,0,0,0") +
                                            sourcesText + wallText);
  });
  if (solver_->time() >= nextReport_ * (1 - 1e-15)) {
    guardedWrite([&] { writeReport(); });
    nextReport_ = t0 + reportIndex_ * interval;
  }
  const double ckInterval = scene_.checkpointInterval;
  const bool simDue = solver_->time() >= nextCheckpoint_ * (1 - 1e-15);
  const bool wallDue = scene_.checkpointWallInterval > 0 && wall() - lastCheckpointWall_ >= scene_.checkpointWallInterval;
  // A checkpoint due by simulated time is written at the end too (it lets a later run continue
  // with a longer End Time); the wall-clock one is not needed there, the run is over.
  if (simDue || (wallDue && solver_->time() < tEnd * (1 - 1e-15))) {
    guardedWrite([&] { writeCheckpoint(wall()); });
    lastCheckpointWall_ = wall();
  }
  while (solver_->time() >= nextCheckpoint_ * (1 - 1e-15)) nextCheckpoint_ += ckInterval;
  // Viewers plot the kinetic energy of everything that moves: grid phases and particles.
  const double allKinetic = kinetic + (particles_ ? particles_->solver().diagnostics().kinetic : 0.0);
  peakKinetic_ = std::max(peakKinetic_, allKinetic);
  if (scene_.restFraction > 0 && peakKinetic_ > 0 && allKinetic < scene_.restFraction * peakKinetic_) {
    atRest_ = true;  // the flow has come to rest: the final maps are those of this state
  }
  return {solver_->time(), t0, tEnd, steps_, wall(), dt, &d, volume, totalOutflow_, balance, allKinetic,
          released, totalSourceWork_, particles_ ? particles_->mass() : 0.0};
}

void Simulation::guardedWrite(const std::function<void()>& write) {
  try {
    write();
  } catch (const IoError& e) {
    // The run cannot keep its record: stop it, and write what can still be written (the maxima so
    // far and a summary that says "failed" and why), or say that it could not.
    std::ostringstream o;
    o << "output failed at t = " << solver_->time() << " s (step " << steps_ << "): " << e.what();
    failure_ = o.str();
    finalize(Ending::Failed);  // throws IoError itself when the summary cannot be written either
    throw IoError(failure_ + "; the maxima so far and summary.json (status \"failed\") are written");
  }
}

RunSummary Simulation::finish() {
  if (!begun_ || finished_) throw std::logic_error("Simulation::finish outside begin() .. finish()");
  return finalize(atEnd() ? Ending::Completed : Ending::Stopped);
}

RunSummary Simulation::finalize(Ending ending) {
  finished_ = true;
  RunSummary s;
  s.initialVolume = initialVolume_;
  s.steps = steps_;
  s.totalOutflow = totalOutflow_;
  s.wallSeconds = wall();
  s.simulatedSeconds = solver_->time() - scene_.startTime;
  s.finalVolume = totalVolume(solver_->diagnostics());
  s.cellUpdatesPerSecond = s.wallSeconds > 0 ? static_cast<double>(domainCells_) * s.steps / s.wallSeconds : 0;
  s.totalRain = totalRain_;
  s.totalInfiltrated = totalInfiltrated_;
  s.totalEntrained = totalEntrained();
  s.volumeBalanceError = volumeBalance(s.finalVolume);
  s.checkpoints = checkpoints_;
  writeFinal(s, ending);
  return s;
}

}  // namespace talus::sim
