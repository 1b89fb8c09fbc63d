#include "sim/RunTimes.hpp"

#include <cmath>

namespace talus::sim {

double minutesOnReportGrid(double minutes, double reportInterval) {
  const double seconds = 60.0 * minutes;
  if (!(reportInterval > 0) || !(seconds > 0)) return seconds;
  const double n = std::round(seconds / reportInterval);
  if (n < 1) return seconds;  // shorter than one interval: no report time to land on but the start
  const double onGrid = n * reportInterval;
  return std::fabs(seconds - onGrid) <= 1e-6 * onGrid ? onGrid : seconds;
}

}  // namespace talus::sim
