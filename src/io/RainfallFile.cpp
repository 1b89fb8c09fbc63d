#include "io/RainfallFile.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "core/Error.hpp"
#include "io/LisemValues.hpp"

namespace talus::io {
namespace {

constexpr double kMmPerHourToMetresPerSecond = 1.0 / (3600.0 * 1000.0);

/// A whole-token number; false when the token is not one.
bool number(const std::string& token, double& out) {
  std::istringstream in(token);
  in >> out;
  return !in.fail() && in.peek() == std::char_traits<char>::eof() && std::isfinite(out);
}

}  // namespace

Rainfall Rainfall::uniform(double intensityMmPerHour) { return Rainfall({0.0}, {intensityMmPerHour}); }

Rainfall::Rainfall(std::vector<double> timesSeconds, std::vector<double> intensitiesMmPerHour)
    : times_(std::move(timesSeconds)), values_(std::move(intensitiesMmPerHour)) {
  if (times_.size() != values_.size()) throw InputError("rainfall: as many times as intensities are needed");
  for (std::size_t k = 0; k < times_.size(); ++k) {
    if (!(values_[k] >= 0) || !std::isfinite(values_[k])) throw InputError("rainfall intensity must be finite and >= 0");
    if (k > 0 && !(times_[k] > times_[k - 1])) throw InputError("rainfall record times must increase");
  }
}

double Rainfall::intensity(double t) const {
  if (times_.empty()) return 0.0;
  // The last record at or before t; before the first record, the first (fillValues: t_this = -inf).
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  const std::size_t k = after == times_.begin() ? 0 : static_cast<std::size_t>(after - times_.begin()) - 1;
  return values_[k];
}

double Rainfall::depth(double t0, double t1) const {
  if (times_.empty() || !(t1 > t0)) return 0.0;
  double sum = 0;  // mm/h x s
  // From the record that holds at t0 (binary search: called every step, files hold thousands of
  // records) to the last one that starts before t1.
  const auto after = std::upper_bound(times_.begin(), times_.end(), t0);
  for (std::size_t k = after == times_.begin() ? 0 : static_cast<std::size_t>(after - times_.begin()) - 1;
       k < times_.size() && (k == 0 || times_[k] < t1); ++k) {
    const double from = k == 0 ? -HUGE_VAL : times_[k];
    const double to = k + 1 < times_.size() ? times_[k + 1] : HUGE_VAL;
    const double overlap = std::min(to, t1) - std::max(from, t0);
    if (overlap > 0) sum += values_[k] * overlap;
  }
  return sum * kMmPerHourToMetresPerSecond;
}

Rainfall readRainfallFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("rainfall file '" + path + "' cannot be opened");
  // Non-empty lines with their line numbers (OpenLISEM skips empty lines before counting).
  std::vector<std::pair<int, std::string>> lines;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos) lines.emplace_back(n, line);
  }
  auto fail = [&](int n, const std::string& why) -> InputError {
    return InputError("rainfall file '" + path + "' line " + std::to_string(n) + ": " + why);
  };
  if (lines.size() < 2) throw InputError("rainfall file '" + path + "' needs a description line and a column count");
  double columns = 0;
  std::istringstream countLine(lines[1].second);
  std::string countText;
  countLine >> countText;
  if (!number(countText, columns) || columns != std::floor(columns) || columns < 2)
    throw fail(lines[1].first, "expected the number of columns (2: time and one station), found '" + lines[1].second + "'");
  if (columns > 2)
    throw fail(lines[1].first, std::to_string(static_cast<int>(columns) - 1) +
                                   " stations: Talus reads rainfall files of one station (2 columns)");
  const std::size_t first = 2 + static_cast<std::size_t>(columns);
  if (lines.size() <= first) throw InputError("rainfall file '" + path + "' has no records after its column names");
  std::vector<double> times, values;
  for (std::size_t r = first; r < lines.size(); ++r) {
    std::istringstream row(lines[r].second);
    std::vector<std::string> tokens;
    for (std::string tok; row >> tok;) tokens.push_back(tok);
    if (tokens.size() != 2)
      throw fail(lines[r].first, "expected a time [min] and one intensity [mm/h], found " +
                                     std::to_string(tokens.size()) + " values");
    double minutes = 0, mmh = 0;
    // openLISEM 6 stamps its series as day:minute (lisRainfall.cpp, getTimefromString).
    if (!number(tokens[0], minutes) && !readDayMinute(tokens[0], minutes))
      throw fail(lines[r].first, "time '" + tokens[0] + "' is neither minutes nor day:minute (ddd:mmmm)");
    if (!number(tokens[1], mmh)) {
      const bool isMap = std::any_of(tokens[1].begin(), tokens[1].end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)); });
      throw fail(lines[r].first, isMap ? "rainfall maps ('" + tokens[1] + "') are not supported; give intensities in mm/h"
                                       : "intensity '" + tokens[1] + "' is not a number");
    }
    if (mmh < 0) throw fail(lines[r].first, "negative intensity " + tokens[1]);
    if (!times.empty() && !(60.0 * minutes > times.back())) throw fail(lines[r].first, "record times must increase");
    times.push_back(60.0 * minutes);
    values.push_back(mmh);
  }
  return Rainfall(std::move(times), std::move(values));
}

}  // namespace talus::io
