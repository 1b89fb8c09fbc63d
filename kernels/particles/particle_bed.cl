#include "common/real.cl"

// The particles as part of the grid's bed (hybrid mode, spec §6), one work-item per terrain cell,
// after the particles were transferred to the grid (P2G: thickness H_c, mass M_c, momentum P_c):
//   particle_grid_bed:     the bed the grid phases see, (H_c, u_c, v_c) per cell, with u_c the
//                          confined phase's velocity after the drag exchange (P_c / M_c + du).
//   particle_cell_velocity: the same velocity alone, (u_c, v_c) per cell (0 where no particle mass),
//                          for the PIC share of the G2P after the drag exchange.
//   particle_bed_velocity: the impulse J the grid phases gave that bed over a grid step (momentum per
//                          area, kernels/flow/debris_stage.cl) as a velocity change of the cell's
//                          confined phase, du = J_eff dx^2 / M_c; G2P with the P2G weights then gives
//                          every particle its share, so the particles gain exactly the momentum the
//                          grid lost to them (sum_p m_p sum_c w_pc du_c = sum_c M_c du_c).
//                          J_eff: the cell's own J plus, from each 4-neighbour without particles
//                          (M = 0) whose J is not zero (the solids' centred bed gradient reaches one
//                          cell beyond the particles), its J shared equally among that neighbour's
//                          own neighbours with particles; a J with no such neighbour is lost (none
//                          arises: J is non-zero only within one cell of the particles).

__kernel void particle_grid_bed(const int n, __global const real* Hc, __global const real* Mc,
                                __global const real* Px, __global const real* Py, __global const real* du,
                                __global const real* dv, __global real* bed) {
  const int k = get_global_id(0);
  if (k >= n) return;
  const real m = Mc[k];
  const int has = Hc[k] > (real)0 && m > (real)0;
  bed[k] = has ? Hc[k] : (real)0;
  bed[n + k] = has ? Px[k] / m + du[k] : (real)0;
  bed[2 * n + k] = has ? Py[k] / m + dv[k] : (real)0;
}

__kernel void particle_cell_velocity(const int n, __global const real* Mc, __global const real* Px,
                                     __global const real* Py, __global const real* du, __global const real* dv,
                                     __global real* u, __global real* v) {
  const int k = get_global_id(0);
  if (k >= n) return;
  const real m = Mc[k];
  u[k] = m > (real)0 ? Px[k] / m + du[k] : (real)0;
  v[k] = m > (real)0 ? Py[k] / m + dv[k] : (real)0;
}

/// 1 when cell (i, j) lies on the raster and holds particles.
INLINE int holds_particles(int nx, int ny, __global const real* Mc, int i, int j) {
  return i >= 0 && j >= 0 && i < nx && j < ny && Mc[j * nx + i] > (real)0;
}

/// Share of the impulse of cell (i, j) (without particles) that each of its neighbours with
/// particles takes: 1 / their number (0 when it has none).
INLINE real neighbour_share(int nx, int ny, __global const real* Mc, int i, int j) {
  const int c = holds_particles(nx, ny, Mc, i - 1, j) + holds_particles(nx, ny, Mc, i + 1, j) +
                holds_particles(nx, ny, Mc, i, j - 1) + holds_particles(nx, ny, Mc, i, j + 1);
  return c > 0 ? (real)1 / (real)c : (real)0;
}

__kernel void particle_bed_velocity(const int nx, const int ny, const real dx, __global const real* Mc,
                                    __global const real* impulse, __global real* du, __global real* dv) {
  const int k = get_global_id(0);
  const int n = nx * ny;
  if (k >= n) return;
  const real m = Mc[k];
  if (!(m > (real)0)) {
    du[k] = dv[k] = 0;
    return;
  }
  const int i = k % nx, j = k / nx;
  real jx = impulse[k], jy = impulse[n + k];
  const int di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
  for (int q = 0; q < 4; ++q) {
    const int a = i + di[q], b = j + dj[q];
    if (a < 0 || b < 0 || a >= nx || b >= ny || Mc[b * nx + a] > (real)0) continue;
    const real share = neighbour_share(nx, ny, Mc, a, b);
    jx += share * impulse[b * nx + a];
    jy += share * impulse[n + b * nx + a];
  }
  du[k] = jx * dx * dx / m;
  dv[k] = jy * dx * dx / m;
}
