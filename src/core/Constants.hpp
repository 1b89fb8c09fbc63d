// Physical constants shared by host and kernels (kernels/common/real.cl defines the same values).
#pragma once

namespace talus {

/// Gravitational acceleration [m/s^2] (spec §1: one value everywhere).
inline constexpr double kGravity = 9.81;

}  // namespace talus
