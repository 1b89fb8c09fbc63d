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

/// The largest earth-pressure coefficient the two-phase model can give any cell of the scene: the
/// constant K, or Savage and Hutter's passive coefficient (kernels/flow/debris_closures.cl) at the
/// cell's internal and bed friction angles.
double largestEarthPressure(const flow::FlowInput& in, const flow::FlowSettings& s) {
  if (!s.twoPhase) return 1.0;
  if (s.debris.earthPressure == flow::EarthPressure::Constant) return std::max(1.0, s.debris.kConst);
  double kmax = 1.0;
  for (std::size_t k = 0; k < in.phi.size(); ++k) {
    if (!in.mask[k]) continue;
    const double phi = in.phi[k];
    const double delta = s.debris.deltaFromPhi || in.delta.size() <= k ? phi : in.delta[k];
    const double cp = std::cos(phi), cd = std::cos(delta);
    const double root = std::sqrt(std::max(0.0, 1.0 - cp * cp / (cd * cd)));
    if (cp > 0) kmax = std::max(kmax, 2.0 / (cp * cp) * (1.0 + root) - 1.0);
  }
  return kmax;
}

}  // namespace

HealthCheck::HealthCheck(const Raster& dem, const flow::FlowInput& in, const flow::FlowSettings& settings)
    : grid_(dem.grid), cfl_(settings.cfl), hDry_(settings.hDry) {
  double zmin = HUGE_VAL, zmax = -HUGE_VAL, hmax = 0, v0 = 0;
  for (std::size_t k = 0; k < in.bed.size(); ++k) {
    if (!in.mask[k]) continue;
    const double hs = in.hs.empty() ? 0.0 : std::max(0.0, in.hs[k]);
    const double column = std::max(0.0, in.h[k]) + hs;
    zmin = std::min(zmin, in.bed[k]);
    zmax = std::max(zmax, in.bed[k] + column);
    hmax = std::max(hmax, column);
    if (in.h[k] > hDry_ && !in.qx.empty()) v0 = std::max(v0, std::hypot(in.qx[k], in.qy[k]) / in.h[k]);
    if (hs > hDry_ && !in.qsx.empty()) v0 = std::max(v0, std::hypot(in.qsx[k], in.qsy[k]) / hs);
  }
  const double drop = zmax > zmin ? zmax - zmin : 0.0;
  const double kmax = largestEarthPressure(in, settings);
  speedBound_ = std::sqrt(2.0 * kGravity * drop) + 2.0 * std::sqrt(kGravity * kmax * hmax) + v0;
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
    // Films at or below the dry threshold carry no velocity: the fastest flow is a thicker layer.
    const double score = negative ? -hh[k] : hh[k] > hDry_ ? std::hypot(ax[k], ay[k]) / hh[k] : 0.0;
    if (score > worstValue) worstValue = score, worst = k, worstSolid = solid;
  };
  // Non-finite values spread to the neighbours within a step (two stages, two-cell stencils), so
  // the message names the region and the bad cell nearest its centroid, where it most likely began.
  std::size_t badCount = 0;
  int iMin = grid_.nx, iMax = -1, jMin = grid_.ny, jMax = -1;
  double iSum = 0, jSum = 0;
  auto isBad = [&](std::size_t k) {
    return !std::isfinite(h[k]) || !std::isfinite(qx[k]) || !std::isfinite(qy[k]) ||
           (solids && (!std::isfinite(hs[k]) || !std::isfinite(qsx[k]) || !std::isfinite(qsy[k])));
  };
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (isBad(k)) {
      const int i = static_cast<int>(k % grid_.nx), j = static_cast<int>(k / grid_.nx);
      ++badCount;
      iMin = std::min(iMin, i), iMax = std::max(iMax, i), jMin = std::min(jMin, j), jMax = std::max(jMax, j);
      iSum += i, jSum += j;
      continue;
    }
    consider(h, qx, qy, false, k);
    if (solids) consider(hs, qsx, qsy, true, k);
  }
  if (badCount > 0) {
    const double ic = iSum / badCount, jc = jSum / badCount;
    std::size_t centre = 0;
    double best = HUGE_VAL;
    for (std::size_t k = 0; k < h.size(); ++k) {
      if (!isBad(k)) continue;
      const double di = static_cast<double>(k % grid_.nx) - ic, dj = static_cast<double>(k / grid_.nx) - jc;
      if (di * di + dj * dj < best) best = di * di + dj * dj, centre = k;
    }
    o << what << ": non-finite state h = " << h[centre] << " m, qx = " << qx[centre] << ", qy = " << qy[centre]
      << " m^2/s";
    if (solids) o << ", h_s = " << hs[centre] << " m, q_sx = " << qsx[centre] << ", q_sy = " << qsy[centre] << " m^2/s";
    o << " in " << where(grid_, centre);
    if (badCount > 1)
      o << ", the centre of " << badCount << " non-finite cells (columns " << iMin << "-" << iMax << ", rows " << jMin
        << "-" << jMax << ")";
    return o.str();
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
  // Energy: the material speed (not a wave speed, which earth pressure or viscosity may make large
  // in a slow flow) against the bound the scene's relief and release allow.
  if (d.maxFlowSpeed > speedBound_) {
    std::ostringstream o;
    o << "runaway velocity: flow speed " << d.maxFlowSpeed << " m/s exceeds " << speedBound_
      << " m/s, the fastest the scene's relief and release can drive (energy bound); ";
    return o.str() + locate(solver, "fastest flow");
  }
  // Stability: the step was taken with dt <= cfl dx / a_old. If the state it produced needs a wave
  // speed for which that dt exceeds the absolute stability limit (Courant number 1), the step was
  // not stable. Films at or below Minimum Flow Height carry no velocity and are left out.
  const double courant = dt * d.maxWaveSpeedWet / solver.grid().dx;
  if (courant > 1.0 && courant > 2.0 * cfl_) {
    std::ostringstream o;
    o << "CFL violation: the step of " << dt << " s reached Courant number " << courant
      << " (limit 1): the wave speed jumped to " << d.maxWaveSpeedWet << " m/s within one step; ";
    return o.str() + locate(solver, "fastest flow");
  }
  return "";
}

}  // namespace talus::sim
