// The per-step health check of a run (guarded runs): non-finite values, negative thickness, a step
// that broke the CFL condition, and flow speeds no energy in the scene can explain. A failed check
// names the time, the cell (column, row, world x/y) and the quantity it found wrong.
#pragma once
#include <string>

#include "core/Raster.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/FlowSolver.hpp"

namespace talus::sim {

class HealthCheck {
 public:
  /// Derives the speed bound from the scene (see speedBound()).
  HealthCheck(const Raster& dem, const flow::FlowInput& input, const flow::FlowSettings& settings);
  /// "" when the step that just ended with time step dt is healthy, else the diagnosis.
  std::string check(const flow::FlowSolver& solver, double dt) const;
  /// The largest material speed the scene's energy allows:
  ///   v_max = sqrt(2 g Z) + 2 sqrt(g K_max H_max) + v_0,
  /// Z the fall from the highest initial surface to the lowest bed (a frictionless fall over the whole
  /// relief), H_max the thickest initial column, K_max the largest earth-pressure coefficient the
  /// scene can use (1 for water), 2 sqrt(g K H) the fastest front a collapsing column drives (Ritter's
  /// simple wave, the whole pressure work of the release in the front's kinetic energy) and v_0 the
  /// fastest initial speed. v^2 <= 2 g Z + 4 g K H + ... and sqrt(a + b) <= sqrt(a) + sqrt(b), so the
  /// sum bounds every combination of fall and release; friction, drag and viscosity only take away.
  double speedBound() const { return speedBound_; }

 private:
  std::string locate(const flow::FlowSolver& solver, const char* what) const;
  Grid grid_;
  double speedBound_ = 0;
  double cfl_ = 0.5;
  double hDry_ = 0;
};

}  // namespace talus::sim
