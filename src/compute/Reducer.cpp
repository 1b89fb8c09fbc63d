#include "compute/Reducer.hpp"

#include <algorithm>

#include "compute/Context.hpp"
#include "compute/Program.hpp"

namespace talus::compute {

Reducer::Reducer(Context& ctx)
    : ctx_(ctx),
      stage_(ctx.program("common/reduce.cl"), "reduce_stage"),
      partials_(ctx, kMaxGroups, "reduction partials"),
      result_(ctx, 1, "reduction result") {}

double Reducer::reduce(const RealBuffer& in, std::size_t n, ReduceOp op) {
  const int opCode = static_cast<int>(op);
  const std::size_t groups = std::max<std::size_t>(1, std::min(kMaxGroups, (n + kLocal - 1) / kLocal));
  const std::size_t realBytes = realSize(ctx_.precision());
  stage_.bind(in, static_cast<unsigned>(n), opCode, partials_).setLocal(4, kLocal * realBytes);
  stage_.launch({groups * kLocal}, {kLocal}, "reduce");
  stage_.bind(partials_, static_cast<unsigned>(groups), opCode, result_).setLocal(4, kLocal * realBytes);
  stage_.launch({kLocal}, {kLocal}, "reduce");
  return result_.download()[0];
}

}  // namespace talus::compute
