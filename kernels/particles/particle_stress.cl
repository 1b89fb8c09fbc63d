// Thickness and stress of the particles over one sub-step (spec §5, OpenLISEM Hazard P.74-P.75,
// P.79-P.82, P.26, P.41-P.43), in one pass over each particle's neighbours:
// 0. the thickness H_i and areal density rhoA_i = rho_i H_i (particle_density.cl);
// 1. velocity gradient L_i = [sum_j A_j (v_j - v_i) (x) grad_i W_ij] C_i, A_j the area a particle
//    stands for (particle_density.cl), with the kernel-gradient correction C = M^-1 of
//    M_i = sum_j A_j (x_j - x_i) (x) grad_i W_ij (Bonet & Lok 1999), which makes L exact for linear
//    velocity fields also at free edges. M is symmetric and positive semi-definite, I for a full
//    support, and singular for a particle with fewer than three neighbours in general position (a
//    fragment, a pair flying apart). C is its damped inverse (M^2 + d^2 I)^-1 M, d = 0.01: M^-1 to
//    1e-4 for a full support (eigenvalues ~1), 4e-4 where it is half full; where it is not, the exact finite difference
//    along the directions the neighbours span, tapering to 0 as they leave (a lone particle has no
//    strain rate). (Until 2026-12 a particle with det M <= 1e-3 took C = I: its L then scaled with
//    its neighbours' areas A_j, whose growth dA/dt = A div v fed back on itself; in the paper's
//    fragmenting setup 1 C two particles flying apart reached A = 1e34 m^2, overflowed in float,
//    and were counted as outflow.);
// 2. the elasto-plastic update of the in-plane elastic stress (Jaumann rate, Drucker-Prager return,
//    cohesion degradation and the fractions that follow the bonds: particle_material.cl) with the
//    Bell-Rankine lateral stress sigma_lat = -max(0, K p_zz - 2 c sqrt(K)), p_zz = rho g_n H / 2,
//    added to both normal components for the yield check (the total in-plane stress is
//    sigma + sigma_lat I) and the vertical stress sigma_zz = -p_zz (P.41);
// 3. the depth-integrated stress N = H (sigma + sigma_lat I) and C_i, used by particle_forces (whose
//    forces are the adjoint of this L for any symmetric C);
// 4. the list of the neighbours within the support (j != i, at most nb_cap, in the grid's visiting
//    order) with their kernel-gradient factor (sph_grad_factor) and their count, so particle_forces
//    visits only those and evaluates no kernel for them.
// K: Savage-Hutter from phi and delta, active while the particle's velocity field extends or stays
// (tr L >= 0) and ramping to passive as it contracts (as the grid's solids), or constant.
#include "common/earth_pressure.cl"
#include "particles/artificial_stress.cl"
#include "particles/particle_density.cl"
#include "particles/particle_material.cl"

/// K of a particle whose velocity field has the divergence tr L: constant, or Savage-Hutter with the
/// grid's ramp from active to passive over the contraction rate -tr L (common/earth_pressure.cl; it
/// used to switch on the sign of tr L, which flips K on the velocity noise of a settling deposit).
INLINE real particle_earth_pressure(__constant const ParticleParams* p, real phi, real delta, real divergence,
                                    real gn, real H) {
  if (p->earth_pressure == PARTICLE_EARTH_CONSTANT) return p->k_const;
  return earth_pressure(phi, delta, passive_share_of_rate(-divergence, gn, H));
}

__kernel void particle_stress(__constant const ParticleParams* p, __constant const NeighbourGridParams* ng,
                              __global const uint* cell_start, __global const uint* cell_end,
                              __global const real* x, __global const real* y, __global const real* vx,
                              __global const real* vy, __global const real* V, __global const real* A,
                              __global real* H, __global const real* rho, __global const real* patch,
                              __global const real* phi, __global const real* delta, __global real* sxx,
                              __global real* syy, __global real* sxy, __global real* coh,
                              __global const real* coh0, __global real* plastic, __global real* Nxx,
                              __global real* Nyy, __global real* Nxy, __global real* corr, __global real* share,
                              __global real* numberDensity, __global real* rhoA, __global real* Rart,
                              __global uint* nb_list, __global real* nb_grad, __global uint* nb_count, const uint nb_cap,
                              const real dt) {
  const int i = get_global_id(0);
  if (i >= p->count) return;
  const real h = p->h, r2max = (real)4 * h * h;
  const real xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  real g00 = 0, g01 = 0, g10 = 0, g11 = 0;  // sum A_j (v_j - v_i) (x) grad W
  real m00 = 0, m01 = 0, m10 = 0, m11 = 0;  // sum A_j (x_j - x_i) (x) grad W
  ThicknessSums th = {0, 0};
  real S = 0;  // the number density sum_j W_ij, i included (particle_density.cl)
  uint found = 0;  // neighbours j != i within the support, listed for particle_forces
  __global uint* list = nb_list + (size_t)i * nb_cap;
  __global real* grad = nb_grad + (size_t)i * nb_cap;
  // The thickness sums look as far as 2 h_i (particle_density.cl), the rest as far as 2 h <= 2 h_i.
  const real hi = thickness_smoothing_length(h, p->h_max, p->seed_area, A[i]), r2wide = (real)4 * hi * hi;
  FOR_EACH_PARTICLE_WITHIN(ng, cell_start, cell_end, xi, yi, (real)2 * hi, j) {
    const real dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
    if (r2 >= r2wide) continue;
    const real r = sqrt(r2);
    const real w = sph_w(r, hi);
    S += w;
    thickness_add(&th, V[j], A[j], w);
    if (r2 >= r2max || j == (uint)i) continue;
    const real fw = sph_grad_factor_at(r, h);
    const real2 gw = (real2)(fw * dx, fw * dy);  // grad_i W_ij
    const real aj = A[j];  // the area the neighbour stands for
    const real du = vx[j] - vxi, dv = vy[j] - vyi;
    g00 += aj * du * gw.x;
    g01 += aj * du * gw.y;
    g10 += aj * dv * gw.x;
    g11 += aj * dv * gw.y;
    m00 -= aj * dx * gw.x;
    m01 -= aj * dx * gw.y;
    m10 -= aj * dy * gw.x;
    m11 -= aj * dy * gw.y;
    if (found < nb_cap) {
      list[found] = j;
      grad[found] = fw;
    }
    ++found;
  }
  // C = (M^2 + d^2 I)^-1 M with d = 0.01 (header, point 1); M symmetric: m01 = m10 up to rounding.
  // With P = det M it is C = [P tr(M) I + (d^2 - P) M] / D,
  // D = det(M^2 + d^2 I) = P^2 + d^2 (m00^2 + m11^2 + 2 m01^2) + d^4 > 0, every term formed without
  // cancelling products of M^2's size (the expanded det(M^2 + d^2 I) cancels terms of tr(M)^4, which
  // in float left D <= 0 for a nearly rank-1 M of size 75 and made C infinite).
  real i00, i01, i11;
  {
    const real mo = (real)0.5 * (m01 + m10), d2 = (real)1e-4;
    const real P = m00 * m11 - mo * mo;
    const real D = P * P + d2 * (m00 * m00 + m11 * m11 + (real)2 * mo * mo) + d2 * d2;
    i00 = (P * m11 + d2 * m00) / D;
    i01 = (d2 - P) * mo / D;
    i11 = (P * m00 + d2 * m11) / D;
  }
  nb_count[i] = found;  // more than nb_cap: particle_forces walks the grid for this particle
  const real i10 = i01;
  const real L00 = g00 * i00 + g01 * i10, L01 = g00 * i01 + g01 * i11;
  const real L10 = g10 * i00 + g11 * i10, L11 = g10 * i01 + g11 * i11;
  const real Hi = thickness_of(th), rhoi = rho[i];
  const real rhoAi = rhoi * Hi;
  H[i] = Hi;
  rhoA[i] = rhoAi;
  const real gni = bed_normal_gravity(bed_gradient(p, patch, xi, yi));  // as particle_integrate's gravity
  const real pzz = (real)0.5 * rhoi * gni * Hi;
  const real K = particle_earth_pressure(p, phi[i], delta[i], L00 + L11, gni, Hi);
  MaterialState s = {sxx[i], syy[i], sxy[i], coh[i], plastic[i]};
  const real lat = particle_material_update(p, &s, L00, L01, L10, L11, pzz, K, phi[i], coh0[i], dt);
  sxx[i] = s.sxx;
  syy[i] = s.syy;
  sxy[i] = s.sxy;
  coh[i] = s.c;
  plastic[i] = s.plastic;
  Nxx[i] = Hi * (s.sxx + lat);
  Nyy[i] = Hi * (s.syy + lat);
  Nxy[i] = Hi * s.sxy;
  // The correction matrix for the momentum equation (M is symmetric: one off-diagonal term).
  const int cap = p->count;  // stride of the corr rows
  corr[i] = i00;
  corr[cap + i] = i01;
  corr[2 * cap + i] = i11;
  // The area's anchor (particle_density.cl): set once, where the particle's area is still the
  // seeding's (or a checkpoint's from before the anchor was kept), then carried with the particle.
  if (!(share[i] > (real)0)) share[i] = A[i] * S;
  numberDensity[i] = S;  // particle_integrate's new area: A = share / S
  // The artificial stress of the new N (artificial_stress.cl), once per particle for particle_forces.
  const real ri2 = rhoAi * rhoAi;
  const real4 R = p->eps_art > (real)0
                      ? artificial_stress(p->eps_art, Nxx[i] / ri2, Nyy[i] / ri2, Nxy[i] / ri2)
                      : (real4)(0);
  Rart[i] = R.x;
  Rart[cap + i] = R.y;
  Rart[2 * cap + i] = R.z;
}
