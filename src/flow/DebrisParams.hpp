// Host mirror of the two-phase kernels' DebrisParams block (kernels/flow/debris_closures.cl).
#pragma once
#include <cstddef>
#include <cstdint>

#include "compute/Buffer.hpp"
#include "compute/Precision.hpp"
#include "flow/FlowSettings.hpp"

namespace talus::flow {

template <class Real>
struct DebrisParamsT {
  int32_t earthPressure;  // 0 Savage-Hutter active/passive, 1 constant
  int32_t dragLaw;        // 0 off, 1 linear, 2 quadratic
  int32_t virtualMass;
  int32_t deltaFromPhi;
  int32_t rheology;  // flow::Rheology
  int32_t padInt;
  Real kConst, rhoF, poreB, dragMult, dragM, dragBigM, dragKappa, viscA, viscB, phiDefault, rhoSDefault, dDefault;
  Real filmH, invNR, invNRA, chi, xi;
  Real rheo[4];  // parameters of the basal law (flow/Rheology.hpp)
  Real packing;  // solid volume fraction of the saturated skeleton
};

static_assert(offsetof(DebrisParamsT<float>, kConst) == 24 && sizeof(DebrisParamsT<float>) == 112, "DebrisParams<float>");
static_assert(offsetof(DebrisParamsT<double>, kConst) == 24 && sizeof(DebrisParamsT<double>) == 200,
              "DebrisParams<double>");

/// Material defaults of the two-phase kernels where a cell has no solids.
inline constexpr double kDebrisDefaultPhi = 0.5235987755982988;  // 30 degrees
inline constexpr double kDebrisDefaultRhoS = 2650.0;
inline constexpr double kDebrisDefaultGrain = 0.01;

/// Writes the DebrisParams block of `d` in the kernels' precision (buf: sizeof(DebrisParamsT<double>)).
void writeDebrisParams(compute::RawBuffer& buf, const DebrisSettings& d, compute::Precision precision);

}  // namespace talus::flow
