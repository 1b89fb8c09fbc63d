#include "sim/RunControl.hpp"

#include <exception>
#include <utility>

#include "core/Error.hpp"

namespace talus::sim {

RunControl::RunControl(Simulation& sim, Callbacks callbacks) : sim_(sim), callbacks_(std::move(callbacks)) {}

RunControl::~RunControl() {
  stop();
  wait();
}

void RunControl::start(bool paused) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (alive_ || worker_.joinable()) return;
  alive_ = true;
  paused_ = paused;
  worker_ = std::thread([this] { loop(); });
}

void RunControl::pause() {
  std::lock_guard<std::mutex> lock(mutex_);
  paused_ = true;
}

void RunControl::resume() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    paused_ = false;
    stepRequests_ = 0;
  }
  wake_.notify_all();
}

void RunControl::stepOnce() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    paused_ = true;
    ++stepRequests_;
  }
  wake_.notify_all();
}

void RunControl::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopRequested_ = true;
  }
  wake_.notify_all();
}

void RunControl::post(std::function<void(Simulation&)> job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (alive_) {
      jobs_.push_back(std::move(job));
      wake_.notify_all();
      return;
    }
  }
  job(sim_);
}

void RunControl::wait() {
  if (worker_.joinable() && worker_.get_id() != std::this_thread::get_id()) worker_.join();
}

bool RunControl::isRunning() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return alive_;
}

bool RunControl::isPaused() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return paused_;
}

void RunControl::loop() {
  RunOutcome outcome;
  try {
    sim_.begin();
    for (;;) {
      std::deque<std::function<void(Simulation&)>> jobs;
      bool stop = false, step = false;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopRequested_ || !jobs_.empty() || !paused_ || stepRequests_ > 0; });
        jobs.swap(jobs_);
        stop = stopRequested_;
        step = !paused_ || stepRequests_ > 0;
        if (step && paused_) --stepRequests_;
      }
      for (auto& job : jobs) job(sim_);
      if (stop || sim_.atEnd()) break;
      if (!step) continue;
      const Progress p = sim_.stepOnce();
      if (callbacks_.onStep) callbacks_.onStep(p);
    }
    outcome.kind = sim_.atEnd() ? RunOutcome::Kind::Completed : RunOutcome::Kind::Stopped;
    outcome.summary = sim_.finish();
  } catch (const std::exception& e) {
    // A SimulationError has already written the outputs so far (Simulation::stepOnce).
    outcome.kind = RunOutcome::Kind::Failed;
    outcome.error = e.what();
  }
  drainAndEnd();
  if (callbacks_.onEnd) callbacks_.onEnd(outcome);
}

void RunControl::drainAndEnd() {
  for (;;) {
    std::deque<std::function<void(Simulation&)>> jobs;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (jobs_.empty()) {
        alive_ = false;
        return;
      }
      jobs.swap(jobs_);
    }
    // The run is over: a failing job (a snapshot of a broken state) must not take the process down.
    for (auto& job : jobs) {
      try {
        job(sim_);
      } catch (const std::exception&) {
      }
    }
  }
}

}  // namespace talus::sim
