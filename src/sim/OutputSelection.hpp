// Which maps a run writes and under which names: Talus's keys (Output Format, Report Series,
// Series Names) and, where those are not given, OpenLISEM Hazard's output switches (Output GeoTIFF
// format, Output timeseries and its per-variable switches; bastianvandenbout/LISEM,
// lisem/model/modelruninit.cpp lines 283-300, modelreport.cpp lines 410-465).
#pragma once
#include <string>

#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"

namespace talus::sim {

/// The series written at each report time.
struct SeriesSelection {
  bool any = true;  ///< series at all (Report Series, or OpenLISEM's Output timeseries)
  /// The variables (OpenLISEM's prefixes): fluid thickness and speed, solid thickness and speed,
  /// solid fraction, total thickness and the thickness-averaged speed of the mixture.
  bool hf = true, vf = true, hs = true, vs = true, sf = false, ht = false, vt = false;
  /// OpenLISEM's names: prefix, zeros to 8 characters, the model step with a dot after its first
  /// digit (hf000000.012: step 12), in the output folder itself; else series/hf_NNNN with the
  /// report index.
  bool lisemNames = false;
  int reportEvery = 1;  ///< model steps (Timestep) per report: OpenLISEM numbers series by step
};

/// The raster format of the outputs: Output Format when given, else OpenLISEM's Output GeoTIFF
/// format when given, else GeoTIFF.
io::RasterFormat outputFormat(const io::RunConfig& cfg);

/// The series selection of a run-file. With OpenLISEM's Output timeseries given (and Report Series
/// not), exactly the variables its switches select are written, as OpenLISEM does.
SeriesSelection seriesSelection(const io::RunConfig& cfg);

/// The file name of series map `prefix` at report `index` (without extension for Talus's names,
/// which OutputWriter::writeMap adds; OpenLISEM's carry their own).
std::string seriesName(const SeriesSelection& s, const std::string& prefix, int index);

}  // namespace talus::sim
