// Command-line helpers shared by the benchmarks.
#pragma once
#include <sstream>
#include <string>
#include <vector>

namespace talus::bench {

/// "a,b,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

}  // namespace talus::bench
