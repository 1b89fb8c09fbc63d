// Particle-grid transfers of the hybrid mode (spec §6; kernels/particles/particle_grid.cl explains
// the method): P2G by gather with the tensor-product cubic B-spline weights of P.87, deterministic and
// without atomics, and G2P with the same weights and a PIC/FLIP blend.
//
// Cells are those of the terrain grid (row-major, nx * ny, cell (i, j) spans [i dx, (i + 1) dx) x
// [j dx, (j + 1) dx)); particle positions are in the same frame. Stencil cells beyond the raster are
// folded onto the edge cells, so the weights of every particle sum to 1 over the raster and P2G
// conserves volume, mass and momentum to round-off.
//
// P2G reads the particles through a NeighbourGrid after build() and the reordering of the particle
// arrays by its order (every particle buffer passed must be in that sorted order and hold at least
// grid.count() entries); it sums over the particles inside the neighbour grid's box (the first
// readInsideCount() sorted ones). Any ratio of the neighbour cell size to dx works; h = dx (cell
// 2 dx) visits 3 x 3 neighbour cells per work-item, a block of 2 x 2 terrain cells. G2P needs no
// neighbour grid.
#pragma once
#include <cstddef>
#include <initializer_list>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "core/Grid.hpp"
#include "particles/NeighbourGrid.hpp"

namespace talus::particles {

/// How fieldToGrid combines a particle field on the cells.
enum class FieldTransfer {
  Sum,          ///< out_c = sum_p w_pc q_p f_p
  WeightedMean  ///< out_c = sum_p w_pc q_p f_p / sum_p w_pc q_p (0 where no particle reaches c)
};

class ParticleGridTransfer {
 public:
  /// Transfers between particles and the cells of `grid` (nx, ny >= 1, dx > 0; throws InputError).
  ParticleGridTransfer(compute::Context& ctx, const Grid& grid);

  /// P2G of the confined phase: per cell the thickness H_c = sum w V_p / dx^2 [m], the mass
  /// sum w m_p [kg] and the momentum sum w m_p v_p [kg m/s]. x, y [m], volume V [m^3], mass m [kg],
  /// vx, vy [m/s]: particle buffers in the neighbour grid's sorted order. Outputs: nx * ny cells.
  void confinedToGrid(const NeighbourGrid& ng, const compute::RealBuffer& x, const compute::RealBuffer& y,
                      const compute::RealBuffer& volume, const compute::RealBuffer& mass,
                      const compute::RealBuffer& vx, const compute::RealBuffer& vy, compute::RealBuffer& thickness,
                      compute::RealBuffer& cellMass, compute::RealBuffer& momentumX, compute::RealBuffer& momentumY);

  /// P2G of the fluid released by the particles this step (P.27-P.28): per cell the added fluid
  /// thickness sum w dV_p / dx^2 [m] and the added discharge sum w dV_p v_p / dx^2 [m^2/s] (the
  /// fluid leaves with the velocity passed, normally the particle's). releasedVolume dV [m^3].
  /// With accumulate, the increments are added to the outputs (e.g. the flow solver's h, qx, qy)
  /// instead of replacing them.
  void releasedToGrid(const NeighbourGrid& ng, const compute::RealBuffer& x, const compute::RealBuffer& y,
                      const compute::RealBuffer& releasedVolume, const compute::RealBuffer& vx,
                      const compute::RealBuffer& vy, compute::RealBuffer& fluidThickness,
                      compute::RealBuffer& dischargeX, compute::RealBuffer& dischargeY, bool accumulate = false);

  /// P2G of any particle field f weighted by q (mass or volume, one value per particle), summed or
  /// averaged per cell (FieldTransfer). All particle buffers in sorted order.
  void fieldToGrid(const NeighbourGrid& ng, const compute::RealBuffer& x, const compute::RealBuffer& y,
                   const compute::RealBuffer& weight, const compute::RealBuffer& field, FieldTransfer mode,
                   compute::RealBuffer& out);

  /// G2P of a cell field: out[p] = sum_c w_pc field[c] for particles 0..n-1 (any order; 0 for a
  /// particle at a non-finite position).
  void gridToParticles(const compute::RealBuffer& field, const compute::RealBuffer& x, const compute::RealBuffer& y,
                       std::size_t n, compute::RealBuffer& out);

  /// G2P of the grid velocity with the PIC/FLIP blend: v_p <- (1 - a) (v_p + dv(x_p)) + a v(x_p) for
  /// particles 0..n-1, with (u, v) the cell velocity after the grid step and (du, dv) its change
  /// during the step [m/s]; picFraction a in [0, 1] (1 PIC, 0 FLIP; throws InputError outside).
  /// Particles at non-finite positions keep their velocity.
  void gridVelocityToParticles(const compute::RealBuffer& u, const compute::RealBuffer& v,
                               const compute::RealBuffer& du, const compute::RealBuffer& dv, double picFraction,
                               const compute::RealBuffer& x, const compute::RealBuffer& y, std::size_t n,
                               compute::RealBuffer& vx, compute::RealBuffer& vy);

  const Grid& grid() const { return grid_; }

 private:
  void checkParticles(std::size_t n, std::initializer_list<const compute::RealBuffer*> buffers, const char* what) const;
  void checkCells(std::initializer_list<const compute::RealBuffer*> buffers, const char* what) const;

  compute::Context& ctx_;
  Grid grid_;
  compute::RealBuffer scratch_;  ///< the unused mass-like output of releasedToGrid
  compute::Kernel p2g_, p2gField_, g2p_, g2pVelocity_;
};

}  // namespace talus::particles
