#include "sim/ViewPacker.hpp"

#include <string>

#include "compute/ClError.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "compute/Program.hpp"

namespace talus::sim {

ViewPacker::ViewPacker(compute::Context& ctx) : ctx_(ctx) {
  const cl_program program = ctx.program("view/view_pack.cl").handle();
  cl_int status = CL_SUCCESS;
  values_ = clCreateKernel(program, "view_pack_values", &status);
  compute::clCheck(status, "creating kernel 'view_pack_values' (kernels/view/view_pack.cl)");
  positions_ = clCreateKernel(program, "view_pack_positions", &status);
  compute::clCheck(status, "creating kernel 'view_pack_positions' (kernels/view/view_pack.cl)");
}

ViewPacker::~ViewPacker() {
  if (values_) clReleaseKernel(values_);
  if (positions_) clReleaseKernel(positions_);
}

namespace {

/// Binds kernel arguments in order: cl_mem, int, and `real` scalars (double on the host, converted
/// to the context's precision). The output cl_mem may be foreign to compute::Buffer (a GL buffer),
/// hence raw clSetKernelArg rather than compute::Kernel.
class ArgBinder {
 public:
  ArgBinder(cl_kernel k, bool doublePrecision) : k_(k), double_(doublePrecision) {}
  ArgBinder& mem(cl_mem m) { return set(&m, sizeof m); }
  ArgBinder& integer(int v) { return set(&v, sizeof v); }
  ArgBinder& single(float v) { return set(&v, sizeof v); }
  ArgBinder& real(double v) {
    if (double_) return set(&v, sizeof v);
    const float f = static_cast<float>(v);
    return set(&f, sizeof f);
  }

 private:
  ArgBinder& set(const void* p, std::size_t bytes) {
    compute::clCheck(clSetKernelArg(k_, i_, bytes, p), "setting argument " + std::to_string(i_) + " of a view packing kernel");
    ++i_;
    return *this;
  }
  cl_kernel k_;
  bool double_;
  cl_uint i_ = 0;
};

}  // namespace

void ViewPacker::launch(cl_kernel kernel, std::size_t n, cl_command_queue queue) {
  if (n == 0) return;
  const std::size_t local = 64, global = compute::roundUp(n, local);
  compute::clCheck(clEnqueueNDRangeKernel(queue ? queue : ctx_.queue(), kernel, 1, nullptr, &global, &local, 0,
                                          nullptr, nullptr),
                   "launching a view packing kernel (kernels/view/view_pack.cl)");
}

void ViewPacker::packValues(PackMode mode, std::size_t n, const PackInputs& in, double hDry, cl_mem out,
                            cl_command_queue queue, float noValue) {
  // Inputs a mode does not read are bound to `a` (any valid buffer will do).
  auto or_a = [&](cl_mem m) { return m ? m : in.a; };
  ArgBinder(values_, ctx_.precision() == compute::Precision::Double)
      .integer(static_cast<int>(n))
      .integer(static_cast<int>(mode))
      .real(hDry)
      .mem(in.a)
      .mem(or_a(in.b))
      .mem(or_a(in.c))
      .mem(or_a(in.d))
      .mem(or_a(in.e))
      .mem(or_a(in.f))
      .mem(in.valid ? in.valid : in.a)
      .integer(in.valid ? 1 : 0)
      .single(noValue)
      .mem(out);
  launch(values_, n, queue);
}

void ViewPacker::packPositions(std::size_t n, cl_mem x, cl_mem y, cl_mem H, cl_mem bed, const Grid& grid, cl_mem out,
                               cl_command_queue queue) {
  const auto& t = grid.geoTransform;
  ArgBinder(positions_, ctx_.precision() == compute::Precision::Double)
      .integer(static_cast<int>(n))
      .mem(x)
      .mem(y)
      .mem(H)
      .mem(bed)
      .integer(grid.nx)
      .integer(grid.ny)
      .real(grid.dx)
      .real(t[0])
      .real(t[1])
      .real(t[2])
      .real(t[3])
      .real(t[4])
      .real(t[5])
      .mem(out);
  launch(positions_, n, queue);
}

}  // namespace talus::sim
