// What a finished (or cut-short) Talus output folder holds, as `talus run` writes it
// (docs/outputs.md): its summary, the maps at the top (maxima, final, arrival, ...), the series of
// maps per report time (series/NAME_NNNN), the particle layers (particles/particles_NNNN.gpkg,
// particles_final.gpkg), diagnostics.csv and the resolved run-file that names the DEM. Only lists
// files; the rasters are read when shown (ResultsReplay).
#pragma once
#include <QString>
#include <QStringList>
#include <vector>

namespace talus::gui {

/// One map of the folder's top level (hfmax.tif, hffinal.tif, tarrival.tif, ...).
struct ResultsMap {
  QString name;  ///< file name without extension, the layer's name ("hfmax")
  QString path;
};

/// The frames of one series variable (hf, vf, hs, ...): one file per report index, "" where missing.
struct ResultsSeries {
  QString name;
  std::vector<QString> files;  ///< parallel to ResultsFolder::frameTimes
};

struct ResultsFolder {
  QString dir;         ///< absolute path of the folder
  QString status;      ///< summary.json "status" ("completed", "stopped", "failed")
  QString statusNote;  ///< summary.json's diagnosis of a failed run, when it gives one
  QString demPath;     ///< the DEM the run read ("" when the run-file cannot tell)
  double demMultiplier = 1;
  QString diagnosticsPath;  ///< "" when the folder has no diagnostics.csv
  std::vector<ResultsMap> maps;
  std::vector<double> frameTimes;   ///< report time of each series frame [s]
  std::vector<ResultsSeries> series;
  std::vector<QString> particleFrames;  ///< per series frame, "" where none
  QString particlesFinal;               ///< particles_final.gpkg, "" when none
  QStringList warnings;                 ///< what could not be read but did not stop the opening

  /// A run that did not complete (stopped, failed): what it wrote is shown, marked as partial.
  bool isPartial() const { return status != "completed"; }
  bool hasParticles() const { return !particlesFinal.isEmpty() || !particleFrames.empty(); }

  /// Lists the folder. Throws std::runtime_error naming the folder when it does not exist, is not a
  /// Talus output folder (no summary.json) or its summary.json cannot be read.
  static ResultsFolder open(const QString& dir);
};

}  // namespace talus::gui
