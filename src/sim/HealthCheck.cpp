#include "sim/HealthCheck.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/Constants.hpp"

namespace talus::sim {
namespace {

std::string where(const Grid& g, std::size_t k) {
  const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
  std::ostringstream o;
  o << "cell (column " << i << ", row " << j << ") at x = " << g.cellX(i) << ", y = " << g.cellY(j);
  return o.str();
}

}  // namespace

HealthCheck::HealthCheck(const Raster& dem, const flow::FlowInput& in, double cfl) : grid_(dem.grid), cfl_(cfl) {
  double zmin = HUGE_VAL, zmax = -HUGE_VAL, v0 = 0;
  for (std::size_t k = 0; k < in.bed.size(); ++k) {
    if (!in.mask[k]) continue;
    zmin = std::min(zmin, in.bed[k]);
    zmax = std::max(zmax, in.bed[k] + in.h[k] + (in.hs.empty() ? 0.0 : in.hs[k]));
    if (in.h[k] > 0 && !in.qx.empty())
      v0 = std::max(v0, (std::fabs(in.qx[k]) + std::fabs(in.qy[k])) / in.h[k]);
  }
  // The largest fall any water can make: from the highest surface to the lowest bed.
  const double drop = std::max(0.0, zmax - zmin);
  speedLimit_ = 2.0 * std::sqrt(2.0) * std::sqrt(2.0 * kGravity * drop) + 2.0 * std::sqrt(kGravity * drop) + 2.0 * v0;
}

std::string HealthCheck::locate(const flow::FlowSolver& solver, const char* what) const {
  // Full read-back only on failure, to name the cell: the fluid, and the solids in a two-phase run
  // (a dry granular run has no fluid at all, so its fields alone would name an empty cell).
  const std::vector<double> h = solver.h(), qx = solver.qx(), qy = solver.qy();
  const bool solids = solver.twoPhase();
  const std::vector<double> hs = solids ? solver.hs() : std::vector<double>(), qsx = solids ? solver.qsx() : hs,
                            qsy = solids ? solver.qsy() : hs;
  const bool negative = std::string(what) == "negative thickness";
  std::ostringstream o;
  std::size_t worst = 0;
  bool worstSolid = false;
  double worstValue = -HUGE_VAL;
  auto consider = [&](const std::vector<double>& hh, const std::vector<double>& ax, const std::vector<double>& ay,
                      bool solid, std::size_t k) {
    const double score = negative ? -hh[k] : hh[k] > 0 ? std::hypot(ax[k], ay[k]) / hh[k] : 0.0;
    if (score > worstValue) worstValue = score, worst = k, worstSolid = solid;
  };
  for (std::size_t k = 0; k < h.size(); ++k) {
    const bool bad = !std::isfinite(h[k]) || !std::isfinite(qx[k]) || !std::isfinite(qy[k]) ||
                     (solids && (!std::isfinite(hs[k]) || !std::isfinite(qsx[k]) || !std::isfinite(qsy[k])));
    if (bad) {
      o << what << ": non-finite state h = " << h[k] << " m, qx = " << qx[k] << ", qy = " << qy[k] << " m^2/s";
      if (solids) o << ", h_s = " << hs[k] << " m, q_sx = " << qsx[k] << ", q_sy = " << qsy[k] << " m^2/s";
      o << " in " << where(grid_, k);
      return o.str();
    }
    consider(h, qx, qy, false, k);
    if (solids) consider(hs, qsx, qsy, true, k);
  }
  const std::vector<double>& hh = worstSolid ? hs : h;
  const std::vector<double>& ax = worstSolid ? qsx : qx;
  const std::vector<double>& ay = worstSolid ? qsy : qy;
  o << what << " in " << where(grid_, worst) << " (" << (worstSolid ? "solids: h_s = " : "h = ") << hh[worst]
    << " m, speed = " << (hh[worst] > 0 ? std::hypot(ax[worst], ay[worst]) / hh[worst] : 0.0) << " m/s)";
  return o.str();
}

std::string HealthCheck::check(const flow::FlowSolver& solver, double dt) const {
  const flow::FlowDiagnostics& d = solver.diagnostics();
  if (!std::isfinite(d.volume) || !std::isfinite(d.maxSpeed) || !std::isfinite(d.kinetic))
    return locate(solver, "NaN or infinity");
  if (d.minH < 0) return locate(solver, "negative thickness");
  if (d.maxSpeed > speedLimit_) {
    std::ostringstream o;
    o << "runaway velocity: wave speed " << d.maxSpeed << " m/s exceeds the energy bound " << speedLimit_ << " m/s; ";
    return o.str() + locate(solver, "fastest flow");
  }
  // The step was taken with dt <= cfl dx / a_old; if the state it produced needs a wave speed for
  // which that dt exceeds the absolute stability limit (CFL 1), the step was not stable.
  const double courant = dt * d.maxSpeed / solver.grid().dx;
  if (courant > 1.0 && courant > 2.0 * cfl_) {
    std::ostringstream o;
    o << "CFL violation: the step of " << dt << " s reached Courant number " << courant
      << " (limit 1): the wave speed jumped to " << d.maxSpeed << " m/s within one step; ";
    return o.str() + locate(solver, "fastest flow");
  }
  return "";
}

}  // namespace talus::sim
