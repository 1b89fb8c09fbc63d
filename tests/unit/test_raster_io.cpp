// Unit tests of io/RasterIO: GeoTIFF, PCRaster and ESRI ASCII round trips, nodata handling, the
// errors for bad files and mismatched grids, and atomic writing. No GDAL here: rasters are written
// through writeRaster, ESRI ASCII grids by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>

#include <unistd.h>

#include "core/Error.hpp"
#include "io/RasterIO.hpp"

namespace fs = std::filesystem;
using talus::Grid;
using talus::InputError;
using talus::Raster;
using talus::io::RasterFormat;

namespace {

/// EPSG:31287, MGI / Austria Lambert.
const char* kAustriaLambertWkt =
    "PROJCS[\"MGI / Austria Lambert\",GEOGCS[\"MGI\",DATUM[\"Militar_Geographische_Institut\","
    "SPHEROID[\"Bessel 1841\",6377397.155,299.1528128,AUTHORITY[\"EPSG\",\"7004\"]],"
    "AUTHORITY[\"EPSG\",\"6312\"]],PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],"
    "UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],AUTHORITY[\"EPSG\",\"4312\"]],"
    "PROJECTION[\"Lambert_Conformal_Conic_2SP\"],PARAMETER[\"latitude_of_origin\",47.5],"
    "PARAMETER[\"central_meridian\",13.3333333333333],PARAMETER[\"standard_parallel_1\",49],"
    "PARAMETER[\"standard_parallel_2\",46],PARAMETER[\"false_easting\",400000],"
    "PARAMETER[\"false_northing\",400000],UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],"
    "AUTHORITY[\"EPSG\",\"31287\"]]";

/// A test raster with float-exact values, a few invalid cells and a projected georeference.
Raster makeRaster(int nx = 7, int ny = 5, double dx = 5.0, double x0 = 450000.0, double y0 = 380000.0) {
  Grid g = Grid::make(nx, ny, dx, x0, y0);
  g.projectionWkt = kAustriaLambertWkt;
  Raster r(g, 0.0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) r.at(i, j) = 100.0 + 0.25 * i - 1.5 * j;
  }
  r.valid[g.index(0, 0)] = 0;
  r.valid[g.index(nx - 1, ny - 1)] = 0;
  r.valid[g.index(2, 1)] = 0;
  return r;
}

/// Runs fn, expects an InputError whose text contains every one of parts.
void expectInputError(const std::function<void()>& fn, std::initializer_list<std::string> parts) {
  try {
    fn();
    ADD_FAILURE() << "expected talus::InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(what.find(part), std::string::npos) << "'" << part << "' not in: " << what;
    }
  }
}

void writeText(const fs::path& path, const std::string& text) {
  std::FILE* f = std::fopen(path.string().c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fprintf(f, "%s", text.c_str());
  std::fclose(f);
}

/// Expects read to match written: grid, values of valid cells, the mask.
void expectSameContent(const Raster& written, const Raster& read) {
  ASSERT_EQ(read.grid.nx, written.grid.nx);
  ASSERT_EQ(read.grid.ny, written.grid.ny);
  EXPECT_DOUBLE_EQ(read.grid.dx, written.grid.dx);
  for (int k = 0; k < 6; ++k) {
    EXPECT_DOUBLE_EQ(read.grid.geoTransform[k], written.grid.geoTransform[k]) << "geotransform " << k;
  }
  EXPECT_TRUE(talus::sameGrid(read.grid, written.grid));
  for (std::size_t k = 0; k < written.values.size(); ++k) {
    EXPECT_EQ(read.valid[k], written.valid[k]) << "cell " << k;
    if (written.valid[k] != 0) {
      EXPECT_DOUBLE_EQ(read.values[k], written.values[k]) << "cell " << k;
    }
  }
}

}  // namespace

/// Fixture: a fresh temporary folder per test, removed afterwards.
class RasterIO : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / ("talus_rasterio_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

TEST_F(RasterIO, GeoTiffRoundTripPreservesValuesMaskAndGeoreference) {
  const Raster r = makeRaster();
  talus::io::writeRaster(file("a.tif"), r);
  const Raster a = talus::io::readRaster(file("a.tif"));
  expectSameContent(r, a);
  EXPECT_DOUBLE_EQ(a.nodata, r.nodata);
  ASSERT_FALSE(a.grid.projectionWkt.empty());
  EXPECT_NE(a.grid.projectionWkt.find("31287"), std::string::npos) << a.grid.projectionWkt;
  // A second round trip keeps the projection text as GDAL reports it.
  talus::io::writeRaster(file("b.tif"), a);
  const Raster b = talus::io::readRaster(file("b.tif"));
  EXPECT_EQ(b.grid.projectionWkt, a.grid.projectionWkt);
  expectSameContent(a, b);
}

TEST_F(RasterIO, GeoTiffFloat64RoundTripIsExact) {
  Raster r = makeRaster();
  r.at(3, 2) = 0.1;        // not representable in float
  r.at(4, 2) = 1234.5678901234;
  talus::io::writeRaster(file("f64.tif"), r, RasterFormat::GeoTiff, true);
  const Raster a = talus::io::readRaster(file("f64.tif"));
  expectSameContent(r, a);
  EXPECT_EQ(a.at(3, 2), 0.1);
  EXPECT_EQ(a.at(4, 2), 1234.5678901234);
  // Float32 rounds the same values.
  talus::io::writeRaster(file("f32.tif"), r);
  const Raster b = talus::io::readRaster(file("f32.tif"));
  EXPECT_EQ(b.at(3, 2), static_cast<double>(0.1f));
}

TEST_F(RasterIO, PCRasterRoundTripPreservesValuesMaskAndGeoreference) {
  const Raster r = makeRaster(9, 6, 2.5, -1000.0, 250.0);
  ASSERT_EQ(talus::io::formatForPath(file("dem.map")), RasterFormat::PCRaster);
  talus::io::writeRaster(file("dem.map"), r, RasterFormat::PCRaster);
  const Raster a = talus::io::readRaster(file("dem.map"));
  expectSameContent(r, a);
  ASSERT_FALSE(a.grid.projectionWkt.empty());
  talus::io::writeRaster(file("dem2.map"), a, RasterFormat::PCRaster);
  const Raster b = talus::io::readRaster(file("dem2.map"));
  EXPECT_EQ(b.grid.projectionWkt, a.grid.projectionWkt);
  expectSameContent(a, b);
}

TEST_F(RasterIO, EsriAsciiIsReadWithNodataAndGeoreference) {
  const std::string path = file("h.asc");
  std::FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fprintf(f, "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 5\nNODATA_value -9999\n");
  std::fprintf(f, "1.5 2 3 4\n5 -9999 7 8\n9 10 11 -9999\n");
  std::fclose(f);
  writeText(file("h.prj"), kAustriaLambertWkt);

  const Raster a = talus::io::readRaster(path);
  ASSERT_EQ(a.grid.nx, 4);
  ASSERT_EQ(a.grid.ny, 3);
  EXPECT_DOUBLE_EQ(a.grid.dx, 5.0);
  EXPECT_TRUE(talus::sameGrid(a.grid, Grid::make(4, 3, 5.0, 1000.0, 2000.0)));
  EXPECT_DOUBLE_EQ(a.grid.geoTransform[3], 2015.0);
  EXPECT_DOUBLE_EQ(a.nodata, -9999.0);
  EXPECT_DOUBLE_EQ(a.at(0, 0), 1.5);
  EXPECT_DOUBLE_EQ(a.at(3, 1), 8.0);
  EXPECT_DOUBLE_EQ(a.at(2, 2), 11.0);
  EXPECT_FALSE(a.isValid(1, 1));
  EXPECT_FALSE(a.isValid(3, 2));
  EXPECT_TRUE(a.isValid(0, 0));
  EXPECT_FALSE(a.grid.projectionWkt.empty());

  // Through GeoTIFF and back: same content and projection.
  talus::io::writeRaster(file("h.tif"), a);
  const Raster b = talus::io::readRaster(file("h.tif"));
  expectSameContent(a, b);
  EXPECT_FALSE(b.grid.projectionWkt.empty());
}

TEST_F(RasterIO, NonFiniteValuesBecomeInvalid) {
  Raster r = makeRaster();
  r.at(1, 1) = std::numeric_limits<double>::quiet_NaN();
  r.at(3, 3) = std::numeric_limits<double>::infinity();
  talus::io::writeRaster(file("nan.tif"), r);
  const Raster a = talus::io::readRaster(file("nan.tif"));
  EXPECT_FALSE(a.isValid(1, 1));
  EXPECT_FALSE(a.isValid(3, 3));
  EXPECT_FALSE(a.isValid(0, 0));
  EXPECT_TRUE(a.isValid(1, 2));
}

TEST_F(RasterIO, MissingFileErrorNamesPath) {
  const std::string path = file("does_not_exist.tif");
  expectInputError([&] { talus::io::readRaster(path); }, {path});
}

TEST_F(RasterIO, TruncatedGeoTiffThrowsNamingFile) {
  // Incompressible values, so the cell data dominate the file and truncation cuts into them.
  Raster r(Grid::make(300, 300, 1.0), 0.0);
  unsigned state = 12345u;
  for (double& v : r.values) {
    state = state * 1664525u + 1013904223u;
    v = static_cast<double>(state >> 8) / 65536.0;
  }
  const std::string path = file("cut.tif");
  talus::io::writeRaster(path, r);
  fs::resize_file(path, fs::file_size(path) / 2);
  expectInputError([&] { talus::io::readRaster(path); }, {path});
}

TEST_F(RasterIO, GarbageTextFileThrowsNamingFile) {
  const std::string path = file("garbage.tif");
  writeText(path, "this is not a raster\nat all, just some text 1 2 3\n");
  expectInputError([&] { talus::io::readRaster(path); }, {path});
}

TEST_F(RasterIO, MismatchedGridsThrowNamingBothFiles) {
  const std::string a = file("dem.tif"), same = file("same.tif");
  const std::string size = file("size.tif"), shift = file("shift.tif"), cell = file("cell.tif");
  talus::io::writeRaster(a, makeRaster(7, 5, 5.0, 100.0, 200.0));
  talus::io::writeRaster(same, makeRaster(7, 5, 5.0, 100.0, 200.0));
  talus::io::writeRaster(size, makeRaster(7, 6, 5.0, 100.0, 200.0));
  talus::io::writeRaster(shift, makeRaster(7, 5, 5.0, 102.5, 200.0));
  talus::io::writeRaster(cell, makeRaster(7, 5, 10.0, 100.0, 200.0));
  const Raster ra = talus::io::readRaster(a);
  EXPECT_NO_THROW(talus::io::requireSameGrid(ra, a, talus::io::readRaster(same), same));
  for (const std::string& other : {size, shift, cell}) {
    const Raster ro = talus::io::readRaster(other);
    expectInputError([&] { talus::io::requireSameGrid(ra, a, ro, other); },
                     {a, other, "does not share the grid", "7x5 cells of 5 m"});
  }
  expectInputError([&] { talus::io::requireSameGrid(ra, a, talus::io::readRaster(size), size); },
                   {"map 'size'", "of 'dem'", "7x6 cells"});
}

TEST_F(RasterIO, ZeroCellSizeThrowsNamingFile) {
  const std::string path = file("zero.asc");
  writeText(path, "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0\nNODATA_value -9999\n1 2\n3 4\n");
  expectInputError([&] { talus::io::readRaster(path); }, {path});
}

TEST_F(RasterIO, NonSquareCellsThrowNamingBothSizes) {
  const std::string path = file("rect.asc");
  writeText(path, "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ndx 5\ndy 10\nNODATA_value -9999\n1 2\n3 4\n");
  expectInputError([&] { talus::io::readRaster(path); }, {path, "non-square", "5", "10"});
}

TEST_F(RasterIO, AtomicWriteLeavesNoTemporaryFiles) {
  const std::string tif = file("out.tif"), map = file("out.map");
  talus::io::writeRaster(tif, makeRaster());
  talus::io::writeRaster(map, makeRaster(), RasterFormat::PCRaster);
  // Overwriting an existing file replaces it.
  Raster r2 = makeRaster(4, 4, 1.0);
  r2.at(1, 1) = 42.0;
  talus::io::writeRaster(tif, r2);
  talus::io::writeRaster(map, r2, RasterFormat::PCRaster);
  EXPECT_EQ(talus::io::readRaster(tif).grid.nx, 4);
  EXPECT_DOUBLE_EQ(talus::io::readRaster(map).at(1, 1), 42.0);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

TEST_F(RasterIO, UnwritableFolderThrowsNamingPath) {
  const std::string blocker = file("plain_file");
  writeText(blocker, "x");
  const std::string target = blocker + "/sub/x.tif";
  expectInputError([&] { talus::io::writeRaster(target, makeRaster()); }, {target});
  expectInputError([&] { talus::io::writeRaster(blocker + "/y.map", makeRaster(), RasterFormat::PCRaster); },
                   {blocker + "/y.map"});
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

TEST_F(RasterIO, FormatForPathUsesLowercaseExtension) {
  EXPECT_EQ(talus::io::formatForPath("a/b/dem.map"), RasterFormat::PCRaster);
  EXPECT_EQ(talus::io::formatForPath("DEM.MAP"), RasterFormat::PCRaster);
  EXPECT_EQ(talus::io::formatForPath("dem.tif"), RasterFormat::GeoTiff);
  EXPECT_EQ(talus::io::formatForPath("dem"), RasterFormat::GeoTiff);
  EXPECT_EQ(talus::io::formatForPath("map"), RasterFormat::GeoTiff);
}
