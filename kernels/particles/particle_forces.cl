// Internal accelerations of the particles (spec §5, OpenLISEM Hazard P.78 with P.83-P.86).
// The stress term is the one the strain rate of particle_stress implies (variational consistency,
// Bonet & Lok 1999): particle_stress takes L_i = sum_j A_j (v_j - v_i) (x) C_i g_ij with
// g_ij = grad_i W_ij and C_i its kernel-gradient correction (symmetric; `corr`, the damped inverse of
// M_i, particle_stress.cl), so the stress power
// sum_i A_i N_i : L_i is minus the power of the forces
//   F_i = A_i sum_j A_j (N_i C_i + N_j C_j) g_ij,   dv_i/dt = F_i / m_i,
// each particle's stress paired with its own correction. F_ij = -F_ji (g_ji = -g_ij), so momentum is
// conserved to round-off, and the elastic energy the stress stores is exactly the work the forces do:
// no mode can gain energy. (The earlier form (N_i + N_j)(C_i + C_j)/2 was not the adjoint of the
// strain rate: near free edges and corners, where C departs from I, a stress-free block sliding on a
// DEM with float round-off in its slope grew a single-particle oscillation exponentially, e-folding in
// ~100 sub-steps, until the particle failed in tension and the block cracked along its edges.)
// N = H (sigma + sigma_lat I) the depth-integrated in-plane stress (tension positive; from
// particle_stress), A the area a particle stands for, m its mass. With C = I and A_j = m_j / rhoA_j
// this is the usual sum_j m_j (N_i + N_j) g_ij / (rhoA_i rhoA_j), P.78.
// The regularising terms:
//   dv_i/dt += sum_j m_j f_ij^n R_ij . g_ij - sum_j m_j Pi_ij g_ij,   g_ij = grad_i W_ij,
// - Pi_ij (Monaghan 1992): for approaching pairs, mu = h v_ij . x_ij / (r^2 + 0.01 h^2) < 0,
//   Pi_ij = (-alpha c mu + beta mu^2) / mean(rhoA), a pressure-like repulsion (Pi_ij >= 0 pushes the
//   pair apart) along the plain kernel gradient g_ij, as Monaghan has it: the pair's power is
//   -m_i m_j Pi_ij v_ij . g_ij <= 0 (g_ij is x_ij times W'(r)/r < 0 and v_ij . x_ij < 0), so the
//   viscosity only ever takes energy. (Until 2026-12-05 it acted along the corrected gradient
//   G_ij = (C_i + C_j) / 2 g_ij. Where C departs from I, G_ij has a part across x_ij whose work has
//   either sign: in two avaKot
//   runs a particle reached 282 m/s at 24 s, and the viscosity's tally fell by 1.6e11 J within 6 s,
//   i.e. it gave that energy to the flow. C also amplifies g_ij up to 1 / (2 d) = 50 times where a
//   particle's neighbours nearly line up, which the viscosity's stiffness need not follow.)
// - R_ij = R_i + R_j (Gray, Monaghan & Swift 2001): in the principal frame of N_i / rhoA_i^2, each
//   tensile principal value s > 0 gives -eps s, compressive ones 0; rotated back. f_ij = W_ij / W(dp),
//   dp the mean particle spacing. It acts only in tension, against the tensile clumping instability,
//   along the plain gradient g_ij as Gray et al. (and spec P.78) have it. (Until 2026-12-07 along
//   G_ij: on the smooth 40-degree plane of TerrainRoughness.ParticleBlockOnANoisyPlaneStaysBelowFreeFall
//   with alpha_Pi = 0.1 a stress-free block's particles then left it at 50 m/s while its centre of
//   mass slid at free fall; along g_ij the deviation stays below 2 m/s.) Its work is not returned
//   over a cycle of tension (it is not the adjoint of the strain rate): an undamped elastic block
//   breathing in and out of tension gains 65 times its energy in 10 s with eps = 0.3 and keeps it
//   without (test_particle_energy.cpp), so it is off by default (eps = 0; docs/particles.md).
// Energy of the regularising terms: the viscous and the artificial-stress accelerations also go to
// rows 1-2 and 3-4 of `tally` (rows of p->count entries), where particle_integrate turns them into
// their work over the sub-step (see there).
#include "particles/artificial_stress.cl"
#include "particles/particle_common.cl"

/// One particle's sums over its neighbours (particle_forces below).
typedef struct {
  real accx, accy;  // artificial stress, sum_j m_j f^n R_ij . g_ij
  real avx, avy;    // artificial viscosity, -sum_j m_j Pi_ij g_ij
  real fx, fy;      // stress term, sum_j A_j (N_i C_i + N_j C_j) g_ij
} ForceSums;

/// The pair (i, j) within the support (r2 < 4 h^2, j != i) added to particle i's sums; fw the factor
/// of its kernel gradient; `own` holds i's correction (0-2), stress (3-5) and artificial stress (6-8).
INLINE void add_pair(__constant const ParticleParams* p, ForceSums* acc, int i, uint j, real dx, real dy, real r2, real fw,
                     real vxi, real vyi, const real* own, int ri_on, __global const real* vx, __global const real* vy,
                     __global const real* m, __global const real* A, __global const real* rhoA,
                     __global const real* Nxx, __global const real* Nyy, __global const real* Nxy,
                     __global const real* corr, __global const real* Rart) {
  const real h = p->h;
  const int cap = p->count;
  const real ai00 = own[0], ai01 = own[1], ai11 = own[2];
  const real2 g0 = (real2)(fw * dx, fw * dy);  // grad_i W_ij (fw its factor, sph.cl)
  // Stress term: N_i C_i g + N_j C_j g.
  const real ux = ai00 * g0.x + ai01 * g0.y, uy = ai01 * g0.x + ai11 * g0.y;
  const real bj00 = corr[j], bj01 = corr[cap + j], bj11 = corr[2 * cap + j];
  const real wx = bj00 * g0.x + bj01 * g0.y, wy = bj01 * g0.x + bj11 * g0.y;
  const real njxx = Nxx[j], njyy = Nyy[j], njxy = Nxy[j];
  acc->fx += A[j] * (own[3] * ux + own[5] * uy + njxx * wx + njxy * wy);
  acc->fy += A[j] * (own[5] * ux + own[4] * uy + njxy * wx + njyy * wy);
  // Regularising terms with G_ij (most pairs have none: no tension, not approaching).
  real txx = 0, tyy = 0, txy = 0, pi = 0;
  const real rjxx = Rart[j], rjyy = Rart[cap + j], rjxy = Rart[2 * cap + j];
  if (ri_on || rjxx != (real)0 || rjyy != (real)0 || rjxy != (real)0) {
    const real f = sph_w(sqrt(r2), h) / p->w_spacing;
    real fn = (real)1;
    for (int k = 0; k < (int)p->n_art; ++k) fn *= f;
    txx += fn * (own[6] + rjxx);
    tyy += fn * (own[7] + rjyy);
    txy += fn * (own[8] + rjxy);
  }
  const real vdotr = (vxi - vx[j]) * dx + (vyi - vy[j]) * dy;
  if (vdotr < (real)0 && (p->alpha_pi > (real)0 || p->beta_pi > (real)0)) {
    const real mu = h * vdotr / (r2 + (real)0.01 * h * h);
    pi = (-p->alpha_pi * p->sound_speed * mu + p->beta_pi * mu * mu) / ((real)0.5 * (rhoA[i] + rhoA[j]));
  }
  if (txx != (real)0 || tyy != (real)0 || txy != (real)0 || pi != (real)0) {
    // Both along the plain kernel gradient (header).
    acc->accx += m[j] * (txx * g0.x + txy * g0.y);
    acc->accy += m[j] * (txy * g0.x + tyy * g0.y);
    acc->avx -= m[j] * pi * g0.x;
    acc->avy -= m[j] * pi * g0.y;
  }
}

/// Neighbours come from the list particle_stress wrote in the same sub-step (nb_list, nb_count:
/// the pairs within the support in the neighbour grid's visiting order, so the sums are bitwise
/// those of the grid loop); a particle with more neighbours than the list holds (nb_cap) walks the
/// grid itself.
__kernel void particle_forces(__constant const ParticleParams* p, __constant const NeighbourGridParams* ng,
                              __global const uint* cell_start, __global const uint* cell_end,
                              __global const uint* nb_list, __global const real* nb_grad, __global const uint* nb_count,
                              const uint nb_cap,
                              __global const real* x, __global const real* y, __global const real* vx,
                              __global const real* vy, __global const real* m, __global const real* A, __global const real* rhoA,
                              __global const real* Nxx, __global const real* Nyy, __global const real* Nxy,
                              __global const real* corr, __global const real* Rart, __global real* ax, __global real* ay,
                              __global real* tally) {
  const int i = get_global_id(0);
  if (i >= p->count) return;
  const real h = p->h, r2max = (real)4 * h * h;
  const real xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  const int cap = p->count;  // stride of the corr and Rart rows
  const real own[9] = {corr[i], corr[cap + i], corr[2 * cap + i], Nxx[i], Nyy[i], Nxy[i],
                       Rart[i], Rart[cap + i], Rart[2 * cap + i]};
  const int ri_on = own[6] != (real)0 || own[7] != (real)0 || own[8] != (real)0;
  ForceSums acc = {0, 0, 0, 0, 0, 0};
  const uint n = nb_count[i];
  if (n <= nb_cap) {
    __global const uint* list = nb_list + (size_t)i * nb_cap;
    __global const real* grad = nb_grad + (size_t)i * nb_cap;
    for (uint q = 0; q < n; ++q) {
      const uint j = list[q];
      const real dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
      add_pair(p, &acc, i, j, dx, dy, r2, grad[q], vxi, vyi, own, ri_on, vx, vy, m, A, rhoA, Nxx, Nyy, Nxy, corr, Rart);
    }
  } else {
    FOR_EACH_PARTICLE_WITHIN(ng, cell_start, cell_end, xi, yi, (real)2 * h, j) {
      if (j == (uint)i) continue;
      const real dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
      if (r2 >= r2max) continue;
      add_pair(p, &acc, i, j, dx, dy, r2, sph_grad_factor((real2)(dx, dy), h), vxi, vyi, own, ri_on, vx, vy, m, A, rhoA, Nxx, Nyy, Nxy, corr, Rart);
    }
  }
  const real s = A[i] / m[i];
  ax[i] = acc.accx + acc.avx + s * acc.fx;
  ay[i] = acc.accy + acc.avy + s * acc.fy;
  tally[cap + i] = acc.avx;
  tally[2 * cap + i] = acc.avy;
  tally[3 * cap + i] = acc.accx;
  tally[4 * cap + i] = acc.accy;
}
