// Manning's basal friction in its slope-consistent form, for the water and for the fluid of the
// two-phase model (spec §4, OpenLISEM Hazard P.46 on a horizontal bed).
//
// On a bed z = b(x, y) the flow moves along the bed with speed |U| = sqrt(|u|^2 + (u.grad b)^2) (u the
// horizontal velocity) over the bed-normal thickness h_n = h cos(theta) (h vertical). Manning's
// basal shear tau = rho g n^2 |U|^2 / h_n^(1/3) acts against U on the bed area, 1 / cos(theta) per unit
// horizontal area; its horizontal part per unit of horizontal momentum rho h u gives
//   du/dt = -g n^2 |U| u / (h_n^(1/3) h cos(theta)) = -g n^2 |U| u / h_n^(4/3).
// On a plane of
// slope theta the steady flow is then Manning's law along the bed, U = sqrt(sin theta) h_n^(2/3) / n
// (the bed force of the model is g cos^2(theta) grad b, spec §1); the horizontal form
// -g n^2 |u| u / h^(4/3) gives a speed larger by cos(theta)^(-7/6) (26 % at 35 degrees).
// cos2 = cos^2(theta) and (bx, by) = grad b are those of the slope correction (g_n = g cos2). Built
// with -DMANNING_ALONG_BED=0 (slope correction off: cos2 = 1) this is the classical horizontal form.
// Applied semi-implicitly, q <- q / factor, so it can slow a flow to rest but never reverses it.
#ifndef TALUS_FLOW_MANNING_CL
#define TALUS_FLOW_MANNING_CL
#include "common/real.cl"

#ifndef MANNING_ALONG_BED
#define MANNING_ALONG_BED 1
#endif

INLINE real manning_factor(real n, real h, real u, real v, real bx, real by, real cos2, real dt) {
#if MANNING_ALONG_BED
  const real w = u * bx + v * by;
#else
  const real w = 0;
#endif
  const real speed = sqrt(u * u + v * v + w * w);
  const real hn = h * sqrt(cos2);
  return (real)1 + dt * GRAVITY * n * n * speed / (hn * cbrt(hn));
}

#endif
