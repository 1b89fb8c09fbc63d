// What the merge and the calibration read of one finished member: its maximum thickness, maximum
// speed and arrival maps, its summary.json, and the figures derived from them (affected area,
// runout, volumes).
#pragma once
#include <string>
#include <vector>

#include "core/Raster.hpp"
#include "io/RasterIO.hpp"

namespace talus::ensemble {

/// One member's maps on the DEM's grid, in single precision (the maps are Float32 files, so this
/// loses nothing). Cells outside the domain hold 0; never-reached cells hold arrival = -1.
struct MemberMaps {
  std::vector<float> hmax;     ///< htmax (two-phase: both phases) where written, else hfmax [m]
  std::vector<float> vmax;     ///< vfmax, or the larger of vfmax and vsmax in the two-phase model [m/s]
  std::vector<float> arrival;  ///< tarrival [s], -1 where the thickness never exceeded the threshold
};

/// A member's figures for the table (members.csv) and the calibration.
struct MemberFigures {
  long long member = 0;
  std::string status;            ///< summary.json "status" ("completed")
  double areaM2 = 0;             ///< cells with hmax > Affected Threshold, times the cell area [m^2]
  bool hasRunout = false;        ///< false when no release cell or no affected cell was found
  double runoutM = 0;            ///< horizontal distance from the highest release cell to the farthest affected cell [m]
  double runoutX = 0, runoutY = 0;  ///< world coordinates of that farthest affected cell
  double volumeInitialM3 = 0, volumeFinalM3 = 0;  ///< summary.json volume.initial_m3, volume.final_m3
};

/// Reads the maps of the member folder `dir` (extension by format); requires them on the DEM's grid.
/// Throws InputError naming the file when one is missing or on another grid.
MemberMaps readMemberMaps(const std::string& dir, const Raster& dem, io::RasterFormat format);

/// The figures of a member from its maps and summary.json. Release cells are those whose arrival
/// time is the start time (material there from the start); runout is measured from the highest of
/// them (the DEM's elevation; ties: the first in row-major order) to the affected cell farthest from
/// it (ties: the first in row-major order).
MemberFigures memberFigures(long long member, const std::string& dir, const MemberMaps& maps, const Raster& dem,
                            double startTime, double affectedThreshold);

}  // namespace talus::ensemble
