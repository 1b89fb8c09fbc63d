// Particle layers: the particles of the hybrid mode as a GeoPackage point layer (spec §8), one point
// feature per particle with one floating-point field per named attribute, in the DEM's world
// coordinates and projection. Written through GDAL's OGR API in one transaction and atomically
// (temporary file in the same folder, then rename). Callers see only talus types; GDAL stays in io.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/Grid.hpp"

namespace talus::io {

/// One per-particle attribute: the field name in the layer and one value per particle.
struct ParticleAttribute {
  std::string name;
  std::vector<double> values;
};

/// The particles to write, as a structure of arrays. x, y are in the terrain grid's frame (the frame
/// of ParticleState): x = (i + u) dx from the left edge of the raster, y = (j + v) dx counted in row
/// order from the first (usually northern) row, so y grows southwards on a north-up raster. The
/// attributes are written as given: turn vectors to world axes first (gridFrameVectorToWorld).
struct ParticleRecords {
  std::vector<double> x, y;                   ///< position in the grid frame [m]
  std::vector<ParticleAttribute> attributes;  ///< written as fields in this order

  std::size_t size() const { return x.size(); }
  /// Appends an attribute (its values must have size() entries when written).
  void add(std::string name, std::vector<double> values) {
    attributes.push_back({std::move(name), std::move(values)});
  }
  /// The values of the attribute called name, or nullptr when there is none.
  const std::vector<double>* find(const std::string& name) const {
    for (const ParticleAttribute& a : attributes)
      if (a.name == name) return &a.values;
    return nullptr;
  }
};

/// Options of writeParticleLayer.
struct ParticleLayerOptions {
  std::string layerName = "particles";  ///< the layer (table) name
  /// Build the GeoPackage R-tree index. It speeds up drawing zoomed-in views of large layers but
  /// costs about 11-15 us a particle on top of the 2.5-3 us of the features (SQLite's R-tree inserts),
  /// so it is off by default; `SELECT CreateSpatialIndex('particles', 'geom')` adds it later.
  bool spatialIndex = false;
};

/// Writes records as the point layer options.layerName of a new GeoPackage at path (an existing file is
/// replaced). The world position of a particle is the grid's geotransform applied to its fractional
/// pixel coordinates (x / dx, y / dx), so rotation terms and the (negative) pixel height are
/// honoured; the layer's spatial reference is grid.projectionWkt (the GeoPackage's "Undefined
/// Cartesian SRS", srs_id -1, when it is empty). Every
/// attribute becomes a Real (double) field; NaN values are written as NULL, infinities as they are.
/// A particle with a non-finite position keeps its feature (its attributes stay aligned by FID) with
/// no geometry. Feature FIDs are 1..n in the order of the records. All features go in one
/// transaction; the file is written first to "<stem>.tmp-<pid>.gpkg" in the same folder, then
/// renamed over path. Throws std::invalid_argument when the arrays' sizes differ or an attribute name
/// is empty or repeated (case-insensitively, as SQLite compares column names), and talus::InputError
/// naming path when the folder does not exist or is not writable, the projection is not valid WKT,
/// or GDAL fails; the temporary file is removed on failure.
void writeParticleLayer(const std::string& path, const Grid& grid, const ParticleRecords& records,
                        const ParticleLayerOptions& options = {});

/// A point layer as read back by readParticleLayer.
struct ParticleLayer {
  std::string layerName;
  std::vector<double> worldX, worldY;         ///< point coordinates (NaN for a feature with no point)
  std::vector<ParticleAttribute> attributes;  ///< numeric fields in layer order; NULL reads as NaN
  std::string projectionWkt;                  ///< the layer's spatial reference (empty when none)
  int epsg = 0;                               ///< its EPSG code, 0 when it has none
  bool spatialIndex = false;                  ///< the layer has a spatial index
  std::size_t size() const { return worldX.size(); }
  const std::vector<double>* find(const std::string& name) const {
    for (const ParticleAttribute& a : attributes)
      if (a.name == name) return &a.values;
    return nullptr;
  }
};

/// Reads the first layer of a vector file GDAL opens (mainly for tests and tools): features in FID
/// order, point coordinates in world units, integer and real fields as doubles; the GeoPackage's
/// undefined systems (srs_id -1 and 0) read as an empty projection. Throws
/// talus::InputError naming path when the file is missing, not a vector file, or has no layer.
ParticleLayer readParticleLayer(const std::string& path);

/// True when two WKT strings describe the same coordinate reference system (GDAL's IsSame); two
/// empty strings are the same, an empty and a non-empty one are not.
bool sameSpatialReference(const std::string& wktA, const std::string& wktB);

/// World coordinates of a point in the grid frame (x, y as in ParticleRecords): the geotransform
/// applied to the pixel coordinates (x / dx, y / dx). Written as x * (gt[1] / dx) so that a north-up
/// grid maps exactly: (gt[0] + x, gt[3] - y).
inline std::pair<double, double> gridFrameToWorld(const Grid& grid, double x, double y) {
  const auto& gt = grid.geoTransform;
  const double d = grid.dx;
  return {gt[0] + x * (gt[1] / d) + y * (gt[2] / d), gt[3] + x * (gt[4] / d) + y * (gt[5] / d)};
}

/// A vector (velocity, force) given along the grid frame's axes (x along columns, y along rows, so
/// southwards on a north-up grid) turned to world axes (east, north): the linear part of the
/// geotransform over dx. On a north-up grid (vx, vy) becomes (vx, -vy).
inline std::pair<double, double> gridFrameVectorToWorld(const Grid& grid, double vx, double vy) {
  const auto& gt = grid.geoTransform;
  const double d = grid.dx;
  return {vx * (gt[1] / d) + vy * (gt[2] / d), vx * (gt[4] / d) + vy * (gt[5] / d)};
}

}  // namespace talus::io
