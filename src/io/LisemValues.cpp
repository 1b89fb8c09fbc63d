// OpenLISEM Hazard value readings: decimal commas, day:minute times, Windows drive paths and
// case-insensitive file names (see LisemValues.hpp for why each exists).
#include "io/LisemValues.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <system_error>

namespace talus::io {

namespace fs = std::filesystem;

namespace {

bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

/// Length of the run of digits starting at text[i].
std::size_t digitsAt(const std::string& text, std::size_t i) {
  std::size_t n = 0;
  while (i + n < text.size() && isDigit(text[i + n])) ++n;
  return n;
}

std::string lowerCopy(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

DecimalComma readDecimalComma(const std::string& text, std::string& dotted) {
  std::size_t i = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
  const std::size_t whole = digitsAt(text, i);
  if (whole == 0 || i + whole >= text.size() || text[i + whole] != ',') return DecimalComma::None;
  const std::size_t fracStart = i + whole + 1;
  const std::size_t frac = digitsAt(text, fracStart);
  if (frac == 0) return DecimalComma::None;
  std::size_t end = fracStart + frac;
  if (end < text.size() && (text[end] == 'e' || text[end] == 'E')) {  // exponent: e-3, E+2, e5
    std::size_t k = end + 1;
    if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
    const std::size_t exp = digitsAt(text, k);
    if (exp == 0) return DecimalComma::None;
    end = k + exp;
  }
  if (end != text.size()) return DecimalComma::None;  // "1,2,3" (a list) or "0,5m": not a number
  if (text[i] != '0' && whole <= 3 && frac == 3 && end == fracStart + frac) return DecimalComma::Ambiguous;
  dotted = text;
  dotted[i + whole] = '.';
  return DecimalComma::Read;
}

bool readDayMinute(const std::string& text, double& minutes) {
  double parts[3] = {0, 0, 0};
  int n = 0;
  std::size_t i = 0;
  while (i <= text.size()) {
    if (n == 3) return false;
    const std::size_t len = digitsAt(text, i);
    std::size_t end = i + len;
    if (end < text.size() && text[end] == '.') end += 1 + digitsAt(text, end + 1);  // 0030.5
    if (len == 0) return false;
    const auto [p, ec] = std::from_chars(text.data() + i, text.data() + end, parts[n]);
    if (ec != std::errc() || p != text.data() + end) return false;
    ++n;
    if (end == text.size()) break;
    if (text[end] != ':') return false;
    i = end + 1;
  }
  if (n < 2) return false;  // a plain number is minutes, read elsewhere
  minutes = n == 2 ? parts[0] * 1440 + parts[1] : parts[0] * 1440 + parts[1] * 60 + parts[2];
  return std::isfinite(minutes);
}

bool isWindowsDrivePath(const std::string& text) {
  return text.size() >= 3 && std::isalpha(static_cast<unsigned char>(text[0])) && text[1] == ':' &&
         (text[2] == '/' || text[2] == '\\');
}

std::string lastPathComponent(const std::string& text) {
  std::size_t end = text.size();
  while (end > 0 && (text[end - 1] == '/' || text[end - 1] == '\\')) --end;
  std::size_t start = end;
  while (start > 0 && text[start - 1] != '/' && text[start - 1] != '\\') --start;
  const std::string last = text.substr(start, end - start);
  return isWindowsDrivePath(last + "/") ? "" : last;  // "C:" alone is a drive, not a folder
}

std::string findIgnoringCase(const std::string& path) {
  const fs::path p(path);
  const std::string wanted = lowerCopy(p.filename().string());
  std::error_code ec;
  if (wanted.empty() || !fs::is_directory(p.parent_path(), ec)) return "";
  std::string found;
  for (fs::directory_iterator it(p.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    if (lowerCopy(it->path().filename().string()) != wanted) continue;
    if (!found.empty()) return "";  // DEM.map and dem.MAP: which one is meant is not ours to guess
    found = it->path().string();
  }
  return found;
}

}  // namespace talus::io
