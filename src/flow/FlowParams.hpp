// Host mirror of the kernels' FlowParams block (kernels/flow/flow_common.cl), for float and double.
#pragma once
#include <cstddef>
#include <cstdint>

namespace talus::flow {

template <class Real>
struct FlowParamsT {
  int32_t nx, ny;
  int32_t tilesX, tilesY;
  int32_t edgeBoundary;    // 0 wall, 1 open, 2 level
  int32_t nodataBoundary;  // 0 wall, 1 open
  int32_t skipDryTiles;
  int32_t pad0;
  Real dx;
  Real hDry;
  Real arrivalH;
  Real pad1;
};

// The OpenCL C struct has the same member order; both layouts must match byte for byte.
static_assert(offsetof(FlowParamsT<float>, dx) == 32 && sizeof(FlowParamsT<float>) == 48, "FlowParams<float>");
static_assert(offsetof(FlowParamsT<double>, dx) == 32 && sizeof(FlowParamsT<double>) == 64, "FlowParams<double>");

/// Tile edge in cells (kernels built with -DTILE=kTile); a tile is one work-group of the diagnostics.
inline constexpr int kTile = 16;
/// The Courant number up to which the unsplit second-order stage is positive by itself (Audusse et
/// al. 2004, thm. 2.1); the split sweeps limit draining cells' fluxes and take up to 1
/// (kernels/flow/stage.cl).
inline constexpr double kPositiveCfl = 0.5;

}  // namespace talus::flow
