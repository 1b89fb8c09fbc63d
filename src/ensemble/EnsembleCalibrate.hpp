// Calibration: each member's affected area (hmax > Affected Threshold) against an observed
// deposit or affected-area raster, and its runout point against an observed one. Members are
// ranked by the chosen measure; the best member's parameters are reported with a map of agreement.
//
// Measures, over the cells valid in both the DEM and the observed map (docs/ensembles.md):
//   TP, FP, FN, TN  model/observation both affected, model only, observation only, neither
//   Jaccard index J = TP / (TP + FP + FN)            (Jaccard 1901; r.avaflow's CSI), 1 = perfect
//   TPR = TP / (TP + FN), FPR = FP / (FP + TN)        (the ROC point, Fawcett 2006)
//   D2PC = sqrt((1 - TPR)^2 + FPR^2)                  distance to perfect classification, 0 = perfect
//   AUROC = (1 + TPR - FPR) / 2                       area under the ROC curve of one binary map
//   FoC = (TP + FP) / (TP + FN)                        factor of conservativeness: > 1 over-, < 1 under-predicts
//   runout distance: from the member's runout point to the observed one [m]
#pragma once
#include <string>
#include <vector>

#include "core/Raster.hpp"
#include "ensemble/EnsembleFile.hpp"
#include "ensemble/MemberOutputs.hpp"
#include "io/RasterIO.hpp"

namespace talus::ensemble {

/// One member's agreement with the observations.
struct MemberFit {
  long long member = 0;
  long long tp = 0, fp = 0, fn = 0, tn = 0;
  double jaccard = 0, tpr = 0, fpr = 0, d2pc = 0, auroc = 0, foc = 0;
  bool hasDistance = false;
  double runoutDistanceM = 0;  ///< modelled to observed runout point [m]
};

/// The confusion counts and measures of one affected mask against the observed one; `domain`
/// marks the cells compared.
MemberFit fitMask(const std::vector<unsigned char>& modelled, const std::vector<unsigned char>& observed,
                  const std::vector<unsigned char>& domain);

/// Agreement codes: 0 neither, 1 model only, 2 observation only, 3 both; 255 outside the domain.
std::vector<unsigned char> agreementMap(const std::vector<unsigned char>& modelled,
                                        const std::vector<unsigned char>& observed,
                                        const std::vector<unsigned char>& domain);

/// Ranks the members (whose maps are `maps`, figures `figures`, same order) against the spec's
/// observations and writes into `dir`: calibration.csv (every member, ranked), calibration.json
/// (the best member and its parameters) and, with an Observed Map, agreement.tif (the best member's
/// agreement codes on the DEM's grid). Returns the fits in rank order.
std::vector<MemberFit> calibrate(const EnsembleSpec& spec, const Raster& dem, const std::vector<MemberMaps>& maps,
                                 const std::vector<MemberFigures>& figures, const std::string& dir,
                                 io::RasterFormat format);

}  // namespace talus::ensemble
