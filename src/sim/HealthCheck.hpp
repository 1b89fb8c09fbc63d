// The per-step health check of a run (guarded runs): non-finite values, negative thickness, a step
// that broke the CFL condition, and speeds no energy in the scene can explain. A failed check names
// the time, the cell (column, row, world x/y) and the quantity.
#pragma once
#include <string>

#include "core/Raster.hpp"
#include "flow/FlowSolver.hpp"

namespace talus::sim {

class HealthCheck {
 public:
  /// Derives the speed limit from the scene: with Z the fall from the highest initial water surface
  /// to the lowest bed, no flow is faster than v = sqrt(2 g Z) (energy bound) and no water deeper
  /// than Z, so the wave-speed measure (|u| + |v| + 2c) may not exceed 2 sqrt(2) v + 2 sqrt(g Z) plus
  /// twice the initial speeds. Exceeding it means the numerics created energy.
  HealthCheck(const Raster& dem, const flow::FlowInput& input, double cfl);
  /// "" when the step that just ended with time step dt is healthy, else the diagnosis.
  std::string check(const flow::FlowSolver& solver, double dt) const;
  double speedLimit() const { return speedLimit_; }

 private:
  std::string locate(const flow::FlowSolver& solver, const char* what) const;
  Grid grid_;
  double speedLimit_ = 0;
  double cfl_ = 0.5;
};

}  // namespace talus::sim
