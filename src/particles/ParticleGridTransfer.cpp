#include "particles/LaunchSize.hpp"
#include "particles/ParticleGridTransfer.hpp"

#include <cmath>
#include <initializer_list>
#include <string>

#include "compute/Program.hpp"
#include "core/Error.hpp"

namespace talus::particles {
namespace {

constexpr const char* kFile = "particles/particle_grid.cl";
constexpr std::size_t kBlock = 2;  // terrain cells per side of a P2G work-item (PG_BLOCK in the kernels)

/// P2G work-items for a grid: one per block of kBlock x kBlock cells.
compute::Range blocksOf(const Grid& g) {
  const std::size_t bx = (static_cast<std::size_t>(g.nx) + kBlock - 1) / kBlock;
  const std::size_t by = (static_cast<std::size_t>(g.ny) + kBlock - 1) / kBlock;
  return compute::Range{bx * by};
}

}  // namespace

ParticleGridTransfer::ParticleGridTransfer(compute::Context& ctx, const Grid& grid) : ctx_(ctx), grid_(grid) {
  if (grid.nx < 1 || grid.ny < 1 || !(grid.dx > 0) || !std::isfinite(grid.dx))
    throw InputError("particle-grid transfer: the grid needs nx, ny >= 1 and a positive cell size");
  if (static_cast<double>(grid.nx) * grid.ny >= 2147483648.0)
    throw InputError("particle-grid transfer: more than 2^31 cells");
  scratch_ = compute::RealBuffer(ctx, grid.cells(), "released fluid scratch");
  scratch_.fill(0.0);
  compute::Program& program = ctx.program(kFile);
  p2g_ = compute::Kernel(program, "particles_to_grid");
  p2gField_ = compute::Kernel(program, "particles_field_to_grid");
  g2p_ = compute::Kernel(program, "grid_to_particles");
  g2pVelocity_ = compute::Kernel(program, "grid_velocity_to_particles");
}

void ParticleGridTransfer::checkParticles(std::size_t n, std::initializer_list<const compute::RealBuffer*> buffers,
                                          const char* what) const {
  if (n >= 2147483648.0) throw ComputeError(std::string(what) + ": more than 2^31 particles");
  for (const compute::RealBuffer* b : buffers)
    if (b->size() < n)
      throw ComputeError(std::string(what) + ": a particle buffer holds " + std::to_string(b->size()) +
                         " values for " + std::to_string(n) + " particles");
}

void ParticleGridTransfer::checkCells(std::initializer_list<const compute::RealBuffer*> buffers,
                                      const char* what) const {
  for (const compute::RealBuffer* b : buffers)
    if (b->size() < grid_.cells())
      throw ComputeError(std::string(what) + ": a cell buffer holds " + std::to_string(b->size()) + " values for " +
                         std::to_string(grid_.cells()) + " cells");
}

void ParticleGridTransfer::confinedToGrid(const NeighbourGrid& ng, const compute::RealBuffer& x,
                                          const compute::RealBuffer& y, const compute::RealBuffer& volume,
                                          const compute::RealBuffer& mass, const compute::RealBuffer& vx,
                                          const compute::RealBuffer& vy, compute::RealBuffer& thickness,
                                          compute::RealBuffer& cellMass, compute::RealBuffer& momentumX,
                                          compute::RealBuffer& momentumY) {
  checkParticles(ng.count(), {&x, &y, &volume, &mass, &vx, &vy}, "confined P2G");
  checkCells({&thickness, &cellMass, &momentumX, &momentumY}, "confined P2G");
  if (ng.count() == 0) {  // no tables to read (a grid never built has none)
    for (compute::RealBuffer* b : {&thickness, &cellMass, &momentumX, &momentumY}) b->fill(0.0);
    return;
  }
  const double dx = grid_.dx;
  p2g_.bind(grid_.nx, grid_.ny, compute::RealArg{dx}, ng.params(), ng.cellStart(), ng.cellEnd(), x, y, volume, mass,
            vx, vy, compute::RealArg{1.0 / (dx * dx)}, compute::RealArg{1.0}, 0, thickness, cellMass, momentumX,
            momentumY);
  p2g_.launch(blocksOf(grid_), {0, 0}, "particles_to_grid");
}

void ParticleGridTransfer::releasedToGrid(const NeighbourGrid& ng, const compute::RealBuffer& x,
                                          const compute::RealBuffer& y, const compute::RealBuffer& releasedVolume,
                                          const compute::RealBuffer& vx, const compute::RealBuffer& vy,
                                          compute::RealBuffer& fluidThickness, compute::RealBuffer& dischargeX,
                                          compute::RealBuffer& dischargeY, bool accumulate) {
  checkParticles(ng.count(), {&x, &y, &releasedVolume, &vx, &vy}, "released-fluid P2G");
  checkCells({&fluidThickness, &dischargeX, &dischargeY}, "released-fluid P2G");
  if (ng.count() == 0) {
    if (!accumulate)
      for (compute::RealBuffer* b : {&fluidThickness, &dischargeX, &dischargeY}) b->fill(0.0);
    return;
  }
  const compute::RealArg perArea{1.0 / (grid_.dx * grid_.dx)};
  p2g_.bind(grid_.nx, grid_.ny, compute::RealArg{grid_.dx}, ng.params(), ng.cellStart(), ng.cellEnd(), x, y,
            releasedVolume, releasedVolume, vx, vy, perArea, perArea, accumulate ? 1 : 0, fluidThickness, scratch_,
            dischargeX, dischargeY);
  p2g_.launch(blocksOf(grid_), {0, 0}, "particles_released_to_grid");
}

void ParticleGridTransfer::fieldToGrid(const NeighbourGrid& ng, const compute::RealBuffer& x,
                                       const compute::RealBuffer& y, const compute::RealBuffer& weight,
                                       const compute::RealBuffer& field, FieldTransfer mode, compute::RealBuffer& out) {
  checkParticles(ng.count(), {&x, &y, &weight, &field}, "field P2G");
  checkCells({&out}, "field P2G");
  if (ng.count() == 0) {
    out.fill(0.0);
    return;
  }
  p2gField_.bind(grid_.nx, grid_.ny, compute::RealArg{grid_.dx}, ng.params(), ng.cellStart(), ng.cellEnd(), x, y,
                 weight, field, mode == FieldTransfer::WeightedMean ? 1 : 0, out);
  p2gField_.launch(blocksOf(grid_), {0, 0}, "particles_field_to_grid");
}

void ParticleGridTransfer::gridToParticles(const compute::RealBuffer& field, const compute::RealBuffer& x,
                                           const compute::RealBuffer& y, std::size_t n, compute::RealBuffer& out) {
  checkParticles(n, {&x, &y, &out}, "G2P");
  checkCells({&field}, "G2P");
  if (n == 0) return;
  g2p_.bind(grid_.nx, grid_.ny, compute::RealArg{grid_.dx}, field, x, y, static_cast<cl_uint>(n), out);
  g2p_.launch(compute::Range{n}, kParticleGroup, "grid_to_particles");
}

void ParticleGridTransfer::gridVelocityToParticles(const compute::RealBuffer& u, const compute::RealBuffer& v,
                                                   const compute::RealBuffer& du, const compute::RealBuffer& dv,
                                                   double picFraction, const compute::RealBuffer& x,
                                                   const compute::RealBuffer& y, std::size_t n,
                                                   compute::RealBuffer& vx, compute::RealBuffer& vy) {
  if (!(picFraction >= 0 && picFraction <= 1))
    throw InputError("G2P velocity: the PIC fraction must lie in [0, 1], got " + std::to_string(picFraction));
  checkParticles(n, {&x, &y, &vx, &vy}, "G2P velocity");
  checkCells({&u, &v, &du, &dv}, "G2P velocity");
  if (n == 0) return;
  g2pVelocity_.bind(grid_.nx, grid_.ny, compute::RealArg{grid_.dx}, u, v, du, dv, compute::RealArg{picFraction}, x, y,
                    static_cast<cl_uint>(n), vx, vy);
  g2pVelocity_.launch(compute::Range{n}, kParticleGroup, "grid_velocity_to_particles");
}

}  // namespace talus::particles
