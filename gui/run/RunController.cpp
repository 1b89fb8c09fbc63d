#include "run/RunController.hpp"

#include <QMetaObject>

#include "core/Error.hpp"
#include "render/TerrainRenderer.hpp"  // kGlNoData: device copies of layers are drawn as they are

namespace talus::gui {

namespace {
constexpr double kEmitInterval = 0.05;  ///< [s] wall time between progress signals
constexpr double kLogInterval = 2.0;    ///< [s] wall time between mass-balance lines in the log
constexpr int kSnapshotMs = 100;        ///< snapshots for the viewer at most 10 times a second
}  // namespace

RunController::RunController(QObject* parent) : QObject(parent) {
  qRegisterMetaType<RunProgress>();
  snapshotTimer_.setInterval(kSnapshotMs);
  connect(&snapshotTimer_, &QTimer::timeout, this, [this] {
    if (last_.steps != snapshotSteps_) requestSnapshot();
  });
}

RunController::~RunController() {
  cancelPrepare_ = true;
  if (preparer_.joinable()) preparer_.join();
  control_.reset();  // stops and joins the worker
}

void RunController::setState(State s) {
  if (s == state_) return;
  state_ = s;
  emit stateChanged(s);
}

void RunController::teardown() {
  snapshotTimer_.stop();
  cancelPrepare_ = true;
  if (preparer_.joinable()) preparer_.join();
  control_.reset();
  view_.reset();
  sim_.reset();
  scene_.reset();
  snapshotPending_ = false;
  snapshotSteps_ = -1;
  ++generation_;
}

void RunController::reset() {
  if (isActive()) return;
  teardown();
  config_.reset();
  restartConfig_.reset();
  last_ = {};
  pending_ = {};
  setState(State::Idle);
}

void RunController::start(const io::RunConfig& config, bool overwrite, bool paused) {
  if (isActive()) return;
  teardown();
  config_ = std::make_unique<io::RunConfig>(config);
  overwrite_ = overwrite;
  startPaused_ = paused;
  cancelPrepare_ = false;
  last_ = {};
  pending_ = {};
  lastEmitWall_ = lastLogWall_ = -1;
  setState(State::Preparing);
  emit log(QString("loading %1").arg(QString::fromStdString(config.sourceName())));
  // Reading rasters and building kernels takes seconds: do it off the GUI thread.
  preparer_ = std::thread([this, gen = int(generation_)] {
    QString error;
    try {
      auto scene = std::make_unique<sim::Scene>(sim::loadScene(*config_));
      auto sim = std::make_unique<sim::Simulation>(
          *scene, *config_, "", overwrite_ ? sim::OutputMode::Overwrite : sim::OutputMode::New);
      scene_ = std::move(scene);
      sim_ = std::move(sim);
    } catch (const std::exception& e) {
      error = QString::fromUtf8(e.what());
    }
    if (cancelPrepare_) return;
    QMetaObject::invokeMethod(this, [this, error, gen] {
      if (gen != generation_) return;
      if (preparer_.joinable()) preparer_.join();
      if (!error.isEmpty()) {
        setState(State::Idle);
        emit log("error: " + error);
        emit prepareFailed(error);
        return;
      }
      onPrepared();
    }, Qt::QueuedConnection);
  });
}

void RunController::onPrepared() {
  view_ = std::make_unique<sim::ViewFields>(*scene_, sim_->solver(), sim_->particleView());
  // Layers made of the solver's own device fields are packed on the device (and, with GL sharing,
  // copied device to device into the viewer's buffers).
  view_->setDeviceFields(sim_->context(), sim_->solver().viewBuffers());
  const Grid& g = scene_->dem.grid;
  emit log(QString("%1 on %2 (%3), grid %4 x %5 of %6 m, t = %7 .. %8 s; outputs in %9")
               .arg(QString::fromStdString(scene_->runFile), QString::fromStdString(sim_->context().device().name),
                    QString::fromStdString(scene_->precision))
               .arg(g.nx)
               .arg(g.ny)
               .arg(g.dx)
               .arg(scene_->startTime)
               .arg(scene_->endTime)
               .arg(QString::fromStdString(config_->directory("Output Directory"))));
  for (const std::string& w : scene_->warnings) emit log("warning: " + QString::fromStdString(w));
  const std::string particleCost = sim_->particleCost();
  if (!particleCost.empty()) emit log("particles: " + QString::fromStdString(particleCost));
  sim::RunControl::Callbacks cb;
  cb.onStep = [this](const sim::Progress& p) { onStep(p); };
  cb.onEnd = [this](const sim::RunOutcome& o) { onEnd(o); };
  control_ = std::make_unique<sim::RunControl>(*sim_, cb);
  emit prepared();
  // The initial state, taken before the worker starts (RunControl::post runs a job at once while no
  // worker is alive): every live series begins at the start time. Requested after the start, it
  // raced with the first steps and, on a short run, was taken at the end instead (a probe then
  // held one point).
  requestSnapshot();
  control_->start(startPaused_);
  setState(startPaused_ ? State::Paused : State::Running);
  snapshotTimer_.start();
}

void RunController::onStep(const sim::Progress& p) {
  // Worker thread: keep the latest, hand it to the GUI thread at most every kEmitInterval.
  RunProgress r;
  r.time = p.time;
  r.startTime = p.startTime;
  r.endTime = p.endTime;
  r.steps = p.steps;
  r.wallSeconds = p.wallSeconds;
  r.fluidVolume = p.diagnostics ? p.diagnostics->volume : 0;
  r.solidVolume = p.diagnostics ? p.diagnostics->volumeSolid : 0;
  r.cumulativeOutflow = p.cumulativeOutflow;
  r.balanceError = p.balanceError;
  r.kineticEnergy = p.kineticEnergy;
  r.energyReleased = p.energyReleased;
  r.frictionWork = p.frictionWork;
  r.particleMass = p.particleMass;
  const bool paused = control_ && control_->isPaused();
  {
    std::lock_guard<std::mutex> lock(progressMutex_);
    pending_ = r;
    if (!paused && p.time < p.endTime && p.wallSeconds - lastEmitWall_ < kEmitInterval) return;
    lastEmitWall_ = p.wallSeconds;
  }
  QMetaObject::invokeMethod(this, [this, gen = int(generation_)] {
    if (gen != generation_) return;
    RunProgress now;
    {
      std::lock_guard<std::mutex> lock(progressMutex_);
      now = pending_;
    }
    if (now.steps <= last_.steps && last_.steps > 0) return;
    last_ = now;
    if (now.wallSeconds - lastLogWall_ >= kLogInterval) {
      lastLogWall_ = now.wallSeconds;
      QString line = QString("t = %1 s, step %2: volume %3 m3, outflow %4 m3, mass balance error %5")
                         .arg(now.time, 0, 'f', 2)
                         .arg(now.steps)
                         .arg(now.fluidVolume + now.solidVolume, 0, 'g', 8)
                         .arg(now.cumulativeOutflow, 0, 'g', 6)
                         .arg(now.balanceError, 0, 'e', 2);
      if (now.particleMass > 0) line += QString(", particles %1 kg").arg(now.particleMass, 0, 'g', 8);
      emit log(line);
    }
    emit progress(now);
  }, Qt::QueuedConnection);
}

void RunController::onEnd(const sim::RunOutcome& outcome) {
  QMetaObject::invokeMethod(this, [this, outcome, gen = int(generation_)] {
    if (gen != generation_) return;
    {
      std::lock_guard<std::mutex> lock(progressMutex_);
      last_ = pending_;
    }
    emit progress(last_);
    snapshotTimer_.stop();
    // The final state, taken and delivered here (the worker has ended) before the state turns
    // Ended, so whoever waits for Ended sees it (queued, it arrived after Ended).
    snapshotPending_ = false;
    if (view_ && sim_) {
      try {
        deliverSnapshot(takeSnapshot(*sim_));
      } catch (const std::exception&) {
        // A failed run's state may not pack (RunControl::drainAndEnd); the log says why it failed.
      }
    }
    QString message;
    const sim::RunSummary& s = outcome.summary;
    switch (outcome.kind) {
      case sim::RunOutcome::Kind::Completed:
      case sim::RunOutcome::Kind::Stopped:
        message = QString("%1: %2 steps, %3 s simulated in %4 s, volume balance error %5")
                      .arg(outcome.kind == sim::RunOutcome::Kind::Completed ? "run completed" : "run stopped")
                      .arg(s.steps)
                      .arg(s.simulatedSeconds, 0, 'f', 2)
                      .arg(s.wallSeconds, 0, 'f', 2)
                      .arg(s.volumeBalanceError, 0, 'e', 2);
        break;
      case sim::RunOutcome::Kind::Failed:
        message = "run failed: " + QString::fromStdString(outcome.error);
        break;
    }
    emit log(message);
    setState(State::Ended);
    emit ended(outcome.kind, message);
    if (restartConfig_) {
      const io::RunConfig config = *restartConfig_;
      restartConfig_.reset();
      start(config, true, false);
    }
  }, Qt::QueuedConnection);
}

void RunController::pause() {
  if (state_ != State::Running) return;
  control_->pause();
  setState(State::Paused);
  emit log("paused");
}

void RunController::resume() {
  if (state_ != State::Paused) return;
  control_->resume();
  setState(State::Running);
  emit log("resumed");
}

void RunController::step() {
  if (state_ != State::Paused && state_ != State::Running) return;
  control_->stepOnce();
  setState(State::Paused);
}

void RunController::stop() {
  if (state_ == State::Preparing) {
    cancelPrepare_ = true;
    if (preparer_.joinable()) preparer_.join();
    teardown();
    setState(State::Idle);
    emit log("cancelled");
    return;
  }
  if (state_ != State::Running && state_ != State::Paused) return;
  emit log("stopping after the current step");
  control_->stop();
}

void RunController::restart(const io::RunConfig& config) {
  if (state_ == State::Running || state_ == State::Paused) {
    // The worker finishes the current step and writes its outputs first; onEnd then starts it.
    // (config_ stays: the running Simulation reads it.)
    restartConfig_ = std::make_unique<io::RunConfig>(config);
    control_->stop();
    return;
  }
  if (state_ == State::Preparing) stop();
  start(config, true, false);
}

std::shared_ptr<sim::ViewSnapshot> RunController::takeSnapshot(sim::Simulation& sim) {
  auto s = std::make_shared<sim::ViewSnapshot>(view_->snapshot({}, deviceSnapshots_, kGlNoData));
  s->steps = sim.steps();
  return s;
}

void RunController::deliverSnapshot(std::shared_ptr<const sim::ViewSnapshot> s) {
  snapshotSteps_ = s->steps;
  emit snapshotReady(std::move(s));
}

void RunController::requestSnapshot() {
  if (!control_ || !view_ || snapshotPending_) return;
  snapshotPending_ = true;
  control_->post([this](sim::Simulation& sim) {
    auto s = takeSnapshot(sim);
    QMetaObject::invokeMethod(this, [this, s, gen = int(generation_)] {
      if (gen != generation_) return;
      snapshotPending_ = false;
      deliverSnapshot(s);
    }, Qt::QueuedConnection);
  });
}

}  // namespace talus::gui
