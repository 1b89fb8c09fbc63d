// The time loop of a run: CFL step clipped to report times, per-step diagnostics and health check,
// maps at report times, checkpoints, and the final maps, CSV and JSON summary (spec §7-§8).
#pragma once
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "compute/Context.hpp"
#include "flow/FlowSolver.hpp"
#include "io/RunConfig.hpp"
#include "sim/HealthCheck.hpp"
#include "sim/OutputWriter.hpp"
#include "sim/ParticleRun.hpp"
#include "sim/ParticleView.hpp"
#include "sim/Scene.hpp"

namespace talus::sim {

/// Where a run stands, handed to the progress callback after every step.
struct Progress {
  double time = 0, startTime = 0, endTime = 0;  ///< simulated [s]
  long long steps = 0;
  double wallSeconds = 0;
  double dt = 0;
  const flow::FlowDiagnostics* diagnostics = nullptr;
  double volume = 0;             ///< both phases [m^3]
  double cumulativeOutflow = 0;  ///< volume that has left the domain so far [m^3]
  double balanceError = 0;       ///< (volume + outflow + infiltrated - initial - rain) / (initial + rain), cumulative
  double kineticEnergy = 0;      ///< [J], grid phases and particles
  double energyReleased = 0;     ///< two-phase: potential energy released since the start [J]
  double frictionWork = 0;       ///< two-phase: work of friction and drag since the start [J]
  double particleMass = 0;       ///< mass of the particles in the domain [kg] (0 without particles)
};

/// What a finished run reports (also written to summary.json).
struct RunSummary {
  long long steps = 0;
  double simulatedSeconds = 0;
  double wallSeconds = 0;
  double cellUpdatesPerSecond = 0;     ///< domain cells x steps / wall time
  double initialVolume = 0, finalVolume = 0, totalOutflow = 0;
  double totalRain = 0, totalInfiltrated = 0;  ///< rain added and water infiltrated [m^3] (docs/sources.md)
  double totalEntrained = 0;           ///< bed material taken up by entrainment [m^3] (docs/entrainment.md)
  double volumeBalanceError = 0;       ///< (V_end + outflow + infiltrated - V_0 - rain) / (V_0 + rain)
  int checkpoints = 0;                 ///< checkpoints written by this process
};

/// How to open the output folder.
enum class OutputMode {
  New,        ///< refuse a folder that already holds a run
  Overwrite,  ///< replace a previous run in the folder
  Resume      ///< continue the run in the folder from its checkpoint.bin
};

class Simulation {
 public:
  /// Opens the device, builds the solver and prepares the output folder (outDir empty: the
  /// scene's). With OutputMode::Resume the state, counters and outputs so far come from the
  /// folder's checkpoint and the run continues bitwise as if it had never stopped.
  Simulation(const Scene& scene, const io::RunConfig& config, const std::string& outDir, OutputMode mode);
  /// Runs to the end time. Throws SimulationError (after writing the maxima so far, the summary
  /// and keeping the last checkpoint) when the health check fails. `onProgress` runs every step.
  /// Equivalent to begin(), stepOnce() until atEnd(), finish().
  RunSummary run(const std::function<void(const Progress&)>& onProgress = {});

  // Step-wise driving, for callers that own the loop (the desktop application pauses, single-steps
  // and stops between steps). The outputs are the same as run()'s: begin() writes the first report,
  // each stepOnce() the diagnostics row, reports and checkpoints that fall due, finish() the final
  // maps and summary.json.
  /// Starts the clock and writes the report at the start time (not when resuming). Call once.
  void begin();
  /// True when the simulated time has reached the end time.
  bool atEnd() const;
  /// Advances by one CFL step (clipped to the next report and the end time) and returns where the
  /// run stands. Throws SimulationError, after writing the outputs so far, when the health check fails.
  Progress stepOnce();
  /// Writes the final maps and summary.json and returns the summary. Before atEnd() this stops the
  /// run early: the outputs describe the state reached and summary.json says "status": "stopped".
  RunSummary finish();
  /// The particles of this run for viewers, or nullptr when the run has none.
  const ParticleView* particleView() const { return particles_.get(); }
  const Scene& scene() const { return scene_; }
  /// Steps taken so far (including those before a resume).
  long long steps() const { return steps_; }
  compute::Context& context() { return *ctx_; }
  flow::FlowSolver& solver() { return *solver_; }
  /// Simulated time the run starts (or resumes) from [s].
  double resumeTime() const { return solver_->time(); }
  /// The particles' cost, for the user to see before the run starts: count, sub-step and
  /// particle-updates per simulated second ("" without particles).
  std::string particleCost();

 private:
  void writeReport();
  /// Layers thinner than this have speed 0 in the speed maps (as in the maxima maps) [m].
  double speedThickness() const;
  void writeCheckpoint(double wallSeconds);
  /// How a run ended, as summary.json reports it.
  enum class Ending { Completed, Stopped, Failed };
  double wall() const;
  /// Relative volume balance error of a total volume, with the cumulative sources and sinks.
  double volumeBalance(double volume) const;
  RunSummary finalize(Ending ending);
  void writeFinal(const RunSummary& summary, Ending ending);
  /// Runs a write of the step loop; an IoError ends the run as failed (see the definition).
  void guardedWrite(const std::function<void()>& write);
  /// Runs a write of the final outputs, keeping the first IoError's message in `firstError`.
  void attemptWrite(const std::function<void()>& write, std::string& firstError);
  std::string summaryJson(const RunSummary& s, Ending ending) const;

  const Scene& scene_;
  const io::RunConfig& config_;
  std::unique_ptr<compute::Context> ctx_;
  std::unique_ptr<flow::FlowSolver> solver_;
  std::unique_ptr<OutputWriter> out_;
  std::unique_ptr<HealthCheck> health_;
  std::unique_ptr<ParticleRun> particles_;  ///< hybrid mode only
  std::size_t domainCells_ = 0;
  std::string failure_;
  bool fluidSeries_ = true;  ///< the scene can hold fluid: fluid series are written
  // Loop bookkeeping (restored on resume).
  long long steps_ = 0;
  int reportIndex_ = 0;
  double initialVolume_ = 0, totalOutflow_ = 0, wallBefore_ = 0;
  double totalRain_ = 0, totalInfiltrated_ = 0;  ///< cumulative sources and sinks of the water [m^3]
  /// Erodible volume at the start of the run (entrainment): the volume entrained so far is this minus
  /// what is left (FlowDiagnostics::erodible), a source of the volume balance.
  double initialErodible_ = 0;
  double totalEntrained() const;
  double initialPotential_ = 0, initialMechanical_ = 0;  ///< two-phase energy at the initial state [J]
  double lastReleased_ = 0, lastLost_ = 0;              ///< energy columns of the last step [J]
  double totalSourceWork_ = 0;  ///< two-phase: work of friction and drag since the start [J] (restored on resume)
  std::string seriesIndex_ = "index,time_s,h_file,v_file\n";
  int checkpoints_ = 0;
  // State of the step-wise loop (begin() .. finish()).
  bool begun_ = false, finished_ = false;
  double peakKinetic_ = 0;  ///< largest kinetic energy so far [J] (Stop At Rest Fraction)
  bool atRest_ = false;     ///< the kinetic energy fell below Stop At Rest Fraction of its peak
  std::chrono::steady_clock::time_point start_;
  double nextReport_ = 0, nextCheckpoint_ = 0, lastCheckpointWall_ = 0;
};

}  // namespace talus::sim
