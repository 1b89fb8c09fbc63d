#include "compute/Buffer.hpp"

#include <string>

#include "compute/Context.hpp"
#include "core/Error.hpp"

namespace talus::compute {

RawBuffer::RawBuffer(Context& ctx, std::size_t bytes, const char* label) : bytes_(bytes), queue_(ctx.queue()) {
  cl_int status = CL_SUCCESS;
  // OpenCL rejects zero-sized buffers; keep one element so empty fields stay valid arguments.
  mem_ = clCreateBuffer(ctx.context(), CL_MEM_READ_WRITE, bytes == 0 ? 16 : bytes, nullptr, &status);
  clCheck(status, std::string("allocating ") + label + " (" + std::to_string(bytes) + " bytes)");
}

void RawBuffer::reset() {
  if (mem_) clReleaseMemObject(mem_);
  mem_ = nullptr;
  bytes_ = 0;
}

void RawBuffer::writeBytes(const void* src, std::size_t bytes, std::size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > bytes_) throw ComputeError("buffer write past the end of the buffer");
  clCheck(clEnqueueWriteBuffer(queue_, mem_, CL_TRUE, offset, bytes, src, 0, nullptr, nullptr), "writing buffer");
}

void RawBuffer::readBytes(void* dst, std::size_t bytes, std::size_t offset) const {
  if (bytes == 0) return;
  if (offset + bytes > bytes_) throw ComputeError("buffer read past the end of the buffer");
  clCheck(clEnqueueReadBuffer(queue_, mem_, CL_TRUE, offset, bytes, dst, 0, nullptr, nullptr), "reading buffer");
}

void RawBuffer::fillBytes(const void* pattern, std::size_t patternBytes) {
  if (bytes_ == 0) return;
  clCheck(clEnqueueFillBuffer(queue_, mem_, pattern, patternBytes, 0, bytes_, 0, nullptr, nullptr),
          "filling buffer");
}

void RawBuffer::copyFrom(const RawBuffer& src) {
  if (src.bytes_ != bytes_) throw ComputeError("buffer copy between buffers of different sizes");
  if (bytes_ == 0) return;
  clCheck(clEnqueueCopyBuffer(queue_, src.mem_, mem_, 0, 0, bytes_, 0, nullptr, nullptr), "copying buffer");
}

RealBuffer::RealBuffer(Context& ctx, std::size_t n, const char* label)
    : raw_(ctx, n * realSize(ctx.precision()), label), n_(n), precision_(ctx.precision()) {}

void RealBuffer::upload(const std::vector<double>& v) {
  if (v.size() != n_) throw ComputeError("upload of " + std::to_string(v.size()) + " values into a buffer of " +
                                         std::to_string(n_));
  if (precision_ == Precision::Double) {
    raw_.writeBytes(v.data(), n_ * sizeof(double));
  } else {
    std::vector<float> f(v.begin(), v.end());
    raw_.writeBytes(f.data(), n_ * sizeof(float));
  }
}

std::vector<double> RealBuffer::download() const {
  if (precision_ == Precision::Double) {
    std::vector<double> v(n_);
    raw_.readBytes(v.data(), n_ * sizeof(double));
    return v;
  }
  std::vector<float> f(n_);
  raw_.readBytes(f.data(), n_ * sizeof(float));
  return std::vector<double>(f.begin(), f.end());
}

void RealBuffer::fill(double value) {
  if (precision_ == Precision::Double) {
    raw_.fillBytes(&value, sizeof(double));
  } else {
    const float f = static_cast<float>(value);
    raw_.fillBytes(&f, sizeof(float));
  }
}

}  // namespace talus::compute
