// Rendering of an output map (hmax, hsfinal, cfracfinal, ...) to a PNG picture for reports: the
// map's values through a colour ramp, drawn over a hillshade of the DEM, with a legend bar, its
// range and a label below. Written through GDAL (an in-memory dataset copied with the PNG driver),
// so the engine needs no image or GUI library. `talus render` (src/cli/main.cpp) calls
// renderCommand; tests call renderMap and the helpers directly.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/Raster.hpp"

namespace talus::io {

/// An 8-bit colour.
struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
};

/// The colour ramps: depth (pale to deep blue, for thicknesses), heat (yellow to dark red, for
/// speeds and pressures), viridis (an approximation of matplotlib's, for times), cohesion (red at
/// 0 = fractured, through yellow, to green at 1 = intact).
enum class Ramp { Depth, Heat, Viridis, Cohesion };

/// The ramp of a name ("depth", "heat", "viridis", "cohesion"); throws InputError listing the names.
Ramp parseRamp(const std::string& name);

/// The colour of the ramp at t in [0, 1] (t is clamped; NaN gives the colour at 0). Piecewise
/// linear between the ramp's control colours, rounded to the nearest integer.
Rgb rampColour(Ramp ramp, double t);

/// Grey levels (0..255) of a hillshade of the DEM: sun from the north-west (azimuth 315 deg) at
/// 45 deg, Horn's gradient, mapped to 70 + 170 * cos(angle to the sun) so dark slopes stay
/// readable; flat ground gives 70 + 170 sin 45 deg = 190. A missing neighbour (nodata or off the
/// raster) takes the cell's own elevation; a nodata cell itself gets 255 (white).
std::vector<std::uint8_t> hillshade(const Raster& dem);

/// Options of renderMap (see `talus render --help`).
struct RenderOptions {
  std::string hillshadeDem;   ///< DEM to shade under the map ("" = flat grey background)
  Ramp ramp = Ramp::Depth;
  bool fixedRange = false;    ///< use [lo, hi] instead of the range of the shown cells
  double lo = 0.0, hi = 1.0;
  double threshold = 0.0;     ///< cells with value <= threshold (or nodata) show only the background
  std::string label;          ///< text of the legend ("" = the map's file name)
  int scale = 0;              ///< pixels per cell (0 = automatic: the map about 800 pixels wide or tall)
};

/// Where renderMap put things in the picture (pixels; x to the right, y down).
struct RenderLayout {
  int width = 0, height = 0;  ///< size of the picture
  int scale = 1;              ///< pixels per cell: cell (i, j) covers x in [mapX + i s, mapX + (i+1) s)
  int mapX = 0, mapY = 0;     ///< top-left corner of the map
  double lo = 0.0, hi = 1.0;  ///< the value range of the ramp
  int shownCells = 0;         ///< cells drawn in ramp colours
};

/// Renders the raster at `rasterPath` to the PNG file `pngPath`. A shown cell (valid, value >
/// threshold) gets rampColour(ramp, (v - lo) / (hi - lo)); other cells get the grey hillshade of
/// the DEM (or a flat grey 210 without one). Throws InputError naming the file on unreadable
/// rasters, a DEM on another grid than the map, an empty range or a PNG that cannot be written.
RenderLayout renderMap(const std::string& rasterPath, const std::string& pngPath, const RenderOptions& options);

/// `talus render` with its arguments (after the word "render"): parses them, renders, prints
/// one line about the picture. Returns the exit status (0 on success); throws InputError on bad
/// options or input.
int renderCommand(const std::vector<std::string>& args);

}  // namespace talus::io
