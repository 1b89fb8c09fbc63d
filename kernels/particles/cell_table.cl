// Cell keys of the particles and the per-cell start/end tables of the sorted particles
// (the data layout is described in kernels/particles/neighbours.cl).
//
// One build of the tables: particles_clear_cells erases the entries the previous build wrote (so a
// build costs O(particles), not O(cells)), particles_cell_keys keys every particle by its cell, the
// (key, index) pairs are sorted (bitonic_sort.cl), and particles_cell_ranges marks where each run of
// equal keys starts and ends in the sorted order.
#include "particles/neighbours.cl"

/// keys[i] = the cell of particle i, CELL_KEY_OUTSIDE when it lies outside the box.
__kernel void particles_cell_keys(__constant const NeighbourGridParams* grid, __global const real* x,
                                  __global const real* y, const uint n, __global uint* keys) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  keys[i] = neighbour_key_of(grid, x[i], y[i]);
}

/// Resets cell_start and cell_end to 0 for every cell that holds particles in `sorted_keys` (the
/// sorted keys of the previous build). Only the first particle of each run writes.
__kernel void particles_clear_cells(__global const uint* sorted_keys, const uint n, __global uint* cell_start,
                                    __global uint* cell_end) {
  const uint r = get_global_id(0);
  if (r >= n) return;
  const uint key = sorted_keys[r];
  if (key == CELL_KEY_OUTSIDE || (r > 0u && sorted_keys[r - 1u] == key)) return;
  cell_start[key] = 0u;
  cell_end[key] = 0u;
}

/// For each run of equal keys in sorted_keys[0, n): cell_start[key] = first position of the run,
/// cell_end[key] = one past its last position. inside[0] = the number of particles inside the grid
/// (they come first: outside keys sort last); the host sets it to 0 beforehand.
__kernel void particles_cell_ranges(__global const uint* sorted_keys, const uint n, __global uint* cell_start,
                                    __global uint* cell_end, __global uint* inside) {
  const uint r = get_global_id(0);
  if (r >= n) return;
  const uint key = sorted_keys[r];
  if (key == CELL_KEY_OUTSIDE) return;
  if (r == 0u || sorted_keys[r - 1u] != key) cell_start[key] = r;
  const bool last = r + 1u == n || sorted_keys[r + 1u] != key;
  if (last) cell_end[key] = r + 1u;
  if (last && (r + 1u == n || sorted_keys[r + 1u] == CELL_KEY_OUTSIDE)) inside[0] = r + 1u;
}
