#include "compute/Precision.hpp"

#include "core/Error.hpp"

namespace talus::compute {

Precision parsePrecision(const std::string& name) {
  if (name == "float" || name == "single") return Precision::Float;
  if (name == "double") return Precision::Double;
  throw InputError("precision '" + name + "' is not one of: float, double");
}

std::string precisionBuildOptions(Precision p) {
  return p == Precision::Double ? "-DTALUS_DOUBLE=1" : "-DTALUS_DOUBLE=0";
}

}  // namespace talus::compute
