#include "particles/ParticleSolver.hpp"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <string>

#include "compute/Program.hpp"
#include "core/Constants.hpp"
#include "core/Error.hpp"
#include "flow/DebrisParams.hpp"
#include "flow/SlopeGravity.hpp"
#include "particles/LaunchSize.hpp"
#include "particles/ParticleParams.hpp"

namespace talus::particles {
namespace {

/// The cell-centre elevations of the particles' bed surface (particle_common.cl, bed_gradient):
/// the DEM's, and in each nodata cell the mean of its nearest domain cells (rings of 4-neighbours, filled
/// outwards), so the surface near a nodata hole or edge continues flat instead of falling to a placeholder.
std::vector<double> surfaceElevations(const Grid& g, const std::vector<double>& bed, const std::vector<uint8_t>& mask) {
  std::vector<double> z(g.cells(), 0.0);
  std::vector<uint8_t> known(g.cells(), 0);
  std::vector<std::size_t> front;
  for (std::size_t k = 0; k < g.cells(); ++k)
    if (mask[k]) z[k] = bed[k], known[k] = 1, front.push_back(k);
  const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
  while (!front.empty()) {
    std::vector<std::size_t> next;
    for (std::size_t k : front) {
      const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
      for (int d = 0; d < 4; ++d) {
        const int a = i + di[d], b = j + dj[d];
        if (a < 0 || b < 0 || a >= g.nx || b >= g.ny || known[g.index(a, b)]) continue;
        known[g.index(a, b)] = 2;  // in this ring: its value is the mean of its known neighbours
        next.push_back(g.index(a, b));
      }
    }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    for (std::size_t k : next) {
      const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
      double sum = 0;
      int count = 0;
      for (int d = 0; d < 4; ++d) {
        const int a = i + di[d], b = j + dj[d];
        if (a >= 0 && b >= 0 && a < g.nx && b < g.ny && known[g.index(a, b)] == 1) sum += z[g.index(a, b)], ++count;
      }
      z[k] = sum / count;
    }
    for (std::size_t k : next) known[k] = 1;
    front.swap(next);
  }
  return z;
}

/// The largest smoothing length of the thickness sums, in units of h (kernels/particles/
/// particle_density.cl): a particle left alone keeps (1/3)^2 of the floor a fixed h gives its
/// thickness (W(0, 3h) = W(0, h) / 9: 1.3 % of the seeded thickness at 4 particles per cell instead of
/// 11 %), and its search covers at most 7 x 7 cells of the neighbour grid (edge 2h). A layer expanded
/// up to 9 times in area keeps its seeded h / dp.
constexpr double kThicknessSmoothingGrowth = 3.0;

template <class Real>
void fillParams(compute::RawBuffer& buf, const Grid& g, const ParticleSettings& s, double h, std::size_t count,
                double soundSpeed, double wSpacing, double seedArea) {
  ParticleParamsT<Real> p{};
  p.nx = g.nx;
  p.ny = g.ny;
  p.count = static_cast<int32_t>(count);
  p.earthPressure = static_cast<int32_t>(s.earthPressure);
  p.edgeWall = s.edgeWalls ? 1 : 0;
  p.nodataWall = s.nodataWalls ? 1 : 0;
  p.dx = static_cast<Real>(g.dx);
  p.h = static_cast<Real>(h);
  p.shearModulus = static_cast<Real>(s.shearModulus());
  p.planeBulkModulus = static_cast<Real>(s.planeBulkModulus());
  p.soundSpeed = static_cast<Real>(soundSpeed);
  p.alphaPi = static_cast<Real>(s.alphaPi);
  p.betaPi = static_cast<Real>(s.betaPi);
  p.epsArt = static_cast<Real>(s.epsArt);
  p.nArt = static_cast<Real>(s.nArt);
  p.wSpacing = static_cast<Real>(wSpacing);
  p.dilatancy = static_cast<Real>(s.dilatancy);
  p.epsCrit = static_cast<Real>(s.epsCrit);
  p.kConst = static_cast<Real>(s.kConst);
  p.poreB = static_cast<Real>(s.poreB);
  p.rhoF = static_cast<Real>(s.fluidDensity);
  p.seedArea = static_cast<Real>(seedArea);
  p.hMax = static_cast<Real>(kThicknessSmoothingGrowth * h);
  buf.writeBytes(&p, sizeof p);
}

/// The 2D cubic spline W(r, h) (kernels/particles/sph.cl) on the host, for W(dp).
double splineW(double r, double h) {
  const double q = r / h, s = 10.0 / (7.0 * 3.14159265358979323846 * h * h);
  if (q < 1) return s * (1 - 1.5 * q * q + 0.75 * q * q * q);
  if (q < 2) return s * 0.25 * (2 - q) * (2 - q) * (2 - q);
  return 0;
}

std::vector<double> perParticle(const std::vector<double>& v, std::size_t n, const char* what) {
  if (v.size() == n) return v;
  if (v.size() == 1) return std::vector<double>(n, v[0]);
  throw InputError(std::string("particle material '") + what + "' has " + std::to_string(v.size()) +
                   " values for " + std::to_string(n) + " particles");
}

}  // namespace

ParticleSolver::ParticleSolver(compute::Context& ctx, const Grid& grid, const ParticleTerrain& terrain,
                               const ParticleSettings& settings)
    : ctx_(ctx), grid_(grid), settings_(settings), reducer_(ctx) {
  const std::size_t n = grid.cells();
  if (terrain.mask.size() != n || terrain.bed.size() != n)
    throw InputError("particle terrain: mask and bed must have " + std::to_string(n) + " cells");
  if (!(settings.smoothingFactor > 0) || !(settings.cfl > 0 && settings.cfl <= 1) || !(settings.youngModulus > 0) ||
      !(settings.poisson > -1 && settings.poisson < 0.5))
    throw InputError("particle settings: smoothing factor > 0, CFL in (0, 1], E > 0 and Poisson ratio in (-1, 0.5) required");
  h_ = settings.smoothingFactor * grid.dx;
  flow::FlowSettings fs;
  fs.slopeCorrection = terrain.slopeCorrection;
  const flow::SlopeGravity sg = flow::computeSlopeGravity(grid, terrain.bed, terrain.mask, fs);
  mask_ = compute::Buffer<uint8_t>(ctx, n, "particle terrain mask");
  mask_.write(terrain.mask);
  bed_ = compute::RealBuffer(ctx, n, "particle bed elevation");
  std::vector<double> bed = terrain.bed;
  for (std::size_t k = 0; k < n; ++k)
    if (!terrain.mask[k]) bed[k] = 0.0;  // never read: a nodata face is a wall or an outlet (particle_integrate.cl)
  bed_.upload(bed);
  {
    // The bed surface's bilinear patches (particle_common.cl, bed_gradient), in double: the slopes
    // of each patch's edges from its lower-left cell centre and its twist, rows of n.
    const std::vector<double> z = surfaceElevations(grid, terrain.bed, terrain.mask);
    std::vector<double> patch(3 * n, 0.0);
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t k = grid.index(i, j);
        const bool east = i + 1 < grid.nx, north = j + 1 < grid.ny;
        const double b00 = z[k], b10 = east ? z[grid.index(i + 1, j)] : b00, b01 = north ? z[grid.index(i, j + 1)] : b00;
        const double b11 = east && north ? z[grid.index(i + 1, j + 1)] : east ? b10 : b01;
        patch[k] = (b10 - b00) / grid.dx;
        patch[n + k] = (b01 - b00) / grid.dx;
        patch[2 * n + k] = (b11 - b10 - b01 + b00) / grid.dx;
      }
    bedPatch_ = compute::RealBuffer(ctx, 3 * n, "particle bed surface patches");
    bedPatch_.upload(patch);
    patchHost_ = std::move(patch);
  }
  slopeCorrection_ = terrain.slopeCorrection;
  limitedSlope_ = compute::RealBuffer(ctx, 2 * n, "particle limited bed slope");
  {
    std::vector<double> ls = sg.slopeX;
    ls.insert(ls.end(), sg.slopeY.begin(), sg.slopeY.end());
    limitedSlope_.upload(ls);
  }
  params_ = compute::RawBuffer(ctx, sizeof(ParticleParamsT<double>), "particle parameters");
  const bool curved = terrain.slopeCorrection && terrain.curvature;
  const std::string metric = std::string("-DPARTICLE_METRIC=") + (terrain.slopeCorrection ? "1" : "0");
  const std::string integrateOpts = std::string("-DPARTICLE_CURVATURE=") + (curved ? "1 " : "0 ") + metric;
  stress_ = compute::Kernel(ctx.program("particles/particle_stress.cl", metric), "particle_stress");
  forces_ = compute::Kernel(ctx.program("particles/particle_forces.cl"), "particle_forces");
  integrate_ = compute::Kernel(ctx.program("particles/particle_integrate.cl", integrateOpts), "particle_integrate");
  speedKernel_ = compute::Kernel(ctx.program("particles/particle_integrate.cl", integrateOpts), "particle_totals");
  // The neighbour grid covers the raster with a margin of one support, so particles near the edge
  // see all their neighbours; particles leave the raster through the integrate kernel.
  const double r = 2 * h_;
  neighbours_ = std::make_unique<NeighbourGrid>(ctx, DomainBox{-r, -r, grid.nx * grid.dx + r, grid.ny * grid.dx + r}, r);
  transfer_ = std::make_unique<ParticleGridTransfer>(ctx, grid);
  releasedMap_ = compute::RealBuffer(ctx, n, "released fluid map");
  scratchX_ = compute::RealBuffer(ctx, n, "released discharge x");
  scratchY_ = compute::RealBuffer(ctx, n, "released discharge y");
  releasedMap_.fill(0.0);
  hMax_ = compute::RealBuffer(ctx, n, "particle peak thickness");
  vMax_ = compute::RealBuffer(ctx, n, "particle peak speed");
  hMax_.fill(0.0);
  vMax_.fill(0.0);
  trackH_ = compute::RealBuffer(ctx, n, "particle thickness for the peak maps");
  trackM_ = compute::RealBuffer(ctx, n, "particle mass for the peak maps");
  trackPx_ = compute::RealBuffer(ctx, n, "particle momentum x for the peak maps");
  trackPy_ = compute::RealBuffer(ctx, n, "particle momentum y for the peak maps");
  maxima_ = compute::Kernel(ctx.program("particles/particle_maxima.cl"), "particle_track_maxima");
}

double ParticleSolver::normalGravityAt(double x, double y) const {
  if (!slopeCorrection_ || !(std::isfinite(x) && std::isfinite(y))) return kGravity;
  const std::size_t n = grid_.cells();
  const double fx = x / grid_.dx - 0.5, fy = y / grid_.dx - 0.5;
  const int i0 = std::clamp(static_cast<int>(std::floor(fx)), 0, std::max(grid_.nx - 2, 0));
  const int j0 = std::clamp(static_cast<int>(std::floor(fy)), 0, std::max(grid_.ny - 2, 0));
  const std::size_t k = grid_.index(i0, j0);
  const double t = patchHost_[2 * n + k], bx = patchHost_[k] + t * (fy - j0), by = patchHost_[n + k] + t * (fx - i0);
  return kGravity / (1 + bx * bx + by * by);
}

void ParticleSolver::trackMaxima() {
  if (count_ == 0) return;
  neighbours_->build(x_, y_, count_);
  reorderAll();
  transfer_->confinedToGrid(*neighbours_, x_, y_, V_, m_, vx_, vy_, trackH_, trackM_, trackPx_, trackPy_);
  const int cells = static_cast<int>(grid_.cells());
  maxima_.bind(cells, trackH_, trackM_, trackPx_, trackPy_, hMax_, vMax_);
  maxima_.launch(compute::Range{grid_.cells()}, kParticleGroup, "particle_track_maxima");
}

double ParticleSolver::releaseToGrid(compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy) {
  const double volume = diag_.pendingRelease;
  if (count_ == 0 || !(volume > 0)) return 0.0;
  neighbours_->build(x_, y_, count_);
  reorderAll();
  transfer_->releasedToGrid(*neighbours_, x_, y_, released_, vx_, vy_, h, qx, qy, true);
  transfer_->releasedToGrid(*neighbours_, x_, y_, released_, vx_, vy_, releasedMap_, scratchX_, scratchY_, true);
  released_.fill(0.0);
  diag_.pendingRelease = 0;
  return volume;
}

void ParticleSolver::setFluidCoupling(const flow::DebrisSettings& fluid, double grain) {
  if (!(grain > 0)) throw InputError("particle fluid coupling: grain size must be positive");
  debrisParams_ = compute::RawBuffer(ctx_, sizeof(flow::DebrisParamsT<double>), "particle drag parameters");
  flow::writeDebrisParams(debrisParams_, fluid, ctx_.precision());
  drag_ = compute::Kernel(ctx_.program("particles/particle_exchange.cl"), "particle_fluid_drag");
  gridBed_ = compute::Kernel(ctx_.program("particles/particle_bed.cl"), "particle_grid_bed");
  bedVelocity_ = compute::Kernel(ctx_.program("particles/particle_bed.cl"), "particle_bed_velocity");
  const std::size_t cells = grid_.cells();
  for (compute::RealBuffer* b : {&cellH_, &cellM_, &cellPx_, &cellPy_, &cellDu_, &cellDv_})
    *b = compute::RealBuffer(ctx_, cells, "particle exchange cell field");
  if (settings_.picFraction > 0) {
    cellVelocity_ = compute::Kernel(ctx_.program("particles/particle_bed.cl"), "particle_cell_velocity");
    cellU_ = compute::RealBuffer(ctx_, cells, "particle exchange cell velocity x");
    cellV_ = compute::RealBuffer(ctx_, cells, "particle exchange cell velocity y");
  }
  grain_ = grain;
  coupled_ = true;
}

void ParticleSolver::exchangeWithFluid(const compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy,
                                       double dt) {
  if (!coupled_ || count_ == 0) return;
  neighbours_->build(x_, y_, count_);
  reorderAll();
  transfer_->confinedToGrid(*neighbours_, x_, y_, V_, m_, vx_, vy_, cellH_, cellM_, cellPx_, cellPy_);
  const int cells = static_cast<int>(grid_.cells());
  drag_.bind(debrisParams_, cells, compute::RealArg{grid_.dx}, compute::RealArg{1e-6}, compute::RealArg{grain_}, cellH_,
             cellM_, cellPx_, cellPy_, h, qx, qy, cellDu_, cellDv_, compute::RealArg{dt});
  drag_.launch(compute::Range{grid_.cells()}, kParticleGroup, "particle_fluid_drag");
  // FLIP: each particle gains the velocity change of the cells it weighs on (same weights as P2G);
  // the PIC share takes the cells' velocity after the exchange instead (spec §6, `PIC Fraction`).
  const double pic = settings_.picFraction;
  if (pic > 0) {
    cellVelocity_.bind(cells, cellM_, cellPx_, cellPy_, cellDu_, cellDv_, cellU_, cellV_);
    cellVelocity_.launch(compute::Range{grid_.cells()}, kParticleGroup, "particle_cell_velocity");
  }
  transfer_->gridVelocityToParticles(pic > 0 ? cellU_ : cellDu_, pic > 0 ? cellV_ : cellDv_, cellDu_, cellDv_, pic, x_,
                                     y_, count_, vx_, vy_);
  transfer_->gridToParticles(h, x_, y_, count_, fluidDepth_);
  gridValid_ = true;
  updateDiagnostics();
}

void ParticleSolver::refreshGridTransfer() {
  if (!coupled_ || count_ == 0) return;
  neighbours_->build(x_, y_, count_);
  reorderAll();
  transfer_->confinedToGrid(*neighbours_, x_, y_, V_, m_, vx_, vy_, cellH_, cellM_, cellPx_, cellPy_);
  gridValid_ = true;
}

void ParticleSolver::writeGridBed(compute::RealBuffer& bed) {
  if (!coupled_ || count_ == 0 || !gridValid_) {
    bed.fill(0.0);
    return;
  }
  const int cells = static_cast<int>(grid_.cells());
  gridBed_.bind(cells, cellH_, cellM_, cellPx_, cellPy_, cellDu_, cellDv_, bed);
  gridBed_.launch(compute::Range{grid_.cells()}, kParticleGroup, "particle_grid_bed");
}

void ParticleSolver::applyBedImpulse(const compute::RealBuffer& impulse) {
  if (!coupled_ || count_ == 0 || !gridValid_) return;
  bedVelocity_.bind(grid_.nx, grid_.ny, compute::RealArg{grid_.dx}, cellM_, impulse, cellDu_, cellDv_);
  bedVelocity_.launch(compute::Range{grid_.cells()}, kParticleGroup, "particle_bed_velocity");
  transfer_->gridVelocityToParticles(cellDu_, cellDv_, cellDu_, cellDv_, 0.0, x_, y_, count_, vx_, vy_);
  updateDiagnostics();
}

ParticleGridFields ParticleSolver::gridFields() {
  const std::size_t cells = grid_.cells();
  ParticleGridFields f;
  if (count_ == 0) {
    f.thickness.assign(cells, 0.0);
    f.cohesionFraction.assign(cells, -1.0);
    f.releasedFluid = releasedMap_.download();
    return f;
  }
  neighbours_->build(x_, y_, count_);
  reorderAll();
  compute::RealBuffer h(ctx_, cells, "particle thickness on the grid"), mass(ctx_, cells, "particle mass on the grid");
  compute::RealBuffer px(ctx_, cells, "particle momentum x"), py(ctx_, cells, "particle momentum y");
  transfer_->confinedToGrid(*neighbours_, x_, y_, V_, m_, vx_, vy_, h, mass, px, py);
  compute::RealBuffer c(ctx_, cells, "mean cohesion"), c0(ctx_, cells, "mean initial cohesion");
  transfer_->fieldToGrid(*neighbours_, x_, y_, m_, coh_, FieldTransfer::WeightedMean, c);
  transfer_->fieldToGrid(*neighbours_, x_, y_, m_, coh0_, FieldTransfer::WeightedMean, c0);
  f.thickness = h.download();
  f.releasedFluid = releasedMap_.download();
  const std::vector<double> cm = c.download(), c0m = c0.download();
  f.cohesionFraction.resize(cells);
  for (std::size_t k = 0; k < cells; ++k) f.cohesionFraction[k] = c0m[k] > 0 ? cm[k] / c0m[k] : -1.0;
  return f;
}

void ParticleSolver::setParticles(const SeededParticles& seeded, const ParticleMaterial& material) {
  const std::size_t n = seeded.size();
  gridValid_ = false;
  const std::vector<double> rho = perParticle(material.density, n, "density");
  const std::vector<double> phi = perParticle(material.phi, n, "phi");
  const std::vector<double> delta = perParticle(material.delta, n, "delta");
  const std::vector<double> coh = perParticle(material.cohesion, n, "cohesion");
  capacity_ = std::max<std::size_t>(n, 1);
  count_ = n;
  diag_.viscousDissipation = diag_.artificialStressWork = diag_.frictionWork = diag_.potentialReleased = 0;
  auto make = [&](compute::RealBuffer& b, const char* label) { b = compute::RealBuffer(ctx_, capacity_, label); };
  make(A_, "particle area"), make(V_, "particle volume"), make(numberDensity_, "particle number density");
  make(areaShare_, "particle area share");
  make(fsc0_, "particle initial structured fraction"), make(ffc0_, "particle initial confined fraction");
  make(Vf_, "particle confined fluid"), make(Vf0_, "particle initial confined fluid"), make(released_, "particle released fluid");
  make(fluidDepth_, "fluid depth at the particles");
  make(liftOff_, "particle lift-off speed");
  make(x_, "particle x"), make(y_, "particle y"), make(vx_, "particle vx"), make(vy_, "particle vy");
  make(m_, "particle mass"), make(rho_, "particle density"), make(phi_, "particle phi"), make(delta_, "particle delta");
  make(coh_, "particle cohesion"), make(coh0_, "particle initial cohesion"), make(sxx_, "particle sxx");
  make(syy_, "particle syy"), make(sxy_, "particle sxy"), make(plastic_, "particle plastic strain");
  make(rhoA_, "particle areal density"), make(H_, "particle thickness"), make(Nxx_, "particle Nxx");
  make(Nyy_, "particle Nyy"), make(Nxy_, "particle Nxy"), make(ax_, "particle ax"), make(ay_, "particle ay");
  tally_ = compute::RealBuffer(ctx_, 5 * capacity_, "particle sub-step tallies");
  speed_ = compute::RealBuffer(ctx_, 5 * capacity_, "particle totals");
  gradCorrection_ = compute::RealBuffer(ctx_, 3 * capacity_, "particle gradient correction");
  artStress_ = compute::RealBuffer(ctx_, 3 * capacity_, "particle artificial stress");
  if (n == 0) {
    allocateNeighbourLists();
    writeParams();
    updateDiagnostics();
    return;
  }
  const std::vector<double> zero(n, 0.0);
  A_.upload(seeded.area), V_.upload(seeded.volume), areaShare_.upload(zero);  // share 0: set at the first stress pass
  fsc0_.upload(material.structured.empty() ? std::vector<double>(n, 1.0) : perParticle(material.structured, n, "structured"));
  ffc0_.upload(material.confined.empty() ? std::vector<double>(n, 1.0) : perParticle(material.confined, n, "confined"));
  const std::vector<double> vf = material.fluidVolume.empty() ? zero : perParticle(material.fluidVolume, n, "fluid volume");
  for (std::size_t q = 0; q < n; ++q)
    if (!(vf[q] >= 0 && vf[q] <= seeded.volume[q]))
      throw InputError("particle " + std::to_string(q) + ": confined fluid volume " + std::to_string(vf[q]) +
                       " m^3 outside [0, the particle's volume " + std::to_string(seeded.volume[q]) + "]");
  Vf_.upload(vf), Vf0_.upload(vf), released_.upload(zero), fluidDepth_.upload(zero);
  liftOff_.upload(zero);
  x_.upload(seeded.x), y_.upload(seeded.y), vx_.upload(zero), vy_.upload(zero), m_.upload(seeded.mass);
  rho_.upload(rho), phi_.upload(phi), delta_.upload(delta), coh_.upload(coh), coh0_.upload(coh);
  sxx_.upload(zero), syy_.upload(zero), sxy_.upload(zero), plastic_.upload(zero);
  std::vector<uint32_t> cells = seeded.cell;
  std::sort(cells.begin(), cells.end());
  const double seededCells = static_cast<double>(std::unique(cells.begin(), cells.end()) - cells.begin());
  spacing_ = grid_.dx * std::sqrt(seededCells / static_cast<double>(n));
  allocateNeighbourLists();
  const double rhoMin = *std::min_element(rho.begin(), rho.end());
  const double elastic = std::sqrt(settings_.inPlaneWaveModulus() / rhoMin);
  waveSpeed_ = settings_.soundSpeed > 0 ? settings_.soundSpeed : elastic;
  writeParams();
  updateDiagnostics();
}

void ParticleSolver::allocateNeighbourLists() {
  // Room for 1.5 times the neighbours a particle has at the seeding's spacing, pi (2h / spacing)^2
  // (about 50 at 4 particles per cell and h = dx: 80 entries of an index and a kernel-gradient
  // factor). Denser spots than that (compressed by half in area) walk the grid instead: the same
  // pairs, only slower.
  const double expected = spacing_ > 0 ? 3.14159265358979 * std::pow(2 * h_ / spacing_, 2) : 0.0;
  const unsigned automatic = std::max(static_cast<unsigned>(8 * std::ceil(1.5 * expected / 8)), 16u);
  nbCap_ = settings_.neighbourListEntries > 0 ? settings_.neighbourListEntries : automatic;
  nbList_ = compute::Buffer<cl_uint>(ctx_, capacity_ * nbCap_, "particle neighbour lists");
  nbCount_ = compute::Buffer<cl_uint>(ctx_, capacity_, "particle neighbour counts");
  nbGrad_ = compute::RealBuffer(ctx_, capacity_ * nbCap_, "particle neighbour kernel gradients");
}

void ParticleSolver::setVelocities(const std::vector<double>& vx, const std::vector<double>& vy) {
  if (vx.size() != count_ || vy.size() != count_) throw InputError("particle velocities: wrong count");
  if (count_ == 0) return;
  vx_.upload(vx);
  vy_.upload(vy);
  updateDiagnostics();
}

void ParticleSolver::writeParams() {
  // The artificial stress scales with f_ij = W_ij / W(dp), dp the mean particle spacing: f = 1 for
  // a neighbour at the typical distance (with dp = h instead, f^4 reaches 67 for the 2 x 2 particles
  // per cell and the "correction" flips the sign of the stress: a blow-up from round-off).
  const double w = splineW(spacing_, h_);
  if (ctx_.precision() == compute::Precision::Double)
    fillParams<double>(params_, grid_, settings_, h_, count_, waveSpeed_, w, spacing_ * spacing_);
  else
    fillParams<float>(params_, grid_, settings_, h_, count_, waveSpeed_, w, spacing_ * spacing_);
}

double ParticleSolver::stableSubStep() {
  if (count_ == 0) return std::numeric_limits<double>::infinity();
  return settings_.cfl * h_ / (waveSpeed_ + diag_.maxSpeed);
}

void ParticleSolver::step(double dt) {
  if (!(dt > 0)) throw SimulationError("particle step: dt must be positive");
  gridValid_ = false;  // the particles move: the last P2G no longer describes them
  diag_.outflowMass = 0;
  diag_.subSteps = 0;
  double done = 0;
  while (done < dt && count_ > 0) {
    const double remaining = dt - done;
    const double sub = std::min(remaining, stableSubStep());
    const int k = static_cast<int>(std::ceil(remaining / sub - 1e-12));
    const double ds = remaining / std::max(k, 1);
    subStep(ds);
    done += ds;
    ++diag_.subSteps;
    if (k <= 1) break;
  }
  time_ += dt;
  updateDiagnostics();
}

// Every per-particle field: reordered together at each neighbour build, saved in checkpoints.
const std::vector<compute::RealBuffer ParticleSolver::*>& ParticleSolver::stateFields() {
  using S = ParticleSolver;
  static const std::vector<compute::RealBuffer S::*> fields = {
      &S::x_,   &S::y_,   &S::vx_,  &S::vy_,     &S::m_,       &S::rho_,  &S::phi_,     &S::delta_,
      &S::coh_, &S::coh0_, &S::sxx_, &S::syy_,   &S::sxy_,     &S::plastic_, &S::A_,    &S::V_,
      &S::fsc0_, &S::ffc0_, &S::Vf_, &S::Vf0_,   &S::released_, &S::fluidDepth_,
      &S::liftOff_, &S::areaShare_};
  return fields;
}

void ParticleSolver::reorderAll() {
  for (auto f : stateFields()) neighbours_->reorder(this->*f);
}

// Checkpoint layout: count, time, the four cumulative energies (artificial viscosity, artificial
// stress, friction, potential released), each state field's first `count` entries, then the two
// peak maps (thickness, speed; one value per cell).
std::vector<char> ParticleSolver::saveState() const {
  const uint64_t count = count_;
  const double energies[4] = {diag_.viscousDissipation, diag_.artificialStressWork, diag_.frictionWork,
                              diag_.potentialReleased};
  std::vector<char> bytes(sizeof count + sizeof time_ + sizeof energies);
  std::memcpy(bytes.data(), &count, sizeof count);
  std::memcpy(bytes.data() + sizeof count, &time_, sizeof time_);
  std::memcpy(bytes.data() + sizeof count + sizeof time_, energies, sizeof energies);
  const std::size_t each = count_ * compute::realSize(ctx_.precision());
  for (auto f : stateFields()) {
    const std::size_t at = bytes.size();
    bytes.resize(at + each);
    if (each) (this->*f).raw().readBytes(bytes.data() + at, each);
  }
  for (const compute::RealBuffer* map : {&hMax_, &vMax_}) {
    const std::size_t at = bytes.size(), size = map->raw().bytes();
    bytes.resize(at + size);
    map->raw().readBytes(bytes.data() + at, size);
  }
  return bytes;
}

void ParticleSolver::restoreState(const std::vector<char>& bytes) {
  uint64_t count = 0;
  gridValid_ = false;
  const auto& fields = stateFields();
  const std::size_t unit = compute::realSize(ctx_.precision());
  if (bytes.size() >= sizeof count + sizeof time_) std::memcpy(&count, bytes.data(), sizeof count);
  // Three layouts restore, newest first: four energies, every field and the peak maps; before
  // 2026-12-05 two energies (no friction work, no potential), every field but the last (the area
  // share) and no peak maps; before the energies were tallied, neither. Missing energies start from
  // zero; a missing area share is set again from the restored areas at the first stress pass; missing
  // peak maps restart from zero (the run warns: maxMapsRestored).
  struct Layout {
    std::size_t energies, fields, maps;
  };
  const std::size_t head = sizeof count + sizeof time_, mapBytes = hMax_.raw().bytes();
  const Layout layouts[3] = {{4, fields.size(), 2}, {2, fields.size() - 1, 0}, {0, fields.size() - 1, 0}};
  const Layout* found = nullptr;
  for (const Layout& l : layouts)
    if (bytes.size() == head + l.energies * sizeof(double) + l.fields * count * unit + l.maps * mapBytes) {
      found = &l;
      break;
    }
  if (!found || count > capacity_)
    throw InputError("checkpoint: the particle state does not fit this run's particles (" + std::to_string(capacity_) +
                     " seeded, " + compute::precisionName(ctx_.precision()) + ")");
  std::memcpy(&time_, bytes.data() + sizeof count, sizeof time_);
  double energies[4] = {0, 0, 0, 0};
  std::memcpy(energies, bytes.data() + head, found->energies * sizeof(double));
  diag_.viscousDissipation = energies[0];
  diag_.artificialStressWork = energies[1];
  diag_.frictionWork = energies[2];
  diag_.potentialReleased = energies[3];
  count_ = count;
  std::size_t at = head + found->energies * sizeof(double);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    compute::RealBuffer& f = this->*fields[k];
    if (k >= found->fields) {
      if (count) f.upload(std::vector<double>(capacity_, 0.0));
      continue;
    }
    if (count) f.raw().writeBytes(bytes.data() + at, count * unit);
    at += count * unit;
  }
  maxMapsRestored_ = found->maps == 2;
  for (compute::RealBuffer* map : {&hMax_, &vMax_}) {
    if (!maxMapsRestored_) {
      map->fill(0.0);
      continue;
    }
    map->raw().writeBytes(bytes.data() + at, mapBytes);
    at += mapBytes;
  }
  writeParams();
  updateDiagnostics();
}

bool ParticleSolver::sortAndEvaluateStress(double ds) {
  NeighbourGrid& ng = *neighbours_;
  ng.build(x_, y_, count_);
  reorderAll();
  const std::size_t inside = ng.readInsideCount();
  if (inside != count_) {
    count_ = inside;  // removed particles (NaN positions) sorted behind the live ones
    writeParams();
  }
  if (count_ == 0) return false;
  const compute::Range global{count_};
  stress_.bind(params_, ng.params(), ng.cellStart(), ng.cellEnd(), x_, y_, vx_, vy_, V_, A_, H_, rho_, bedPatch_, phi_, delta_, sxx_,
               syy_, sxy_, coh_, coh0_, plastic_, Nxx_, Nyy_, Nxy_, gradCorrection_, areaShare_, numberDensity_, rhoA_,
               artStress_, nbList_, nbGrad_, nbCount_, nbCap_, compute::RealArg{ds});
  stress_.launch(global, kParticleGroup, "particle_stress");
  return true;
}

void ParticleSolver::subStep(double ds) {
  if (!sortAndEvaluateStress(ds)) return;
  NeighbourGrid& ng = *neighbours_;
  const compute::Range global{count_};
  forces_.bind(params_, ng.params(), ng.cellStart(), ng.cellEnd(), nbList_, nbGrad_, nbCount_, nbCap_, x_, y_, vx_, vy_, m_, A_,
               rhoA_,
               Nxx_, Nyy_, Nxy_, gradCorrection_, artStress_, ax_, ay_, tally_);
  forces_.launch(global, kParticleGroup, "particle_forces");
  integrate_.bind(params_, mask_, bed_, bedPatch_, limitedSlope_, x_, y_, vx_, vy_, m_, delta_, ax_, ay_, A_, areaShare_, numberDensity_, V_, rho_, Vf_,
                  Vf0_, coh_, coh0_, released_, fluidDepth_, liftOff_, tally_, compute::RealArg{ds});
  integrate_.launch(global, kParticleGroup, "particle_integrate");
  // Rows of count_ entries (particle_integrate): the outflow mass, the work of the artificial
  // viscosity and of the artificial stress over the sub-step (with the midpoint velocity), and the
  // energy friction and walls took, the potential energy released.
  using compute::ReduceOp;
  const std::vector<double> t =
      reducer_.reduceRows(tally_, count_, {ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Sum}, count_);
  diag_.outflowMass += t[0];
  diag_.viscousDissipation -= t[1];
  diag_.artificialStressWork += t[2];
  diag_.frictionWork += t[3];
  diag_.potentialReleased += t[4];
}

void ParticleSolver::computeDerivedFields() {
  // A stress update over zero time leaves the stress, cohesion and plastic strain as they are
  // (constitutive.cl: the trial stress is the current one) and evaluates N and the divergence.
  if (count_ > 0) sortAndEvaluateStress(0.0);
  updateDiagnostics();
}

void ParticleSolver::updateDiagnostics() {
  diag_.count = count_;
  if (count_ == 0) {
    diag_.mass = diag_.kinetic = diag_.maxSpeed = diag_.confinedFluid = diag_.pendingRelease = 0;
    return;
  }
  speedKernel_.bind(params_, bedPatch_, x_, y_, vx_, vy_, m_, Vf_, released_, speed_, static_cast<int>(capacity_));
  speedKernel_.launch(compute::Range{count_}, kParticleGroup, "particle_totals");
  using compute::ReduceOp;
  const std::vector<double> r = reducer_.reduceRows(
      speed_, count_, {ReduceOp::Max, ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Sum, ReduceOp::Sum}, capacity_);
  diag_.maxSpeed = r[0];
  diag_.kinetic = r[1];
  diag_.mass = r[2];
  diag_.confinedFluid = r[3];
  diag_.pendingRelease = r[4];
}

ParticleState ParticleSolver::state() const {
  ParticleState s;
  if (count_ == 0) return s;
  auto get = [&](const compute::RealBuffer& b) {
    std::vector<double> v = b.download();
    v.resize(count_);
    return v;
  };
  s.x = get(x_), s.y = get(y_), s.vx = get(vx_), s.vy = get(vy_), s.mass = get(m_);
  s.sxx = get(sxx_), s.syy = get(syy_), s.sxy = get(sxy_), s.cohesion = get(coh_), s.cohesion0 = get(coh0_);
  s.plastic = get(plastic_), s.H = get(H_), s.density = get(rho_);
  s.Nxx = get(Nxx_), s.Nyy = get(Nyy_), s.Nxy = get(Nxy_), s.structured0 = get(fsc0_), s.confined0 = get(ffc0_);
  return s;
}

}  // namespace talus::particles
