// Small driver for the shallow-water verification tests: builds a FlowInput on Grid::make(nx, ny, dx)
// from functions of position, runs a FlowSolver to a final time and/or a step count with
// dt = min(stableDt, T - t), and returns the fields, the step count, the volume balance and the
// wall time of the stepping loop.
//
// Coordinates: the tests work in the solver's frame, x = (i + 1/2) dx along columns and
// y = (j + 1/2) dx along rows (the solver's y index, see core/Grid.hpp), with qy the discharge in
// +j. This is the frame in which the solver integrates the equations, so analytic solutions are
// evaluated directly in it (the north-up georeference would only mirror y).
#pragma once
#include <functional>
#include <limits>
#include <vector>

#include "compute/Precision.hpp"
#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/FlowSolver.hpp"

namespace talus::test {

/// A field as a function of the cell centre (x, y) in the solver's frame.
using Field = std::function<double(double x, double y)>;

/// Cell-centre coordinates of the solver's frame.
inline double cellX(const Grid& g, int i) { return (i + 0.5) * g.dx; }
inline double cellY(const Grid& g, int j) { return (j + 0.5) * g.dx; }

/// Samples the fields at the cell centres: mask all 1, Manning `manning` everywhere; `qx`, `qy`
/// may be empty (water at rest).
flow::FlowInput makeInput(const Grid& grid, const Field& bed, const Field& h, const Field& qx = {},
                          const Field& qy = {}, double manning = 0.0);

/// A rough DEM for well-balancing and conservation tests: two smooth hill patterns of amplitude
/// 0.8 m and 0.4 m across the grid plus per-cell uniform noise in [-noise, noise] from a fixed
/// std::mt19937 seed, so every run of the suite (with one standard library) sees the same bed.
std::vector<double> roughDem(const Grid& grid, unsigned seed, double noise = 0.5);

/// When a run stops: at `endTime` (the last step is shortened to land on it) or after `maxSteps`
/// steps, whichever comes first.
struct RunLimits {
  double endTime = std::numeric_limits<double>::infinity();
  int maxSteps = std::numeric_limits<int>::max();

  static RunLimits until(double t) {
    RunLimits r;
    r.endTime = t;
    return r;
  }
  static RunLimits steps(int n) {
    RunLimits r;
    r.maxSteps = n;
    return r;
  }
};

/// Everything a test needs from a finished run.
struct FlowRun {
  Grid grid;
  std::vector<double> bed, h, qx, qy;  ///< final fields (bed as given)
  double time = 0;                     ///< simulated time reached [s]
  int steps = 0;
  double volume0 = 0;                  ///< diagnostics().volume after setInput [m^3]
  double volume = 0;                   ///< diagnostics().volume after the last step [m^3]
  double outflow = 0;                  ///< sum over steps of diagnostics().outflow [m^3]
  double wallSeconds = 0;              ///< wall time of the stepping loop (excludes kernel builds)

  /// u = q / h where h > hDry (the solver's velocity there), 0 elsewhere.
  std::vector<double> velocityX(double hDry) const;
  std::vector<double> velocityY(double hDry) const;
};

/// Runs `input` on `grid` with `settings` until `limits` on the shared test device
/// (support/TestDevice.hpp, which fails loudly without a device); `onStep` (optional) sees the
/// solver after every step.
FlowRun runFlow(const Grid& grid, const flow::FlowInput& input, const flow::FlowSettings& settings,
                const RunLimits& limits, compute::Precision precision = compute::Precision::Double,
                const std::function<void(const flow::FlowSolver&)>& onStep = {});

}  // namespace talus::test
