#include "compute/Program.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "compute/ClError.hpp"
#include "compute/Context.hpp"
#include "core/Error.hpp"

namespace talus::compute {
namespace {

/// 64-bit FNV-1a: a stable key for the cache file name (not security relevant).
unsigned long long fnv1a(const std::string& s) {
  unsigned long long h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string cacheFolder() {
  if (const char* dir = std::getenv("TALUS_CACHE_DIR")) return std::string(dir) == "off" ? "" : dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME")) return std::string(xdg) + "/talus";
  if (const char* home = std::getenv("HOME")) return std::string(home) + "/.cache/talus";
  return "";
}

std::string buildLog(cl_program program, cl_device_id device) {
  size_t size = 0;
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
  std::string log(size, '\0');
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

}  // namespace

Program::Program(Context& ctx, const std::string& file, const std::string& source, const std::string& options)
    : ctx_(ctx), file_(file), options_(options) {
  const std::string folder = cacheFolder();
  std::string cachePath;
  if (!folder.empty()) {
    const DeviceInfo& d = ctx.device();
    char name[64];
    std::snprintf(name, sizeof name, "%016llx.clbin",
                  fnv1a(source + "\n" + options + "\n" + d.name + "\n" + d.platformName + "\n" + d.version));
    cachePath = folder + "/" + name;
    if (tryLoadBinary(cachePath)) {
      fromCache_ = true;
      return;
    }
  }
  buildFromSource(source);
  if (!cachePath.empty()) saveBinary(cachePath);
}

Program::~Program() {
  if (program_) clReleaseProgram(program_);
}

bool Program::tryLoadBinary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) return false;
  const unsigned char* ptr = bytes.data();
  const size_t size = bytes.size();
  cl_int binaryStatus = CL_SUCCESS, status = CL_SUCCESS;
  cl_device_id device = ctx_.device().id;
  cl_program p = clCreateProgramWithBinary(ctx_.context(), 1, &device, &size, &ptr, &binaryStatus, &status);
  if (status != CL_SUCCESS || binaryStatus != CL_SUCCESS) {
    if (p) clReleaseProgram(p);
    return false;
  }
  if (clBuildProgram(p, 1, &device, options_.c_str(), nullptr, nullptr) != CL_SUCCESS) {
    clReleaseProgram(p);
    return false;  // stale or foreign binary: rebuild from source
  }
  program_ = p;
  return true;
}

void Program::buildFromSource(const std::string& source) {
  cl_int status = CL_SUCCESS;
  const char* text = source.c_str();
  const size_t length = source.size();
  program_ = clCreateProgramWithSource(ctx_.context(), 1, &text, &length, &status);
  clCheck(status, "creating program from kernels/" + file_);
  cl_device_id device = ctx_.device().id;
  status = clBuildProgram(program_, 1, &device, options_.c_str(), nullptr, nullptr);
  if (status != CL_SUCCESS) {
    std::ostringstream o;
    o << "building kernels/" << file_ << " for '" << ctx_.device().name << "' failed (" << clErrorText(status)
      << ")\n  options: " << options_ << "\n  build log:\n" << buildLog(program_, device);
    throw ComputeError(o.str());
  }
  // The device compiler's warnings, with their text: some drivers (PoCL) print only a count
  // ("2 warnings generated.") themselves. Our kernels build without warnings (the kernel tests check
  // every variant), so any text here is news for whoever reads the log.
  const std::string log = buildLog(program_, device);
  if (log.find("warning") != std::string::npos)
    std::fprintf(stderr, "talus: device compiler warnings in kernels/%s (options %s):\n%s\n", file_.c_str(),
                 options_.c_str(), log.c_str());
}

void Program::saveBinary(const std::string& path) const {
  size_t size = 0;
  if (clGetProgramInfo(program_, CL_PROGRAM_BINARY_SIZES, sizeof(size), &size, nullptr) != CL_SUCCESS || size == 0)
    return;
  std::vector<unsigned char> bytes(size);
  unsigned char* ptr = bytes.data();
  if (clGetProgramInfo(program_, CL_PROGRAM_BINARIES, sizeof(ptr), &ptr, nullptr) != CL_SUCCESS) return;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  // Write-then-rename so concurrent test processes never read a half-written binary.
  const std::string tmp = path + ".tmp" + std::to_string(std::rand());
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) return;
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(size));
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace talus::compute
