// A scene: everything a run needs, read from a run-file and its maps and checked before any
// device work starts (grids match the DEM, no holes or NaN inside the domain, no negative thickness).
#pragma once
#include <string>
#include <vector>

#include "core/Raster.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/FlowSolver.hpp"
#include "io/RainfallFile.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/OutputSelection.hpp"
#include "sim/ParticleScene.hpp"

namespace talus::sim {

struct Scene {
  std::string runFile;           ///< where it came from (for messages and the summary)
  Raster dem;                    ///< DEM as read: grid, georeference, nodata mask
  flow::FlowInput flow;          ///< initial fields for the flow solver
  flow::FlowSettings settings;
  ParticleScene particles;       ///< hybrid mode: structured solids as particles
  io::Rainfall rainfall;         ///< uniform rain intensity in time (empty: no rain; docs/sources.md)
  std::vector<double> infiltration;  ///< constant-rate infiltration capacity [m/s] (empty: none)
  double startTime = 0;          ///< [s]
  double endTime = 60;           ///< [s]
  double reportInterval = 10;    ///< [s]
  double restFraction = 0;       ///< end once E_kin < restFraction * peak E_kin (0: off)
  std::string precision = "float";
  /// The solvers' elevations are DEM - elevationOrigin (the lowest valid DEM cell) [m]: see flow.bed.
  double elevationOrigin = 0;
  std::string device;            ///< device selector ("" = automatic)
  std::string outputDir;         ///< absolute
  io::RasterFormat format = io::RasterFormat::GeoTiff;
  SeriesSelection series;  ///< which series maps, under which names (sim/OutputSelection.hpp)
  double checkpointInterval = 0;      ///< simulated seconds between checkpoints (0: none)
  double checkpointWallInterval = 0;  ///< wall seconds between checkpoints (0: none)
  /// What loading noticed but did not refuse (maps of processes that are off, extra raster bands,
  /// material dropped on the DEM's nodata cells), one sentence each, for the user to see.
  std::vector<std::string> warnings;
};

/// Builds the scene of a parsed run-file. Throws InputError naming the file, key or cell at fault.
Scene loadScene(const io::RunConfig& config);

/// Throws talus::InputError when the scene holds nothing that could move: no water, no solids and
/// no particles inside the DEM's domain. The message names the switches and maps that left it
/// empty (an empty run would report "completed" with all-zero maps).
void requireMaterial(const Scene& scene, const io::RunConfig& config);

}  // namespace talus::sim
