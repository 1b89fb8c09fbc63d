// Rainfall time series in OpenLISEM Hazard's format (bastianvandenbout/LISEM,
// lisem/model/timeseries.h, TimeSeries::LoadFromFile, lines 39-135):
//   line 1        a description
//   line 2        the number of columns N (time plus stations)
//   N lines       one name per column
//   records       time [min] then N - 1 intensities [mm/h], whitespace-separated
// Empty lines are skipped. Times may also be openLISEM 6's day:minute stamps "ddd:mmmm"
// (vjetten/openlisem, lisRainfall.cpp, getTimefromString), which has the same layout. Each record's intensity holds from its time to the next record's (the
// first also before it, the last for ever after: TimeSeries::fillValues, lines 137-180), and the
// rain of a step is the time integral of that step function. Talus reads one station (N = 2);
// files with several stations or with map names as records are refused.
#pragma once
#include <string>
#include <vector>

namespace talus::io {

/// A step-wise constant rainfall intensity in time.
class Rainfall {
 public:
  /// No rain.
  Rainfall() = default;
  /// A constant intensity [mm/h] at all times.
  static Rainfall uniform(double intensityMmPerHour);
  /// Records sorted by time: times [s], intensities [mm/h]; record k holds on [t_k, t_k+1).
  Rainfall(std::vector<double> timesSeconds, std::vector<double> intensitiesMmPerHour);

  /// True when there is no record (no rain).
  bool empty() const { return times_.empty(); }
  /// Intensity at time t [mm/h].
  double intensity(double t) const;
  /// Rain depth that falls between t0 and t1 [m]: the integral of the intensity (mm/h -> m/s by
  /// 1/(3600 * 1000), as OpenLISEM's modelrun.cpp line 114 converts it).
  double depth(double t0, double t1) const;
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& intensities() const { return values_; }

 private:
  std::vector<double> times_, values_;
};

/// Reads an OpenLISEM rainfall file. Throws InputError naming the file and line when it is missing
/// or malformed, or holds several stations or maps.
Rainfall readRainfallFile(const std::string& path);

}  // namespace talus::io
