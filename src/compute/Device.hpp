// OpenCL platform and device discovery, and the choice of the device a run uses.
#pragma once
#include <CL/cl.h>

#include <string>
#include <vector>

namespace talus::compute {

/// What Talus needs to know about one OpenCL device.
struct DeviceInfo {
  cl_platform_id platform = nullptr;
  cl_device_id id = nullptr;
  int index = 0;                 ///< position in listDevices(), the number `--device N` selects
  std::string name;
  std::string platformName;
  std::string vendor;
  std::string version;
  bool isGpu = false;
  bool hasDouble = false;        ///< cl_khr_fp64
  bool hasGlSharing = false;     ///< cl_khr_gl_sharing
  unsigned computeUnits = 0;
  unsigned long long globalMemory = 0;  ///< bytes
  std::size_t maxWorkGroupSize = 0;

  /// One line: "[0] NAME (PLATFORM, GPU|CPU, N CUs, M MiB, fp64)".
  std::string describe() const;
};

/// Every device of every platform; empty when no OpenCL platform is installed.
std::vector<DeviceInfo> listDevices();

/// Chooses a device. `selector`: empty = automatic (first GPU, else the first device), a number =
/// that index in listDevices(), otherwise a case-insensitive substring of the device or platform
/// name ("pocl", "nvidia", "cpu", "gpu"). When `selector` is empty, the environment variable
/// TALUS_DEVICE is used if set. Throws ComputeError listing the devices when nothing matches.
DeviceInfo selectDevice(const std::string& selector);

}  // namespace talus::compute
