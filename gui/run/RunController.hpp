// Drives one run for the desktop application: loads the scene and opens the device on a helper
// thread, then runs the Simulation on a sim::RunControl worker thread, and turns its callbacks into
// Qt signals on the GUI thread (progress and time-series samples at most ~20 times a second,
// snapshots for the viewer on request). The interface never waits for the simulation.
#pragma once
#include <QObject>
#include <QString>
#include <QTimer>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

#include "io/RunConfig.hpp"
#include "sim/RunControl.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"
#include "sim/ViewFields.hpp"

namespace talus::gui {

/// Where a run stands (for the progress bar and the plots).
struct RunProgress {
  double time = 0, startTime = 0, endTime = 0;  ///< simulated [s]
  long long steps = 0;
  double wallSeconds = 0;
  double fluidVolume = 0, solidVolume = 0;      ///< [m^3]
  double cumulativeOutflow = 0;                 ///< [m^3]
  double balanceError = 0;                      ///< relative
  double kineticEnergy = 0;                     ///< [J]
  double energyReleased = 0, frictionWork = 0;  ///< two-phase: potential energy released, work of friction and drag [J]
  double particleMass = 0;                      ///< [kg] (0 without particles)
};

class RunController : public QObject {
  Q_OBJECT

 public:
  enum class State { Idle, Preparing, Running, Paused, Ended };

  explicit RunController(QObject* parent = nullptr);
  /// Stops a run in progress (its outputs are written) and waits for the threads.
  ~RunController() override;

  /// Starts a run of `config` (copied) in the background; outputs go to its Output Directory,
  /// replacing a previous run there when `overwrite`. With `paused` it waits before the first step.
  void start(const io::RunConfig& config, bool overwrite, bool paused = false);
  void pause();
  void resume();
  void step();
  void stop();
  /// Stops the run (if any) and then starts `config` (the open run-file, which may have been edited
  /// since), replacing the outputs.
  void restart(const io::RunConfig& config);
  /// Forgets the run of the previous scene (its scene, device, progress and configuration) and goes
  /// back to Idle; nothing of it reaches the signals any more. Ignored while a run is active.
  void reset();
  /// Whether a run is loading, running or paused.
  bool isActive() const { return state_ == State::Preparing || state_ == State::Running || state_ == State::Paused; }
  /// Asks for a snapshot of every layer (delivered by snapshotReady); ignored while one is pending.
  void requestSnapshot();
  /// Whether snapshots keep the device copies of the layers packed on the device (for a viewer
  /// whose OpenGL buffers are shared with the run's OpenCL context).
  void setDeviceSnapshots(bool keep) { deviceSnapshots_ = keep; }

  State state() const { return state_; }
  /// Valid after prepared() until the next start().
  const sim::Scene* scene() const { return scene_.get(); }
  const sim::ViewFields* viewFields() const { return view_.get(); }
  sim::Simulation* simulation() { return sim_.get(); }
  const RunProgress& lastProgress() const { return last_; }

 signals:
  void stateChanged(State state);
  /// The scene is loaded and the device opened: scene() and viewFields() are valid.
  void prepared();
  /// Loading or opening the device failed (bad input or device); the run did not start.
  void prepareFailed(const QString& message);
  void progress(const RunProgress& p);
  void snapshotReady(std::shared_ptr<const sim::ViewSnapshot> snapshot);
  /// The run ended: completed, stopped or failed (message says how).
  void ended(sim::RunOutcome::Kind kind, const QString& message);
  void log(const QString& line);

 private:
  void setState(State s);
  void onPrepared();
  void onStep(const sim::Progress& p);
  void onEnd(const sim::RunOutcome& outcome);
  void teardown();
  /// A snapshot of every layer of `sim` (on the thread that may touch it: the worker, or any while
  /// no worker runs), and its delivery through snapshotReady (GUI thread).
  std::shared_ptr<sim::ViewSnapshot> takeSnapshot(sim::Simulation& sim);
  void deliverSnapshot(std::shared_ptr<const sim::ViewSnapshot> s);

  State state_ = State::Idle;
  std::unique_ptr<io::RunConfig> config_;
  std::unique_ptr<sim::Scene> scene_;
  std::unique_ptr<sim::Simulation> sim_;
  std::unique_ptr<sim::ViewFields> view_;
  std::unique_ptr<sim::RunControl> control_;
  std::thread preparer_;
  std::unique_ptr<io::RunConfig> restartConfig_;  ///< started when the run being stopped has ended
  bool overwrite_ = false, startPaused_ = false;
  std::atomic<bool> cancelPrepare_{false};
  /// Counts teardowns: what the threads queued for the GUI thread carries the count of its run and
  /// is dropped when that run has been torn down since (another start, or reset).
  std::atomic<int> generation_{0};
  bool snapshotPending_ = false;
  std::atomic<bool> deviceSnapshots_{false};
  long long snapshotSteps_ = -1;
  QTimer snapshotTimer_;
  // Written by the worker, read on the GUI thread.
  std::mutex progressMutex_;
  RunProgress pending_;
  double lastEmitWall_ = -1, lastLogWall_ = -1;
  RunProgress last_;
};

}  // namespace talus::gui

Q_DECLARE_METATYPE(talus::gui::RunProgress)
