#include "compute/Device.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

#include "compute/ClError.hpp"
#include "core/Error.hpp"
#include "core/Text.hpp"

namespace talus::compute {
namespace {

std::string deviceString(cl_device_id d, cl_device_info what) {
  size_t size = 0;
  clGetDeviceInfo(d, what, 0, nullptr, &size);
  std::string s(size, '\0');
  clGetDeviceInfo(d, what, size, s.data(), nullptr);
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string platformString(cl_platform_id p, cl_platform_info what) {
  size_t size = 0;
  clGetPlatformInfo(p, what, 0, nullptr, &size);
  std::string s(size, '\0');
  clGetPlatformInfo(p, what, size, s.data(), nullptr);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

}  // namespace

std::string DeviceInfo::describe() const {
  std::ostringstream o;
  o << "[" << index << "] " << name << " (" << platformName << ", " << (isGpu ? "GPU" : "CPU") << ", "
    << computeUnits << " CUs, " << (globalMemory >> 20) << " MiB" << (hasDouble ? ", fp64" : "")
    << (hasGlSharing ? ", gl_sharing" : "") << ")";
  return o.str();
}

std::vector<DeviceInfo> listDevices() {
  std::vector<DeviceInfo> out;
  cl_uint nPlatforms = 0;
  if (clGetPlatformIDs(0, nullptr, &nPlatforms) != CL_SUCCESS || nPlatforms == 0) return out;
  std::vector<cl_platform_id> platforms(nPlatforms);
  clGetPlatformIDs(nPlatforms, platforms.data(), nullptr);
  for (cl_platform_id p : platforms) {
    cl_uint nDevices = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nDevices) != CL_SUCCESS) continue;
    std::vector<cl_device_id> devices(nDevices);
    clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nDevices, devices.data(), nullptr);
    for (cl_device_id d : devices) {
      DeviceInfo info;
      info.platform = p;
      info.id = d;
      info.index = static_cast<int>(out.size());
      info.name = deviceString(d, CL_DEVICE_NAME);
      info.vendor = deviceString(d, CL_DEVICE_VENDOR);
      info.version = deviceString(d, CL_DEVICE_VERSION);
      info.platformName = platformString(p, CL_PLATFORM_NAME);
      cl_device_type type = 0;
      clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof(type), &type, nullptr);
      info.isGpu = (type & CL_DEVICE_TYPE_GPU) != 0;
      const std::string ext = deviceString(d, CL_DEVICE_EXTENSIONS);
      info.hasDouble = ext.find("cl_khr_fp64") != std::string::npos;
      info.hasGlSharing = ext.find("cl_khr_gl_sharing") != std::string::npos;
      clGetDeviceInfo(d, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof(info.computeUnits), &info.computeUnits, nullptr);
      cl_ulong mem = 0;
      clGetDeviceInfo(d, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof(mem), &mem, nullptr);
      info.globalMemory = mem;
      clGetDeviceInfo(d, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof(info.maxWorkGroupSize),
                      &info.maxWorkGroupSize, nullptr);
      out.push_back(info);
    }
  }
  return out;
}

DeviceInfo selectDevice(const std::string& selectorIn) {
  std::string selector = selectorIn;
  if (selector.empty()) {
    if (const char* env = std::getenv("TALUS_DEVICE")) selector = env;
  }
  const std::vector<DeviceInfo> devices = listDevices();
  if (devices.empty())
    throw ComputeError(
        "no OpenCL device found: install an OpenCL driver (on Debian: apt-get install pocl-opencl-icd "
        "for the CPU, or your GPU vendor's ICD)");
  if (selector.empty()) {
    for (const DeviceInfo& d : devices)
      if (d.isGpu) return d;
    return devices.front();
  }
  const bool numeric = std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); });
  if (numeric) {
    const int k = std::atoi(selector.c_str());
    if (k >= 0 && k < static_cast<int>(devices.size())) return devices[k];
  } else {
    const std::string s = lower(selector);
    for (const DeviceInfo& d : devices) {
      if ((s == "gpu" && d.isGpu) || (s == "cpu" && !d.isGpu)) return d;
      if (lower(d.name).find(s) != std::string::npos || lower(d.platformName).find(s) != std::string::npos)
        return d;
    }
  }
  std::ostringstream o;
  o << "no OpenCL device matches '" << selector << "'"
    << (selectorIn.empty() ? " (from TALUS_DEVICE)" : "") << "; available devices:";
  for (const DeviceInfo& d : devices) o << "\n  " << d.describe();
  throw ComputeError(o.str());
}

}  // namespace talus::compute
