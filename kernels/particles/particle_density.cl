// Areal density of the particles (spec §5, P.74-P.75): rhoA_i = sum_j m_j W_ij over the particles
// within 2h (itself included), and the confined-phase thickness H_i = rhoA_i / rho_i.
#include "particles/particle_common.cl"

__kernel void particle_density(__constant const ParticleParams* p, __constant const NeighbourGridParams* ng,
                               __global const uint* cell_start, __global const uint* cell_end,
                               __global const real* x, __global const real* y, __global const real* m,
                               __global const real* rho, __global real* rhoA, __global real* H) {
  const int i = get_global_id(0);
  if (i >= p->count) return;
  const real xi = x[i], yi = y[i], h = p->h, r2max = (real)4 * h * h;
  real sum = 0;
  const NeighbourCellRange cells = neighbour_cells_around(ng, xi, yi);
  for (int cy = cells.y0; cy <= cells.y1; ++cy)
    for (int cx = cells.x0; cx <= cells.x1; ++cx) {
      const uint c = neighbour_cell_key(ng, cx, cy);
      for (uint j = cell_start[c]; j < cell_end[c]; ++j) {
        const real dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
        if (r2 < r2max) sum += m[j] * sph_w(sqrt(r2), h);
      }
    }
  rhoA[i] = sum;
  H[i] = sum / rho[i];
}
