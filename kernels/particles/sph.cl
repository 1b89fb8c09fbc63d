// SPH kernel of the particle mode (spec §5, OpenLISEM Hazard P.74-P.77): the cubic B-spline of
// Monaghan & Lattanzio (1985) in 2D, W(r, h) = s / h^2 w(q), q = r / h, s = 10 / (7 pi),
//   w(q) = 1 - 3/2 q^2 + 3/4 q^3   (0 <= q < 1),   1/4 (2 - q)^3   (1 <= q < 2),   0 beyond,
// which integrates to 1 over the plane and has support 2h. Its radial derivative
//   dW/dr = s / h^3 w'(q),  w'(q) = -3 q + 9/4 q^2  (q < 1),  -3/4 (2 - q)^2  (1 <= q < 2),
// is continuous at q = 1 (both branches give -3/4) and at q = 2 (0). The gradient with respect to
// particle i of W(|x_i - x_j|) is dW/dr (x_i - x_j) / r, zero at r = 0.
#ifndef TALUS_SPH_CL
#define TALUS_SPH_CL
#include "common/real.cl"

#define SPH_SIGMA_2D ((real)0.45472840883398667)  // 10 / (7 pi)

/// W(r, h) [1/m^2].
INLINE real sph_w(real r, real h) {
  const real q = r / h, s = SPH_SIGMA_2D / (h * h);
  if (q < (real)1) return s * ((real)1 - (real)1.5 * q * q + (real)0.75 * q * q * q);
  if (q < (real)2) {
    const real t = (real)2 - q;
    return s * (real)0.25 * t * t * t;
  }
  return (real)0;
}

/// dW/dr (r, h) [1/m^3].
INLINE real sph_dwdr(real r, real h) {
  const real q = r / h, s = SPH_SIGMA_2D / (h * h * h);
  if (q < (real)1) return s * (-(real)3 * q + (real)2.25 * q * q);
  if (q < (real)2) {
    const real t = (real)2 - q;
    return -s * (real)0.75 * t * t;
  }
  return (real)0;
}

/// The factor f of grad_i W = f d at distance r = |d|, d = x_i - x_j: dW/dr / r, and 0 at r = 0.
INLINE real sph_grad_factor_at(real r, real h) { return r <= (real)0 ? (real)0 : sph_dwdr(r, h) / r; }

/// The same from d = x_i - x_j; grad_i W(|d|, h) = sph_grad_factor(d, h) d.
INLINE real sph_grad_factor(real2 d, real h) { return sph_grad_factor_at(sqrt(d.x * d.x + d.y * d.y), h); }

#endif
