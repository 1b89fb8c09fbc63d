// Particle layers through GDAL's OGR API: a GeoPackage point layer with one Real field per particle
// attribute, filled inside one SQLite transaction (one commit for the whole layer is what makes a
// million points take seconds rather than minutes), written to a temporary file next to the target
// and renamed over it once GDAL has closed it, and a reader for tests and tools.
#include "io/ParticleLayerIO.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>

#include "io/GdalErrors.hpp"
#include "core/Error.hpp"

namespace fs = std::filesystem;

namespace talus::io {
namespace {

/// The local system GDAL's GPKG driver stores as srs_id -1, "Undefined Cartesian SRS".
constexpr const char* kUndefinedCartesianWkt = "LOCAL_CS[\"Undefined cartesian SRS\",UNIT[\"metre\",1]]";

/// True for the GeoPackage's two placeholder systems (srs_id -1 and 0), which mean "no projection".
bool isUndefinedSystem(const OGRSpatialReference& srs) {
  const char* name = srs.GetName();
  return name != nullptr && (EQUAL(name, "Undefined cartesian SRS") || EQUAL(name, "Undefined geographic SRS"));
}

void removeIfPresent(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

/// SQLite's side files of an open database (removed with the temporary file after a failure).
void removeWithSideFiles(const std::string& path) {
  removeIfPresent(path);
  for (const char* suffix : {"-journal", "-wal", "-shm"}) removeIfPresent(path + suffix);
}

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// Programming errors in the records (not user input): sizes and field names.
void checkRecords(const std::string& path, const ParticleRecords& records, const std::string& layerName) {
  const std::size_t n = records.x.size();
  const std::string where = "writeParticleLayer('" + path + "'): ";
  if (layerName.empty()) throw std::invalid_argument(where + "empty layer name");
  if (records.y.size() != n)
    throw std::invalid_argument(where + std::to_string(n) + " x but " + std::to_string(records.y.size()) + " y values");
  std::set<std::string> seen;
  for (const ParticleAttribute& a : records.attributes) {
    if (a.name.empty()) throw std::invalid_argument(where + "an attribute has an empty name");
    if (!seen.insert(lowerCase(a.name)).second)
      throw std::invalid_argument(where + "attribute '" + a.name + "' appears twice");
    if (a.values.size() != n)
      throw std::invalid_argument(where + "attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                                  " values for " + std::to_string(n) + " particles");
  }
}

/// The temporary file for path: "<folder>/<stem>.tmp-<pid>.gpkg". It keeps the .gpkg extension the
/// driver expects, and its ".tmp-" marks it for the clean-up of `talus run --resume`.
std::string temporaryPathFor(const std::string& path) {
  const fs::path p(path);
  const std::string name = p.stem().string() + ".tmp-" + std::to_string(detail::processId()) + ".gpkg";
  return (p.parent_path() / name).string();
}

/// Creates the GeoPackage tmpPath holding the layer and closes it. Errors name the final path.
void writeGeoPackage(const std::string& tmpPath, const std::string& path, const Grid& grid,
                     const ParticleRecords& records, const ParticleLayerOptions& options, const detail::GdalErrorScope& errors) {
  const std::string& layerName = options.layerName;
  const std::string what = "cannot write particle layer '" + path + "': ";
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (driver == nullptr) throw InputError(what + "GDAL has no GPKG driver");

  // A grid without projection gets the GeoPackage's "undefined Cartesian" system (srs_id -1), which
  // GDAL picks for a local system of that name; with no SRS at all it would record an undefined
  // geographic one (srs_id 0), wrong for coordinates in metres.
  OGRSpatialReference srs;
  const std::string wkt = grid.projectionWkt.empty() ? std::string(kUndefinedCartesianWkt) : grid.projectionWkt;
  if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) throw InputError(what + "the grid's projection is not valid WKT");
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = easting, y = northing

  GDALDatasetUniquePtr ds(driver->Create(tmpPath.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) throw IoError(what + errors.describe("GDAL could not create the GeoPackage"));

  CPLStringList layerOptions;
  layerOptions.SetNameValue("FID", "fid");
  layerOptions.SetNameValue("GEOMETRY_NAME", "geom");
  layerOptions.SetNameValue("SPATIAL_INDEX", options.spatialIndex ? "YES" : "NO");
  OGRLayer* layer = ds->CreateLayer(layerName.c_str(), &srs, wkbPoint, layerOptions.List());
  if (layer == nullptr) throw IoError(what + errors.describe("GDAL could not create the layer"));
  for (const ParticleAttribute& a : records.attributes) {
    OGRFieldDefn field(a.name.c_str(), OFTReal);
    if (layer->CreateField(&field) != OGRERR_NONE)
      throw InputError(what + "cannot create field '" + a.name + "': " + errors.describe("GDAL CreateField failed"));
  }

  // Field indices in the layer, looked up once (the driver may not keep our order for every name).
  const OGRFeatureDefn* defn = layer->GetLayerDefn();
  std::vector<int> fieldIndex;
  for (const ParticleAttribute& a : records.attributes) {
    const int index = defn->GetFieldIndex(a.name.c_str());
    if (index < 0) throw InputError(what + "field '" + a.name + "' is missing after creation");
    fieldIndex.push_back(index);
  }

  if (ds->StartTransaction() != OGRERR_NONE)
    throw IoError(what + errors.describe("GDAL could not start a transaction"));
  OGRFeature feature(layer->GetLayerDefn());
  OGRPoint point;
  const std::size_t n = records.size();
  for (std::size_t k = 0; k < n; ++k) {
    feature.SetFID(OGRNullFID);  // let the layer number the features 1..n
    const auto world = gridFrameToWorld(grid, records.x[k], records.y[k]);
    if (std::isfinite(world.first) && std::isfinite(world.second)) {
      point.setX(world.first);
      point.setY(world.second);
      feature.SetGeometry(&point);  // copies
    } else {
      feature.SetGeometry(nullptr);
    }
    for (std::size_t a = 0; a < fieldIndex.size(); ++a) {
      const double v = records.attributes[a].values[k];
      if (std::isnan(v))
        feature.SetFieldNull(fieldIndex[a]);
      else
        feature.SetField(fieldIndex[a], v);
    }
    if (layer->CreateFeature(&feature) != OGRERR_NONE) {
      ds->RollbackTransaction();
      throw IoError(what + "cannot write particle " + std::to_string(k) + ": " +
                       errors.describe("GDAL CreateFeature failed"));
    }
  }
  if (ds->CommitTransaction() != OGRERR_NONE)
    throw IoError(what + errors.describe("GDAL could not commit the transaction"));
  ds.reset();  // GDALClose: finishes the GeoPackage metadata and closes the database
  if (errors.failed()) throw IoError(what + errors.describe("GDAL write failed"));
}

}  // namespace

void writeParticleLayer(const std::string& path, const Grid& grid, const ParticleRecords& records,
                        const ParticleLayerOptions& options) {
  checkRecords(path, records, options.layerName);
  detail::ensureGdalRegistered();
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw InputError("cannot write particle layer '" + path + "': folder '" + folder.string() +
                     "' does not exist or is not a folder");
  if (fs::is_directory(path, ec))
    throw InputError("cannot write particle layer '" + path + "': a folder of that name exists");

  const std::string tmpPath = temporaryPathFor(path);
  removeWithSideFiles(tmpPath);  // left over by a killed process with our pid: GPKG Create refuses to overwrite
  detail::GdalErrorScope errors;
  try {
    writeGeoPackage(tmpPath, path, grid, records, options, errors);
    fs::rename(tmpPath, path, ec);
    if (ec) throw IoError("cannot move '" + tmpPath + "' to '" + path + "': " + ec.message());
  } catch (...) {
    removeWithSideFiles(tmpPath);
    throw;
  }
}

ParticleLayer readParticleLayer(const std::string& path) {
  detail::ensureGdalRegistered();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError("particle layer file '" + path + "' does not exist");
  detail::GdalErrorScope errors;
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds)
    throw InputError("cannot open particle layer '" + path + "': " +
                     errors.describe("not a vector format GDAL recognises"));
  if (ds->GetLayerCount() < 1) throw InputError("file '" + path + "' holds no layer");
  OGRLayer* layer = ds->GetLayer(0);

  ParticleLayer out;
  out.layerName = layer->GetName();
  out.spatialIndex = layer->TestCapability(OLCFastSpatialFilter) != 0;
  const OGRSpatialReference* srs = layer->GetSpatialRef();
  if (srs != nullptr && !isUndefinedSystem(*srs)) {
    char* wkt = nullptr;
    if (srs->exportToWkt(&wkt) == OGRERR_NONE && wkt != nullptr) out.projectionWkt = wkt;
    CPLFree(wkt);
    const char* authority = srs->GetAuthorityName(nullptr);
    const char* code = srs->GetAuthorityCode(nullptr);
    if (authority != nullptr && code != nullptr && EQUAL(authority, "EPSG")) out.epsg = std::atoi(code);
  }

  const OGRFeatureDefn* defn = layer->GetLayerDefn();
  std::vector<int> numeric;  // indices of the fields read
  for (int f = 0; f < defn->GetFieldCount(); ++f) {
    const OGRFieldType type = defn->GetFieldDefn(f)->GetType();
    if (type == OFTReal || type == OFTInteger || type == OFTInteger64) {
      numeric.push_back(f);
      out.attributes.push_back({defn->GetFieldDefn(f)->GetNameRef(), {}});
    }
  }
  const GIntBig count = layer->GetFeatureCount();
  if (count > 0) {
    out.worldX.reserve(static_cast<std::size_t>(count));
    out.worldY.reserve(static_cast<std::size_t>(count));
    for (ParticleAttribute& a : out.attributes) a.values.reserve(static_cast<std::size_t>(count));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  layer->ResetReading();
  for (auto& feature : *layer) {
    const OGRGeometry* g = feature->GetGeometryRef();
    const OGRPoint* p = (g != nullptr && wkbFlatten(g->getGeometryType()) == wkbPoint && !g->IsEmpty())
                            ? g->toPoint()
                            : nullptr;
    out.worldX.push_back(p != nullptr ? p->getX() : nan);
    out.worldY.push_back(p != nullptr ? p->getY() : nan);
    for (std::size_t a = 0; a < numeric.size(); ++a)
      out.attributes[a].values.push_back(feature->IsFieldSetAndNotNull(numeric[a])
                                             ? feature->GetFieldAsDouble(numeric[a])
                                             : nan);
  }
  if (errors.failed())
    throw InputError("cannot read particle layer '" + path + "': " + errors.describe("GDAL read error"));
  return out;
}

bool sameSpatialReference(const std::string& wktA, const std::string& wktB) {
  if (wktA.empty() || wktB.empty()) return wktA.empty() && wktB.empty();
  detail::ensureGdalRegistered();
  detail::GdalErrorScope errors;
  OGRSpatialReference a, b;
  if (a.importFromWkt(wktA.c_str()) != OGRERR_NONE || b.importFromWkt(wktB.c_str()) != OGRERR_NONE) return false;
  return a.IsSame(&b) != 0;
}

}  // namespace talus::io
