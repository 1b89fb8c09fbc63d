// Hostile and malformed input: raster headers that lie, degenerate georeferences, binary garbage and
// absurd lines in run-files, paths of the wrong kind, unwritable output folders, map values outside
// their key's range. Every case must end in a talus::InputError (exit status 2 from the command line)
// whose message names the file, key, line or cell at fault; none may crash or allocate what a header
// merely claims. Complements test_raster_io.cpp, test_runfile.cpp, test_scene.cpp and test_cli.cpp;
// the fuzz targets in fuzz/ search the same surfaces at random.
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/Error.hpp"
#include "core/Grid.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"

#ifndef TALUS_BINARY
#define TALUS_BINARY ""
#endif

// Address-space limits (RLIMIT_AS) cannot be used under AddressSanitizer, which reserves terabytes.
#if defined(__SANITIZE_ADDRESS__)
#define TALUS_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TALUS_TEST_ASAN 1
#endif
#endif

namespace fs = std::filesystem;
using talus::Grid;
using talus::InputError;
using talus::Raster;
using talus::io::RunConfig;
using talus::sim::talusRunKeys;

#include "support/CliRun.hpp"
#include "support/ExpectInputError.hpp"

namespace {

using talus::test::Outcome;
using talus::test::shellQuote;
using talus::test::slurp;

using talus::test::contains;
using talus::test::expectInputError;

/// A small georeferenced raster (12 x 10 cells of 2 m) filled by f(i, j).
Raster gridRaster(const std::function<double(int, int)>& f) {
  Grid g = Grid::make(12, 10, 2.0, 500000.0, 5100000.0);
  Raster r(g, 0.0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) r.at(i, j) = f(i, j);
  return r;
}

/// Fixture: a fresh temporary folder per test (removed afterwards), with writers for text, bytes
/// and rasters, and a runner for the talus executable.
class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_hostile_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string path(const std::string& rel) const { return (dir_ / rel).string(); }
  /// Writes bytes (any, NULs included) to a file under the temp folder; returns its path.
  std::string write(const std::string& rel, const std::string& bytes) {
    const fs::path p = dir_ / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }
  std::string writeMap(const std::string& rel, const Raster& r, bool float64 = false) {
    const std::string p = path(rel);
    fs::create_directories(fs::path(p).parent_path());
    talus::io::writeRaster(p, r, talus::io::RasterFormat::GeoTiff, float64);
    return p;
  }
  /// A tiny valid scene: dem.tif (a gentle slope) and the run-file `name` with `extra` appended,
  /// then a 1 cm film of water (a scene with nothing to move is refused).
  std::string writeScene(const std::string& extra, const std::string& name = "case.run") {
    writeMap("dem.tif", gridRaster([](int i, int) { return 10.0 + 0.1 * i; }));
    return write(name, "[Talus run file]\nDEM=dem.tif\nEnd Time=0.01\nTimestep=60\n" + extra +
                           "\nInclude Initial Water=1\nInitial Fluid Height=0.01\n");
  }
  talus::sim::Scene loadScene(const std::string& runFile) {
    const RunConfig cfg = RunConfig::load(runFile, talusRunKeys());
    return talus::sim::loadScene(cfg);
  }

  /// Runs `talus ARGS` (already shell-quoted as needed) in the temp folder.
  Outcome talus(const std::string& args) {
    return talus::test::runIn(dir_, TALUS_BINARY, args);
  }
  void requireBinary() {
    ASSERT_FALSE(std::string(TALUS_BINARY).empty()) << "TALUS_BINARY is not defined (tests/CMakeLists.txt)";
    ASSERT_TRUE(fs::is_regular_file(TALUS_BINARY)) << "talus executable not found at " << TALUS_BINARY;
  }

  fs::path dir_;
};

const char* kAsciiTail = "xllcorner 0\nyllcorner 0\ncellsize 5\nNODATA_value -9999\n1 2 3\n4 5 6\n";

}  // namespace

// ---------------------------------------------------------------------------------------------
// Rasters
// ---------------------------------------------------------------------------------------------

TEST_F(HostileInput, AsciiHeaderClaimingEnormousGridIsRefusedBeforeAllocating) {
  // 10^16 cells claimed by a 100-byte file: refused on the header (GDAL's ESRI ASCII driver already
  // refuses to open it), so there is nothing to allocate; the test finishes at once.
  const std::string huge = write("huge.asc", std::string("ncols 100000000\nnrows 100000000\n") + kAsciiTail);
  expectInputError([&] { talus::io::readRaster(huge); }, {huge});
  // 2.5e9 cells: GDAL opens it, readRaster's cap (2^31 cells) refuses it before allocating.
  const std::string big = write("big.asc", std::string("ncols 50000\nnrows 50000\n") + kAsciiTail);
  expectInputError([&] { talus::io::readRaster(big); }, {big, "too large", "50000x50000"});
  // Dimensions at the int limit.
  const std::string wide = write("wide.asc", std::string("ncols 2147483647\nnrows 2\n") + kAsciiTail);
  expectInputError([&] { talus::io::readRaster(wide); }, {wide});
  // Zero, negative and non-numeric dimensions.
  for (const char* header : {"ncols 0\nnrows 3\n", "ncols -3\nnrows 2\n", "ncols 3\nnrows -2\n",
                             "ncols three\nnrows 2\n", "ncols 99999999999999999999\nnrows 2\n"}) {
    SCOPED_TRACE(header);
    const std::string p = write("dims.asc", std::string(header) + kAsciiTail);
    expectInputError([&] { talus::io::readRaster(p); }, {p});
  }
}

TEST_F(HostileInput, AsciiHeaderClaimingAGigacellWithLittleDataFailsWithoutAllocatingIt) {
  // FAILS UNTIL FIXED (src/io/RasterIO.cpp, readRaster): 40000 x 40000 = 1.6e9 cells is under the
  // 2^31-cell cap, so readRaster sizes and zero-fills 14.4 GB (values + mask) for a 120-byte file
  // before GDAL reports that the data are missing. On a machine with that much memory the zero-fill
  // succeeds (or the OOM killer ends the process); here the address space is limited to 1 GiB more
  // than the process already uses, so today the allocation fails and the error says "too large to
  // load" instead of naming the missing data. The fix: verify the data exist (e.g. read the last row,
  // or compare the file size with what the format needs) before allocating the full grid.
#ifdef TALUS_TEST_ASAN
  GTEST_SKIP() << "RLIMIT_AS does not work under AddressSanitizer";
#else
  const std::string p = write("liar.asc", std::string("ncols 40000\nnrows 40000\n") + kAsciiTail);
  const std::string report = path("child.txt");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0) << std::strerror(errno);
  if (child == 0) {
    long vmKb = 0;
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmSize:", 0) == 0) vmKb = std::atol(line.c_str() + 7);
    const rlim_t limit = static_cast<rlim_t>(vmKb) * 1024 + (1ull << 30);
    const rlimit rl{limit, limit};
    ::setrlimit(RLIMIT_AS, &rl);
    int code = 3;  // 0 InputError about the data, 1 InputError from the allocation, 2 other, 3 none
    std::string what = "nothing thrown";
    try {
      talus::io::readRaster(p);
    } catch (const InputError& e) {
      what = e.what();
      code = contains(what, "too large to load") ? 1 : 0;
    } catch (const std::exception& e) {
      what = e.what();
      code = 2;
    }
    std::ofstream(report) << what;
    std::_Exit(code);
  }
  int raw = 0;
  ASSERT_EQ(::waitpid(child, &raw, 0), child);
  ASSERT_TRUE(WIFEXITED(raw)) << "readRaster crashed (signal " << (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0) << ")";
  const std::string what = slurp(report);
  EXPECT_TRUE(contains(what, p)) << what;
  EXPECT_EQ(WEXITSTATUS(raw), 0) << "readRaster allocated the grid the header claims before checking the data "
                                    "(0 = InputError about the data, 1 = allocation failure, 2 = other exception, "
                                    "3 = no error): "
                                 << what;
#endif
}

TEST_F(HostileInput, NegativeOrNonFiniteCellSizeIsRefusedNamingFile) {
  for (const char* cellsize : {"-5", "0", "-0", "nan", "inf", "-inf"}) {
    SCOPED_TRACE(cellsize);
    const std::string p = write("neg.asc", std::string("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize ") +
                                               cellsize + "\nNODATA_value -9999\n1 2 3\n4 5 6\n");
    expectInputError([&] { talus::io::readRaster(p); }, {p});
  }
  // A GeoTIFF written with a negative pixel width (its geotransform, not its header, lies).
  Raster r = gridRaster([](int, int) { return 1.0; });
  r.grid.geoTransform[1] = -2.0;
  const std::string tif = writeMap("negwidth.tif", r);
  expectInputError([&] { talus::io::readRaster(tif); }, {tif, "negative"});
}

TEST_F(HostileInput, CellSizeWhoseAreaUnderflowsOrOverflowsIsRefused) {
  // FAILS UNTIL FIXED (src/io/RasterIO.cpp, readRaster, or sim/Scene.cpp): a positive, finite, square
  // cell size is all that is checked, so 1e-320 m (a subnormal: the cell area dx * dx is 0, and dx is
  // 0 as a float) and 1e200 m (dx * dx is inf) are accepted as grids; the solver then divides by a
  // zero area or steps with dt ~ 1e-320 s forever. Cell sizes need a sane range.
  for (const char* cellsize : {"1e-320", "1e200"}) {
    SCOPED_TRACE(cellsize);
    const std::string p = write("absurd.asc", std::string("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize ") +
                                                  cellsize + "\nNODATA_value -9999\n1 2 3\n4 5 6\n");
    expectInputError([&] { talus::io::readRaster(p); }, {p, "cell size"});
  }
}

TEST_F(HostileInput, AllNodataGeoTiffAsDemIsRefused) {
  Raster dem = gridRaster([](int, int) { return 5.0; });
  std::fill(dem.valid.begin(), dem.valid.end(), 0);
  const std::string demPath = writeMap("dem_nodata.tif", dem);
  const std::string run = write("case.run", "DEM=dem_nodata.tif\n");
  expectInputError([&] { loadScene(run); }, {demPath, "no valid cells"});
  // Also when only NaN is left: a Float64 DEM of NaN without a nodata value.
  Raster nan = gridRaster([](int, int) { return std::nan(""); });
  nan.nodata = 1e30;
  const std::string nanPath = writeMap("dem_nan.tif", nan, true);
  const std::string run2 = write("nan.run", "DEM=dem_nan.tif\n");
  expectInputError([&] { loadScene(run2); }, {nanPath, "no valid cells"});
}

TEST_F(HostileInput, DemMultiplierOverflowingToInfinityIsRefused) {
  // FAILS UNTIL FIXED (src/sim/Scene.cpp, loadScene): the DEM's multiplier is applied after
  // readRaster dropped non-finite cells, and nothing checks the product, so 1e300 x 1e10 = inf
  // enters the bed elevation of cells inside the domain (Scene promises no NaN/inf inside the domain).
  const std::string demPath =
      writeMap("dem.tif", gridRaster([](int i, int j) { return i == 3 && j == 4 ? 1e300 : 100.0; }), true);
  const std::string run = write("case.run", "DEM=dem.tif=1e10\n");
  expectInputError([&] { loadScene(run); }, {"DEM"});
}

TEST_F(HostileInput, MapPathThatIsADirectoryIsRefused) {
  fs::create_directories(path("maps/sub.tif"));
  writeMap("maps/dem.tif", gridRaster([](int, int) { return 1.0; }));
  // As a map key: the run-file parser names line, key and folder.
  const std::string msg = expectInputError(
      [&] { RunConfig::fromText("Map Directory=maps\nDEM=dem.tif\nInitial Fluid Height=sub.tif\nInclude Initial Water=1\n", dir_.string(),
                                talusRunKeys(), "case.run"); },
      {"case.run:3", "key 'Initial Fluid Height'", path("maps/sub.tif"), "folder"});
  expectInputError([&] { RunConfig::fromText("DEM=.\n", dir_.string(), talusRunKeys(), "case.run"); },
                   {"case.run:1", "key 'DEM'", "folder"});
  // Straight to the raster reader (an empty folder, and the temp folder itself).
  expectInputError([&] { talus::io::readRaster(path("maps/sub.tif")); }, {path("maps/sub.tif")});
  expectInputError([&] { talus::io::readRaster(dir_.string()); }, {dir_.string()});
  // A run-file path that is a folder.
  expectInputError([&] { RunConfig::load(path("maps"), talusRunKeys()); }, {path("maps"), "folder"});
}

TEST_F(HostileInput, ManningOutOfRangeInMapIsRefusedNamingFileKeyAndCell) {
  // Manning's declared range is [0, 1] s/m^(1/3); one cell of the map holds 1.5.
  writeMap("dem.tif", gridRaster([](int i, int) { return 10.0 + 0.1 * i; }));
  const std::string n = writeMap("n.tif", gridRaster([](int i, int j) { return i == 7 && j == 2 ? 1.5 : 0.03; }));
  const std::string run = write("case.run", "DEM=dem.tif\nManning=n.tif\n");
  expectInputError([&] { loadScene(run); }, {n, "Manning", "column 7, row 2"});
  // In range in the file, out of range after the multiplier.
  const std::string m = writeMap("m.tif", gridRaster([](int, int) { return 0.8; }));
  const std::string run2 = write("mult.run", "DEM=dem.tif\nManning=m.tif=2\n");
  expectInputError([&] { loadScene(run2); }, {m, "Manning", "column 0, row 0"});
  // Initial Fluid Height above its 10 km upper bound.
  const std::string h = writeMap("h.tif", gridRaster([](int i, int j) { return i == 0 && j == 9 ? 2e4 : 0.0; }));
  const std::string run3 = write("h.run", "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=h.tif\n");
  expectInputError([&] { loadScene(run3); }, {h, "Initial Fluid Height", "column 0, row 9"});
  // A negative roughness.
  const std::string neg = writeMap("neg.tif", gridRaster([](int i, int) { return i == 11 ? -0.01 : 0.03; }));
  const std::string run4 = write("neg.run", "DEM=dem.tif\nManning=neg.tif\n");
  expectInputError([&] { loadScene(run4); }, {neg, "Manning", "column 11"});
}

// ---------------------------------------------------------------------------------------------
// Run-files
// ---------------------------------------------------------------------------------------------

TEST_F(HostileInput, RunFileWithBinaryGarbageIsRefusedNamingLines) {
  write("dem.tif", "x");
  const std::string nul(1, '\0');
  // A line of control bytes, invalid UTF-8, a NUL ending a number, a NUL inside free text.
  const std::string text = "DEM=dem.tif\n"                     // 1
                           "\x01\x02\x03\x7f\xff\xfe\n"        // 2: no '='
                           "Limiter=\xc3\x28\n"                // 3: bad choice
                           "End Time=1" + nul + "\n"           // 4: bad number (the message is cut at the NUL)
                           "Device=\xc3\x28" + nul + "gpu\n";  // 5: free text, accepted as given
  const std::string msg = expectInputError(
      [&] { RunConfig::fromText(text, dir_.string(), talusRunKeys(), "case.run"); },
      {"case.run:2", "no '='", "case.run:3: key 'Limiter'", "case.run:4: key 'End Time'", "bad number"});
  EXPECT_FALSE(contains(msg, "case.run:5")) << msg;
  // The same bytes read from a file.
  const std::string file = write("garbage.run", text);
  expectInputError([&] { RunConfig::load(file, talusRunKeys()); }, {file + ":2", file + ":3", file + ":4"});
  // 64 KiB of pseudo-random bytes (deterministic), with and without NULs.
  std::string noise(64 * 1024, '\0');
  unsigned state = 2463534242u;
  for (char& c : noise) {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    c = static_cast<char>(state & 0xff);
  }
  expectInputError([&] { RunConfig::fromText(noise, dir_.string(), talusRunKeys(), "noise.run"); }, {"noise.run"});
  const std::string noiseFile = write("noise.run", noise);
  expectInputError([&] { RunConfig::load(noiseFile, talusRunKeys()); }, {noiseFile});
  // Only NULs: no line is a key, so the required DEM is missing.
  expectInputError([&] { RunConfig::fromText(std::string(4096, '\0'), dir_.string(), talusRunKeys(), "z.run"); },
                   {"z.run"});
}

TEST_F(HostileInput, NulByteInRunFileDoesNotCutOffTheErrorReport) {
  // FAILS UNTIL FIXED (src/io/RunConfig.cpp): messages quote run-file text byte for byte, and
  // InputError::what() is a C string, so a NUL in a quoted key name ends the whole report there: the
  // user sees "case.run:2: key 'CFL" and none of the later problems (nor the rest of line 2's).
  // Non-printable bytes in quoted text should be escaped (e.g. as \x00), which also keeps terminal
  // control sequences from a run-file off the user's terminal.
  write("dem.tif", "x");
  const std::string text = "DEM=dem.tif\nCFL" + std::string(1, '\0') + "=0.5\nEnd Time=abc\nLimiter\n";
  const std::string msg = expectInputError(
      [&] { RunConfig::fromText(text, dir_.string(), talusRunKeys(), "case.run"); },
      {"case.run:2", "unknown key", "case.run:3: key 'End Time'", "bad number", "case.run:4", "no '='"});
  EXPECT_FALSE(contains(msg, std::string(1, '\0'))) << "raw NUL in the message";
  const std::string esc = expectInputError(
      [&] { RunConfig::fromText("DEM=dem.tif\n\x1b[2J\x1b]0;owned\x07=1\n", dir_.string(), talusRunKeys(), "e.run"); },
      {"e.run:2", "unknown key"});
  EXPECT_FALSE(contains(esc, "\x1b")) << "raw escape sequence in the message";
}

TEST_F(HostileInput, RunFileWithBinaryGarbageExits2FromTheCommandLine) {
  requireBinary();
  writeScene("\x01\x02\x03" + std::string(1, '\0') + "\xff garbage\n");  // line 5
  const Outcome r = talus("run case.run --quiet");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "case.run:5")) << r;
  EXPECT_FALSE(fs::exists(path("output"))) << "no output before the run-file is valid";
}

TEST_F(HostileInput, RunFileWithExtremelyLongLines) {
  write("dem.tif", "x");
  // A 4 MiB free-text value is kept as given.
  const std::string longValue(4 * 1024 * 1024, 'g');
  const RunConfig c = RunConfig::fromText("DEM=dem.tif\nDevice=" + longValue + "\n", dir_.string(), talusRunKeys());
  EXPECT_EQ(c.text("Device"), longValue);
  // A 256 KiB unknown key name: refused at its line (the spelling suggestions stay bounded).
  const std::string longKey(256 * 1024, 'k');
  expectInputError([&] { RunConfig::fromText("DEM=dem.tif\n" + longKey + "=1\n", dir_.string(), talusRunKeys(), "l.run"); },
                   {"l.run:2", "unknown key"});
  // A 1 MiB number, a 1 MiB multiplier, a 1 MiB map path that does not exist.
  const std::string digits(1024 * 1024, '7');
  expectInputError([&] { RunConfig::fromText("DEM=dem.tif\nCFL=0." + digits + "x\n", dir_.string(), talusRunKeys(), "n.run"); },
                   {"n.run:2: key 'CFL'", "bad number"});
  expectInputError([&] { RunConfig::fromText("DEM=dem.tif\nCFL=0.5=" + digits + "\n", dir_.string(), talusRunKeys(), "m.run"); },
                   {"m.run:2: key 'CFL'"});
  expectInputError([&] { RunConfig::fromText("DEM=" + digits + ".tif\n", dir_.string(), talusRunKeys(), "p.run"); },
                   {"p.run:1: key 'DEM'", "does not exist"});
  // A single 8 MiB line without a newline or '='.
  expectInputError([&] { RunConfig::fromText(std::string(8 * 1024 * 1024, 'a'), dir_.string(), talusRunKeys(), "a.run"); },
                   {"a.run:1", "no '='"});
}

TEST_F(HostileInput, KeysRepeatedInDifferentCaseAndSpacingAreRefused) {
  write("dem.tif", "x");
  const std::string msg = expectInputError(
      [&] {
        RunConfig::fromText("DEM=dem.tif\nmanning=0.02\nMANNING=0.03\n  MaNnInG  =0.04\nEnd Time=2\nend   TIME=3\n"
                            "dem=dem.tif\n",
                            dir_.string(), talusRunKeys(), "case.run");
      },
      {"case.run:3: key 'Manning': given twice, at case.run:2", "case.run:4: key 'Manning'",
       "case.run:6: key 'End Time': given twice, at case.run:5", "case.run:7: key 'DEM'"});
  // A repeated key through --set replaces the value instead (the command line overrides the file).
  RunConfig c = RunConfig::fromText("DEM=dem.tif\nManning=0.02\n", dir_.string(), talusRunKeys());
  c.set("MANNING=0.05");
  EXPECT_DOUBLE_EQ(c.map("Manning").constant, 0.05);
}

// ---------------------------------------------------------------------------------------------
// Output folders (through the command line: exit status 2 before any device work)
// ---------------------------------------------------------------------------------------------

TEST_F(HostileInput, OutputFolderThatIsAFileExits2) {
  requireBinary();
  writeScene("");
  const std::string blocker = write("results", "I am a file");
  const Outcome r = talus("run case.run --quiet --out results");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, blocker)) << r;
  EXPECT_EQ(slurp(blocker), "I am a file") << "the file in the way must be left alone";
  // A folder below a file, given in the run-file.
  writeScene("Output Directory=results/run1\n", "below.run");
  const Outcome below = talus("run below.run --quiet");
  EXPECT_EQ(below.status, 2) << below;
  EXPECT_TRUE(contains(below.err, path("results/run1"))) << below;
}

TEST_F(HostileInput, OutputFolderInUnwritableLocationExits2) {
  requireBinary();
  writeScene("");
  // Nobody, root included, can make folders in /proc.
  const Outcome r = talus("run case.run --quiet --out /proc/talus_out");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "/proc/talus_out")) << r;
  EXPECT_FALSE(fs::exists("/proc/talus_out"));
  // The same through the run-file key.
  writeScene("Output Directory=/proc/talus_out/deeper\n", "proc.run");
  const Outcome key = talus("run proc.run --quiet");
  EXPECT_EQ(key.status, 2) << key;
  EXPECT_TRUE(contains(key.err, "/proc/talus_out/deeper")) << key;
}

// Found by the raster fuzzer in CI: a 257-byte TIFF whose strip is declared 2^32 rows high made GDAL
// allocate 4 GB on the first read. readRaster must refuse it by name before any read.
// And a 436-byte TIFF of 65282 x 2 cells with 3584 pixel-interleaved Float64 bands in one strip:
// GDAL reads the whole interleaved block (3.7 GB) to give band 1.
TEST_F(HostileInput, TiffDeclaringHugeBlocksIsRefusedBeforeReading) {
  for (const char* name : {"oom_huge_strip.tif.bin", "oom_interleaved_bands.tif.bin"}) {
    const std::string input = slurp(std::string(TALUS_TEST_DATA_DIR) + "/../tests/data/" + name);
    ASSERT_GT(input.size(), 1u) << "tests/data/" << name << " missing";
    const std::string file = write(std::string(name) + ".tif", input.substr(1));  // byte 0 chose the extension
    try {
      talus::io::readRaster(file);
      ADD_FAILURE() << name << ": a TIFF with absurd block sizes was accepted";
    } catch (const talus::InputError& e) {
      EXPECT_TRUE(contains(e.what(), file)) << e.what();
      EXPECT_TRUE(contains(e.what(), "declares")) << e.what();
    }
  }
}
