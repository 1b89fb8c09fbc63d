// The run's output folder: maps on the DEM's grid (GeoTIFF or PCRaster), text files written
// atomically, the per-step diagnostics CSV, and protection of an existing run's outputs.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "core/Raster.hpp"
#include "io/RasterIO.hpp"

namespace talus::sim {

class OutputWriter {
 public:
  /// Prepares `dir` (created if missing). A folder that already holds a run (summary.json or
  /// diagnostics.csv) is refused unless `overwrite` or `resume`; `resume` keeps the run's files
  /// (see truncateDiagnostics). Throws InputError naming the folder.
  OutputWriter(const std::string& dir, const Raster& dem, io::RasterFormat format, bool overwrite,
               bool resume = false);
  ~OutputWriter();
  OutputWriter(const OutputWriter&) = delete;
  OutputWriter& operator=(const OutputWriter&) = delete;

  /// Writes `values` as map `name` (extension added by format). Cells outside the DEM's domain, and
  /// cells where `values` equals `nodataValue` when given, are written as nodata.
  void writeMap(const std::string& name, const std::vector<double>& values, const double* nodataValue = nullptr);
  /// Writes a text file atomically (temporary file, then rename).
  void writeText(const std::string& name, const std::string& content);
  /// Resuming: keeps the header and the first `rows` data rows of diagnostics.csv (a row cut by a
  /// kill is dropped) and appends after them. Throws InputError when fewer rows exist.
  void truncateDiagnostics(const std::string& header, long long rows);
  /// Appends one line to diagnostics.csv (the header is written on the first call) and flushes it.
  void appendDiagnostics(const std::string& header, const std::string& line);
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  const Raster& dem_;
  io::RasterFormat format_;
  std::FILE* csv_ = nullptr;
};

}  // namespace talus::sim
