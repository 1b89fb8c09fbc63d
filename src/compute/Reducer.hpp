// Device reductions (sum, min, max) of a RealBuffer; only the final scalar is read back.
#pragma once
#include <cstddef>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Kernel.hpp"

namespace talus::compute {

enum class ReduceOp { Sum = 0, Min = 1, Max = 2 };

class Reducer {
 public:
  explicit Reducer(Context& ctx);
  /// Reduces the first n elements of `in` (n = 0 gives the identity: 0, +max, -max).
  double reduce(const RealBuffer& in, std::size_t n, ReduceOp op);
  double sum(const RealBuffer& in, std::size_t n) { return reduce(in, n, ReduceOp::Sum); }
  double min(const RealBuffer& in, std::size_t n) { return reduce(in, n, ReduceOp::Min); }
  double max(const RealBuffer& in, std::size_t n) { return reduce(in, n, ReduceOp::Max); }
  /// Reduces the first n entries of ops.size() (at most 16) rows of `in` that start every `stride`
  /// entries (stride 0 means n), row r with ops[r], in one launch and one read-back.
  std::vector<double> reduceRows(const RealBuffer& in, std::size_t n, const std::vector<ReduceOp>& ops,
                                 std::size_t stride = 0);

 private:
  static constexpr std::size_t kLocal = 128;
  static constexpr std::size_t kMaxGroups = 64;
  Context& ctx_;
  Kernel stage_;
  Kernel rows_;
  RealBuffer partials_;
  RealBuffer result_;
};

}  // namespace talus::compute
