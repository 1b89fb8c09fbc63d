// Raster file input/output through GDAL: reading band 1 of any GDAL raster into talus::Raster with
// validation of the georeference, grid comparison with readable errors, and atomic writing of
// GeoTIFF (deflate, tiled) and PCRaster maps. The only translation unit of the engine using GDAL.
#include "io/RasterIO.hpp"

#include <gdal_priv.h>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <new>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "core/Error.hpp"
#include "core/Memory.hpp"
#include "io/AsciiGridScan.hpp"
#include "io/GdalErrors.hpp"
#include "io/RasterCrs.hpp"

namespace fs = std::filesystem;

namespace talus::io {
namespace {

/// Largest raster readRaster accepts: 2^31 cells (about 19 GB as values plus mask).
constexpr unsigned long long kMaxCells = 1ull << 31;

using detail::ensureGdalRegistered;
using detail::GdalErrorScope;

bool isVirtualPath(const std::string& path) { return path.rfind("/vsi", 0) == 0; }

/// Grid description for error messages: "100x80 cells of 5 m at (x0, y0)".
std::string describeGrid(const Grid& g) {
  std::ostringstream s;
  s.precision(12);
  s << g.nx << "x" << g.ny << " cells of " << g.dx << " m at (" << g.geoTransform[0] << ", "
    << g.geoTransform[3] << ")";
  return s.str();
}

std::string mapName(const std::string& path) { return fs::path(path).stem().string(); }

/// Removes a file if it is there, ignoring errors (used for clean-up on failure).
void removeQuietly(const std::string& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

/// The cell values to write: r.values with r.nodata in the invalid cells.
std::vector<double> valuesForWriting(const Raster& r) {
  std::vector<double> out(r.values);
  if (!r.valid.empty()) {
    for (std::size_t k = 0; k < out.size(); ++k) {
      if (r.valid[k] == 0) out[k] = r.nodata;
    }
  }
  return out;
}

/// Fills band 1 of ds with the values of r and sets georeference, projection and nodata.
void fillDataset(GDALDataset& ds, const Raster& r, const std::string& path) {
  std::vector<double> data = valuesForWriting(r);
  GDALRasterBand* band = ds.GetRasterBand(1);
  if (band->RasterIO(GF_Write, 0, 0, r.grid.nx, r.grid.ny, data.data(), r.grid.nx, r.grid.ny,
                     GDT_Float64, 0, 0, nullptr) != CE_None) {
    throw IoError("cannot write raster '" + path + "': " + CPLGetLastErrorMsg());
  }
  std::array<double, 6> gt = r.grid.geoTransform;
  if (ds.SetGeoTransform(gt.data()) != CE_None) {
    throw IoError("cannot set the georeference of '" + path + "': " + CPLGetLastErrorMsg());
  }
  if (!r.grid.projectionWkt.empty() && ds.SetProjection(r.grid.projectionWkt.c_str()) != CE_None) {
    throw IoError("cannot set the projection of '" + path + "': " + CPLGetLastErrorMsg());
  }
  if (band->SetNoDataValue(r.nodata) != CE_None) {
    throw IoError("cannot set the nodata value of '" + path + "': " + CPLGetLastErrorMsg());
  }
}

GDALDriver* driverOrThrow(const char* name, const std::string& path) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(name);
  if (driver == nullptr) {
    throw InputError(std::string("cannot write raster '") + path + "': GDAL has no " + name + " driver");
  }
  return driver;
}

/// Writes the GeoTIFF or PCRaster file tmpPath (GDAL closes it before returning).
void writeWithGdal(const std::string& tmpPath, const std::string& path, const Raster& r,
                   RasterFormat format, bool asFloat64, const GdalErrorScope& errors) {
  const Grid& g = r.grid;
  if (format == RasterFormat::GeoTiff) {
    GDALDriver* gtiff = driverOrThrow("GTiff", path);
    CPLStringList options;
    options.SetNameValue("COMPRESS", "DEFLATE");
    options.SetNameValue("TILED", "YES");
    options.SetNameValue("BIGTIFF", "IF_SAFER");
    GDALDatasetUniquePtr ds(gtiff->Create(tmpPath.c_str(), g.nx, g.ny, 1,
                                          asFloat64 ? GDT_Float64 : GDT_Float32, options.List()));
    if (!ds) {
      throw IoError("cannot create raster '" + path + "': " + errors.describe("GDAL Create failed"));
    }
    fillDataset(*ds, r, path);
    ds.reset();  // GDALClose: flushes and compresses the last tiles
  } else {
    // The PCRaster driver only supports CreateCopy: build the map in memory first.
    GDALDriver* mem = driverOrThrow("MEM", path);
    GDALDriver* pcraster = driverOrThrow("PCRaster", path);
    GDALDatasetUniquePtr src(mem->Create("", g.nx, g.ny, 1, GDT_Float32, nullptr));
    if (!src) {
      throw IoError("cannot build raster '" + path + "' in memory: " +
                       errors.describe("GDAL MEM Create failed"));
    }
    fillDataset(*src, r, path);
    CPLStringList options;
    options.SetNameValue("PCRASTER_VALUESCALE", "VS_SCALAR");
    GDALDatasetUniquePtr ds(
        pcraster->CreateCopy(tmpPath.c_str(), src.get(), FALSE, options.List(), nullptr, nullptr));
    if (!ds) {
      throw IoError("cannot create raster '" + path + "': " +
                       errors.describe("GDAL PCRaster CreateCopy failed"));
    }
    ds.reset();
  }
  if (errors.failed()) {
    throw IoError("cannot write raster '" + path + "': " + errors.describe("GDAL write failed"));
  }
}

/// Metres per horizontal unit of the raster's CRS. Throws for a geographic CRS (its cells are
/// degrees, not lengths) and for a projected one in another unit unless the options convert it.
double horizontalUnitToMetre(const std::string& path, const char* wkt, const RasterReadOptions& options) {
  const detail::CrsUnits crs = detail::inspectCrs(wkt != nullptr ? wkt : "");
  if (crs.none) return 1.0;  // no CRS: taken as metres (docs/runfile.md)
  if (crs.geographic)
    throw InputError("raster '" + path + "' is in a geographic CRS (" + crs.description + ", unit " +
                     crs.horizontalUnit + "): its cells are angles, not lengths; reproject it to a projected "
                     "CRS in metres (e.g. gdalwarp -t_srs EPSG:<UTM zone>)");
  if (crs.metric()) return 1.0;
  if (!options.convertLinearUnits) {
    std::ostringstream s;
    s.precision(10);
    s << "raster '" << path << "' is in " << crs.description << " with horizontal unit " << crs.horizontalUnit
      << " (" << crs.horizontalToMetre << " m) and vertical unit " << crs.verticalUnit << " ("
      << crs.verticalToMetre << " m); Talus computes in metres: reproject it, or set 'Convert Raster Units=1' "
      << "to convert cell sizes and elevations/thicknesses to metres";
    throw InputError(s.str());
  }
  return crs.horizontalToMetre;
}

/// Metres per unit of the values (elevations): the vertical unit of the CRS (1 unless converting).
double verticalUnitToMetre(const char* wkt, const RasterReadOptions& options) {
  if (!options.convertLinearUnits) return 1.0;
  const detail::CrsUnits crs = detail::inspectCrs(wkt != nullptr ? wkt : "");
  return crs.none || crs.geographic ? 1.0 : crs.verticalToMetre;
}

/// Refuses a raster whose values and mask would not fit into the memory this process can still
/// take, before anything is allocated (a small sparse file can declare billions of cells).
void requireMemoryFor(const std::string& path, int nx, int ny) {
  const double cells = static_cast<double>(nx) * static_cast<double>(ny);
  const double need = cells * (sizeof(double) + sizeof(uint8_t));
  const double available = static_cast<double>(availableMemoryBytes());
  if (available > 0 && need > available)
    throw InputError("raster '" + path + "' declares " + std::to_string(nx) + "x" + std::to_string(ny) + " cells (" +
                     std::to_string(static_cast<unsigned long long>(cells)) + "), which need " + formatBytes(need) +
                     " to load, but only " + formatBytes(available) + " of memory is available");
}

/// Applies GDAL's band scale and offset (e.g. an Int16 DEM in decimetres with scale 0.1) to the
/// valid cells. Nodata has been matched against the raw values before, as the file stores them.
void applyScaleAndOffset(GDALRasterBand& band, Raster& r) {
  int hasScale = 0, hasOffset = 0;
  const double scale = band.GetScale(&hasScale), offset = band.GetOffset(&hasOffset);
  const double a = hasScale != 0 ? scale : 1.0, b = hasOffset != 0 ? offset : 0.0;
  if (a == 1.0 && b == 0.0) return;
  for (std::size_t k = 0; k < r.values.size(); ++k)
    if (r.valid[k] != 0) r.values[k] = r.values[k] * a + b;
}

}  // namespace

Raster readRaster(const std::string& path, const RasterReadOptions& options, std::vector<std::string>* warnings) {
  ensureGdalRegistered();
  if (!isVirtualPath(path)) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError("raster file '" + path + "' does not exist");
  }
  GdalErrorScope errors;
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) {
    throw InputError("cannot open raster '" + path +
                     "': " + errors.describe("not a raster format GDAL recognises"));
  }
  if (ds->GetRasterCount() < 1) throw InputError("file '" + path + "' holds no raster band");

  const int nx = ds->GetRasterXSize();
  const int ny = ds->GetRasterYSize();
  if (nx <= 0 || ny <= 0) throw InputError("raster '" + path + "' has no cells");
  const unsigned long long cells = static_cast<unsigned long long>(nx) * static_cast<unsigned long long>(ny);
  if (cells > kMaxCells) {
    throw InputError("raster '" + path + "' is too large: " + std::to_string(nx) + "x" +
                     std::to_string(ny) + " cells (at most " + std::to_string(kMaxCells) + ")");
  }

  std::array<double, 6> gt{};
  if (ds->GetGeoTransform(gt.data()) != CE_None) {
    throw InputError("raster '" + path + "' has no georeference (geotransform), so no cell size");
  }
  if (gt[2] != 0.0 || gt[4] != 0.0) {
    throw InputError("raster '" + path + "' has a rotated geotransform, which is not supported");
  }
  const double nativeWidth = gt[1];
  const double height = -gt[5];  // north-up rasters have a negative pixel height
  if (!std::isfinite(nativeWidth) || !std::isfinite(height) || nativeWidth <= 0.0 || height == 0.0) {
    std::ostringstream s;
    s << "raster '" << path << "' has a zero or negative cell size (width " << nativeWidth + 0.0
      << " m, height " << height + 0.0 << " m)";
    throw InputError(s.str());
  }
  if (height < 0.0) {
    throw InputError("raster '" + path + "' is south-up (positive pixel height), which is not supported");
  }
  const double toMetre = horizontalUnitToMetre(path, ds->GetProjectionRef(), options);
  const double width = nativeWidth * toMetre;
  // Cells from a millimetre to a thousand kilometres: outside that the cell area under- or
  // overflows, or the grid is surely a unit mistake (degrees for metres, say).
  if (width < 1e-3 || width > 1e6) {
    std::ostringstream s;
    s << "raster '" << path << "' has a cell size of " << width << " m, outside [0.001, 1e6] m "
      << "(a projected grid in metres is needed)";
    throw InputError(s.str());
  }
  if (std::fabs(nativeWidth - height) > 1e-7 * std::max(nativeWidth, height)) {
    std::ostringstream s;
    s.precision(12);
    s << "raster '" << path << "' has non-square cells (" << nativeWidth << " m wide, " << height
      << " m high); resample it to square cells";
    throw InputError(s.str());
  }

  Raster r;
  r.grid.nx = nx;
  r.grid.ny = ny;
  r.grid.dx = width;
  r.grid.geoTransform = gt;
  const char* wkt = ds->GetProjectionRef();
  r.grid.projectionWkt = wkt != nullptr ? wkt : "";
  if (ds->GetRasterCount() > 1 && warnings != nullptr)
    warnings->push_back("raster '" + path + "' has " + std::to_string(ds->GetRasterCount()) +
                        " bands; only band 1 is read");
  GDALRasterBand* band = ds->GetRasterBand(1);
  {
    // Check that the data can exist before allocating the grid: a short file whose header claims a
    // huge grid then fails here instead of after gigabytes were allocated and zero-filled. ASCII
    // grids need at least two bytes a cell; other formats (random access) must yield their last row.
    // A crafted header can declare blocks (strips, tiles) far larger than the raster, which GDAL
    // would allocate whole on the first read (seen by the fuzzer: 4 GB for a 5-column file). A
    // pixel-interleaved block holds every band's values, so its bytes count all bands (seen by the
    // fuzzer: a 65282x2 strip of 3584 Float64 bands, 3.7 GB, in a 436-byte file). Allowed: four
    // times the raster's own Float64 values, and at least 32 MiB.
    int bx = 0, by = 0;
    band->GetBlockSize(&bx, &by);
    const unsigned long long blockCells = static_cast<unsigned long long>(std::max(bx, 0)) *
                                          static_cast<unsigned long long>(std::max(by, 0));
    const char* interleave = ds->GetMetadataItem("INTERLEAVE", "IMAGE_STRUCTURE");
    const unsigned long long samples =
        interleave && std::string(interleave) == "PIXEL" ? static_cast<unsigned long long>(std::max(ds->GetRasterCount(), 1)) : 1ull;
    const unsigned long long blockBytes =
        blockCells * samples * static_cast<unsigned long long>(std::max(GDALGetDataTypeSizeBytes(band->GetRasterDataType()), 1));
    if (blockBytes > std::max<unsigned long long>(4ull * cells, 1ull << 22) * sizeof(double))
      throw InputError("raster '" + path + "' declares blocks of " + std::to_string(bx) + "x" + std::to_string(by) +
                       " cells" + (samples > 1 ? " of " + std::to_string(samples) + " interleaved bands" : std::string()) +
                       " (" + formatBytes(static_cast<double>(blockBytes)) + " each) for a " + std::to_string(nx) + "x" +
                       std::to_string(ny) + " raster (corrupt header?)");
    const std::string driver = ds->GetDriver() ? ds->GetDriver()->GetDescription() : "";
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(path, ec);
    // A TIFF may declare strips or tiles of more bytes than the file holds; libtiff allocates the
    // declared size on read (seen by the fuzzer: 4 GB for a 257-byte file). GDAL reports each
    // block's declared byte count in the "TIFF" metadata domain.
    if (driver == "GTiff" && !ec && bx > 0 && by > 0) {
      const long long blocksX = (nx + bx - 1) / bx, blocksY = (ny + by - 1) / by;
      if (blocksX * blocksY <= 100000)
        for (long long yb = 0; yb < blocksY; ++yb)
          for (long long xb = 0; xb < blocksX; ++xb) {
            const std::string key = "BLOCK_SIZE_" + std::to_string(xb) + "_" + std::to_string(yb);
            const char* size = band->GetMetadataItem(key.c_str(), "TIFF");
            if (size && std::strtoull(size, nullptr, 10) > bytes)
              throw InputError("raster '" + path + "' declares a data block of " + size + " bytes in a file of " +
                               std::to_string(bytes) + " bytes (truncated or corrupt)");
          }
    }
    if (driver == "AAIGrid" && !ec && bytes < 2 * cells)
      throw InputError("raster '" + path + "' is truncated: its header claims " + std::to_string(nx) + "x" +
                       std::to_string(ny) + " cells but the file has only " + std::to_string(bytes) + " bytes");
    if (driver == "AAIGrid") {
      const std::string bad = detail::findNonNumericAsciiCell(path, nx, ny);
      if (!bad.empty())
        throw InputError("ESRI ASCII grid '" + path + "' holds a value that is not a number: " + bad +
                         " (GDAL would read it as 0; write the grid's NODATA_value there instead)");
    }
    requireMemoryFor(path, nx, ny);
    if (driver != "AAIGrid") {
      std::vector<double> lastRow(static_cast<std::size_t>(nx));
      if (band->RasterIO(GF_Read, 0, ny - 1, nx, 1, lastRow.data(), nx, 1, GDT_Float64, 0, 0, nullptr) != CE_None ||
          errors.failed())
        throw InputError("cannot read the data of raster '" + path + "' (truncated or corrupt?): " +
                         errors.describe("GDAL read error"));
    }
  }
  try {
    r.values.resize(cells);
    r.valid.assign(cells, 1);
  } catch (const std::bad_alloc&) {  // the estimate above was too optimistic (overcommit, fragmentation)
    throw InputError("raster '" + path + "' is too large to load: " + std::to_string(cells) + " cells");
  }

  if (band->RasterIO(GF_Read, 0, 0, nx, ny, r.values.data(), nx, ny, GDT_Float64, 0, 0, nullptr) !=
          CE_None ||
      errors.failed()) {
    throw InputError("cannot read the data of raster '" + path + "' (truncated or corrupt?): " +
                     errors.describe("GDAL read error"));
  }

  int hasNodata = 0;
  const double nodata = band->GetNoDataValue(&hasNodata);
  // Float32 files store the nodata value rounded to float; match that too.
  const double nodataAsFloat = static_cast<double>(static_cast<float>(nodata));
  const bool nodataIsNan = hasNodata != 0 && std::isnan(nodata);
  if (hasNodata != 0 && !nodataIsNan) r.nodata = nodata;
  for (std::size_t k = 0; k < r.values.size(); ++k) {
    const double v = r.values[k];
    if (!std::isfinite(v) || (hasNodata != 0 && (v == nodata || v == nodataAsFloat))) r.valid[k] = 0;
  }
  applyScaleAndOffset(*band, r);
  if (options.valuesAreLengths) {
    const double toMetreVertical = verticalUnitToMetre(ds->GetProjectionRef(), options);
    if (toMetreVertical != 1.0)
      for (double& v : r.values) v *= toMetreVertical;
  }
  return r;
}

void requireSameGrid(const Raster& reference, const std::string& referencePath, const Raster& other,
                     const std::string& otherPath) {
  if (sameGrid(reference.grid, other.grid)) return;
  throw InputError("map '" + mapName(otherPath) + "' (" + otherPath + ") does not share the grid of '" +
                   mapName(referencePath) + "' (" + referencePath + "): " + describeGrid(other.grid) +
                   " vs " + describeGrid(reference.grid));
}

void writeRaster(const std::string& path, const Raster& r, RasterFormat format, bool asFloat64) {
  ensureGdalRegistered();
  const Grid& g = r.grid;
  if (g.nx <= 0 || g.ny <= 0 || r.values.size() != g.cells() ||
      (!r.valid.empty() && r.valid.size() != g.cells())) {
    throw std::invalid_argument("writeRaster('" + path + "'): raster values/mask do not match its " +
                                std::to_string(g.nx) + "x" + std::to_string(g.ny) + " grid");
  }
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw InputError("cannot write raster '" + path + "': folder '" + folder.string() +
                     "' does not exist or is not a folder");
  }

  const std::string tmpPath = path + ".tmp-" + std::to_string(detail::processId());
  const std::string tmpAux = tmpPath + ".aux.xml";
  GdalErrorScope errors;
  try {
    writeWithGdal(tmpPath, path, r, format, asFloat64, errors);
    fs::rename(tmpPath, path, ec);
    if (ec) throw IoError("cannot move '" + tmpPath + "' to '" + path + "': " + ec.message());
    // Side-car metadata GDAL may keep next to the file (e.g. the projection of a PCRaster map).
    const std::string aux = path + ".aux.xml";
    if (fs::exists(tmpAux, ec)) {
      fs::rename(tmpAux, aux, ec);
      if (ec) throw IoError("cannot move '" + tmpAux + "' to '" + aux + "': " + ec.message());
    } else {
      removeQuietly(aux);  // a stale side-car would describe the old file
    }
  } catch (...) {
    removeQuietly(tmpPath);
    removeQuietly(tmpAux);
    throw;
  }
}

RasterFormat formatForPath(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".map" ? RasterFormat::PCRaster : RasterFormat::GeoTiff;
}

}  // namespace talus::io
