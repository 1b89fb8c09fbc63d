#include "sim/ParticleRun.hpp"

#include <cstdint>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/Error.hpp"
#include "io/ParticleLayerIO.hpp"

namespace talus::sim {

ParticleRun::ParticleRun(compute::Context& ctx, const Raster& dem, const ParticleScene& scene, flow::FlowSolver& flow)
    : dem_(dem), flow_(flow) {
  solver_ = std::make_unique<particles::ParticleSolver>(ctx, dem.grid, scene.terrain, scene.settings);
  solver_->setParticles(scene.seeded, scene.material);
  solver_->setFluidCoupling(scene.fluid, scene.grain);
  solver_->computeDerivedFields();  // the layer at the start time is written before any step
  solver_->trackMaxima();           // the peak maps start with the release
  fluidDensity_ = scene.settings.fluidDensity;
  initialMass_ = solver_->diagnostics().mass;
  // The grid sees the particles from its first step on (a zero-length exchange changes nothing).
  if (flow_.settings().particleBed) {
    flow_.changeDischarge([&](compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy) {
      solver_->exchangeWithFluid(h, qx, qy, 0.0);
      solver_->writeGridBed(flow_.particleBed());
    });
    fluidAtParticles_ = true;
  }
}

double ParticleRun::maxStep() { return 200 * solver_->stableSubStep(); }

std::string ParticleRun::step(double dt, double time) {
  flow::FlowSolver& flow = flow_;
  // The reaction of the grid's bed forces on the particles in the grid step just taken; the
  // particles have not moved since the exchange that set that bed.
  if (flow.settings().particleBed) solver_->applyBedImpulse(flow.bedImpulse());
  solver_->step(dt);
  cacheValid_ = false;
  const particles::ParticleDiagnostics& d = solver_->diagnostics();
  outflow_ += d.outflowMass;
  releasedLast_ = 0;
  if (d.pendingRelease > 0)
    flow.addFluid([&](compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy) {
      releasedLast_ = solver_->releaseToGrid(h, qx, qy);
    });
  releasedTotal_ += releasedLast_;
  coupleToGrid(dt);
  solver_->trackMaxima();
  // A particle faster than the elastic wave speed times 10 (or NaN) means the explicit scheme has
  // blown up: no physical flow on a DEM gets there.
  if (!std::isfinite(d.maxSpeed) || !std::isfinite(d.kinetic)) {
    std::ostringstream o;
    o << "particles: non-finite velocity at t = " << time << " s (" << d.count << " particles)";
    return o.str();
  }
  return "";
}

void ParticleRun::coupleToGrid(double dt) {
  flow::FlowSolver& flow = flow_;
  // Drag with the free fluid, and the fluid depth at the particles for their friction: skipped while
  // the grid holds no fluid (once more after it dried, to clear the depth the particles hold). With
  // the particle bed, the exchange (its P2G) runs whenever the grid holds any material, which then
  // flows over the particles in the next grid step; an empty grid needs no bed.
  const flow::FlowDiagnostics& d = flow.diagnostics();
  const bool wet = d.volume > 0, any = wet || d.volumeSolid > 0;
  const bool bed = flow.settings().particleBed && any;
  // The bed of the next step is written inside the edit, so the diagnostics the edit recomputes
  // (the time step's wave speed) see it.
  if (wet || fluidAtParticles_ || bed)
    flow.changeDischarge([&](compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy) {
      solver_->exchangeWithFluid(h, qx, qy, dt);
      if (flow.settings().particleBed) solver_->writeGridBed(flow.particleBed());
    });
  else if (flow.settings().particleBed)
    solver_->writeGridBed(flow.particleBed());
  fluidAtParticles_ = wet;
}

// Layout: bookkeeping (5 doubles), the particle bed the next grid step uses (its byte count, then
// its bytes; empty in runs without it), the particle solver's state.
std::vector<char> ParticleRun::saveState() const {
  const double book[5] = {initialMass_, outflow_, releasedTotal_, fluidAtParticles_ ? 1.0 : 0.0,
                          solver_->gridTransferValid() ? 1.0 : 0.0};
  std::vector<char> bytes(sizeof book);
  std::memcpy(bytes.data(), book, sizeof book);
  const bool bed = flow_.settings().particleBed;
  const uint64_t bedBytes = bed ? flow_.particleBed().raw().bytes() : 0;
  const std::size_t at = bytes.size();
  bytes.resize(at + sizeof bedBytes + bedBytes);
  std::memcpy(bytes.data() + at, &bedBytes, sizeof bedBytes);
  if (bed) flow_.particleBed().raw().readBytes(bytes.data() + at + sizeof bedBytes, bedBytes);
  const std::vector<char> s = solver_->saveState();
  bytes.insert(bytes.end(), s.begin(), s.end());
  return bytes;
}

void ParticleRun::restoreState(const std::vector<char>& bytes) {
  double book[5];
  uint64_t bedBytes = 0;
  if (bytes.size() < sizeof book + sizeof bedBytes) throw InputError("checkpoint: the particle state is truncated");
  std::memcpy(book, bytes.data(), sizeof book);
  std::memcpy(&bedBytes, bytes.data() + sizeof book, sizeof bedBytes);
  const bool bed = flow_.settings().particleBed;
  const std::size_t at = sizeof book + sizeof bedBytes;
  if (bedBytes != (bed ? flow_.particleBed().raw().bytes() : 0) || bytes.size() < at + bedBytes)
    throw InputError("checkpoint: the particle bed does not match this run");
  initialMass_ = book[0], outflow_ = book[1], releasedTotal_ = book[2], fluidAtParticles_ = book[3] != 0;
  solver_->restoreState(std::vector<char>(bytes.begin() + at + bedBytes, bytes.end()));
  if (bed) {
    flow_.particleBed().raw().writeBytes(bytes.data() + at, bedBytes);
    // The time step's wave speed includes the particle bed's slope: recompute the diagnostics.
    flow_.refreshDiagnostics();
    // The P2G that the pending bed impulse is shared out with: recomputed from the same positions.
    if (book[4] != 0) solver_->refreshGridTransfer();
  }
  cacheValid_ = false;
}

double ParticleRun::balanceError() const {
  // Released water left the particles for the grid (and the pending part is still on its way).
  const double released = fluidDensity_ * (releasedTotal_ + solver_->diagnostics().pendingRelease);
  return initialMass_ > 0 ? (mass() + outflow_ + released - initialMass_) / initialMass_ : 0.0;
}

std::string ParticleRun::csvRow() const {
  const particles::ParticleDiagnostics& d = solver_->diagnostics();
  char line[256];
  std::snprintf(line, sizeof line, "%zu,%.12g,%.6g,%.6g,%.6g,%.6g,%.6g,%.9g", d.count, d.mass, d.outflowMass, d.kinetic,
                d.viscousDissipation, d.artificialStressWork, d.frictionWork, d.potentialReleased);
  return line;
}

void ParticleRun::writeLayer(const std::string& path) const {
  const particles::ParticleState& s = state();
  const Grid& g = dem_.grid;
  const std::size_t n = s.size();
  // Particles removed in the last sub-step (NaN position) are not written: they are outflow.
  std::vector<std::size_t> live;
  for (std::size_t q = 0; q < n; ++q)
    if (std::isfinite(s.x[q]) && std::isfinite(s.y[q])) live.push_back(q);
  auto keep = [&](const std::vector<double>& v) {
    std::vector<double> out(live.size());
    for (std::size_t k = 0; k < live.size(); ++k) out[k] = v[live[k]];
    return out;
  };
  io::ParticleRecords r;
  r.x = keep(s.x);
  r.y = keep(s.y);
  std::vector<double> vx(n), vy(n), speed(n), I1(n), sqrtJ2(n), frac(n), fsc(n), ffc(n);
  for (std::size_t q = 0; q < n; ++q) {
    const auto [ex, ny] = io::gridFrameVectorToWorld(g, s.vx[q], s.vy[q]);
    vx[q] = ex, vy[q] = ny;
    speed[q] = std::hypot(s.vx[q], s.vy[q]);
    // Total stress: the depth-integrated in-plane stress over H, and the overburden (P.41).
    const double H = s.H[q];
    const double xx = H > 0 ? s.Nxx[q] / H : 0, yy = H > 0 ? s.Nyy[q] / H : 0, xy = H > 0 ? s.Nxy[q] / H : 0;
    const double zz = -0.5 * s.density[q] * solver_->normalGravityAt(s.x[q], s.y[q]) * H;
    const double p2 = 0.5 * (xx + yy), d = 0.5 * (xx - yy);
    I1[q] = xx + yy + zz;
    sqrtJ2[q] = std::sqrt(d * d + xy * xy + (p2 - zz) * (p2 - zz) / 3);
    frac[q] = s.cohesion0[q] > 0 ? s.cohesion[q] / s.cohesion0[q] : 1.0;
    fsc[q] = s.structured0[q] * frac[q];
    ffc[q] = s.confined0[q] * frac[q];
  }
  r.add("vx", keep(vx));
  r.add("vy", keep(vy));
  r.add("speed", keep(speed));
  r.add("I1", keep(I1));
  r.add("sqrtJ2", keep(sqrtJ2));
  r.add("cohesion_fraction", keep(frac));
  r.add("f_sc", keep(fsc));
  r.add("f_fc", keep(ffc));
  r.add("plastic_strain", keep(s.plastic));
  r.add("mass", keep(s.mass));
  r.add("thickness", keep(s.H));
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  io::writeParticleLayer(path, g, r);
}

const particles::ParticleState& ParticleRun::state() const {
  if (!cacheValid_) {
    cache_ = solver_->state();
    cacheValid_ = true;
  }
  return cache_;
}

std::size_t ParticleRun::count() const { return solver_->diagnostics().count; }

std::vector<ParticleAttributeInfo> ParticleRun::attributes() const {
  return {{"velocity", "m/s"}, {"stress invariant", "Pa"}, {"cohesion fraction", "-"}, {"thickness", "m"}};
}

std::vector<float> ParticleRun::positions() const {
  const particles::ParticleState& s = state();
  const Grid& g = dem_.grid;
  const auto& gt = g.geoTransform;
  std::vector<float> out;
  out.reserve(3 * s.size());
  for (std::size_t q = 0; q < s.size(); ++q) {
    if (!std::isfinite(s.x[q])) continue;  // removed in the last sub-step
    const double u = s.x[q] / g.dx, v = s.y[q] / g.dx;  // column, row coordinates
    const int i = std::min(std::max(static_cast<int>(u), 0), g.nx - 1), j = std::min(std::max(static_cast<int>(v), 0), g.ny - 1);
    out.push_back(static_cast<float>(gt[0] + u * gt[1] + v * gt[2]));
    out.push_back(static_cast<float>(gt[3] + u * gt[4] + v * gt[5]));
    out.push_back(static_cast<float>(dem_.values[g.index(i, j)] + s.H[q]));
  }
  return out;
}

std::vector<float> ParticleRun::attribute(const std::string& name) const {
  const particles::ParticleState& s = state();
  std::vector<float> out;
  out.reserve(s.size());
  for (std::size_t q = 0; q < s.size(); ++q) {
    if (!std::isfinite(s.x[q])) continue;
    double v = 0;
    if (name == "velocity") {
      v = std::hypot(s.vx[q], s.vy[q]);
    } else if (name == "stress invariant") {
      // sqrt(J2) of the in-plane elastic stress with its trace part removed (2D deviator).
      const double d = 0.5 * (s.sxx[q] - s.syy[q]);
      v = std::sqrt(d * d + s.sxy[q] * s.sxy[q]);
    } else if (name == "cohesion fraction") {
      v = s.cohesion0[q] > 0 ? s.cohesion[q] / s.cohesion0[q] : 1.0;
    } else if (name == "thickness") {
      v = s.H[q];
    } else {
      return {};
    }
    out.push_back(static_cast<float>(v));
  }
  return out;
}

}  // namespace talus::sim
