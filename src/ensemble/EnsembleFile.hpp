// An ensemble description (docs/ensembles.md): the base run-file, the uncertain parameters with
// their distributions, the number of members and the seed, the thresholds of the merged maps and the
// observations calibration compares against. The file uses the run-file syntax ("[Section]",
// "Key=Value", "#" or ";" comments); every error names the file, line and key.
#pragma once
#include <string>
#include <vector>

namespace talus::ensemble {

/// How a parameter's draw reaches the run-file key.
enum class ApplyMode {
  Value,  ///< the draw is the key's value ("Manning=0.05")
  Scale,  ///< the draw multiplies the key's value (map keys: the run-file multiplier "=1.2")
};

/// The distribution a parameter is drawn from.
enum class Distribution {
  Uniform,    ///< uniform on [a, b)
  Normal,     ///< normal, mean a, standard deviation b
  LogNormal,  ///< ln X normal with mean a and standard deviation b
  List,       ///< the listed values (a design axis: members run through the combinations)
  Grid,       ///< n values evenly spaced from a to b inclusive (a design axis)
};

/// One uncertain run-file key.
struct Parameter {
  std::string key;  ///< the run-file key as written in the ensemble file
  ApplyMode mode = ApplyMode::Value;
  Distribution distribution = Distribution::Uniform;
  double a = 0, b = 0;          ///< the distribution's two numbers (see Distribution)
  std::vector<double> values;   ///< List: the values; Grid: the n values, computed
  int line = 0;                 ///< line of the ensemble file (for messages)
  /// True for List and Grid: the parameter is an axis of the design, not drawn at random.
  bool isDesign() const { return distribution == Distribution::List || distribution == Distribution::Grid; }
};

/// A parsed and checked ensemble description. Paths are absolute.
struct EnsembleSpec {
  std::string file;        ///< the ensemble file itself
  std::string runFile;     ///< [Ensemble] Run File: the base run-file every member starts from
  std::string outputDir;   ///< [Ensemble] Output Directory (default: the file's name without extension, beside it)
  int members = 0;         ///< [Ensemble] Members (default: the number of design combinations, else required)
  unsigned long long seed = 1;  ///< [Ensemble] Seed
  std::vector<Parameter> parameters;  ///< [Parameters], in file order
  std::vector<double> thicknessThresholds{0.1};  ///< [Maps] Thickness Thresholds [m]: P(hmax > t)
  std::vector<double> speedThresholds{1.0};      ///< [Maps] Speed Thresholds [m/s]: P(vmax > t)
  std::vector<double> arrivalTimes;              ///< [Maps] Arrival Times [s]: P(arrival <= t)
  std::vector<double> percentiles{10, 50, 90};   ///< [Maps] Percentiles of hmax and vmax, in [0, 100]
  /// [Maps] Affected Threshold [m]: a cell is affected by a member when its hmax exceeds this
  /// (area, runout and calibration).
  double affectedThreshold = 0.1;
  std::string observedMap;         ///< [Calibration] Observed Map ("" = none)
  double observedThreshold = 0.0;  ///< [Calibration] Observed Threshold: observed where value > this
  bool hasObservedRunout = false;
  double observedX = 0, observedY = 0;  ///< [Calibration] Observed Runout: world x y of the runout point
  /// [Calibration] Rank By: jaccard, d2pc or runout (default jaccard with an Observed Map, runout
  /// with only an Observed Runout, "" without observations: no calibration).
  std::string rankBy;
  /// Number of combinations of the design parameters (1 when there are none).
  long long designSize() const;
};

/// Reads and checks an ensemble file. Throws talus::InputError listing every problem, each as
/// "FILE:LINE: key 'K': ...".
EnsembleSpec loadEnsembleFile(const std::string& path);
/// As loadEnsembleFile, from text; relative paths resolve against baseDir; messages name displayName.
EnsembleSpec parseEnsembleText(const std::string& text, const std::string& baseDir, const std::string& displayName);

/// The name of a distribution as written in the file ("uniform", ...).
std::string distributionName(Distribution d);

}  // namespace talus::ensemble
