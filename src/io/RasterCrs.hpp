// Internal to src/io: what a raster's coordinate reference system says about the units of its
// cells and values. Talus computes in metres, so a grid in degrees or feet must be refused (or, on
// request, converted) before its cell size reaches the solver.
#pragma once
#include <string>

namespace talus::io::detail {

/// The units of a raster's CRS as far as Talus cares.
struct CrsUnits {
  bool none = false;          ///< no CRS at all (taken as metres)
  bool geographic = false;    ///< angular coordinates (degrees): no cell size in metres
  std::string description;    ///< "NAD83 / California zone 5 (ftUS), EPSG:2229"
  std::string horizontalUnit = "metre";
  double horizontalToMetre = 1;  ///< metres per horizontal unit
  std::string verticalUnit = "metre";  ///< of a compound CRS's vertical part, else the horizontal unit
  double verticalToMetre = 1;
  bool metric() const { return horizontalToMetre == 1 && verticalToMetre == 1; }
};

/// Reads the CRS of a WKT string (empty: none). A WKT GDAL cannot parse counts as none.
CrsUnits inspectCrs(const std::string& wkt);

}  // namespace talus::io::detail
