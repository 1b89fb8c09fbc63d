// Rainfall and infiltration: the mass sources and sinks of the water (docs/sources.md), applied
// once per step after the flux update and friction (operator splitting, as friction is):
//   h' = h + r                      (rain: r = the step's rain depth [m], uniform, no momentum)   (S1)
//   s  = min(h', f dt)              (constant-rate infiltration, capacity f [m/s] per cell)       (S2)
//   h'' = h' - s,   q'' = q h''/h'  (infiltration keeps the velocity u = q/h)                      (S3)
// and q'' = 0 where h'' <= Minimum Flow Height (dry cells carry no momentum, as after every stage).
// Sources change h only where η = h + b would change uniformly: uniform rain on a lake at rest raises
// η everywhere by r and adds no momentum, so the lake stays at rest (well-balanced).
// One work-item per cell of the whole grid (dry tiles included: rain wets them). sink[k] is the
// depth removed by (S2) in cell k, 0 outside the domain, for the volume tally.
#include "flow/flow_common.cl"

__kernel void flow_sources(__constant const FlowParams* p, __global const uchar* mask,
                           __global const real* infiltration, const real rain, const real dt, __global real* h,
                           __global real* qx, __global real* qy, __global real* sink) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= p->nx || j >= p->ny) return;
  const int k = cell_index(p, i, j);
  if (!cell_inside(p, mask, i, j)) {
    sink[k] = (real)0;
    return;
  }
  const real wet = h[k] + rain;                        // (S1)
  const real loss = fmin(wet, infiltration[k] * dt);   // (S2)
  const real left = wet - loss;                        // (S3)
  h[k] = left;
  sink[k] = loss;
  if (left <= p->h_dry) {
    qx[k] = (real)0;
    qy[k] = (real)0;
  } else if (loss > (real)0) {
    const real keep = left / wet;
    qx[k] *= keep;
    qy[k] *= keep;
  }
}
