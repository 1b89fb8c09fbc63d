// One OpenCL kernel: arguments bound once (by position, in declaration order), launched by name.
#pragma once
#include <CL/cl.h>

#include <cstddef>
#include <string>

#include "compute/Buffer.hpp"

namespace talus::compute {

class Program;
class Context;

/// A kernel argument that is a scalar of the kernels' `real` type (float or double).
struct RealArg {
  double value;
};

/// Global/local NDRange of up to two dimensions. A zero local size lets the driver choose.
struct Range {
  std::size_t x = 1, y = 0;
  std::size_t dims() const { return y == 0 ? 1 : 2; }
};

class Kernel {
 public:
  Kernel() = default;
  Kernel(Program& program, const std::string& name);
  ~Kernel();
  Kernel(Kernel&& o) noexcept;
  Kernel& operator=(Kernel&& o) noexcept;
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;

  /// Binds all arguments in order; call again only for those that change (setArg).
  template <class... Args>
  Kernel& bind(const Args&... args) {
    cl_uint i = 0;
    (setArg(i++, args), ...);
    return *this;
  }
  Kernel& setArg(cl_uint i, const RawBuffer& b) { return setMem(i, b.mem()); }
  Kernel& setArg(cl_uint i, const RealBuffer& b) { return setMem(i, b.mem()); }
  template <class T>
  Kernel& setArg(cl_uint i, const Buffer<T>& b) { return setMem(i, b.mem()); }
  Kernel& setArg(cl_uint i, RealArg r);
  Kernel& setArg(cl_uint i, int v) { return setBytes(i, &v, sizeof v); }
  Kernel& setArg(cl_uint i, unsigned v) { return setBytes(i, &v, sizeof v); }
  /// Local memory of `bytes` bytes.
  Kernel& setLocal(cl_uint i, std::size_t bytes);

  /// Enqueues the kernel. The global size is rounded up to a multiple of the local size (kernels
  /// check their bounds). Timed under the kernel's name (or `label`) in the context's profiler.
  void launch(Range global, Range local = {0, 0}, const char* label = nullptr);
  const std::string& name() const { return name_; }

 private:
  Kernel& setMem(cl_uint i, cl_mem m);
  Kernel& setBytes(cl_uint i, const void* p, std::size_t n);
  Context* ctx_ = nullptr;
  cl_kernel kernel_ = nullptr;
  std::string name_;
  std::string file_;
};

/// Rounds n up to a multiple of m.
inline std::size_t roundUp(std::size_t n, std::size_t m) { return m == 0 ? n : ((n + m - 1) / m) * m; }

}  // namespace talus::compute
