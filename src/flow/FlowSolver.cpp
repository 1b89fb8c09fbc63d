#include "flow/FlowSolver.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "compute/Program.hpp"
#include "core/Error.hpp"
#include "flow/FlowParams.hpp"
#include "flow/SlopeGravity.hpp"

namespace talus::flow {
namespace {

constexpr int kDiagnosticRows = 12;    // see kernels/flow/diagnostics.cl (7 single-phase, 12 two-phase)
const compute::Range kLocal2D{kTile, kTile};

std::string buildOptions(const FlowSettings& s) {
  return "-DLIMITER=" + std::to_string(static_cast<int>(s.limiter)) +
         " -DRIEMANN=" + std::to_string(static_cast<int>(s.riemann)) + " -DTILE=" + std::to_string(kTile) +
         // Manning's friction acts along the bed where the slope correction is on (flow/manning.cl).
         " -DMANNING_ALONG_BED=" + (s.slopeCorrection ? "1" : "0") +
         // SPLIT: the split sweeps, which stay positive by the draining time up to CFL 1 (stage.cl).
         " -DSPLIT=" + (sweeps(s.scheme) ? "1" : "0") +
         // HANCOCK: each sweep one MUSCL-Hancock stage (flow_common.cl, hancock_predict).
         " -DHANCOCK=" + (s.scheme == TimeScheme::Hancock ? "1" : "0");
}

template <class Real>
void writeParams(compute::RawBuffer& buf, const Grid& g, int tx, int ty, const FlowSettings& s) {
  FlowParamsT<Real> p{};
  p.nx = g.nx;
  p.ny = g.ny;
  p.tilesX = tx;
  p.tilesY = ty;
  p.edgeBoundary = static_cast<int32_t>(s.edge);
  p.nodataBoundary = static_cast<int32_t>(s.nodata);
  p.skipDryTiles = s.skipDryTiles ? 1 : 0;
  p.dx = static_cast<Real>(g.dx);
  p.hDry = static_cast<Real>(s.hDry);
  p.arrivalH = static_cast<Real>(s.arrivalH);
  buf.writeBytes(&p, sizeof p);
}

}  // namespace

FlowSolver::FlowSolver(compute::Context& ctx, const Grid& grid, const FlowSettings& settings)
    : ctx_(ctx),
      grid_(grid),
      settings_(settings),
      tilesX_((grid.nx + kTile - 1) / kTile),
      tilesY_((grid.ny + kTile - 1) / kTile),
      params_(ctx, sizeof(FlowParamsT<double>), "flow parameters"),
      mask_(ctx, grid.cells(), "mask"),
      tileActive_(ctx, static_cast<std::size_t>(tilesX_) * tilesY_, "tile active"),
      tileWet_(ctx, static_cast<std::size_t>(tilesX_) * tilesY_, "tile wet"),
      tileList_(ctx, static_cast<std::size_t>(tilesX_) * tilesY_, "tile list"),
      tileCount_(ctx, 1, "tile count"),
      bed_(ctx, grid.cells(), "bed"),
      gp_(ctx, grid.cells(), "g_p"),
      gn_(ctx, grid.cells(), "g_n"),
      manning_(ctx, grid.cells(), "manning"),
      slopeSpeed_(ctx, grid.cells(), "slope speed"),
      farLevel_(ctx, grid.cells(), "outside level"),
      bedSlope_(ctx, 2 * grid.cells(), "bed slope"),
      h_(ctx, grid.cells(), "h"),
      qx_(ctx, grid.cells(), "qx"),
      qy_(ctx, grid.cells(), "qy"),
      h1_(ctx, grid.cells(), "h stage"),
      qx1_(ctx, grid.cells(), "qx stage"),
      qy1_(ctx, grid.cells(), "qy stage"),
      // outflow of the water (of the fluid and the solids, and the sources' work, in the two-phase model)
      outStep_(ctx, (settings.twoPhase ? 3 : 1) * grid.cells(), "outflow per step"),
      partial_(ctx, kDiagnosticRows * static_cast<std::size_t>(tilesX_) * tilesY_, "tile partials"),
      hMax_(ctx, grid.cells(), "h max"),
      vMax_(ctx, grid.cells(), "v max"),
      arrival_(ctx, grid.cells(), "arrival"),
      infiltration_(ctx, grid.cells(), "infiltration capacity"),
      sink_(ctx, grid.cells(), "infiltrated depth"),
      reducer_(ctx) {
  if (grid.nx < 1 || grid.ny < 1 || !(grid.dx > 0)) throw InputError("flow solver needs a grid of at least 1x1 cells");
  if (!(settings.cfl > 0 && settings.cfl <= 1.0)) throw InputError("CFL must lie in (0, 1]");
  if (settings.cfl > kPositiveCfl && !sweeps(settings.scheme))
    throw InputError("a CFL above 0.5 needs Time Scheme=split or hancock (water only): the unsplit stage is positive "
                     "only up to 0.5");
  if (settings.particleBed && !settings.twoPhase) throw InputError("the particle bed needs the two-phase grid model");
  if (settings.twoPhase && sweeps(settings.scheme))
    throw InputError("the dimensionally split time scheme is for water only (the two-phase model runs unsplit)");
  const std::string opts = buildOptions(settings);
  stage_ = compute::Kernel(ctx.program("flow/stage.cl", opts), "flow_stage");
  friction_ = compute::Kernel(ctx.program("flow/friction.cl", opts), "flow_friction");
  track_ = compute::Kernel(ctx.program("flow/track.cl", opts), "flow_track_maxima");
  diagnostics_ = compute::Kernel(ctx.program("flow/diagnostics.cl", opts), "flow_tile_diagnostics");
  compact_ = compute::Kernel(ctx.program("flow/diagnostics.cl", opts), "flow_compact_tiles");
  sources_ = compute::Kernel(ctx.program("flow/water_sources.cl", opts), "flow_sources");
  infiltration_.fill(0.0);
  if (ctx.precision() == compute::Precision::Double)
    writeParams<double>(params_, grid, tilesX_, tilesY_, settings);
  else
    writeParams<float>(params_, grid, tilesX_, tilesY_, settings);
  outStep_.fill(0.0);
  if (settings.twoPhase) buildDebris();
  if (settings.entrainment.enabled) buildEntrainment();
}

void FlowSolver::setInput(const FlowInput& in, double startTime) {
  const std::size_t n = grid_.cells();
  auto need = [&](std::size_t size, const char* what) {
    if (size != n) throw InputError(std::string("flow input '") + what + "' has " + std::to_string(size) +
                                    " values, the grid has " + std::to_string(n));
  };
  need(in.mask.size(), "mask");
  need(in.bed.size(), "bed");
  need(in.manning.size(), "manning");
  need(in.h.size(), "h");
  mask_.write(in.mask);
  domainCells_ = 0;
  for (uint8_t m : in.mask) domainCells_ += m ? 1 : 0;
  // Outside cells carry no water; their bed value is never read.
  std::vector<double> h = in.h, bed = in.bed;
  for (std::size_t k = 0; k < n; ++k)
    if (!in.mask[k]) h[k] = 0.0, bed[k] = 0.0;
  bed_.upload(bed);
  manning_.upload(in.manning);
  hasFriction_ = false;
  for (std::size_t k = 0; k < n; ++k) hasFriction_ = hasFriction_ || (in.mask[k] && in.manning[k] > 0.0);
  const SlopeGravity sg = computeSlopeGravity(grid_, bed, in.mask, settings_);
  gp_.upload(sg.gp);
  gn_.upload(sg.gn);
  slopeSpeed_.upload(sg.slopeSpeed);
  {
    std::vector<double> slope = sg.slopeX;
    slope.insert(slope.end(), sg.slopeY.begin(), sg.slopeY.end());
    bedSlope_.upload(slope);
  }
  maxSlopeSpeed_ = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (in.mask[k]) maxSlopeSpeed_ = std::max(maxSlopeSpeed_, sg.slopeSpeed[k]);
  h_.upload(h);
  {
    // The level outside a level edge: the initial water surface, over the solids in the two-phase
    // model (its fluid's bed is b + h_s).
    std::vector<double> far(n);
    const bool solids = settings_.twoPhase && in.hs.size() == n;
    for (std::size_t k = 0; k < n; ++k) far[k] = bed[k] + h[k] + (solids && in.mask[k] ? in.hs[k] : 0.0);
    farLevel_.upload(far);
  }
  // Momentum of dry and outside cells is discarded, as the update does after every stage.
  auto momentum = [&](const std::vector<double>& q, const char* what) {
    if (q.empty()) return std::vector<double>(n, 0.0);
    need(q.size(), what);
    std::vector<double> out = q;
    for (std::size_t k = 0; k < n; ++k)
      if (h[k] <= settings_.hDry) out[k] = 0.0;
    return out;
  };
  qx_.upload(momentum(in.qx, "qx"));
  qy_.upload(momentum(in.qy, "qy"));
  h1_.fill(0.0);
  qx1_.fill(0.0);
  qy1_.fill(0.0);
  outStep_.fill(0.0);
  hMax_.upload(h);
  vMax_.fill(0.0);
  arrival_.fill(-1.0);
  if (settings_.twoPhase) setDebrisInput(in, h);
  if (settings_.entrainment.enabled) setEntrainmentInput(in);
  time_ = startTime;
  splitStep_ = 0;
  // Every tile runs the first diagnostics, which finds the wet tiles.
  activateAllTiles();
  enqueueTrackMaxima();
  computeDiagnostics();
}

void FlowSolver::activateAllTiles() {
  std::vector<int> all(static_cast<std::size_t>(tilesX_) * tilesY_);
  std::iota(all.begin(), all.end(), 0);
  tileList_.write(all);
  tileActive_.fill(1);
  tileWet_.fill(0);
  activeTiles_ = tileCount();
}

void FlowSolver::addFluid(const FluidEdit& add) {
  add(h_, qx_, qy_);
  activateAllTiles();
  computeDiagnostics();
}

void FlowSolver::changeDischarge(const FluidEdit& change) {
  change(h_, qx_, qy_);
  computeDiagnostics();  // the wet tiles are unchanged: the active list still covers them
}

double FlowSolver::stableDt() const {
  if (std::isnan(diag_.maxSpeed)) return std::numeric_limits<double>::quiet_NaN();
  if (diag_.maxSpeed <= 0) return std::numeric_limits<double>::infinity();
  return settings_.cfl * grid_.dx / diag_.maxSpeed;
}

void FlowSolver::setInfiltration(const std::vector<double>& rate) {
  if (rate.empty()) {
    infiltration_.fill(0.0);
    hasInfiltration_ = false;
    return;
  }
  if (rate.size() != grid_.cells())
    throw InputError("infiltration map has " + std::to_string(rate.size()) + " values, the grid has " +
                     std::to_string(grid_.cells()));
  for (double f : rate)
    if (!(f >= 0) || !std::isfinite(f)) throw InputError("infiltration capacity must be finite and >= 0");
  infiltration_.upload(rate);
  hasInfiltration_ = true;
}

void FlowSolver::step(double dt, double rainDepth) {
  if (!(dt > 0) || !std::isfinite(dt)) throw SimulationError("flow step with invalid dt " + std::to_string(dt));
  if (!(rainDepth >= 0) || !std::isfinite(rainDepth))
    throw SimulationError("flow step with invalid rain depth " + std::to_string(rainDepth));
  if (settings_.twoPhase) {
    enqueueDebrisStage(true, dt);
    enqueueDebrisStage(false, dt);
    if (settings_.entrainment.enabled) enqueueEntrainment(dt);
  } else {
    if (sweeps(settings_.scheme)) {
      // One sweep per direction, x first on even steps and y first on odd ones (the alternation
      // makes Lie splitting second order, as Strang's symmetric form; Strang 1968). A sweep is one
      // SSP-RK2 (two stages) or one MUSCL-Hancock stage (its predictor is in the stage kernel).
      const int first = (splitStep_ % 2 == 0) ? kDirX : kDirY;
      const int second = first == kDirX ? kDirY : kDirX;
      if (settings_.scheme == TimeScheme::Hancock) {
        // Friction Strang-split around the sweeps (flow/hancock.cl): dt/2 here, dt/2 after.
        if (hasFriction_) enqueueFriction(0.5 * dt);
        enqueueStage(h_, qx_, qy_, h1_, qx1_, qy1_, dt, 0.0, true, first);
        enqueueStage(h1_, qx1_, qy1_, h_, qx_, qy_, dt, 0.0, false, second);
      } else {
        enqueueStage(h_, qx_, qy_, h1_, qx1_, qy1_, dt, 0.0, true, first);
        enqueueStage(h1_, qx1_, qy1_, h_, qx_, qy_, dt, 0.5, false, first);
        enqueueStage(h_, qx_, qy_, h1_, qx1_, qy1_, dt, 0.0, false, second);
        enqueueStage(h1_, qx1_, qy1_, h_, qx_, qy_, dt, 0.5, false, second);
      }
      ++splitStep_;
    } else {
      enqueueStage(h_, qx_, qy_, h1_, qx1_, qy1_, dt, 0.0, true, kDirX | kDirY);
      enqueueStage(h1_, qx1_, qy1_, h_, qx_, qy_, dt, 0.5, false, kDirX | kDirY);
    }
    if (hasFriction_) enqueueFriction(settings_.scheme == TimeScheme::Hancock ? 0.5 * dt : dt);
  }
  // Rain and infiltration act on the water: the single-phase model's, or the fluid phase of the
  // two-phase model (h_, qx_, qy_ hold the fluid there too), after the phases' own step.
  const bool sources = rainDepth > 0 || hasInfiltration_;
  const double infiltrated = sources ? enqueueSources(dt, rainDepth) : 0.0;
  time_ += dt;
  enqueueTrackMaxima();
  computeDiagnostics();
  diag_.rain = rainDepth * static_cast<double>(domainCells_) * grid_.dx * grid_.dx;
  diag_.infiltrated = infiltrated;
}

void FlowSolver::applySources(double dt, double rainDepth) {
  const double infiltrated = enqueueSources(dt, rainDepth);
  computeDiagnostics();
  diag_.rain = rainDepth * static_cast<double>(domainCells_) * grid_.dx * grid_.dx;
  diag_.infiltrated = infiltrated;
}

double FlowSolver::filmStableDt() const {
  if (!(maxSlopeSpeed_ > 0)) return std::numeric_limits<double>::infinity();
  // The film's wave speed is 2 w over both directions (unsplit), w along one (split).
  const double directions = sweeps(settings_.scheme) ? 1.0 : 2.0;
  return settings_.cfl * grid_.dx / (directions * maxSlopeSpeed_);
}

double FlowSolver::enqueueSources(double dt, double rainDepth) {
  sources_.bind(params_, mask_, infiltration_, compute::RealArg{rainDepth}, compute::RealArg{dt}, h_, qx_, qy_, sink_);
  const compute::Range global{static_cast<std::size_t>(tilesX_) * kTile, static_cast<std::size_t>(tilesY_) * kTile};
  sources_.launch(global, kLocal2D, "flow_sources");
  // Rain wets dry tiles, which the active list may not hold: the maxima and the diagnostics then
  // run over every tile, and the diagnostics find the wet ones (infiltration only dries cells, so
  // the list still covers the water).
  if (rainDepth > 0) activateAllTiles();
  return hasInfiltration_ ? reducer_.sum(sink_, grid_.cells()) * grid_.dx * grid_.dx : 0.0;
}

void FlowSolver::enqueueStage(const compute::RealBuffer& hSt, const compute::RealBuffer& qxSt,
                               const compute::RealBuffer& qySt, compute::RealBuffer& hOut,
                               compute::RealBuffer& qxOut, compute::RealBuffer& qyOut, double dt, double a,
                               bool firstStage, int directions) {
  // Base state of the RK combination is always U0 (h_, qx_, qy_); in stage 2 the output is U0 too,
  // which is safe because each work-item reads its own cell's base value before writing it.
  stage_.bind(params_, mask_, tileList_, bed_, gp_, gn_, farLevel_, h_, qx_, qy_, hSt, qxSt, qySt, hOut, qxOut, qyOut,
              outStep_, compute::RealArg{dt}, compute::RealArg{a},
              compute::RealArg{settings_.scheme == TimeScheme::Hancock ? dt : 0.5 * dt}, firstStage ? 1 : 0,
              directions);
  stage_.launch(tileRange(), kLocal2D, firstStage ? "flow_stage_1" : "flow_stage_2");
}

void FlowSolver::enqueueFriction(double dt) {
  friction_.bind(params_, mask_, tileList_, manning_, gn_, bedSlope_, h_, qx_, qy_, compute::RealArg{dt});
  friction_.launch(tileRange(), kLocal2D);
}

void FlowSolver::enqueueTrackMaxima() {
  if (settings_.twoPhase) {
    enqueueDebrisTrack();
    return;
  }
  track_.bind(params_, mask_, tileList_, h_, qx_, qy_, hMax_, vMax_, arrival_, compute::RealArg{time_});
  track_.launch(tileRange(), kLocal2D);
}

void FlowSolver::computeDiagnostics() {
  const std::size_t ntiles = static_cast<std::size_t>(tilesX_) * tilesY_;
  using compute::ReduceOp;
  if (activeTiles_ > 0) {
    std::vector<ReduceOp> ops = {ReduceOp::Max, ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Sum,
                                 ReduceOp::Min, ReduceOp::Max, ReduceOp::Max};
    if (settings_.twoPhase) {
      enqueueDebrisDiagnostics();
      for (int r = 0; r < 5; ++r) ops.push_back(ReduceOp::Sum);
    } else {
      diagnostics_.bind(params_, mask_, tileList_, h_, qx_, qy_, slopeSpeed_, outStep_, partial_, tileWet_);
      diagnostics_.launch(tileRange(), kLocal2D);
    }
    const std::vector<double> r = reducer_.reduceRows(partial_, static_cast<std::size_t>(activeTiles_), ops, ntiles);
    const bool tp = settings_.twoPhase;
    diag_ = {r[0], r[1], r[2], r[3], r[4], tp ? r[7] : 0.0, tp ? r[8] : 0.0, tp ? r[9] : 0.0, tp ? r[10] : 0.0,
             r[5], r[6]};
    if (tp) diag_.sourceWork = r[11];
  } else {
    diag_ = {};
  }
  if (settings_.entrainment.enabled) diag_.erodible = erodibleVolume_;
  // Next step's active tiles: the wet tiles and their neighbours, as an ascending list.
  compact_.bind(params_, tileWet_, tileActive_, tileList_, tileCount_);
  compact_.launch({256}, {256});
  activeTiles_ = tileCount_.read()[0];
}

std::vector<char> FlowSolver::saveState() const {
  std::vector<const compute::RawBuffer*> fields = {&h_.raw(), &qx_.raw(), &qy_.raw(), &hMax_.raw(), &vMax_.raw(),
                                                   &arrival_.raw()};
  if (settings_.twoPhase) fields.insert(fields.end(), {&solid0_.raw(), &maxima_.raw(), &lock0_.raw()});
  // Entrainment changes the bed and with it every slope field: all of them are state.
  if (settings_.entrainment.enabled)
    fields.insert(fields.end(), {&erodible_.raw(), &bedChange_.raw(), &bed_.raw(), &gn_.raw(), &gp_.raw(),
                                 &slopeSpeed_.raw(), &bedSlope_.raw()});
  std::vector<char> bytes;
  for (const compute::RawBuffer* f : fields) {
    const std::size_t at = bytes.size();
    bytes.resize(at + f->bytes());
    f->readBytes(bytes.data() + at, f->bytes());
  }
  // The split scheme's sweep order of the next step (one byte; unsplit checkpoints have none).
  if (sweeps(settings_.scheme)) bytes.push_back(static_cast<char>(splitStep_ % 2));
  return bytes;
}

void FlowSolver::restoreState(const std::vector<char>& bytes, double time) {
  std::vector<compute::RawBuffer*> fields = {&h_.raw(), &qx_.raw(), &qy_.raw(), &hMax_.raw(), &vMax_.raw(),
                                             &arrival_.raw()};
  if (settings_.twoPhase) fields.insert(fields.end(), {&solid0_.raw(), &maxima_.raw(), &lock0_.raw()});
  if (settings_.entrainment.enabled)
    fields.insert(fields.end(), {&erodible_.raw(), &bedChange_.raw(), &bed_.raw(), &gn_.raw(), &gp_.raw(),
                                 &slopeSpeed_.raw(), &bedSlope_.raw()});
  std::size_t total = 0;
  for (const compute::RawBuffer* f : fields) total += f->bytes();
  const bool split = sweeps(settings_.scheme);
  if (split) total += 1;
  if (bytes.size() != total)
    throw InputError("checkpoint state has " + std::to_string(bytes.size()) +
                     " bytes, this grid, model and precision need " + std::to_string(total));
  std::size_t at = 0;
  for (compute::RawBuffer* f : fields) {
    f->writeBytes(bytes.data() + at, f->bytes());
    at += f->bytes();
  }
  if (split) splitStep_ = static_cast<std::uint64_t>(bytes.back() != 0);
  time_ = time;
  if (settings_.entrainment.enabled) erodibleVolume_ = reducer_.sum(erodible_, grid_.cells()) * grid_.dx * grid_.dx;
  // Diagnostics and the active tiles follow from the state alone: recompute them over every tile.
  std::vector<int> all(static_cast<std::size_t>(tilesX_) * tilesY_);
  std::iota(all.begin(), all.end(), 0);
  tileList_.write(all);
  activeTiles_ = tileCount();
  outStep_.fill(0.0);
  computeDiagnostics();
}

std::map<std::string, cl_mem> FlowSolver::viewBuffers() const {
  return {{"h", h_.mem()},       {"qx", qx_.mem()},     {"qy", qy_.mem()},
          {"hMax", hMax_.mem()}, {"vMax", vMax_.mem()}, {"arrival", arrival_.mem()}};
}

compute::Range FlowSolver::tileRange() const {
  return {static_cast<std::size_t>(activeTiles_) * kTile, static_cast<std::size_t>(kTile)};
}

}  // namespace talus::flow
