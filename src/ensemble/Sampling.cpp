// Counter-based sampling of member parameters (see Sampling.hpp).
#include "ensemble/Sampling.hpp"

#include <cmath>

namespace talus::ensemble {
namespace {

/// SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijection of 64-bit words whose output
/// bits all depend on all input bits.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

double uniform01(std::uint64_t seed, std::uint64_t member, std::uint64_t parameter, std::uint64_t draw) {
  // Chained mixing keeps the four counters apart: (s, m, p, d) and any other tuple give unrelated words.
  const std::uint64_t h = mix(mix(mix(mix(seed) ^ member) ^ parameter) ^ draw);
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

double standardNormal(std::uint64_t seed, std::uint64_t member, std::uint64_t parameter) {
  const double u1 = 1.0 - uniform01(seed, member, parameter, 0);  // (0, 1]: the log is finite
  const double u2 = uniform01(seed, member, parameter, 1);
  const double pi = 3.14159265358979323846;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * pi * u2);
}

double parameterValue(const EnsembleSpec& spec, std::size_t index, long long member) {
  const Parameter& p = spec.parameters[index];
  const auto m = static_cast<std::uint64_t>(member);
  switch (p.distribution) {
    case Distribution::Uniform: return p.a + (p.b - p.a) * uniform01(spec.seed, m, index, 0);
    case Distribution::Normal: return p.a + p.b * standardNormal(spec.seed, m, index);
    case Distribution::LogNormal: return std::exp(p.a + p.b * standardNormal(spec.seed, m, index));
    case Distribution::List:
    case Distribution::Grid: break;
  }
  // Mixed-radix digit of the member's combination: design parameters before this one vary faster.
  long long combination = member % spec.designSize();
  for (std::size_t k = 0; k < index; ++k)
    if (spec.parameters[k].isDesign()) combination /= static_cast<long long>(spec.parameters[k].values.size());
  return p.values[static_cast<std::size_t>(combination % static_cast<long long>(p.values.size()))];
}

std::vector<double> memberValues(const EnsembleSpec& spec, long long member) {
  std::vector<double> v;
  for (std::size_t k = 0; k < spec.parameters.size(); ++k) v.push_back(parameterValue(spec, k, member));
  return v;
}

}  // namespace talus::ensemble
