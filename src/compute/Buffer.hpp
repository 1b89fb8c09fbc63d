// Owned device buffers: RawBuffer (bytes), Buffer<T> (a host type), RealBuffer (the kernels' `real`).
#pragma once
#include <CL/cl.h>

#include <cstddef>
#include <utility>
#include <vector>

#include "compute/ClError.hpp"
#include "compute/Precision.hpp"

namespace talus::compute {

class Context;

/// A device allocation that releases itself. Move-only.
class RawBuffer {
 public:
  RawBuffer() = default;
  RawBuffer(Context& ctx, std::size_t bytes, const char* label = "buffer");
  ~RawBuffer() { reset(); }
  RawBuffer(RawBuffer&& o) noexcept { *this = std::move(o); }
  RawBuffer& operator=(RawBuffer&& o) noexcept {
    if (this != &o) {
      reset();
      std::swap(mem_, o.mem_);
      std::swap(bytes_, o.bytes_);
      std::swap(queue_, o.queue_);
    }
    return *this;
  }
  RawBuffer(const RawBuffer&) = delete;
  RawBuffer& operator=(const RawBuffer&) = delete;

  cl_mem mem() const { return mem_; }
  std::size_t bytes() const { return bytes_; }
  bool empty() const { return mem_ == nullptr; }

  void writeBytes(const void* src, std::size_t bytes, std::size_t offset = 0);
  void readBytes(void* dst, std::size_t bytes, std::size_t offset = 0) const;
  /// Sets every byte pattern-wise to `pattern` (patternBytes long).
  void fillBytes(const void* pattern, std::size_t patternBytes);
  /// Device-side copy of all of `src` (same size) into this buffer.
  void copyFrom(const RawBuffer& src);

 private:
  void reset();
  cl_mem mem_ = nullptr;
  std::size_t bytes_ = 0;
  cl_command_queue queue_ = nullptr;
};

/// A device array of a fixed host type T (int, unsigned char, float, double, ...).
template <class T>
class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& ctx, std::size_t n, const char* label = "buffer") : raw_(ctx, n * sizeof(T), label), n_(n) {}
  std::size_t size() const { return n_; }
  cl_mem mem() const { return raw_.mem(); }
  void write(const std::vector<T>& v) { raw_.writeBytes(v.data(), v.size() * sizeof(T)); }
  std::vector<T> read() const {
    std::vector<T> v(n_);
    raw_.readBytes(v.data(), n_ * sizeof(T));
    return v;
  }
  void fill(const T& value) { raw_.fillBytes(&value, sizeof(T)); }
  RawBuffer& raw() { return raw_; }
  const RawBuffer& raw() const { return raw_; }

 private:
  RawBuffer raw_;
  std::size_t n_ = 0;
};

/// A device array of the kernels' `real` (float or double by the run's precision). The host side
/// always speaks double; conversion happens on upload and download.
class RealBuffer {
 public:
  RealBuffer() = default;
  RealBuffer(Context& ctx, std::size_t n, const char* label = "real buffer");
  std::size_t size() const { return n_; }
  cl_mem mem() const { return raw_.mem(); }
  Precision precision() const { return precision_; }
  void upload(const std::vector<double>& v);
  std::vector<double> download() const;
  void fill(double value);
  void copyFrom(const RealBuffer& src) { raw_.copyFrom(src.raw_); }
  RawBuffer& raw() { return raw_; }
  const RawBuffer& raw() const { return raw_; }

 private:
  RawBuffer raw_;
  std::size_t n_ = 0;
  Precision precision_ = Precision::Float;
};

}  // namespace talus::compute
