#include "compute/Kernel.hpp"

#include <utility>

#include "compute/ClError.hpp"
#include "compute/Context.hpp"
#include "compute/Program.hpp"

namespace talus::compute {

Kernel::Kernel(Program& program, const std::string& name)
    : ctx_(&program.context()), name_(name), file_(program.file()) {
  cl_int status = CL_SUCCESS;
  kernel_ = clCreateKernel(program.handle(), name.c_str(), &status);
  clCheck(status, "creating kernel '" + name + "' from kernels/" + file_);
}

Kernel::~Kernel() {
  if (kernel_) clReleaseKernel(kernel_);
}

Kernel::Kernel(Kernel&& o) noexcept { *this = std::move(o); }

Kernel& Kernel::operator=(Kernel&& o) noexcept {
  if (this != &o) {
    if (kernel_) clReleaseKernel(kernel_);
    kernel_ = std::exchange(o.kernel_, nullptr);
    ctx_ = o.ctx_;
    name_ = std::move(o.name_);
    file_ = std::move(o.file_);
  }
  return *this;
}

Kernel& Kernel::setMem(cl_uint i, cl_mem m) { return setBytes(i, &m, sizeof m); }

Kernel& Kernel::setBytes(cl_uint i, const void* p, std::size_t n) {
  clCheck(clSetKernelArg(kernel_, i, n, p),
          "setting argument " + std::to_string(i) + " of kernel '" + name_ + "' (kernels/" + file_ + ")");
  return *this;
}

Kernel& Kernel::setArg(cl_uint i, RealArg r) {
  if (ctx_->precision() == Precision::Double) return setBytes(i, &r.value, sizeof(double));
  const float f = static_cast<float>(r.value);
  return setBytes(i, &f, sizeof f);
}

Kernel& Kernel::setLocal(cl_uint i, std::size_t bytes) { return setBytes(i, nullptr, bytes); }

void Kernel::launch(Range global, Range local, const char* label) {
  const cl_uint dims = static_cast<cl_uint>(global.dims());
  size_t g[2] = {global.x, global.y == 0 ? 1 : global.y};
  size_t l[2] = {local.x, local.y == 0 ? 1 : local.y};
  const bool haveLocal = local.x != 0;
  if (haveLocal) {
    g[0] = roundUp(g[0], l[0]);
    g[1] = roundUp(g[1], l[1]);
  }
  if (g[0] == 0 || (dims == 2 && g[1] == 0)) return;  // nothing to do
  cl_event event = nullptr;
  Profiler& prof = ctx_->profiler();
  clCheck(clEnqueueNDRangeKernel(ctx_->queue(), kernel_, dims, nullptr, g, haveLocal ? l : nullptr, 0, nullptr,
                                 prof.enabled ? &event : nullptr),
          "launching kernel '" + name_ + "' (kernels/" + file_ + ")");
  if (event) prof.record(label ? label : name_, event);
}

}  // namespace talus::compute
