// Merging the finished members of an ensemble into OUTPUT/merged: probability-of-exceedance maps
// P(hmax > t), P(vmax > t), P(arrival <= t), percentile maps of hmax and vmax, the table of
// per-member figures (members.csv) and, with observations, the calibration (EnsembleCalibrate.hpp).
// Maps are on the DEM's grid with its georeference and nodata mask.
//
// The merge reads the members in index order and every per-cell result depends only on the
// multiset of member values (counts, sorted order statistics), so it is bitwise the same however
// and wherever the members ran (serial, MPI ranks, Slurm array tasks, in any order).
#pragma once
#include <string>
#include <vector>

#include "ensemble/EnsembleFile.hpp"
#include "io/RunConfig.hpp"

namespace talus::ensemble {

/// The linear-interpolation percentile (Hyndman and Fan 1996, type 7) of `sorted` ascending values:
/// x[floor(h)] + (h - floor(h)) (x[floor(h) + 1] - x[floor(h)]) with h = (n - 1) q / 100.
double percentile(const std::vector<float>& sorted, double q);

/// The file name part of a threshold ("0.1", "30"): %g of the value.
std::string thresholdName(double t);

/// What a merge wrote.
struct MergeReport {
  int members = 0;
  std::vector<std::string> files;  ///< paths written, in order
  std::string best;                ///< one line on the best member when calibrated, else ""
};

/// Merges the ensemble's members. Throws InputError listing the members that are not complete
/// (run `talus ensemble FILE` to finish them) and when a finished member's record differs from the
/// ensemble file.
MergeReport mergeEnsemble(const EnsembleSpec& spec, const io::RunConfig& base);

}  // namespace talus::ensemble
