// Scenes with a known answer for the ensemble tests (tests/unit/test_ensemble_*.cpp), written into a
// test's folder as GeoTIFFs, a base run-file and an ensemble file.
#pragma once
#include <filesystem>
#include <string>

namespace talus::test {

/// Flat ground (12 x 10 cells of 1 m), walls, and a uniform initial water height that is the
/// ensemble's parameter: a lake at rest, so hfmax = the parameter exactly and arrival = 0 in
/// every cell. Writes dem.tif, lake.run and lake.ens (members, seed and the [Parameters] line
/// `parameter` given, e.g. "Initial Fluid Height=list 0.05 0.15"; `extra` appended); returns the
/// ensemble file's path. End Time is 0.0001 min (a few steps).
std::string writeLakeEnsemble(const std::filesystem::path& dir, const std::string& parameter, int members,
                              const std::string& extra = "", const std::string& name = "lake.ens");

/// Geometry of the wedge scene below.
constexpr int kWedgeNx = 20, kWedgeNy = 6;
constexpr double kWedgeDx = 2.0, kWedgeX0 = 1000.0, kWedgeY0 = 5000.0;

/// A bed sloping down in +x (DEM 10 - 0.05 i), water thickness 0.01 (nx - i) m scaled by the
/// parameter s ("Initial Fluid Height=scale list 1 2 3 4"), 0.0001 min simulated. With Affected
/// Threshold 0.105 m a member with scale s affects the columns i with (nx - i) s > 10.5. The
/// observed map marks the columns i <= 16 (member s = 3's area) and the observed runout point is
/// the centre of cell (16, ny - 1). Writes dem.tif, wedge.tif, observed.tif, wedge.run, wedge.ens.
std::string writeWedgeEnsemble(const std::filesystem::path& dir);

}  // namespace talus::test
