// Member parameters: each member's draw depends only on (seed, member index, parameter index), from
// a counter-based generator (SplitMix64 of a hash of the three), so a member's parameters are the
// same whichever rank, array task or restart runs it, and adding members never changes earlier ones.
// List and grid parameters form a design whose combinations the members run through in turn.
#pragma once
#include <cstdint>
#include <vector>

#include "ensemble/EnsembleFile.hpp"

namespace talus::ensemble {

/// A uniform double in [0, 1) with 53 random bits for (seed, member, parameter, draw).
double uniform01(std::uint64_t seed, std::uint64_t member, std::uint64_t parameter, std::uint64_t draw);

/// A standard normal deviate (Box-Muller on two uniform01 draws) for (seed, member, parameter).
double standardNormal(std::uint64_t seed, std::uint64_t member, std::uint64_t parameter);

/// The value of parameter `p` (index `index` in the spec) for `member`. Design parameters take
/// the member's combination (`member mod designSize`, the first design parameter varying fastest).
double parameterValue(const EnsembleSpec& spec, std::size_t index, long long member);

/// All parameter values of a member, in the spec's order.
std::vector<double> memberValues(const EnsembleSpec& spec, long long member);

}  // namespace talus::ensemble
