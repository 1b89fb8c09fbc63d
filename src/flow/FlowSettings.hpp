// Numerical and physical options of the shallow-water solver, with their run-file defaults.
#pragma once
#include <string>

namespace talus::flow {

/// Slope limiter of the MUSCL reconstruction; None gives the first-order scheme (for comparisons).
enum class Limiter { Minmod = 0, VanLeer = 1, MC = 2, None = 3 };
enum class RiemannSolver { HLL = 0, HLLC = 1 };
enum class Boundary { Wall = 0, Open = 1 };
enum class DepthPressure { Cos2, Cos4 };

struct FlowSettings {
  Limiter limiter = Limiter::VanLeer;
  RiemannSolver riemann = RiemannSolver::HLLC;
  double cfl = 0.5;                 ///< dt = cfl * dx / max((|u| + c) + (|v| + c))
  double hDry = 1e-6;               ///< [m] below this, velocities are zero
  double arrivalH = 0.01;           ///< [m] thickness that marks arrival
  Boundary edge = Boundary::Open;   ///< raster edge
  Boundary nodata = Boundary::Wall; ///< faces to nodata cells
  bool skipDryTiles = true;         ///< skip tiles with no water within one tile
  bool slopeCorrection = true;      ///< g_n = g cos^2(theta) (spec §1); off: g everywhere
  DepthPressure depthPressure = DepthPressure::Cos2;  ///< g_p = g cos^2 (default) or g cos^4
};

Limiter parseLimiter(const std::string& name);
RiemannSolver parseRiemann(const std::string& name);
Boundary parseBoundary(const std::string& name);
DepthPressure parseDepthPressure(const std::string& name);

}  // namespace talus::flow
