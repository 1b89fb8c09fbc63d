// FlowSolver, two-phase part: buffers, parameters and launchers of the debris-flow grid model
// (kernels/flow/debris_stage.cl, debris_diagnostics.cl). Used when FlowSettings::twoPhase is set.
#include <algorithm>
#include <cmath>
#include <string>

#include "compute/Program.hpp"
#include "core/Error.hpp"
#include "flow/DebrisParams.hpp"
#include "flow/FlowParams.hpp"
#include "flow/FlowSolver.hpp"

namespace talus::flow {
namespace {

constexpr int kSolidComponents = 8;  // h_s, q_sx, q_sy, h_s phi, h_s rho_s, h_s d, h_s c, h_s w (lift-off)
constexpr int kMaximaComponents = 7;
constexpr double kDefaultPhi = kDebrisDefaultPhi;  // 30 degrees, where no solids are
constexpr double kDefaultRhoS = kDebrisDefaultRhoS;
constexpr double kDefaultGrain = kDebrisDefaultGrain;
const compute::Range kLocal2D{kTile, kTile};

/// `v` or, when empty, `fallback` everywhere.
std::vector<double> orFill(const std::vector<double>& v, std::size_t n, double fallback, const char* what) {
  if (v.empty()) return std::vector<double>(n, fallback);
  if (v.size() != n)
    throw InputError(std::string("flow input '") + what + "' has " + std::to_string(v.size()) + " values, the grid has " +
                     std::to_string(n));
  return v;
}

}  // namespace

void FlowSolver::buildDebris() {
  const std::size_t n = grid_.cells();
  compute::Context& ctx = ctx_;
  debrisParams_ = compute::RawBuffer(ctx, sizeof(DebrisParamsT<double>), "debris parameters");
  solid0_ = compute::RealBuffer(ctx, kSolidComponents * n, "solid state");
  solid1_ = compute::RealBuffer(ctx, kSolidComponents * n, "solid state stage");
  delta_ = compute::RealBuffer(ctx, n, "bed friction angle");
  maxima_ = compute::RealBuffer(ctx, kMaximaComponents * n, "two-phase maxima");
  lock0_ = compute::Buffer<uint8_t>(ctx, n, "static solids");
  lock1_ = compute::Buffer<uint8_t>(ctx, n, "static solids stage");
  const std::string opts = "-DLIMITER=" + std::to_string(static_cast<int>(settings_.limiter)) +
                           " -DRIEMANN=" + std::to_string(static_cast<int>(settings_.riemann)) +
                           " -DTILE=" + std::to_string(kTile) +
                           " -DMANNING_ALONG_BED=" + (settings_.slopeCorrection ? "1" : "0") +
                           // The viscous stresses are compiled out when both Reynolds numbers are off.
                           " -DDEBRIS_VISCOUS=" + (settings_.debris.viscous() ? "1" : "0") +
                           // The particle bed of the hybrid mode is compiled out in grid mode.
                           " -DDEBRIS_OBSTACLE=" + (settings_.particleBed ? "1" : "0") +
                           // The bed's curvature term is compiled out unless asked for.
                           " -DDEBRIS_CURVATURE=" + (settings_.curvature && settings_.slopeCorrection ? "1" : "0") +
                           // Only the run's basal law is compiled in (kernels/flow/basal_rheology.cl).
                           " -DRHEOLOGY=" + std::to_string(static_cast<int>(settings_.debris.rheology));
  // Hybrid mode: the particles' bed (H_c, u_c, v_c per cell) and the impulse it takes per step
  // (x, y); one-value placeholders otherwise (the kernel does not read them).
  const std::size_t bedCells = settings_.particleBed ? n : 1;
  particleBed_ = compute::RealBuffer(ctx, 3 * bedCells, "particle bed");
  bedImpulse_ = compute::RealBuffer(ctx, 2 * bedCells, "particle bed impulse");
  particleBed_.fill(0.0);
  bedImpulse_.fill(0.0);
  debrisStage_ = compute::Kernel(ctx.program("flow/debris_stage.cl", opts), "debris_stage");
  debrisTrack_ = compute::Kernel(ctx.program("flow/debris_diagnostics.cl", opts), "debris_track_maxima");
  debrisDiagnostics_ = compute::Kernel(ctx.program("flow/debris_diagnostics.cl", opts), "debris_tile_diagnostics");
  writeDebrisParams(debrisParams_, settings_.debris, ctx.precision());
}

void FlowSolver::setDebrisInput(const FlowInput& in, const std::vector<double>& h) {
  const std::size_t n = grid_.cells();
  std::vector<double> hs = orFill(in.hs, n, 0.0, "hs");
  const std::vector<double> qsx = orFill(in.qsx, n, 0.0, "qsx"), qsy = orFill(in.qsy, n, 0.0, "qsy");
  const std::vector<double> phi = orFill(in.phi, n, kDefaultPhi, "phi");
  const std::vector<double> rho = orFill(in.rhoS, n, kDefaultRhoS, "rhoS");
  const std::vector<double> grain = orFill(in.grain, n, kDefaultGrain, "grain");
  const std::vector<double> cohesion = orFill(in.cohesion, n, 0.0, "cohesion");
  std::vector<double> state(kSolidComponents * n, 0.0);
  std::vector<uint8_t> lock(n, 1);
  std::vector<double> maxima(kMaximaComponents * n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    if (!in.mask[k]) hs[k] = 0.0;
    const bool wet = hs[k] > settings_.hDry;
    state[k] = hs[k];
    state[n + k] = wet ? qsx[k] : 0.0;
    state[2 * n + k] = wet ? qsy[k] : 0.0;
    state[3 * n + k] = hs[k] * phi[k];
    state[4 * n + k] = hs[k] * rho[k];
    state[5 * n + k] = hs[k] * grain[k];
    state[6 * n + k] = hs[k] * cohesion[k];  // carried with the material from here on
    // state[7 * n + k]: the lift-off speed of the curvature term (solid_bed.cl, point 5), 0: on the bed
    // Solids at rest start static: they move only once their driving force beats friction.
    lock[k] = wet && (state[n + k] != 0.0 || state[2 * n + k] != 0.0) ? 0 : 1;
    maxima[k] = h[k];
    maxima[2 * n + k] = hs[k];
    maxima[4 * n + k] = hs[k] + h[k];
  }
  solid0_.upload(state);
  solid1_.upload(state);
  lock0_.write(lock);
  lock1_.write(lock);
  maxima_.upload(maxima);
  delta_.upload(orFill(in.delta, n, kDefaultPhi, "delta"));
}

void FlowSolver::enqueueDebrisStage(bool first, double dt) {
  // Stage 1: U1 = S_dt(U0 + dt L(U0)); stage 2: U0 = S_dt/2(U0/2 + (U1 + dt L(U1))/2).
  compute::RealBuffer &Sst = first ? solid0_ : solid1_, &Sout = first ? solid1_ : solid0_;
  compute::RealBuffer &hst = first ? h_ : h1_, &qxst = first ? qx_ : qx1_, &qyst = first ? qy_ : qy1_;
  compute::RealBuffer &hout = first ? h1_ : h_, &qxout = first ? qx1_ : qx_, &qyout = first ? qy1_ : qy_;
  compute::Buffer<uint8_t>&lst = first ? lock0_ : lock1_, &lout = first ? lock1_ : lock0_;
  if (first && settings_.particleBed) bedImpulse_.fill(0.0);  // the impulse of this step only
  debrisStage_.bind(params_, debrisParams_, mask_, tileList_, bed_, gp_, gn_, farLevel_, manning_, bedSlope_, delta_,
                    particleBed_, bedImpulse_, solid0_, h_,
                    qx_, qy_, Sst, hst, qxst, qyst, lst, Sout, hout, qxout, qyout, lout, outStep_,
                    compute::RealArg{dt}, compute::RealArg{first ? 0.0 : 0.5}, compute::RealArg{0.5 * dt},
                    compute::RealArg{first ? dt : 0.5 * dt}, first ? 1 : 0);
  debrisStage_.launch(tileRange(), kLocal2D, first ? "debris_stage_1" : "debris_stage_2");
}

void FlowSolver::enqueueDebrisTrack() {
  debrisTrack_.bind(params_, debrisParams_, mask_, tileList_, solid0_, h_, qx_, qy_, maxima_, arrival_,
                    compute::RealArg{time_});
  debrisTrack_.launch(tileRange(), kLocal2D);
}

void FlowSolver::enqueueDebrisDiagnostics() {
  debrisDiagnostics_.bind(params_, debrisParams_, mask_, tileList_, solid0_, h_, qx_, qy_, slopeSpeed_, delta_,
                          particleBed_, bed_, bedSlope_, outStep_, partial_, tileWet_);
  debrisDiagnostics_.launch(tileRange(), kLocal2D);
}

std::vector<double> FlowSolver::solidComponent(int c) const {
  if (!settings_.twoPhase) return std::vector<double>(grid_.cells(), 0.0);
  const std::vector<double> all = solid0_.download();
  const std::size_t n = grid_.cells();
  return std::vector<double>(all.begin() + c * n, all.begin() + (c + 1) * n);
}

std::vector<double> FlowSolver::hs() const { return solidComponent(0); }
std::vector<double> FlowSolver::qsx() const { return solidComponent(1); }
std::vector<double> FlowSolver::qsy() const { return solidComponent(2); }

std::vector<double> FlowSolver::solidScalar(int which) const {
  const std::vector<double> hsv = hs(), s = solidComponent(3 + which);
  const double fallback = which == 0 ? kDefaultPhi : which == 1 ? kDefaultRhoS : which == 2 ? kDefaultGrain : 0.0;
  std::vector<double> out(hsv.size());
  for (std::size_t k = 0; k < hsv.size(); ++k) out[k] = hsv[k] > settings_.hDry ? s[k] / hsv[k] : fallback;
  return out;
}

DebrisMaxima FlowSolver::debrisMaxima() const {
  DebrisMaxima m;
  if (!settings_.twoPhase) return m;
  const std::vector<double> all = maxima_.download();
  const std::size_t n = grid_.cells();
  std::vector<double>* fields[] = {&m.hf, &m.vf, &m.hs, &m.vs, &m.h, &m.solidFraction, &m.impactPressure};
  for (int c = 0; c < kMaximaComponents; ++c) fields[c]->assign(all.begin() + c * n, all.begin() + (c + 1) * n);
  return m;
}

}  // namespace talus::flow
