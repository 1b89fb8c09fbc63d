// The device-side packing of view data into float buffers (kernels/view/view_pack.cl), for
// viewers that draw straight from device memory: solver fields (`real`) combined into one float per
// cell (thickness, speed, fractions, maxima, arrival time), and particle positions in world
// coordinates. The output may be an OpenGL buffer acquired on a GL-shared context.
#pragma once
#include <CL/cl.h>

#include <cstddef>
#include <limits>

#include "core/Grid.hpp"

namespace talus::compute {
class Context;
}

namespace talus::sim {

/// How kernels/view/view_pack.cl (view_pack_values) combines its inputs a..f into one float.
enum class PackMode : int {
  Copy = 0,      ///< a
  Sum = 1,       ///< a + b
  Speed = 2,     ///< |(b, c)| / a where a > hDry, else 0
  SpeedSum = 3,  ///< |(b + e, c + f)| / (a + d) where a + d > hDry, else 0
  Fraction = 4,  ///< b / (a + b) where a + b > hDry, else 0
  Max2 = 5,      ///< max(a, b)
  Arrival = 6,   ///< a, NaN where a < 0
  Norm = 7,      ///< |(a, b)|
};

/// Inputs of one packing: device arrays of the kernels' `real` (unused ones may stay null) and an
/// optional mask (uchar per element; 0 gives NaN).
struct PackInputs {
  cl_mem a = nullptr, b = nullptr, c = nullptr, d = nullptr, e = nullptr, f = nullptr;
  cl_mem valid = nullptr;
};

/// The device-side packing of view data into float buffers (kernels/view/view_pack.cl). The
/// output is any float cl_mem of the context: a plain buffer, or an OpenGL buffer acquired with
/// clEnqueueAcquireGLObjects on a GL-shared context. Not thread-safe: one packer per thread.
class ViewPacker {
 public:
  explicit ViewPacker(compute::Context& ctx);
  ~ViewPacker();
  ViewPacker(const ViewPacker&) = delete;
  ViewPacker& operator=(const ViewPacker&) = delete;

  /// Enqueues out[k] = mode(inputs)[k] (float) for k < n on `queue` (null: the context's queue);
  /// `noValue` where the mask is 0 or the result is not finite.
  void packValues(PackMode mode, std::size_t n, const PackInputs& in, double hDry, cl_mem out,
                  cl_command_queue queue = nullptr, float noValue = std::numeric_limits<float>::quiet_NaN());
  /// Enqueues float x, y, z triples of n particles (grid coordinates x, y [m], thickness H, all
  /// `real`) into out (3 n floats): world x, y through the grid's geotransform, z = bed (`real`,
  /// one per cell) of the particle's cell + H; removed particles (non-finite x) give NaN.
  void packPositions(std::size_t n, cl_mem x, cl_mem y, cl_mem H, cl_mem bed, const Grid& grid, cl_mem out,
                     cl_command_queue queue = nullptr);
  compute::Context& context() { return ctx_; }

 private:
  void launch(cl_kernel kernel, std::size_t n, cl_command_queue queue);
  compute::Context& ctx_;
  cl_kernel values_ = nullptr, positions_ = nullptr;
};

}  // namespace talus::sim
