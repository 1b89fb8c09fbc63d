// Floating-point precision of the kernels: a run option (float or double), fixed per program build.
#pragma once
#include <cstddef>
#include <string>

namespace talus::compute {

enum class Precision { Float, Double };

inline std::size_t realSize(Precision p) { return p == Precision::Double ? sizeof(double) : sizeof(float); }
inline const char* precisionName(Precision p) { return p == Precision::Double ? "double" : "float"; }
/// Parses "float"/"single"/"double" (throws talus::InputError otherwise).
Precision parsePrecision(const std::string& name);
/// Build options that define the kernels' `real` type: -DREAL=float|double and TALUS_DOUBLE.
std::string precisionBuildOptions(Precision p);

}  // namespace talus::compute
