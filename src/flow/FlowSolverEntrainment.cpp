// FlowSolver, entrainment part: the erodible bed layer, its kernel (kernels/flow/entrainment.cl) and
// the refresh of the bed's slope fields after the bed changed (kernels/flow/bed_geometry.cl). Used
// when FlowSettings::entrainment is on (two-phase model only).
#include <cmath>
#include <stdexcept>
#include <string>

#include "compute/Program.hpp"
#include "core/Error.hpp"
#include "flow/FlowParams.hpp"
#include "flow/FlowSolver.hpp"

namespace talus::flow {
namespace {

const compute::Range kLocal2D{kTile, kTile};

}  // namespace

void FlowSolver::buildEntrainment() {
  const std::size_t n = grid_.cells();
  if (!settings_.twoPhase) throw InputError("entrainment needs the two-phase grid model (solids on the grid)");
  if (settings_.particleBed) throw InputError("entrainment is not available with the particles (hybrid mode)");
  if (!(settings_.entrainment.growthRate >= 0))
    throw InputError("entrainment growth rate must be >= 0, not " + std::to_string(settings_.entrainment.growthRate));
  erodible_ = compute::RealBuffer(ctx_, n, "erodible depth");
  bedChange_ = compute::RealBuffer(ctx_, n, "bed change");
  erodedFlag_ = compute::Buffer<int>(ctx_, 1, "bed eroded flag");
  const std::string opts = "-DTILE=" + std::to_string(kTile) +
                           " -DMANNING_ALONG_BED=" + (settings_.slopeCorrection ? "1" : "0") +
                           " -DSLOPE_CORRECTION=" + (settings_.slopeCorrection ? "1" : "0") +
                           " -DDEPTH_COS4=" + (settings_.depthPressure == DepthPressure::Cos4 ? "1" : "0");
  entrain_ = compute::Kernel(ctx_.program("flow/entrainment.cl", opts), "debris_entrain");
  bedSlopeFields_ = compute::Kernel(ctx_.program("flow/bed_geometry.cl", opts), "bed_slope_fields");
}

void FlowSolver::setEntrainmentInput(const FlowInput& in) {
  const std::size_t n = grid_.cells();
  std::vector<double> e = in.erodible.empty() ? std::vector<double>(n, 0.0) : in.erodible;
  if (e.size() != n)
    throw InputError("flow input 'erodible' has " + std::to_string(e.size()) + " values, the grid has " +
                     std::to_string(n));
  for (std::size_t k = 0; k < n; ++k) {
    if (!in.mask[k]) e[k] = 0.0;
    if (!(e[k] >= 0) || !std::isfinite(e[k]))
      throw InputError("erodible depth must be finite and >= 0 (cell " + std::to_string(k) + ": " + std::to_string(e[k]) + ")");
  }
  erodible_.upload(e);
  bedChange_.fill(0.0);
  erodibleVolume_ = reducer_.sum(erodible_, n) * grid_.dx * grid_.dx;
}

void FlowSolver::enqueueEntrainment(double dt) {
  erodedFlag_.fill(0);
  entrain_.bind(params_, debrisParams_, mask_, tileList_, bedSlope_, qx_, qy_, solid0_, bed_, erodible_, bedChange_,
                erodedFlag_, compute::RealArg{settings_.entrainment.growthRate}, compute::RealArg{dt});
  entrain_.launch(tileRange(), kLocal2D, "debris_entrain");
  // Where nothing was taken (the flow at rest, the layer used up) the bed and its slope fields stay.
  if (erodedFlag_.read()[0] == 0) return;
  erodibleVolume_ = reducer_.sum(erodible_, grid_.cells()) * grid_.dx * grid_.dx;
  enqueueBedGeometry();
}

void FlowSolver::enqueueBedGeometry() {
  bedSlopeFields_.bind(params_, mask_, tileList_, bed_, gn_, gp_, slopeSpeed_, bedSlope_);
  bedSlopeFields_.launch(tileRange(), kLocal2D, "bed_slope_fields");
}

void FlowSolver::recomputeBedGeometry() {
  if (!settings_.entrainment.enabled) throw std::logic_error("recomputeBedGeometry needs entrainment on");
  activateAllTiles();
  enqueueBedGeometry();
  computeDiagnostics();
}

std::vector<double> FlowSolver::bedChange() const {
  return settings_.entrainment.enabled ? bedChange_.download() : std::vector<double>(grid_.cells(), 0.0);
}

std::vector<double> FlowSolver::erodibleDepth() const {
  return settings_.entrainment.enabled ? erodible_.download() : std::vector<double>(grid_.cells(), 0.0);
}

}  // namespace talus::flow
