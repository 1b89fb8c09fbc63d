// Explicit neighbour lists from the neighbour grid: the loop of kernels/particles/neighbours.cl
// written out once, over the cells neighbour_cells_within() gives for the radius (the 3 x 3 block or
// less up to the grid's search radius, farther for a larger one, as the thickness sums of an expanded
// particle search: particle_density.cl). Used to check the grid and that cell range against a
// brute-force search and to measure neighbour counts; SPH kernels run the same loops themselves
// instead of storing lists.
#include "particles/neighbours.cl"

/// For each particle i < n (arrays already in the grid's sorted order): count[i] = the number of
/// particles j != i with (x_j - x_i)^2 + (y_j - y_i)^2 <= radius^2, and list[i * capacity + m] the
/// first `capacity` of them in visiting order. Particles outside the grid have no neighbours.
__kernel void particles_neighbour_lists(__constant const NeighbourGridParams* grid, __global const uint* cell_start,
                                        __global const uint* cell_end, __global const real* x,
                                        __global const real* y, const uint n, const real radius,
                                        const uint capacity, __global uint* count, __global uint* list) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const real xi = x[i], yi = y[i], r2 = radius * radius;
  uint found = 0u;
  FOR_EACH_PARTICLE_WITHIN(grid, cell_start, cell_end, xi, yi, radius, j) {
    if (j == i) continue;
    const real dx = x[j] - xi, dy = y[j] - yi;
    if (dx * dx + dy * dy > r2) continue;
    if (found < capacity) list[(size_t)i * capacity + found] = j;
    ++found;
  }
  count[i] = found;
}
