// The run's output folder: maps on the DEM's grid (GeoTIFF or PCRaster), text files written
// atomically, the per-step diagnostics CSV, one run per folder at a time, and protection of an
// existing run's outputs. Every write is checked through close and rename (IoError with the
// system's reason).
#pragma once
#include <set>
#include <string>
#include <vector>

#include "core/FileWrite.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"

namespace talus::sim {

class OutputWriter {
 public:
  /// Opens `dir` (created if missing) for a run and locks it: a second run into the same folder,
  /// also with `overwrite` or `resume`, is refused while this one lives (an advisory lock on the
  /// folder's `.talus-lock`, which the system drops when the process ends, so a killed run never
  /// leaves it stuck). A folder that already holds a run is refused unless `overwrite` or `resume`.
  /// Nothing in the folder is changed until prepare(). Throws InputError naming the folder.
  OutputWriter(const std::string& dir, const Raster& dem, io::RasterFormat format, bool overwrite,
               bool resume = false);
  ~OutputWriter();
  OutputWriter(const OutputWriter&) = delete;
  OutputWriter& operator=(const OutputWriter&) = delete;

  /// Called once the run is known to start: a new or overwriting run removes every file the
  /// folder's previous run wrote (its manifest `.talus-outputs`, see claim()); a resumed run removes
  /// its summary (the run is no longer complete) and temporary files a kill left.
  void prepare();
  /// The path of output `name` (relative to the folder), recorded in the folder's manifest before
  /// the file is written, so that --overwrite can remove exactly the files of this run.
  std::string claim(const std::string& name);
  /// Writes `values` as map `name` (extension added by format). Cells outside the DEM's domain, and
  /// cells where `values` equals `nodataValue` when given, are written as nodata.
  void writeMap(const std::string& name, const std::vector<double>& values, const double* nodataValue = nullptr);
  /// As writeMap, under the exact file name `fileName` (no extension added: OpenLISEM's series
  /// names such as hf000000.012 carry their own).
  void writeMapAs(const std::string& fileName, const std::vector<double>& values);
  /// Writes a text file atomically (temporary file, then rename).
  void writeText(const std::string& name, const std::string& content);
  /// Resuming: throws InputError (changing nothing) unless diagnostics.csv has `rows` complete rows.
  void checkDiagnostics(const std::string& header, long long rows) const;
  /// Resuming, after prepare(): keeps the header and the first `rows` data rows of diagnostics.csv
  /// (a row cut by a kill is dropped) and appends after them. Throws InputError when fewer rows exist.
  void truncateDiagnostics(const std::string& header, long long rows);
  /// Appends one line to diagnostics.csv (the header is written on the first call) and flushes it.
  void appendDiagnostics(const std::string& header, const std::string& line);
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  const std::string& dir() const { return dir_; }

 private:
  void removePreviousRun();
  std::string keptDiagnostics(const std::string& header, long long rows) const;
  std::string dir_;
  const Raster& dem_;
  io::RasterFormat format_;
  bool resume_ = false;
  int lockFd_ = -1;
  AppendFile csv_;
  AppendFile manifest_;
  std::set<std::string> claimed_;
};

}  // namespace talus::sim
