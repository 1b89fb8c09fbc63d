// Raster file input/output: reading maps (GeoTIFF, PCRaster, ESRI ASCII, anything GDAL opens) into
// talus::Raster, checking that maps share a grid, and writing maps atomically. This module is the
// only part of the engine that includes GDAL; callers see only talus types.
#pragma once
#include <string>
#include <vector>

#include "core/Raster.hpp"

namespace talus::io {

/// How readRaster treats a raster whose CRS is projected in a unit other than the metre.
struct RasterReadOptions {
  /// Convert instead of refusing: the cell size becomes metres (the georeference and CRS stay as
  /// the file has them, so outputs overlay the inputs).
  bool convertLinearUnits = false;
  /// With convertLinearUnits: the values are lengths (elevations, thicknesses) and are converted
  /// too, by the vertical unit of a compound CRS, else by the horizontal one.
  bool valuesAreLengths = false;
};

/// Reads band 1 of a GeoTIFF, PCRaster .map or ESRI ASCII grid (anything GDAL opens). Nodata cells
/// (and NaN/Inf values) become invalid in Raster::valid; Raster::nodata takes the file's nodata value
/// when it has one. The band's scale and offset (GDAL metadata) are applied: value = raw * scale +
/// offset. Throws talus::InputError naming the file on: a missing or unreadable file, a file
/// that is not a raster, a missing georeference, zero, negative or non-square cells (naming both
/// sizes), a rotated or south-up geotransform, a geographic CRS (degrees) or a projected one in
/// another unit than the metre (unless options convert it), more than 2^31 cells or more than the
/// memory available (naming both), a token of an ESRI ASCII grid that is not a number, and
/// truncated or corrupt data (GDAL read error). A raster without a CRS is taken to be in metres.
/// Files with several bands use band 1, with a warning appended to warnings (when given).
Raster readRaster(const std::string& path, const RasterReadOptions& options = {},
                  std::vector<std::string>* warnings = nullptr);

/// Throws talus::InputError "map 'B' (path) does not share the grid of 'A' (path): 100x80 cells of
/// 5 m at (x0, y0) vs ..." when sameGrid(reference.grid, other.grid) is false; the map names are the
/// file names without folder and extension.
void requireSameGrid(const Raster& reference, const std::string& referencePath, const Raster& other,
                     const std::string& otherPath);

/// Output file formats of writeRaster.
enum class RasterFormat { GeoTiff, PCRaster };

/// Writes r atomically: first to "<path>.tmp-<pid>" in the same folder, then renames it over path
/// (a GDAL .aux.xml side-car, if one is written, is moved along; a stale one is removed). Invalid
/// cells get r.nodata, which is also recorded as the file's nodata value; georeference and
/// projection come from r.grid. GeoTIFF: Float32 (Float64 when asFloat64), deflate-compressed and
/// tiled. PCRaster: VS_SCALAR REAL4 (asFloat64 is ignored; the projection goes to a side-car).
/// Throws talus::InputError naming the path if the folder does not exist or is not writable, or
/// GDAL fails; the temporary file is removed on failure.
void writeRaster(const std::string& path, const Raster& r, RasterFormat format = RasterFormat::GeoTiff,
                 bool asFloat64 = false);

/// The format for an output path by its (case-insensitive) extension: ".map" -> PCRaster, anything
/// else -> GeoTIFF.
RasterFormat formatForPath(const std::string& path);

}  // namespace talus::io
