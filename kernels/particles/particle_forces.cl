// Internal accelerations of the particles (spec §5, OpenLISEM Hazard P.78 with P.83-P.86):
//   dv_i/dt = sum_j m_j (N_i / rhoA_i^2 + N_j / rhoA_j^2 + f_ij^n R_ij - Pi_ij I) . G_ij,
// with the corrected, antisymmetrised kernel gradient G_ij = (M_i^-1 + M_j^-1) / 2 grad_i W_ij (Bonet &
// Lok 1999; M from particle_stress): on the R2 particle layouts with h = 2 dp the plain gradient
// underestimates the stiffness (an elastic bar rang 5 % slow), the corrected one is exact for linear
// fields and, being antisymmetric (G_ji = -G_ij), still conserves momentum to round-off.
// N = H (sigma + sigma_lat I) the depth-integrated in-plane stress (tension positive; from
// particle_stress), rhoA the areal density. Each pair term is antisymmetric in (i, j) (grad_i W_ij =
// -grad_j W_ji, the bracket is symmetric), so the internal forces conserve momentum to round-off.
// - Pi_ij (Monaghan 1992): for approaching pairs, mu = h v_ij . x_ij / (r^2 + 0.01 h^2) < 0,
//   Pi_ij = (-alpha c mu + beta mu^2) / mean(rhoA), a pressure-like repulsion (the sign convention
//   of the bracket above: Pi_ij >= 0 pushes the pair apart).
// - R_ij = R_i + R_j (Gray, Monaghan & Swift 2001): in the principal frame of N_i / rhoA_i^2, each
//   tensile principal value s > 0 gives -eps s, compressive ones 0; rotated back. f_ij = W_ij / W(dp),
//   dp the mean particle spacing. It acts only in tension, against the tensile clumping instability.
#include "particles/particle_common.cl"

/// The artificial-stress tensor R (xx, yy, xy) of a particle from its S = N / rhoA^2.
inline real4 artificial_stress(real eps, real sxx, real syy, real sxy) {
  const real c = (real)0.5 * (sxx + syy), d = (real)0.5 * (sxx - syy);
  const real rad = sqrt(d * d + sxy * sxy);
  const real s1 = c + rad, s2 = c - rad;
  const real r1 = s1 > (real)0 ? -eps * s1 : (real)0, r2 = s2 > (real)0 ? -eps * s2 : (real)0;
  // Principal direction of s1: angle theta with cos 2 theta = d / rad, sin 2 theta = sxy / rad.
  const real c2 = rad > (real)0 ? d / rad : (real)1, s2t = rad > (real)0 ? sxy / rad : (real)0;
  const real mean = (real)0.5 * (r1 + r2), dev = (real)0.5 * (r1 - r2);
  return (real4)(mean + dev * c2, mean - dev * c2, dev * s2t, 0);
}

__kernel void particle_forces(__constant const ParticleParams* p, __constant const NeighbourGridParams* ng,
                              __global const uint* cell_start, __global const uint* cell_end,
                              __global const real* x, __global const real* y, __global const real* vx,
                              __global const real* vy, __global const real* m, __global const real* rhoA,
                              __global const real* Nxx, __global const real* Nyy, __global const real* Nxy,
                              __global const real* Minv, __global real* ax, __global real* ay) {
  const int i = get_global_id(0);
  if (i >= p->count) return;
  const real h = p->h, r2max = (real)4 * h * h;
  const real xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
  const real ri2 = rhoA[i] * rhoA[i];
  const real Sxx = Nxx[i] / ri2, Syy = Nyy[i] / ri2, Sxy = Nxy[i] / ri2;
  const real4 Ri = p->eps_art > (real)0 ? artificial_stress(p->eps_art, Sxx, Syy, Sxy) : (real4)(0);
  const int cap = p->count;  // stride of the Minv rows
  const real ai00 = Minv[i], ai01 = Minv[cap + i], ai11 = Minv[2 * cap + i];
  real accx = 0, accy = 0;
  FOR_EACH_NEARBY_PARTICLE(ng, cell_start, cell_end, xi, yi, j) {
    if (j == (uint)i) continue;
    const real dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
    if (r2 >= r2max) continue;
    const real r = sqrt(r2);
    const real2 g0 = sph_grad((real2)(dx, dy), h);
    const real c00 = (real)0.5 * (ai00 + Minv[j]), c01 = (real)0.5 * (ai01 + Minv[cap + j]);
    const real c11 = (real)0.5 * (ai11 + Minv[2 * cap + j]);
    const real2 gw = (real2)(c00 * g0.x + c01 * g0.y, c01 * g0.x + c11 * g0.y);
    const real rj2 = rhoA[j] * rhoA[j];
    real txx = Sxx + Nxx[j] / rj2, tyy = Syy + Nyy[j] / rj2, txy = Sxy + Nxy[j] / rj2;
    if (p->eps_art > (real)0) {
      const real4 Rj = artificial_stress(p->eps_art, Nxx[j] / rj2, Nyy[j] / rj2, Nxy[j] / rj2);
      const real f = sph_w(r, h) / p->w_spacing;
      real fn = (real)1;
      for (int k = 0; k < (int)p->n_art; ++k) fn *= f;
      txx += fn * (Ri.x + Rj.x);
      tyy += fn * (Ri.y + Rj.y);
      txy += fn * (Ri.z + Rj.z);
    }
    const real vdotr = (vxi - vx[j]) * dx + (vyi - vy[j]) * dy;
    if (vdotr < (real)0 && (p->alpha_pi > (real)0 || p->beta_pi > (real)0)) {
      const real mu = h * vdotr / (r2 + (real)0.01 * h * h);
      const real pi = (-p->alpha_pi * p->sound_speed * mu + p->beta_pi * mu * mu) / ((real)0.5 * (rhoA[i] + rhoA[j]));
      txx -= pi;
      tyy -= pi;
    }
    accx += m[j] * (txx * gw.x + txy * gw.y);
    accy += m[j] * (txy * gw.x + tyy * gw.y);
  }
  ax[i] = accx;
  ay[i] = accy;
}
