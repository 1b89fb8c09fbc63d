// Geodata semantics and input limits (issue 14, items 4, 6, 8): rasters whose CRS is in degrees or
// feet, GDAL scale/offset, extra bands, non-numeric tokens in ASCII grids, material on nodata DEM
// cells, maps of switched-off processes, empty scenes, rasters and runs larger than the memory
// left, bounded run-file reading, quoted values in run.resolved.run, control characters in --set,
// and times in minutes that must land on report times. Each case failed silently (or ran on) before
// the checks it tests; the rasters are written here through GDAL, so that CRS, scale/offset and
// band count can be set as real files carry them.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/Error.hpp"
#include "core/Memory.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/RunTimes.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"
#include "support/CliRun.hpp"
#include "support/ExpectInputError.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define TALUS_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TALUS_TEST_ASAN 1
#endif
#endif

namespace fs = std::filesystem;
using talus::InputError;
using talus::io::RunConfig;
using talus::sim::talusRunKeys;

namespace {

using talus::test::contains;
using talus::test::expectInputError;

/// WKT of an EPSG code (from PROJ's database).
std::string epsgWkt(int code) {
  OGRSpatialReference srs;
  EXPECT_EQ(srs.importFromEPSG(code), OGRERR_NONE) << "EPSG:" << code;
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string out = wkt != nullptr ? wkt : "";
  CPLFree(wkt);
  return out;
}

/// How a test GeoTIFF is written: everything a real file can carry that matters here.
struct TiffSpec {
  int nx = 8, ny = 6;
  double dx = 5.0, x0 = 512000.0, y0 = 5160000.0;
  GDALDataType type = GDT_Float32;
  int bands = 1;
  std::string wkt = epsgWkt(32633);  // WGS 84 / UTM zone 33N, metres
  double scale = 1.0, offset = 0.0;
  bool hasNodata = false;
  double nodata = -9999.0;
  bool sparse = false;  // no data blocks written (a small file declaring a large grid)
};

/// Writes a GeoTIFF whose band b holds value(i, j) + 1000 b (band 0 = value).
void writeTiff(const std::string& path, const TiffSpec& t, const std::function<double(int, int)>& value) {
  GDALAllRegister();
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  ASSERT_NE(gtiff, nullptr);
  CPLStringList options;
  if (t.sparse) {
    options.SetNameValue("SPARSE_OK", "TRUE");
    options.SetNameValue("TILED", "YES");
  }
  GDALDatasetUniquePtr ds(gtiff->Create(path.c_str(), t.nx, t.ny, t.bands, t.type, options.List()));
  ASSERT_TRUE(ds) << path;
  double gt[6] = {t.x0, t.dx, 0.0, t.y0 + t.ny * t.dx, 0.0, -t.dx};
  ds->SetGeoTransform(gt);
  ds->SetProjection(t.wkt.c_str());
  for (int b = 1; b <= t.bands; ++b) {
    GDALRasterBand* band = ds->GetRasterBand(b);
    if (t.scale != 1.0) band->SetScale(t.scale);
    if (t.offset != 0.0) band->SetOffset(t.offset);
    if (t.hasNodata) band->SetNoDataValue(t.nodata);
    if (t.sparse) continue;
    std::vector<double> v(static_cast<std::size_t>(t.nx) * t.ny);
    for (int j = 0; j < t.ny; ++j)
      for (int i = 0; i < t.nx; ++i) v[static_cast<std::size_t>(j) * t.nx + i] = value(i, j) + 1000.0 * (b - 1);
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, t.nx, t.ny, v.data(), t.nx, t.ny, GDT_Float64, 0, 0, nullptr), CE_None);
  }
}

/// What a forked child with a capped address space (its current size plus `headroom` bytes) saw.
struct ChildResult {
  bool exited = false;
  int code = -1;     // 0: InputError, 1: other exception, 2: nothing thrown
  std::string what;  // the message
};

/// Runs fn in a child process whose address space may grow by at most `headroom` bytes, so that a
/// test can show a refusal without the machine's real memory being at stake.
ChildResult inLimitedChild(const fs::path& report, unsigned long long headroom, const std::function<void()>& fn) {
  ChildResult r;
  const pid_t child = ::fork();
  if (child < 0) return r;
  if (child == 0) {
    long vmKb = 0;
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmSize:", 0) == 0) vmKb = std::atol(line.c_str() + 7);
    const rlim_t limit = static_cast<rlim_t>(vmKb) * 1024 + headroom;
    const rlimit rl{limit, limit};
    ::setrlimit(RLIMIT_AS, &rl);
    int code = 2;
    std::string what = "nothing thrown";
    try {
      fn();
    } catch (const InputError& e) {
      what = e.what();
      code = 0;
    } catch (const std::exception& e) {
      what = e.what();
      code = 1;
    }
    std::ofstream(report) << what;
    std::_Exit(code);
  }
  int raw = 0;
  if (::waitpid(child, &raw, 0) != child) return r;
  r.exited = WIFEXITED(raw);
  r.code = r.exited ? WEXITSTATUS(raw) : -1;
  r.what = talus::test::slurp(report);
  return r;
}

/// Expects the child to have ended by an InputError naming every one of parts.
void expectChildInputError(const ChildResult& r, std::initializer_list<std::string> parts) {
  ASSERT_TRUE(r.exited) << "the child crashed";
  EXPECT_EQ(r.code, 0) << "0 = InputError, 1 = other exception, 2 = nothing thrown: " << r.what;
  for (const std::string& part : parts) EXPECT_TRUE(contains(r.what, part)) << "missing '" << part << "' in: " << r.what;
}

/// A gentle slope, the DEM of the scene tests.
double slope(int i, int j) { return 100.0 + 0.5 * i + 0.25 * j; }

class Geodata : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_geodata_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& rel) const { return (dir_ / rel).string(); }
  std::string write(const std::string& rel, const std::string& text) {
    std::ofstream(path(rel), std::ios::binary) << text;
    return path(rel);
  }
  std::string tiff(const std::string& rel, const TiffSpec& t, const std::function<double(int, int)>& f = slope) {
    writeTiff(path(rel), t, f);
    return path(rel);
  }
  RunConfig load(const std::string& runFile) { return RunConfig::load(runFile, talusRunKeys()); }

  fs::path dir_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// CRS and units
// ---------------------------------------------------------------------------------------------

// Before: 0.001-degree cells were taken as 1 mm cells (93 716 steps in 300 s of a real run).
TEST_F(Geodata, GeographicDemIsRefusedNamingFileAndCrs) {
  TiffSpec t;
  t.wkt = epsgWkt(4326);
  t.dx = 0.001;
  t.x0 = 11.0;
  t.y0 = 47.0;
  const std::string dem = tiff("dem_wgs84.tif", t);
  expectInputError([&] { talus::io::readRaster(dem); }, {dem, "geographic", "WGS 84", "EPSG:4326", "degree"});
}

// Before: a DEM in US survey feet ran as metres (cells and elevations 3.28 times too large).
TEST_F(Geodata, FootCrsIsRefusedUnlessConvertedThenCellsAndElevationsAreMetres) {
  TiffSpec t;
  t.wkt = epsgWkt(2229);  // NAD83 / California zone 5 (ftUS)
  t.dx = 10.0;
  t.x0 = 6400000.0;
  t.y0 = 1800000.0;
  const std::string dem = tiff("dem_ftus.tif", t);
  expectInputError([&] { talus::io::readRaster(dem); }, {dem, "EPSG:2229", "US survey foot", "Convert Raster Units"});

  talus::io::RasterReadOptions convert;
  convert.convertLinearUnits = true;
  convert.valuesAreLengths = true;
  const talus::Raster r = talus::io::readRaster(dem, convert);
  const double usFoot = 1200.0 / 3937.0;  // the US survey foot's definition
  // The file's Float32 values and PROJ's factor (printed to 16 digits) agree to a few ulps of float.
  EXPECT_NEAR(r.grid.dx, 10.0 * usFoot, 1e-12);
  EXPECT_NEAR(r.at(3, 2), slope(3, 2) * usFoot, 1e-5 * slope(3, 2));
  // The georeference stays in the file's CRS, so outputs overlay the inputs.
  EXPECT_EQ(r.grid.geoTransform[0], 6400000.0);
  EXPECT_EQ(r.grid.geoTransform[1], 10.0);
  // Maps that are not lengths (Manning's n) keep their values.
  convert.valuesAreLengths = false;
  EXPECT_NEAR(talus::io::readRaster(dem, convert).at(3, 2), slope(3, 2), 1e-4);
}

TEST_F(Geodata, RasterWithoutCrsIsTakenAsMetres) {
  TiffSpec t;
  t.wkt = "";
  const talus::Raster r = talus::io::readRaster(tiff("plain.tif", t));
  EXPECT_EQ(r.grid.dx, 5.0);
  EXPECT_FLOAT_EQ(static_cast<float>(r.at(1, 1)), static_cast<float>(slope(1, 1)));
}

// Before: the raw Int16 decimetres were read as metres (slopes 10 times too steep).
TEST_F(Geodata, ScaleAndOffsetAreAppliedAndNodataMatchesTheStoredValue) {
  TiffSpec t;
  t.type = GDT_Int16;
  t.scale = 0.1;
  t.offset = 200.0;
  t.hasNodata = true;
  t.nodata = -32768;
  const std::string dem = tiff("dem_dm.tif", t, [](int i, int j) { return i == 0 && j == 0 ? -32768.0 : 10.0 * i + j; });
  const talus::Raster r = talus::io::readRaster(dem);
  EXPECT_FALSE(r.isValid(0, 0)) << "nodata is matched against the stored value, before scaling";
  // Int16 values are exact; 0.1 is not, hence the double round-off tolerance.
  EXPECT_NEAR(r.at(4, 3), (10.0 * 4 + 3) * 0.1 + 200.0, 1e-12);
  EXPECT_NEAR(r.at(7, 0), 7.0 + 200.0, 1e-12);
}

// Before: band 1 of a 3-band raster was read without a word.
TEST_F(Geodata, ExtraBandsAreReportedAndBandOneIsRead) {
  TiffSpec t;
  t.bands = 3;
  const std::string rgb = tiff("three.tif", t);
  std::vector<std::string> warnings;
  const talus::Raster r = talus::io::readRaster(rgb, {}, &warnings);
  EXPECT_FLOAT_EQ(static_cast<float>(r.at(2, 2)), static_cast<float>(slope(2, 2))) << "band 1";
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(contains(warnings[0], rgb) && contains(warnings[0], "3 bands") && contains(warnings[0], "band 1"))
      << warnings[0];
}

// Before: GDAL read "n/a" as 0, a 100 m pit in this DEM.
TEST_F(Geodata, AsciiGridTokenThatIsNotANumberIsRefusedWithItsCell) {
  const std::string asc = write("dem.asc",
                                "ncols 4\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 5\nNODATA_value -9999\n"
                                "100 101 102 103\n100 101 n/a 103\n100 101 102 103\n");
  expectInputError([&] { talus::io::readRaster(asc); }, {asc, "'n/a'", "column 2, row 1"});
  // A decimal comma is the same mistake.
  const std::string comma = write("comma.asc",
                                  "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 5\n100 101,5\n");
  expectInputError([&] { talus::io::readRaster(comma); }, {comma, "'101,5'", "column 1, row 0"});
  // Numbers in every spelling GDAL reads still load.
  const std::string good = write("good.asc",
                                 "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 5\nNODATA_value -9999\n"
                                 "1e2 -9999 +3.5\n");
  const talus::Raster r = talus::io::readRaster(good);
  EXPECT_EQ(r.at(0, 0), 100.0);
  EXPECT_FALSE(r.isValid(1, 0));
  EXPECT_EQ(r.at(2, 0), 3.5);
}

// ---------------------------------------------------------------------------------------------
// Scenes: dropped material, switched-off processes, empty scenes
// ---------------------------------------------------------------------------------------------

// Before: 1 m of water on 4 nodata DEM cells of 5 m (100 m^3) vanished without a word.
TEST_F(Geodata, WaterOnNodataDemCellsIsReportedWithCountAndVolume) {
  TiffSpec t;
  t.hasNodata = true;
  tiff("dem.tif", t, [](int i, int j) { return i < 2 && j < 2 ? -9999.0 : slope(i, j); });
  TiffSpec w = t;
  w.hasNodata = false;
  tiff("water.tif", w, [](int i, int j) { return i < 4 && j < 4 ? 1.0 : 0.0; });
  const std::string run = write("case.run", "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n");
  const talus::sim::Scene s = talus::sim::loadScene(load(run));
  ASSERT_EQ(s.warnings.size(), 1u);
  const std::string& m = s.warnings[0];
  // 4 cells x 1 m x 25 m^2; the volume is a sum of exact binary values.
  EXPECT_TRUE(contains(m, "100 m^3 of initial water") && contains(m, "4 cells") && contains(m, path("water.tif")) &&
              contains(m, path("dem.tif")))
      << m;
}

// Before: a missing map of a process that is off was an error; a given one was ignored silently.
TEST_F(Geodata, MapOfASwitchedOffProcessIsNotReadAndIsReported) {
  tiff("dem.tif", TiffSpec{});
  const std::string run = write("case.run",
                                "DEM=dem.tif\nInitial Fluid Height=nowhere.tif\nInitial Solid Height=gone.tif\n"
                                "Include Initial Water=0\n");
  const RunConfig cfg = load(run);
  const std::vector<std::string> w = cfg.warnings();
  ASSERT_EQ(w.size(), 2u);
  EXPECT_TRUE(contains(w[0], "case.run:2") && contains(w[0], "'Initial Fluid Height'") &&
              contains(w[0], "'Include Initial Water' is 0"))
      << w[0];
  EXPECT_TRUE(contains(w[1], "'Initial Solid Height'") && contains(w[1], "'Include Initial Solids' is 0")) << w[1];
  const talus::sim::Scene s = talus::sim::loadScene(cfg);
  EXPECT_EQ(s.warnings, w);
  // The resolved run-file gives every key, defaults included: only the maps given warn again.
  const RunConfig back = RunConfig::fromText(cfg.echo(), dir_.string(), talusRunKeys(), "run.resolved.run");
  EXPECT_EQ(back.warnings().size(), 2u);
  // With the switch on, the missing map is an error again.
  expectInputError([&] { load(write("on.run", "DEM=dem.tif\nInitial Fluid Height=nowhere.tif\nInclude Initial Water=1\n")); },
                   {"on.run:2", "nowhere.tif", "does not exist"});
}

// Before: a scene with nothing in it ran and reported "completed" with all-zero maps.
TEST_F(Geodata, SceneWithNothingToMoveIsRefusedNamingTheSwitches) {
  tiff("dem.tif", TiffSpec{});
  const RunConfig off = load(write("off.run", "DEM=dem.tif\nInitial Fluid Height=0.5\n"));
  expectInputError([&] { talus::sim::requireMaterial(talus::sim::loadScene(off), off); },
                   {"off.run", "nothing to move", "'Include Initial Water' is 0", "'Include Initial Solids' is 0"});
  const RunConfig zero = load(write("zero.run", "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=0\n"));
  expectInputError([&] { talus::sim::requireMaterial(talus::sim::loadScene(zero), zero); },
                   {"'Initial Fluid Height' is 0 in every cell"});
  const RunConfig wet = load(write("wet.run", "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=0.5\n"));
  EXPECT_NO_THROW(talus::sim::requireMaterial(talus::sim::loadScene(wet), wet));
}

// ---------------------------------------------------------------------------------------------
// Memory
// ---------------------------------------------------------------------------------------------

TEST_F(Geodata, AvailableMemoryIsKnownAndBelowThePhysicalMemory) {
  const double available = static_cast<double>(talus::availableMemoryBytes());
  const double physical = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * ::sysconf(_SC_PAGESIZE);
  EXPECT_GT(available, 0.0);
  EXPECT_LE(available, physical);
  EXPECT_EQ(talus::formatBytes(3.6e9), "3.6 GB");
}

// Before: a small sparse GeoTIFF declaring 20000x20000 cells was allocated (3.6 GB) and ended in
// std::bad_alloc ("too large to load", or the OOM killer on an overcommitting machine).
TEST_F(Geodata, RasterLargerThanTheMemoryLeftIsRefusedBeforeAllocating) {
#ifdef TALUS_TEST_ASAN
  GTEST_SKIP() << "RLIMIT_AS does not work under AddressSanitizer";
#else
  TiffSpec t;
  t.nx = t.ny = 20000;
  t.sparse = true;
  const std::string big = tiff("sparse.tif", t);
  ASSERT_LT(fs::file_size(big), 1u << 20) << "the test file should be small";
  expectChildInputError(inLimitedChild(dir_ / "child.txt", 1ull << 30, [&] { talus::io::readRaster(big); }),
                        {big, "20000x20000", "400000000", "3.6 GB", "available"});
#endif
}

// Before: the scene loaded and the solver's allocations failed later (or the machine swapped).
TEST_F(Geodata, RunWhoseGridsExceedTheMemoryLeftIsRefusedAtLoading) {
#ifdef TALUS_TEST_ASAN
  GTEST_SKIP() << "RLIMIT_AS does not work under AddressSanitizer";
#else
  // 3000 x 3000 cells: the scene's own maps take ~0.4 GB; the solver needs 19 floats a cell
  // (0.68 GB) plus four double output maps (0.29 GB), more than the 0.6 GB headroom leaves.
  TiffSpec t;
  t.nx = t.ny = 3000;
  t.sparse = true;
  t.hasNodata = false;
  tiff("dem.tif", t);
  const std::string run = write("case.run", "DEM=dem.tif\n");
  const auto loadIt = [&] { talus::sim::loadScene(RunConfig::load(run, talusRunKeys())); };
  expectChildInputError(inLimitedChild(dir_ / "child.txt", 600ull << 20, loadIt),
                        {"3000x3000", "19 arrays of float", "available", "dem.tif"});
  // The same scene loads when the memory is there (the estimate is not a blanket refusal).
  const ChildResult ok = inLimitedChild(dir_ / "child2.txt", 4ull << 30, loadIt);
  EXPECT_EQ(ok.code, 2) << ok.what;
#endif
}

// ---------------------------------------------------------------------------------------------
// Run-files: bounded reading, quoting, control characters
// ---------------------------------------------------------------------------------------------

// Before: `talus run /dev/zero` read until memory ran out.
TEST_F(Geodata, RunFileThatIsADeviceOrHugeIsRefused) {
  expectInputError([&] { load("/dev/zero"); }, {"/dev/zero", "not a regular file"});
  std::string huge(5u << 20, '#');
  const std::string big = write("big.run", "DEM=dem.tif\n" + huge + "\n");
  expectInputError([&] { load(big); }, {big, "MiB"});
}

// Before: one 8 MiB misspelt key took 36 s of spelling suggestions and an 8 MiB message.
TEST_F(Geodata, LongMisspeltKeyCostsLittleAndItsMessageIsShort) {
  const std::string key(8u << 20, 'x');
  const auto start = std::chrono::steady_clock::now();
  const std::string what = expectInputError(
      [&] { RunConfig::fromText(key + "=1\nDEM=dem.tif\n", dir_.string(), talusRunKeys(), "long.run"); },
      {"long.run:1", "unknown key", "(8388608 bytes)"});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // A linear pass over 8 MiB takes milliseconds; 5 s leaves room for a slow, loaded CI machine
  // and is still far from the quadratic suggestion work (36 s) it replaces.
  EXPECT_LT(seconds, 5.0);
  EXPECT_LT(what.size(), 1000u);
  // An ordinary misspelling still gets its suggestion.
  expectInputError([&] { RunConfig::fromText("Maning=0.1\nDEM=dem.tif\n", dir_.string(), talusRunKeys(), "s.run"); },
                   {"did you mean 'Manning'"});
}

// Before: a map folder containing '=' gave a resolved run-file that did not read back.
TEST_F(Geodata, ResolvedRunFileReadsBackWithAwkwardPaths) {
  std::ofstream(dir_ / "dem.tif") << "placeholder";  // for the run-file before its Map Directory is set
  for (const std::string folder : {"maps=v2", "a#b;c", " padded ", "back\\slash", "\"quoted\""}) {
    SCOPED_TRACE("folder '" + folder + "'");
    fs::create_directories(dir_ / folder);
    std::ofstream(dir_ / folder / "dem.tif") << "placeholder";  // the parser only checks existence
    std::ofstream(dir_ / folder / "h=1.tif") << "placeholder";
    RunConfig cfg = RunConfig::fromText("DEM=dem.tif\nInclude Initial Water=1\n", dir_.string(), talusRunKeys(), "c.run");
    // Through --set, quoted, so that the folder's own characters reach the parser unchanged.
    std::string quoted = "\"";
    for (char c : folder) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    quoted += "\"";
    cfg.set("Map Directory=" + quoted);
    cfg.set("Initial Fluid Height=\"h=1.tif\"=0.5");
    cfg.set("Device=  spaced = text  ");
    ASSERT_EQ(cfg.directory("Map Directory"), (dir_ / folder).string());
    const RunConfig back = RunConfig::fromText(cfg.echo(), dir_.string(), talusRunKeys(), "run.resolved.run");
    EXPECT_EQ(back.directory("Map Directory"), (dir_ / folder).string());
    EXPECT_EQ(back.map("DEM").file, (dir_ / folder / "dem.tif").string());
    EXPECT_EQ(back.map("Initial Fluid Height").file, (dir_ / folder / "h=1.tif").string());
    EXPECT_EQ(back.map("Initial Fluid Height").multiplier, 0.5);
    EXPECT_EQ(back.text("Device"), cfg.text("Device"));
  }
  // Old run-files read as before: an unquoted '=' still starts a multiplier, backslashes are
  // folder separators.
  fs::create_directories(dir_ / "maps");
  std::ofstream(dir_ / "maps" / "dem.tif") << "placeholder";
  const RunConfig old = RunConfig::fromText("DEM=maps\\dem.tif\nManning=0.05=2\n", dir_.string(), talusRunKeys());
  EXPECT_EQ(old.map("DEM").file, (dir_ / "maps" / "dem.tif").string());
  EXPECT_DOUBLE_EQ(old.map("Manning").constant * old.map("Manning").multiplier, 0.1);
  expectInputError([&] { RunConfig::fromText("DEM=\"dem.tif\n", dir_.string(), talusRunKeys(), "q.run"); },
                   {"q.run:1", "no closing"});
}

// Before: a newline inside --set injected a line into run.resolved.run.
TEST_F(Geodata, ControlCharactersInSetAreRefusedNamingTheKey) {
  fs::create_directories(dir_ / "maps");
  std::ofstream(dir_ / "maps" / "dem.tif") << "placeholder";
  RunConfig cfg = RunConfig::fromText("DEM=maps/dem.tif\n", dir_.string(), talusRunKeys(), "c.run");
  for (const std::string& bad : {std::string("Device=gpu\nEnd Time=999"), std::string("Device=a\rb"),
                                std::string("Device=a") + '\0' + "b", std::string("Device=\x1b[2J")}) {
    expectInputError([&] { cfg.set(bad); }, {"command line --set", "key 'Device'", "control character"});
  }
  EXPECT_EQ(cfg.text("Device"), "");
  cfg.set("Device=\tpocl\t");  // a tab is blank space, as in a run-file line
  EXPECT_EQ(cfg.text("Device"), "pocl");
}

// ---------------------------------------------------------------------------------------------
// Times in minutes
// ---------------------------------------------------------------------------------------------

TEST_F(Geodata, MinutesLandOnTheReportGridWithinRoundOff) {
  using talus::sim::minutesOnReportGrid;
  EXPECT_EQ(minutesOnReportGrid(0.0833333, 5.0), 5.0);   // 4.999998 s: 4e-7 relative off
  EXPECT_EQ(minutesOnReportGrid(1.0 / 12.0, 5.0), 5.0);
  EXPECT_EQ(minutesOnReportGrid(0.08333, 5.0), 60 * 0.08333);  // 4 digits: 4e-5 off, meant as given
  EXPECT_EQ(minutesOnReportGrid(0.5, 7.0), 30.0);  // not near a report time: unchanged
  EXPECT_EQ(minutesOnReportGrid(0.01, 60.0), 0.6);  // shorter than one interval: unchanged
}

// Before: End Time 0.0833333 min ended at 4.999998 s, and the 5 s report was never written; a
// Checkpoint Interval equal to End Time wrote no checkpoint.
TEST_F(Geodata, EndTimeInMinutesWritesItsLastReportAndItsCheckpoint) {
  TiffSpec t;
  tiff("dem.tif", t);
  const std::string run = write("case.run",
                                "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=0.05\nEnd Time=0.0833333\n"
                                "Timestep=5\nCheckpoint Interval=0.0833333\nCheckpoint Wall Interval=0\n"
                                "Precision=double\nOutput Directory=out\n");
  const RunConfig cfg = load(run);
  const talus::sim::Scene scene = talus::sim::loadScene(cfg);
  EXPECT_EQ(scene.endTime, 5.0);
  talus::sim::Simulation sim(scene, cfg, "", talus::sim::OutputMode::New);
  const talus::sim::RunSummary s = sim.run(nullptr);
  EXPECT_EQ(s.simulatedSeconds, 5.0);
  const std::string index = talus::test::slurp(path("out/series/index.csv"));
  EXPECT_TRUE(contains(index, "1,5,series/hf_0001")) << index;
  EXPECT_EQ(s.checkpoints, 1);
  EXPECT_TRUE(fs::exists(path("out/checkpoint.bin")));
}
