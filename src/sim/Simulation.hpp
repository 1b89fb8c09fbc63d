// The time loop of a run: CFL step clipped to report times, per-step diagnostics and health check,
// maps at report times, and the final maps, CSV and JSON summary (spec §7-§8).
#pragma once
#include <functional>
#include <memory>
#include <string>

#include "compute/Context.hpp"
#include "flow/FlowSolver.hpp"
#include "io/RunConfig.hpp"
#include "sim/OutputWriter.hpp"
#include "sim/Scene.hpp"

namespace talus::sim {

/// Where a run stands, handed to the progress callback after every step.
struct Progress {
  double time = 0, startTime = 0, endTime = 0;  ///< simulated [s]
  long long steps = 0;
  double wallSeconds = 0;
  double dt = 0;
  const flow::FlowDiagnostics* diagnostics = nullptr;
};

/// What a finished run reports (also written to summary.json).
struct RunSummary {
  long long steps = 0;
  double simulatedSeconds = 0;
  double wallSeconds = 0;
  double cellUpdatesPerSecond = 0;     ///< domain cells x steps / wall time
  double initialVolume = 0, finalVolume = 0, totalOutflow = 0;
  double volumeBalanceError = 0;       ///< (V_end + outflow - V_0) / V_0
};

class Simulation {
 public:
  /// Opens the device, builds the solver and prepares the output folder.
  Simulation(const Scene& scene, const io::RunConfig& config, const std::string& outDir, bool overwrite);
  /// Runs to the end time. Throws SimulationError (after writing what it has) when the state becomes
  /// unphysical. `onProgress` is called after every step.
  RunSummary run(const std::function<void(const Progress&)>& onProgress = {});
  compute::Context& context() { return *ctx_; }
  flow::FlowSolver& solver() { return *solver_; }

 private:
  void writeReport(int index);
  void writeFinal(const RunSummary& summary, bool failed);
  void checkHealth(long long step, double dt);
  std::string summaryJson(const RunSummary& s, bool failed) const;

  const Scene& scene_;
  const io::RunConfig& config_;
  std::unique_ptr<compute::Context> ctx_;
  std::unique_ptr<flow::FlowSolver> solver_;
  std::unique_ptr<OutputWriter> out_;
  std::size_t domainCells_ = 0;
  std::string failure_;
  std::string seriesIndex_ = "index,time_s,h_file,v_file\n";
};

}  // namespace talus::sim
