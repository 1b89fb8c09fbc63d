// Small text helpers shared by the parsers (run-files, ensemble files, ASCII grids, device names).
#pragma once
#include <cctype>
#include <string>

namespace talus {

/// `s` without leading and trailing white space.
inline std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

/// `s` in lower case (ASCII, C locale).
inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace talus
