// Unit tests of io/MapRender (`talus render`): a synthetic map renders to a PNG that GDAL reads
// back with the layout's size; cells with a value have exactly the ramp's colour, dry and nodata
// cells the grey hillshade; the ramps are continuous and hit their end colours; bad input (missing
// file, a DEM on another grid, a bad option) gives an error naming the file and a non-zero exit.
#include <gdal.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/Error.hpp"
#include "io/MapRender.hpp"
#include "io/RasterIO.hpp"
#include "support/CliRun.hpp"

#ifndef TALUS_BINARY
#define TALUS_BINARY ""
#endif

namespace fs = std::filesystem;
using talus::Grid;
using talus::Raster;
namespace io = talus::io;

namespace {

/// A fresh folder under the system temp folder, removed at the end of the test.
class MapRender : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("talus_map_render_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    GDALAllRegister();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

/// A 12 x 8 map of 5 m cells: a wet patch with values 0.1 .. 2.2 in columns 3..8, rows 2..5; zero
/// elsewhere; one nodata cell inside the patch.
Raster syntheticMap() {
  Raster r(Grid::make(12, 8, 5.0, 1000.0, 2000.0), 0.0);
  r.nodata = -9999.0;
  for (int j = 2; j < 6; ++j)
    for (int i = 3; i < 9; ++i) r.at(i, j) = 0.1 * (i - 2) + 0.3 * (j - 2) + 0.0;
  r.valid[r.grid.index(5, 3)] = 0;
  return r;
}

/// A DEM on the map's grid: a plane rising eastwards on the left half, flat on the right.
Raster syntheticDem() {
  Raster d(Grid::make(12, 8, 5.0, 1000.0, 2000.0), 0.0);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 12; ++i) d.at(i, j) = i < 6 ? 2.0 * i : 10.0;
  return d;
}

/// The picture read back through GDAL: three bands of bytes.
struct Picture {
  int w = 0, h = 0, bands = 0;
  std::vector<std::uint8_t> r, g, b;
  io::Rgb at(int x, int y) const {
    const std::size_t k = static_cast<std::size_t>(y) * w + x;
    return {r[k], g[k], b[k]};
  }
};

Picture readPng(const std::string& path) {
  Picture p;
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  if (ds == nullptr) return p;
  p.w = GDALGetRasterXSize(ds);
  p.h = GDALGetRasterYSize(ds);
  p.bands = GDALGetRasterCount(ds);
  const std::string driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
  EXPECT_EQ(driver, "PNG");
  std::vector<std::uint8_t>* out[3] = {&p.r, &p.g, &p.b};
  for (int b = 0; b < 3 && b < p.bands; ++b) {
    out[b]->resize(static_cast<std::size_t>(p.w) * p.h);
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, b + 1), GF_Read, 0, 0, p.w, p.h, out[b]->data(), p.w, p.h, GDT_Byte,
                           0, 0),
              CE_None);
  }
  GDALClose(ds);
  return p;
}

}  // namespace

TEST_F(MapRender, RampsAreContinuousAndHitTheirEnds) {
  for (const char* name : {"depth", "heat", "viridis", "cohesion"}) {
    const io::Ramp ramp = io::parseRamp(name);
    EXPECT_EQ(io::rampColour(ramp, -1.0), io::rampColour(ramp, 0.0)) << name;
    EXPECT_EQ(io::rampColour(ramp, 2.0), io::rampColour(ramp, 1.0)) << name;
    EXPECT_EQ(io::rampColour(ramp, std::nan("")), io::rampColour(ramp, 0.0)) << name;
    EXPECT_FALSE(io::rampColour(ramp, 0.0) == io::rampColour(ramp, 1.0)) << name;
    for (int k = 1; k <= 1000; ++k) {  // no jump larger than the rounding of a 1/1000 step
      const io::Rgb a = io::rampColour(ramp, (k - 1) / 1000.0), b = io::rampColour(ramp, k / 1000.0);
      EXPECT_LE(std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b), 4) << name << " at " << k;
    }
  }
  EXPECT_THROW(io::parseRamp("rainbow"), talus::InputError);
}

TEST_F(MapRender, HillshadeOfFlatGroundIsUniformAndSlopesDiffer) {
  const Raster dem = syntheticDem();
  const auto shade = io::hillshade(dem);
  ASSERT_EQ(shade.size(), dem.grid.cells());
  EXPECT_EQ(shade[dem.grid.index(9, 4)], 190);  // 70 + 170 sin 45 deg
  EXPECT_EQ(shade[dem.grid.index(10, 4)], 190);
  // The plane rises to the east, so it faces west, towards the north-west sun: brighter than flat.
  EXPECT_GT(shade[dem.grid.index(2, 4)], 190);
}

TEST_F(MapRender, SyntheticMapRendersWithRampAndHillshade) {
  const Raster map = syntheticMap(), dem = syntheticDem();
  io::writeRaster(path("hmax.tif"), map);
  io::writeRaster(path("dem.tif"), dem);
  io::RenderOptions o;
  o.hillshadeDem = path("dem.tif");
  o.ramp = io::Ramp::Depth;
  o.label = "hmax [m]";
  const io::RenderLayout L = io::renderMap(path("hmax.tif"), path("hmax.png"), o);
  ASSERT_TRUE(fs::is_regular_file(path("hmax.png")));
  EXPECT_EQ(L.shownCells, 4 * 6 - 1);
  EXPECT_EQ(L.lo, 0.0);  // non-negative values: the ramp starts at zero
  EXPECT_NEAR(L.hi, 0.1 * 6 + 0.3 * 3, 1e-6);  // the largest value (Float32 in the file)
  EXPECT_GE(L.scale, 1);

  const Picture p = readPng(path("hmax.png"));
  ASSERT_EQ(p.bands, 3);
  EXPECT_EQ(p.w, L.width);
  EXPECT_EQ(p.h, L.height);
  EXPECT_GE(p.w, L.mapX + 12 * L.scale);
  EXPECT_GE(p.h, L.mapY + 8 * L.scale);

  const Raster back = io::readRaster(path("hmax.tif"));
  const auto shade = io::hillshade(dem);
  int rampPixels = 0, greyPixels = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 12; ++i) {
      const std::size_t k = map.grid.index(i, j);
      const bool wet = back.valid[k] && back.values[k] > 0.0;
      const io::Rgb want = wet ? io::rampColour(o.ramp, (back.values[k] - L.lo) / (L.hi - L.lo))
                               : io::Rgb{shade[k], shade[k], shade[k]};
      // Every pixel of the cell's block, not just one.
      for (int y = L.mapY + j * L.scale; y < L.mapY + (j + 1) * L.scale; ++y)
        for (int x = L.mapX + i * L.scale; x < L.mapX + (i + 1) * L.scale; ++x) {
          const io::Rgb got = p.at(x, y);
          ASSERT_EQ(got, want) << "cell (" << i << ", " << j << ") pixel (" << x << ", " << y << "): got " << int(got.r)
                               << "," << int(got.g) << "," << int(got.b) << (wet ? " (wet)" : " (dry)");
        }
      (wet ? rampPixels : greyPixels) += 1;
      if (!wet) {
        EXPECT_TRUE(want.r == want.g && want.g == want.b);
      }
    }
  EXPECT_EQ(rampPixels, 23);
  EXPECT_EQ(greyPixels, 12 * 8 - 23);
  // The nodata cell inside the patch shows the hillshade, not a ramp colour.
  const io::Rgb hole = p.at(L.mapX + 5 * L.scale, L.mapY + 3 * L.scale);
  EXPECT_TRUE(hole.r == hole.g && hole.g == hole.b);
}

TEST_F(MapRender, FixedRangeThresholdAndNoDem) {
  io::writeRaster(path("c.tif"), syntheticMap());
  io::RenderOptions o;
  o.ramp = io::Ramp::Cohesion;
  o.fixedRange = true;
  o.lo = 0.0, o.hi = 1.0;
  o.threshold = 0.5;  // only cells above 0.5 in colour
  o.scale = 3;
  const io::RenderLayout L = io::renderMap(path("c.tif"), path("c.png"), o);
  EXPECT_EQ(L.scale, 3);
  const Picture p = readPng(path("c.png"));
  const Raster back = io::readRaster(path("c.tif"));
  int shown = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 12; ++i) {
      const std::size_t k = back.grid.index(i, j);
      const bool wet = back.valid[k] && back.values[k] > 0.5;
      shown += wet;
      const io::Rgb want = wet ? io::rampColour(o.ramp, back.values[k]) : io::Rgb{210, 210, 210};
      EXPECT_EQ(p.at(L.mapX + i * 3 + 1, L.mapY + j * 3 + 1), want) << i << "," << j;
    }
  EXPECT_EQ(shown, L.shownCells);
  EXPECT_GT(shown, 0);
  o.lo = 1.0;
  EXPECT_THROW(io::renderMap(path("c.tif"), path("c2.png"), o), talus::InputError);
}

TEST_F(MapRender, BadInputNamesTheFile) {
  io::writeRaster(path("hmax.tif"), syntheticMap());
  Raster other(Grid::make(10, 8, 5.0, 1000.0, 2000.0), 1.0);
  io::writeRaster(path("dem_other.tif"), other);
  io::RenderOptions o;
  try {
    io::renderMap(path("missing.tif"), path("x.png"), o);
    ADD_FAILURE() << "expected an error for a missing raster";
  } catch (const talus::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.tif"), std::string::npos) << e.what();
  }
  o.hillshadeDem = path("dem_other.tif");
  try {
    io::renderMap(path("hmax.tif"), path("x.png"), o);
    ADD_FAILURE() << "expected an error for a DEM on another grid";
  } catch (const talus::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dem_other"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hmax"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(MapRender, CommandLine) {
  ASSERT_FALSE(std::string(TALUS_BINARY).empty()) << "TALUS_BINARY is not defined (tests/CMakeLists.txt)";
  io::writeRaster(path("hmax.tif"), syntheticMap());
  io::writeRaster(path("dem.tif"), syntheticDem());
  io::writeRaster(path("dem_other.tif"), Raster(Grid::make(10, 8, 5.0, 1000.0, 2000.0), 1.0));
  using talus::test::runIn;
  const auto ok = runIn(dir_, TALUS_BINARY,
                        "render hmax.tif -o out.png --hillshade dem.tif --ramp heat --range 0 2 --label 'hmax [m]'");
  EXPECT_EQ(ok.status, 0) << ok;
  EXPECT_TRUE(fs::is_regular_file(path("out.png")));
  EXPECT_EQ(readPng(path("out.png")).bands, 3);

  const auto missing = runIn(dir_, TALUS_BINARY, "render nothere.tif -o out2.png");
  EXPECT_NE(missing.status, 0) << missing;
  EXPECT_NE(missing.err.find("nothere.tif"), std::string::npos) << missing;

  const auto mismatch = runIn(dir_, TALUS_BINARY, "render hmax.tif -o out3.png --hillshade dem_other.tif");
  EXPECT_NE(mismatch.status, 0) << mismatch;
  EXPECT_NE(mismatch.err.find("dem_other.tif"), std::string::npos) << mismatch;
  EXPECT_FALSE(fs::exists(path("out3.png")));

  const auto badRamp = runIn(dir_, TALUS_BINARY, "render hmax.tif -o out4.png --ramp rainbow");
  EXPECT_NE(badRamp.status, 0) << badRamp;
  EXPECT_NE(badRamp.err.find("rainbow"), std::string::npos) << badRamp;
  const auto noOut = runIn(dir_, TALUS_BINARY, "render hmax.tif");
  EXPECT_NE(noOut.status, 0) << noOut;
}
