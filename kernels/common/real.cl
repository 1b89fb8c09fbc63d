// The kernels' floating-point type `real`, chosen at build time by -DTALUS_DOUBLE=0|1, and the
// physical constants shared with the host (src/core/Constants.hpp holds the same values).
#ifndef TALUS_REAL_CL
#define TALUS_REAL_CL

// No fused multiply-add contraction: the same expression must round the same way wherever it is
// inlined (a face flux computed by both of its cells must agree bitwise for exact conservation).
#pragma OPENCL FP_CONTRACT OFF

// Every helper function is inlined into the kernel that calls it. LLVM's cost model (PoCL) kept the
// larger ones (the reconstruction, the face flux, the solids' face) as calls inside the work-item
// loop, one call per work-item: in double the water stage ran at 0.6 of its inlined speed
// (docs/performance.md, "Every helper function inlined"). Inlining does not change a result: no
// contraction (above) and no excess precision, so the same expression rounds the same way inlined
// or called.
#define INLINE inline __attribute__((always_inline))

#if TALUS_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
typedef double2 real2;
typedef double4 real4;
#define REAL_MAX DBL_MAX
#define REAL_EPS DBL_EPSILON
#else
typedef float real;
typedef float2 real2;
typedef float4 real4;
#define REAL_MAX FLT_MAX
#define REAL_EPS FLT_EPSILON
#endif

/// Gravitational acceleration [m/s^2], the one value host and kernels use (spec §1).
#define GRAVITY ((real)9.81)

#endif
