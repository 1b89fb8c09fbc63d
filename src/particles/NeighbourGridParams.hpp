// Host mirror of the kernels' NeighbourGridParams block (kernels/particles/neighbours.cl).
#pragma once
#include <cstddef>
#include <cstdint>

namespace talus::particles {

template <class Real>
struct NeighbourGridParamsT {
  int32_t cellsX, cellsY;  ///< cells per row, per column
  Real xMin, yMin;         ///< lower-left corner of the domain box [m]
  Real xMax, yMax;         ///< upper-right corner of the domain box [m]
  Real cellSize;           ///< cell edge [m]
  Real pad0;
};

// The OpenCL C struct has the same member order; both layouts must match byte for byte.
static_assert(offsetof(NeighbourGridParamsT<float>, xMin) == 8 && sizeof(NeighbourGridParamsT<float>) == 32,
              "NeighbourGridParams<float>");
static_assert(offsetof(NeighbourGridParamsT<double>, xMin) == 8 && sizeof(NeighbourGridParamsT<double>) == 56,
              "NeighbourGridParams<double>");

}  // namespace talus::particles
