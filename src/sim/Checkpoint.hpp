// Checkpoints of a run: the solver state (raw device bytes, so a resumed run continues bitwise)
// and the loop's bookkeeping, written atomically to OUTDIR/checkpoint.bin.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace talus::sim {

struct Checkpoint {
  std::string precision;        ///< "float" or "double": must match the resuming run
  int32_t nx = 0, ny = 0;
  double time = 0;              ///< simulated time [s]
  int64_t steps = 0;            ///< steps done (= data rows in diagnostics.csv)
  int32_t reportIndex = 0;      ///< next series map index
  double initialVolume = 0, totalOutflow = 0;
  double totalRain = 0, totalInfiltrated = 0;  ///< cumulative sources and sinks [m^3] (version 3; 0 before)
  double totalSourceWork = 0;   ///< two-phase: work of friction and drag so far [J] (version 4; 0 before)
  double elapsedWall = 0;       ///< wall seconds spent before the checkpoint
  std::string seriesIndex;      ///< contents of series/index.csv so far
  std::vector<char> state;      ///< FlowSolver::saveState()
  std::vector<char> particleState;  ///< ParticleRun::saveState() (empty: a run without particles)
};

/// Writes `c` to `path` atomically (temporary file in the same folder, then rename).
void writeCheckpoint(const std::string& path, const Checkpoint& c);
/// Reads a checkpoint; throws InputError naming the file when it is missing, truncated or foreign.
Checkpoint readCheckpoint(const std::string& path);

}  // namespace talus::sim
