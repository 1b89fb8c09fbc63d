#include "flow/FlowSettings.hpp"

#include "core/Error.hpp"

namespace talus::flow {

Limiter parseLimiter(const std::string& name) {
  if (name == "minmod") return Limiter::Minmod;
  if (name == "vanleer") return Limiter::VanLeer;
  if (name == "mc") return Limiter::MC;
  if (name == "none") return Limiter::None;
  throw InputError("limiter '" + name + "' is not one of: minmod, vanleer, mc, none");
}

RiemannSolver parseRiemann(const std::string& name) {
  if (name == "hll") return RiemannSolver::HLL;
  if (name == "hllc") return RiemannSolver::HLLC;
  throw InputError("Riemann solver '" + name + "' is not one of: hll, hllc");
}

Boundary parseBoundary(const std::string& name) {
  if (name == "wall") return Boundary::Wall;
  if (name == "open") return Boundary::Open;
  if (name == "level") return Boundary::Level;
  throw InputError("boundary type '" + name + "' is not one of: open, wall, level");
}

DepthPressure parseDepthPressure(const std::string& name) {
  if (name == "cos2") return DepthPressure::Cos2;
  if (name == "cos4") return DepthPressure::Cos4;
  throw InputError("depth pressure '" + name + "' is not one of: cos2, cos4");
}

EarthPressure parseEarthPressure(const std::string& name) {
  if (name == "savage-hutter") return EarthPressure::SavageHutter;
  if (name == "constant") return EarthPressure::Constant;
  throw InputError("earth pressure '" + name + "' is not one of: savage-hutter, constant");
}

DragLaw parseDragLaw(const std::string& name) {
  if (name == "off") return DragLaw::Off;
  if (name == "linear") return DragLaw::Linear;
  if (name == "quadratic") return DragLaw::Quadratic;
  throw InputError("drag law '" + name + "' is not one of: off, linear, quadratic");
}

TimeScheme parseTimeScheme(const std::string& name) {
  if (name == "unsplit") return TimeScheme::Unsplit;
  if (name == "split") return TimeScheme::Split;
  if (name == "hancock") return TimeScheme::Hancock;
  throw InputError("time scheme '" + name + "' is not one of: unsplit, split, hancock");
}

}  // namespace talus::flow
