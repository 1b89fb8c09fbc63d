// Error types of the engine. Every error a user can cause names the file, key, line or cell at fault.
#pragma once
#include <stdexcept>
#include <string>

namespace talus {

/// An error caused by input or configuration (bad run-file, raster, parameter). Exit status 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// An error from the compute runtime (OpenCL device, kernel build, launch). Exit status 3.
class ComputeError : public std::runtime_error {
 public:
  explicit ComputeError(const std::string& what) : std::runtime_error(what) {}
};

/// An error of the file system while writing outputs (full disk, no permission, quota, a file size
/// limit), with the system's reason. Exit status 5: the input was fine, the machine was not.
class IoError : public std::runtime_error {
 public:
  explicit IoError(const std::string& what) : std::runtime_error(what) {}
};

/// A simulation that became unphysical (NaN, negative thickness, runaway). Exit status 4.
class SimulationError : public std::runtime_error {
 public:
  explicit SimulationError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace talus
