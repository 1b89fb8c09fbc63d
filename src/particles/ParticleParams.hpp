// Host mirror of the particle kernels' ParticleParams block (kernels/particles/particle_common.cl).
#pragma once
#include <cstddef>
#include <cstdint>

namespace talus::particles {

template <class Real>
struct ParticleParamsT {
  int32_t nx, ny;
  int32_t count;
  int32_t earthPressure;  // 0 Savage-Hutter active/passive, 1 constant
  int32_t edgeWall, nodataWall;  // 1 where the raster edge / nodata faces are walls, 0 open
  Real dx, h, shearModulus, planeBulkModulus, soundSpeed, alphaPi, betaPi, epsArt, nArt, wSpacing, dilatancy, epsCrit,
      kConst, poreB, rhoF, seedArea, hMax, pad1;
};

// The OpenCL C struct has the same member order; both layouts must match byte for byte.
static_assert(offsetof(ParticleParamsT<float>, dx) == 24 && sizeof(ParticleParamsT<float>) == 96, "ParticleParams<float>");
static_assert(offsetof(ParticleParamsT<double>, dx) == 24 && sizeof(ParticleParamsT<double>) == 168,
              "ParticleParams<double>");

}  // namespace talus::particles
