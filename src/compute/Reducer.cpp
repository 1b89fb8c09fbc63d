#include "compute/Reducer.hpp"

#include <algorithm>

#include "compute/Context.hpp"
#include "compute/Program.hpp"
#include "core/Error.hpp"

namespace talus::compute {

Reducer::Reducer(Context& ctx)
    : ctx_(ctx),
      stage_(ctx.program("common/reduce.cl"), "reduce_stage"),
      rows_(ctx.program("common/reduce.cl"), "reduce_rows"),
      partials_(ctx, kMaxGroups, "reduction partials"),
      result_(ctx, 16, "reduction result") {}

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

std::vector<double> Reducer::reduceRows(const RealBuffer& in, std::size_t n, const std::vector<ReduceOp>& ops,
                                        std::size_t stride) {
  if (stride == 0) stride = n;
  if (ops.empty() || ops.size() > 16) throw ComputeError("reduceRows needs 1 to 16 rows");
  if (n > stride || (ops.size() - 1) * stride + n > in.size()) throw ComputeError("reduceRows: rows exceed the buffer");
  unsigned codes = 0;
  for (std::size_t r = 0; r < ops.size(); ++r) codes |= static_cast<unsigned>(ops[r]) << (2 * r);
  rows_.bind(in, static_cast<unsigned>(n), static_cast<unsigned>(stride), codes, result_)
      .setLocal(5, kLocal * realSize(ctx_.precision()));
  rows_.launch({ops.size() * kLocal}, {kLocal}, "reduce_rows");
  std::vector<double> all = result_.download();
  all.resize(ops.size());
  return all;
}

}  // namespace talus::compute
