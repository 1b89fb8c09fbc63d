// Plain C++ reference of the particle-grid transfers (src/particles/ParticleGridTransfer,
// kernels/particles/particle_grid.cl), in double, written from the definitions rather than from the
// kernels: the weight of a particle for a cell is N((x_p - x_c) / dx) N((y_p - y_c) / dx) with the
// cubic B-spline N of P.87, evaluated for every stencil cell from the distance to its centre, and a
// stencil cell beyond the raster gives its weight to the edge cell (clamped index). P2G then loops
// over particles and scatters (the opposite of the device's gather), G2P sums over the stencil.
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

#include "core/Grid.hpp"

namespace talus::test {

/// The cubic B-spline N(d) of P.87: 2/3 - d^2 + |d|^3 / 2 for |d| < 1, (2 - |d|)^3 / 6 for |d| < 2, 0 beyond.
double referenceBSpline(double d);

/// The non-zero weights of a particle at (x, y) on the cells of `g` (row-major index, weight),
/// folded onto the edge cells; entries for one cell are merged.
std::vector<std::pair<std::size_t, double>> referenceCellWeights(const Grid& g, double x, double y);

/// P2G of the confined phase: thickness sum w V / dx^2, mass sum w m, momentum sum w m v.
struct ReferenceConfined {
  std::vector<double> thickness, mass, momentumX, momentumY;
};
/// `use[p]` false skips particle p (outside the neighbour grid); empty means all.
ReferenceConfined referenceConfinedToGrid(const Grid& g, const std::vector<double>& x, const std::vector<double>& y,
                                          const std::vector<double>& volume, const std::vector<double>& mass,
                                          const std::vector<double>& vx, const std::vector<double>& vy,
                                          const std::vector<char>& use = {});

/// P2G of a field f weighted by q: sum w q f per cell, or that divided by sum w q (0 where it is 0).
std::vector<double> referenceFieldToGrid(const Grid& g, const std::vector<double>& x, const std::vector<double>& y,
                                         const std::vector<double>& q, const std::vector<double>& f, bool mean,
                                         const std::vector<char>& use = {});

/// G2P: sum_c w_pc field[c] for every particle.
std::vector<double> referenceGridToParticles(const Grid& g, const std::vector<double>& field,
                                             const std::vector<double>& x, const std::vector<double>& y);

}  // namespace talus::test
