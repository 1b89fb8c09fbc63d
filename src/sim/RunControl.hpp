// Runs a Simulation on a worker thread that a user interface can pause, resume, single-step and
// stop between steps, and that runs jobs (snapshots for viewers) between steps on the thread that
// owns the device queue. No Qt here: the desktop application adapts the callbacks to signals.
#pragma once
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "sim/Simulation.hpp"

namespace talus::sim {

/// How a controlled run ended.
struct RunOutcome {
  enum class Kind { Completed, Stopped, Failed };
  Kind kind = Kind::Completed;
  RunSummary summary;   ///< valid unless a failure happened outside the health check
  std::string error;    ///< the failure message (Failed)
};

class RunControl {
 public:
  /// Called on the worker thread: after every step, and once when the run has ended.
  struct Callbacks {
    std::function<void(const Progress&)> onStep;
    std::function<void(const RunOutcome&)> onEnd;
  };

  /// Controls `sim` (not yet begun; it must outlive this object).
  RunControl(Simulation& sim, Callbacks callbacks);
  /// Stops the run (writing its outputs, as stop()) and waits for the worker.
  ~RunControl();
  RunControl(const RunControl&) = delete;
  RunControl& operator=(const RunControl&) = delete;

  /// Starts the worker thread; with `paused` it waits for resume() or stepOnce() before the first step.
  void start(bool paused = false);
  /// The worker finishes the current step and waits.
  void pause();
  void resume();
  /// While paused: take exactly one more step.
  void stepOnce();
  /// Ends the run after the current step: the final maps and summary.json ("stopped") are written.
  void stop();
  /// Runs `job` on the worker thread between two steps (also while paused); once the worker has
  /// ended, runs it at once on the calling thread.
  void post(std::function<void(Simulation&)> job);
  /// Blocks until the worker has ended.
  void wait();

  bool isRunning() const;
  bool isPaused() const;

 private:
  void loop();
  /// Runs the queued jobs until none is left, then marks the worker ended (under the lock, so that
  /// post() never runs a job on the caller while the worker still uses the simulation).
  void drainAndEnd();

  Simulation& sim_;
  Callbacks callbacks_;
  std::thread worker_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void(Simulation&)>> jobs_;
  bool alive_ = false, paused_ = false, stopRequested_ = false;
  int stepRequests_ = 0;
};

}  // namespace talus::sim
