// A built OpenCL program and its kernels, with an on-disk binary cache.
#pragma once
#include <CL/cl.h>

#include <string>

namespace talus::compute {

class Context;
class Kernel;

class Program {
 public:
  /// Builds `source` (the expanded text of kernels/<file>) with `options`. Loads a cached binary
  /// when one exists for the same source, device, driver and options (folder: TALUS_CACHE_DIR, else
  /// $XDG_CACHE_HOME/talus or ~/.cache/talus; TALUS_CACHE_DIR=off disables it).
  Program(Context& ctx, const std::string& file, const std::string& source, const std::string& options);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  cl_program handle() const { return program_; }
  const std::string& file() const { return file_; }
  const std::string& options() const { return options_; }
  Context& context() const { return ctx_; }
  /// True when this program came from the binary cache.
  bool fromCache() const { return fromCache_; }

 private:
  bool tryLoadBinary(const std::string& path);
  void buildFromSource(const std::string& source);
  void saveBinary(const std::string& path) const;
  Context& ctx_;
  std::string file_;
  std::string options_;
  cl_program program_ = nullptr;
  bool fromCache_ = false;
};

}  // namespace talus::compute
