// The neighbour grid as particle kernels see it: the parameter block (mirrored by
// src/particles/NeighbourGridParams.hpp), the cell of a position, and the block of cells to visit
// for the neighbours of a particle within a radius (3 x 3 or fewer up to the grid's search radius).
//
// The grid covers the domain box [x_min, x_max] x [y_min, y_max] with cells_x * cells_y square
// cells of edge cell_size, numbered row-major from the lower-left corner: key = cy * cells_x + cx.
// A position outside the box (or NaN) has no cell: its key is CELL_KEY_OUTSIDE, which sorts after
// every real key. cell_size is at least the search radius (src/particles/NeighbourGrid.hpp says by
// how much), so every particle within the radius of a particle lies in its own or one of the eight
// surrounding cells.
//
// After NeighbourGrid::build() and the reordering of the particle arrays by its `order`, the
// particles of cell c are the array entries cell_start[c] <= j < cell_end[c] (empty cells have
// cell_start = cell_end = 0). A neighbour loop reads:
//
//   const NeighbourCellRange cells = neighbour_cells_within(grid, x[i], y[i], radius);
//   for (int cy = cells.y0; cy <= cells.y1; ++cy)
//     for (int cx = cells.x0; cx <= cells.x1; ++cx) {
//       const uint c = neighbour_cell_key(grid, cx, cy);
//       for (uint j = cell_start[c]; j < cell_end[c]; ++j) {
//         if (j == i) continue;
//         const real dx = x[j] - x[i], dy = y[j] - y[i];
//         if (dx * dx + dy * dy > radius * radius) continue;
//         ... pair (i, j) ...
//       }
//     }
//
// The visiting order (rows bottom to top, cells left to right, particles by sorted index) is fixed,
// so sums over neighbours are bitwise reproducible run to run.
#ifndef TALUS_NEIGHBOURS_CL
#define TALUS_NEIGHBOURS_CL
#include "common/real.cl"

/// Key of a particle outside the grid (and padding of the sort): sorts after every cell.
#define CELL_KEY_OUTSIDE 0xFFFFFFFFu

/// Geometry of the neighbour grid in __constant memory. Layout checked by the host's static_assert.
typedef struct {
  int cells_x, cells_y;  // cells per row and per column
  real x_min, y_min;     // lower-left corner of the domain box [m]
  real x_max, y_max;     // upper-right corner of the domain box [m]
  real cell_size;        // cell edge [m], >= the search radius
  real pad0;
} NeighbourGridParams;

/// The 3 x 3 block of cells around a particle, clipped to the grid: columns x0..x1, rows y0..y1
/// (inclusive). Empty (x0 > x1) for a particle outside the grid.
typedef struct {
  int x0, x1, y0, y1;
} NeighbourCellRange;

/// Cell (column, row) of a position, or (-1, -1) outside the box or for NaN. The column is
/// floor((x - x_min) / cell_size) clamped to the last column, so x == x_max belongs to the grid.
INLINE int2 neighbour_cell_of(__constant const NeighbourGridParams* g, real x, real y) {
  if (!(x >= g->x_min && x <= g->x_max && y >= g->y_min && y <= g->y_max)) return (int2)(-1, -1);
  // Clamped before the conversion to int as well, so no huge quotient overflows it.
  const real qx = min(floor((x - g->x_min) / g->cell_size), (real)(g->cells_x - 1));
  const real qy = min(floor((y - g->y_min) / g->cell_size), (real)(g->cells_y - 1));
  return (int2)(min((int)qx, g->cells_x - 1), min((int)qy, g->cells_y - 1));
}

/// Row-major key of cell (cx, cy) of the grid.
INLINE uint neighbour_cell_key(__constant const NeighbourGridParams* g, int cx, int cy) {
  return (uint)cy * (uint)g->cells_x + (uint)cx;
}

/// Key of the cell holding a position, CELL_KEY_OUTSIDE outside the box.
INLINE uint neighbour_key_of(__constant const NeighbourGridParams* g, real x, real y) {
  const int2 c = neighbour_cell_of(g, x, y);
  return c.x < 0 ? CELL_KEY_OUTSIDE : neighbour_cell_key(g, c.x, c.y);
}

/// The cells that can hold a particle within `radius` of (x, y), clipped to the grid: those the
/// interval [x - radius, x + radius] (and its y counterpart) touches, widened on each side by
/// 1e-3 of a cell plus 16 REAL_EPS times the grid's cells per row, more than the rounding of the
/// quotients (a few units in the last place of a quotient of up to that many cells), so no cell
/// holding a particle whose computed distance is within the radius is dropped; and never more
/// than ceil(radius / cell_size) cells from the particle's own (for radius <= cell_size: within the
/// 3 x 3 block around it). Empty for a particle outside the grid.
INLINE NeighbourCellRange neighbour_cells_within(__constant const NeighbourGridParams* g, real x, real y, real radius) {
  const int2 c = neighbour_cell_of(g, x, y);
  NeighbourCellRange r;
  if (c.x < 0) {
    r.x0 = 0, r.x1 = -1, r.y0 = 0, r.y1 = -1;
    return r;
  }
  const real q = radius / g->cell_size;
  const real margin = (real)1e-3 + (real)16 * REAL_EPS * (real)max(g->cells_x, g->cells_y);
  const int k = (int)ceil(q);
  const real fx = (x - g->x_min) / g->cell_size, fy = (y - g->y_min) / g->cell_size;
  r.x0 = max(max((int)floor(fx - q - margin), c.x - k), 0);
  r.x1 = min(min((int)floor(fx + q + margin), c.x + k), g->cells_x - 1);
  r.y0 = max(max((int)floor(fy - q - margin), c.y - k), 0);
  r.y1 = min(min((int)floor(fy + q + margin), c.y + k), g->cells_y - 1);
  return r;
}

/// The loop of the header as one statement: visits every particle j (a uint, sorted index, the
/// particle itself included) of the cells of neighbour_cells_within(ng, px, py, radius), whose cell
/// can hold a particle within `radius` (the caller still tests the distance); `continue` skips to
/// the next j.
///   FOR_EACH_PARTICLE_WITHIN(ng, cell_start, cell_end, x[i], y[i], radius, j) { ... }
#define FOR_EACH_PARTICLE_WITHIN(ng, start, end, px, py, radius, j)                              \
  for (NeighbourCellRange nb_r = neighbour_cells_within(ng, px, py, radius), *nb_once = &nb_r; nb_once; \
       nb_once = 0)                                                                              \
    for (int nb_cy = nb_r.y0; nb_cy <= nb_r.y1; ++nb_cy)                                          \
      for (int nb_cx = nb_r.x0; nb_cx <= nb_r.x1; ++nb_cx)                                        \
        for (uint j = start[neighbour_cell_key(ng, nb_cx, nb_cy)], nb_end = end[neighbour_cell_key(ng, nb_cx, nb_cy)]; \
             j < nb_end; ++j)

#endif
