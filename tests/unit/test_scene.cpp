// End-to-end tests of scene loading (sim/Scene) and of the simulation loop with its output folder
// (sim/Simulation, sim/OutputWriter): small scenes are written to a per-test temporary folder (maps
// through io::writeRaster, run-files as text), loaded, run on the test device and their outputs read
// back. Volume balance is checked in double precision; everything else at the file level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/Error.hpp"
#include "core/Grid.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"
#include "support/ExpectInputError.hpp"

namespace fs = std::filesystem;
using talus::Grid;
using talus::InputError;
using talus::Raster;
using talus::io::RunConfig;
using talus::sim::talusRunKeys;

namespace {

/// A projected coordinate system (EPSG:32633, WGS 84 / UTM zone 33N) for the georeference checks.
const char* kUtm33Wkt =
    "PROJCS[\"WGS 84 / UTM zone 33N\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,"
    "298.257223563,AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,"
    "AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],"
    "AUTHORITY[\"EPSG\",\"4326\"]],PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],"
    "PARAMETER[\"central_meridian\",15],PARAMETER[\"scale_factor\",0.9996],PARAMETER[\"false_easting\",500000],"
    "PARAMETER[\"false_northing\",0],UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],"
    "AXIS[\"Northing\",NORTH],AUTHORITY[\"EPSG\",\"32633\"]]";

constexpr int kNx = 20, kNy = 16;
constexpr double kX0 = 512000.0, kY0 = 5160000.0;

using talus::test::contains;
using talus::test::expectInputError;

/// A raster on the scenes' georeferenced grid, filled by f(i, j).
Raster gridRaster(const std::function<double(int, int)>& f, double dx = 2.0, int nx = kNx, int ny = kNy) {
  Grid g = Grid::make(nx, ny, dx, kX0, kY0);
  g.projectionWkt = kUtm33Wkt;
  Raster r(g, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) r.at(i, j) = f(i, j);
  return r;
}

/// Reads a whole text file.
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream o;
  o << in.rdbuf();
  return o.str();
}

/// The comma-separated rows of a CSV file (header included).
std::vector<std::vector<std::string>> readCsv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

/// Fixture: a fresh temporary folder per test (removed afterwards) and scene builders.
class Scene : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_scene_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::remove_all(dir_);
  }

  std::string path(const std::string& rel) const { return (dir_ / rel).string(); }
  std::string writeMap(const std::string& name, const Raster& r) {
    talus::io::writeRaster(path(name), r);
    return path(name);
  }
  std::string writeRun(const std::string& text, const std::string& name = "case.run") {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  RunConfig load(const std::string& runFile) { return RunConfig::load(runFile, talusRunKeys()); }
  talus::sim::Scene loadScene(const std::string& runFile) { return talus::sim::loadScene(load(runFile)); }

  fs::path dir_;
};

/// DEM of the loading tests: a gentle slope with nodata in two corners and the whole of column 7.
Raster loadingDem() {
  Raster dem = gridRaster([](int i, int j) { return 100.0 + 0.5 * i + 0.25 * j; });
  dem.valid[dem.grid.index(0, 0)] = 0;
  dem.valid[dem.grid.index(kNx - 1, kNy - 1)] = 0;
  for (int j = 0; j < kNy; ++j) dem.valid[dem.grid.index(7, j)] = 0;
  return dem;
}

/// water.tif of the loading tests: 1 m in a block, 0 elsewhere, nodata where the DEM has none.
Raster loadingWater(const Raster& dem) {
  Raster w = gridRaster([](int i, int j) { return (i >= 2 && i < 6 && j >= 3 && j < 9) ? 1.0 : 0.0; });
  w.valid = dem.valid;
  return w;
}

const char* kLoadingRun =
    "[openLISEM runfile version 6.0]\n"
    "[Input]\n"
    "DEM=dem.tif\n"
    "Include Initial Water=1\n"
    "Initial Fluid Height=water.tif=0.5\n"
    "[Flow]\n"
    "Manning=0.05=2\n"
    "[Time]\n"
    "Start Time=1\n"
    "End Time=2.5\n"
    "Timestep=15\n"
    "[Numerics]\n"
    "CFL=0.4\n"
    "Precision=double\n"
    "[Output]\n"
    "Output Directory=out/run1\n"
    "Output Format=pcraster\n";

}  // namespace

// ---------------------------------------------------------------------------------------------
// Loading
// ---------------------------------------------------------------------------------------------

TEST_F(Scene, LoadsValidRunFile) {
  const Raster dem = loadingDem();
  writeMap("dem.tif", dem);
  writeMap("water.tif", loadingWater(dem));
  const talus::sim::Scene s = loadScene(writeRun(kLoadingRun));

  ASSERT_EQ(s.dem.grid.nx, kNx);
  ASSERT_EQ(s.dem.grid.ny, kNy);
  EXPECT_TRUE(talus::sameGrid(s.dem.grid, dem.grid));
  ASSERT_EQ(s.flow.mask.size(), dem.grid.cells());
  ASSERT_EQ(s.flow.h.size(), dem.grid.cells());
  ASSERT_EQ(s.flow.manning.size(), dem.grid.cells());
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const std::size_t k = dem.grid.index(i, j);
      SCOPED_TRACE("cell " + std::to_string(i) + "," + std::to_string(j));
      EXPECT_EQ(s.flow.mask[k], dem.valid[k]);  // mask from the DEM's nodata
      if (!dem.valid[k]) continue;
      // The solvers' bed is the DEM above its lowest valid cell (the local origin, sim/Scene.cpp).
      EXPECT_DOUBLE_EQ(s.flow.bed[k], dem.values[k] - s.elevationOrigin);
      EXPECT_LE(s.elevationOrigin, dem.values[k]);
      const bool block = i >= 2 && i < 6 && j >= 3 && j < 9;
      EXPECT_DOUBLE_EQ(s.flow.h[k], block ? 0.5 : 0.0);  // water.tif times 0.5
      EXPECT_DOUBLE_EQ(s.flow.manning[k], 0.1);           // the number 0.05 times 2, uniform
    }
  EXPECT_DOUBLE_EQ(s.startTime, 60.0);  // minutes -> seconds
  EXPECT_DOUBLE_EQ(s.endTime, 150.0);
  EXPECT_DOUBLE_EQ(s.reportInterval, 15.0);  // Timestep is in seconds already
  EXPECT_DOUBLE_EQ(s.settings.cfl, 0.4);
  EXPECT_EQ(s.precision, "double");
  EXPECT_EQ(s.format, talus::io::RasterFormat::PCRaster);
  EXPECT_EQ(fs::path(s.outputDir), fs::path(path("out/run1")));
  EXPECT_TRUE(contains(s.runFile, "case.run"));
}

TEST_F(Scene, InitialWaterIgnoredUnlessIncluded) {
  const Raster dem = loadingDem();
  writeMap("dem.tif", dem);
  writeMap("water.tif", loadingWater(dem));
  const talus::sim::Scene s = loadScene(writeRun("DEM=dem.tif\nInitial Fluid Height=water.tif\n"));
  for (double h : s.flow.h) EXPECT_EQ(h, 0.0);
}

TEST_F(Scene, MapOnDifferentGridNamesBothFiles) {
  const Raster dem = loadingDem();
  writeMap("dem.tif", dem);
  Raster water = gridRaster([](int, int) { return 0.1; }, 2.0, kNx + 1, kNy);
  writeMap("water.tif", water);
  const std::string run = writeRun("DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n");
  expectInputError([&] { loadScene(run); }, {path("dem.tif"), path("water.tif"), "does not share the grid"});
}

TEST_F(Scene, NodataHoleInsideDomainNamesFileAndCell) {
  const Raster dem = loadingDem();
  writeMap("dem.tif", dem);
  Raster water = loadingWater(dem);
  water.valid[water.grid.index(3, 11)] = 0;
  writeMap("water.tif", water);
  const std::string run = writeRun("DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n");
  expectInputError([&] { loadScene(run); },
                   {path("water.tif"), "Initial Fluid Height", "column 3", "row 11", "no data"});
}

TEST_F(Scene, NegativeThicknessNamesCell) {
  const Raster dem = loadingDem();
  writeMap("dem.tif", dem);
  Raster water = loadingWater(dem);
  water.at(12, 5) = -0.25;
  writeMap("water.tif", water);
  const std::string run = writeRun("DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n");
  expectInputError([&] { loadScene(run); }, {path("water.tif"), "column 12", "row 5", "-0.25"});
}

TEST_F(Scene, NegativeManningMapNamesCell) {
  const Raster dem = loadingDem();
  writeMap("dem.tif", dem);
  Raster n = gridRaster([](int, int) { return 0.03; });
  n.at(4, 2) = -0.01;
  writeMap("n.tif", n);
  const std::string run = writeRun("DEM=dem.tif\nManning=n.tif\n");
  expectInputError([&] { loadScene(run); }, {path("n.tif"), "Manning", "column 4", "row 2"});
}

TEST_F(Scene, DemGivenAsNumberIsRefused) {
  const std::string run = writeRun("[Input]\nDEM=100\n");
  expectInputError([&] { loadScene(run); }, {"case.run:2", "DEM", "raster file"});
}

TEST_F(Scene, DemWithoutValidCellsIsRefused) {
  Raster dem = gridRaster([](int, int) { return 5.0; });
  std::fill(dem.valid.begin(), dem.valid.end(), 0);
  writeMap("dem.tif", dem);
  const std::string run = writeRun("DEM=dem.tif\n");
  expectInputError([&] { loadScene(run); }, {path("dem.tif"), "no valid cells"});
}

TEST_F(Scene, MissingMapFileNamesFileLineAndKey) {
  writeMap("dem.tif", loadingDem());
  const std::string run =
      writeRun("[Input]\nDEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=nothere.tif\n");
  expectInputError([&] { loadScene(run); },
                   {"case.run:4", "key 'Initial Fluid Height'", path("nothere.tif"), "does not exist"});
}

TEST_F(Scene, MisspeltKeySuggestsName) {
  writeMap("dem.tif", loadingDem());
  const std::string run = writeRun("DEM=dem.tif\nManing=0.05\n");
  expectInputError([&] { loadScene(run); }, {"case.run:2", "Maning", "did you mean 'Manning'"});
}

// ---------------------------------------------------------------------------------------------
// Simulation (library API)
// ---------------------------------------------------------------------------------------------

namespace {

/// Everything of a finished library run (config and scene outlive the Simulation that refers to them).
struct LibRun {
  RunConfig config;
  talus::sim::Scene scene;
  talus::sim::RunSummary summary;
};

LibRun runScene(const std::string& runFile, long long* progressCalls = nullptr) {
  RunConfig cfg = RunConfig::load(runFile, talusRunKeys());
  talus::sim::Scene scene = talus::sim::loadScene(cfg);
  LibRun r{std::move(cfg), std::move(scene), {}};
  talus::sim::Simulation sim(r.scene, r.config, "", talus::sim::OutputMode::New);
  r.summary = sim.run([&](const talus::sim::Progress&) {
    if (progressCalls) ++*progressCalls;
  });
  return r;
}

/// Compares every declared key of two configurations by value.
void expectSameValues(const RunConfig& a, const RunConfig& b) {
  using talus::io::KeyType;
  for (const talus::io::KeySpec& k : talusRunKeys().keys()) {
    SCOPED_TRACE("key " + k.name);
    switch (k.type) {
      case KeyType::Flag: EXPECT_EQ(a.flag(k.name), b.flag(k.name)); break;
      case KeyType::Integer:
      case KeyType::Real: EXPECT_EQ(a.real(k.name), b.real(k.name)); break;
      case KeyType::Choice: EXPECT_EQ(a.choice(k.name), b.choice(k.name)); break;
      case KeyType::Text: EXPECT_EQ(a.text(k.name), b.text(k.name)); break;
      case KeyType::Directory: EXPECT_EQ(a.directory(k.name), b.directory(k.name)); break;
      case KeyType::Map: {
        const talus::io::MapValue ma = a.map(k.name), mb = b.map(k.name);
        EXPECT_EQ(ma.isFile, mb.isFile);
        EXPECT_EQ(ma.file, mb.file);
        EXPECT_EQ(ma.constant, mb.constant);
        EXPECT_EQ(ma.multiplier, mb.multiplier);
        break;
      }
    }
  }
}

}  // namespace

TEST_F(Scene, ClosedBasinConservesVolume) {
  // A bowl with a column of water on its dry flank; walls all round, wetting and drying inside.
  writeMap("dem.tif", gridRaster([](int i, int j) {
             const double x = i - 9.5, y = j - 7.5;
             return 0.01 * (x * x + y * y);
           }, 1.0));
  writeMap("water.tif", gridRaster([](int i, int j) { return (i < 6 && j < 6) ? 0.5 : 0.0; }, 1.0));
  const std::string run = writeRun(
      "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\nManning=0.02\n"
      "End Time=0.05\nTimestep=1\nPrecision=double\nBoundary Type=wall\nOutput Directory=out\n");
  long long calls = 0;
  const LibRun r = runScene(run, &calls);
  EXPECT_GT(r.summary.steps, 10);
  EXPECT_EQ(calls, r.summary.steps);
  EXPECT_DOUBLE_EQ(r.summary.simulatedSeconds, 3.0);
  EXPECT_DOUBLE_EQ(r.summary.initialVolume, 36 * 0.5);
  EXPECT_EQ(r.summary.totalOutflow, 0.0);
  EXPECT_LT(std::fabs(r.summary.volumeBalanceError), 1e-12);
  EXPECT_LT(std::fabs(r.summary.finalVolume - r.summary.initialVolume), 1e-12 * r.summary.initialVolume);
  const std::string json = slurp(path("out/summary.json"));
  EXPECT_TRUE(contains(json, "\"status\": \"completed\"")) << json;
  EXPECT_TRUE(contains(json, "\"precision\": \"double\"")) << json;
}

namespace {

// The open tilted plane: bed falling 0.6 m per cell (dx = 2 m) towards the east edge, water 0.25 m
// deep in columns 10..14 (rows 2..13), dry upslope of it; nodata in three cells of row 0. The water
// runs out through the east edge; columns 0..5 lie 3 m and more above it and stay dry.
constexpr double kSlopeDrop = 0.6;
bool tiltedWet(int i, int j) { return i >= 10 && i <= 14 && j >= 2 && j <= 13; }
Raster tiltedDem() {
  Raster dem = gridRaster([](int i, int) { return 50.0 + kSlopeDrop * (kNx - 1 - i); });
  for (int i = 3; i < 6; ++i) dem.valid[dem.grid.index(i, 0)] = 0;
  return dem;
}
Raster tiltedWater() { return gridRaster([](int i, int j) { return tiltedWet(i, j) ? 0.25 : 0.0; }); }

const char* kTiltedRun =
    "[openLISEM runfile version 6.0]\n"
    "[Input]\n"
    "Map Directory=maps\n"
    "DEM=dem.tif\n"
    "Include Initial Water=1\n"
    "Initial Fluid Height=water.tif\n"
    "[Flow]\n"
    "Manning=0.03\n"
    "[Time]\n"
    "Start Time=0\n"
    "End Time=0.1\n"
    "Timestep=2.5\n"
    "[Numerics]\n"
    "Precision=double\n"
    "Boundary Type=open\n"
    "[Output]\n"
    "Arrival Threshold=0.01\n"
    "Output Directory=results/tilted\n";

}  // namespace

TEST_F(Scene, OpenTiltedPlaneRunAndOutputs) {
  fs::create_directories(path("maps"));
  const Raster dem = tiltedDem();
  const Raster water = tiltedWater();
  writeMap("maps/dem.tif", dem);
  writeMap("maps/water.tif", water);
  const std::string runFile = writeRun(kTiltedRun);
  const LibRun r = runScene(runFile);
  const talus::sim::RunSummary& s = r.summary;
  const std::string out = path("results/tilted");
  const Grid& g = dem.grid;

  // Volume: final + outflow == initial (double), and a good part of the water has left.
  EXPECT_DOUBLE_EQ(s.initialVolume, 5 * 12 * 0.25 * 4.0);
  EXPECT_GT(s.totalOutflow, 0.05 * s.initialVolume);
  EXPECT_LT(std::fabs(s.finalVolume + s.totalOutflow - s.initialVolume), 1e-12 * s.initialVolume);
  EXPECT_LT(std::fabs(s.volumeBalanceError), 1e-12);
  EXPECT_DOUBLE_EQ(s.simulatedSeconds, 6.0);

  // The output folder.
  for (const char* f : {"hffinal.tif", "hfmax.tif", "vfmax.tif", "tarrival.tif", "summary.json", "diagnostics.csv",
                        "run.resolved.run", "series/index.csv", "series/hf_0000.tif", "series/vf_0000.tif"})
    EXPECT_TRUE(fs::is_regular_file(out + "/" + f)) << f;
  for (const auto& e : fs::recursive_directory_iterator(out))
    EXPECT_FALSE(contains(e.path().filename().string(), ".tmp-")) << "temporary file left: " << e.path();

  // Maps: the DEM's georeference, nodata outside the domain, hfmax >= hffinal and >= initial h.
  const Raster demBack = talus::io::readRaster(path("maps/dem.tif"));
  const Raster hFinal = talus::io::readRaster(out + "/hffinal.tif");
  const Raster hMax = talus::io::readRaster(out + "/hfmax.tif");
  const Raster vMax = talus::io::readRaster(out + "/vfmax.tif");
  const Raster arrival = talus::io::readRaster(out + "/tarrival.tif");
  for (const Raster* m : {&hFinal, &hMax, &vMax, &arrival}) {
    EXPECT_TRUE(talus::sameGrid(m->grid, g));
    EXPECT_EQ(m->grid.geoTransform, demBack.grid.geoTransform);
    EXPECT_FALSE(m->grid.projectionWkt.empty());
    EXPECT_EQ(m->grid.projectionWkt, demBack.grid.projectionWkt);
  }
  bool someArrivedLater = false;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const std::size_t k = g.index(i, j);
      SCOPED_TRACE("cell " + std::to_string(i) + "," + std::to_string(j));
      if (!dem.valid[k]) {
        EXPECT_FALSE(hFinal.valid[k]);
        EXPECT_FALSE(hMax.valid[k]);
        EXPECT_FALSE(vMax.valid[k]);
        EXPECT_FALSE(arrival.valid[k]);
        continue;
      }
      ASSERT_TRUE(hFinal.valid[k] && hMax.valid[k] && vMax.valid[k]);
      EXPECT_GE(hMax.values[k], hFinal.values[k]);
      EXPECT_GE(hMax.values[k], water.values[k]);
      EXPECT_GE(vMax.values[k], 0.0);
      if (tiltedWet(i, j)) {
        ASSERT_TRUE(arrival.valid[k]);
        EXPECT_EQ(arrival.values[k], 0.0);  // water was there at t = 0
      } else if (i <= 5) {
        EXPECT_FALSE(arrival.valid[k]) << "water never reaches the upslope columns";
        EXPECT_EQ(hMax.values[k], 0.0);
      }
      if (arrival.valid[k] && arrival.values[k] > 0) {
        someArrivedLater = true;
        EXPECT_LE(arrival.values[k], 6.0);
        EXPECT_GE(hMax.values[k], 0.01 * (1 - 1e-6));
      }
    }
  EXPECT_TRUE(someArrivedLater) << "water should spread downslope of the block";

  // Series: floor((6 - 0) / 2.5) + 1 = 3 maps at exactly 0, 2.5 and 5 s.
  const auto index = readCsv(out + "/series/index.csv");
  ASSERT_EQ(index.size(), 4u);  // header + 3
  const double expectedTimes[] = {0.0, 2.5, 5.0};
  for (int n = 0; n < 3; ++n) {
    ASSERT_GE(index[n + 1].size(), 2u);
    EXPECT_EQ(std::stoi(index[n + 1][0]), n);
    EXPECT_EQ(std::stod(index[n + 1][1]), expectedTimes[n]);
    char name[64];
    std::snprintf(name, sizeof name, "/series/hf_%04d.tif", n);
    EXPECT_TRUE(fs::is_regular_file(out + name)) << name;
    std::snprintf(name, sizeof name, "/series/vf_%04d.tif", n);
    EXPECT_TRUE(fs::is_regular_file(out + name)) << name;
  }
  EXPECT_FALSE(fs::exists(out + "/series/hf_0003.tif"));
  int seriesMaps = 0;
  for (const auto& e : fs::directory_iterator(out + "/series"))
    if (e.path().filename().string().rfind("hf_", 0) == 0) ++seriesMaps;
  EXPECT_EQ(seriesMaps, 3);
  // The first series map is the initial state.
  const Raster h0 = talus::io::readRaster(out + "/series/hf_0000.tif");
  for (std::size_t k = 0; k < g.cells(); ++k) {
    if (dem.valid[k]) {
      EXPECT_EQ(h0.values[k], water.values[k]);
    }
  }

  // diagnostics.csv: one row per step, step numbers 1..N, time increasing, ending at the end time.
  const auto diag = readCsv(out + "/diagnostics.csv");
  ASSERT_EQ(static_cast<long long>(diag.size()), s.steps + 1);
  ASSERT_FALSE(diag[0].empty());
  EXPECT_EQ(diag[0][0], "step");
  EXPECT_EQ(diag[0][1], "time_s");
  double previous = 0.0;
  for (std::size_t n = 1; n < diag.size(); ++n) {
    ASSERT_GE(diag[n].size(), 2u);
    EXPECT_EQ(std::stoll(diag[n][0]), static_cast<long long>(n));
    const double t = std::stod(diag[n][1]);
    EXPECT_GT(t, previous) << "row " << n;
    previous = t;
  }
  EXPECT_EQ(previous, 6.0);
  // Report times fall on steps: 2.5 and 5 appear as step times.
  for (double t : {2.5, 5.0}) {
    bool found = false;
    for (std::size_t n = 1; n < diag.size(); ++n) found = found || std::stod(diag[n][1]) == t;
    EXPECT_TRUE(found) << "no step ends at report time " << t;
  }

  // summary.json.
  const std::string json = slurp(out + "/summary.json");
  EXPECT_TRUE(contains(json, "\"status\": \"completed\"")) << json;
  EXPECT_TRUE(contains(json, "\"steps\": " + std::to_string(s.steps))) << json;
  EXPECT_TRUE(contains(json, "\"nx\": 20, \"ny\": 16")) << json;

  // run.resolved.run parses again to the same values.
  const RunConfig again = RunConfig::fromText(slurp(out + "/run.resolved.run"), out, talusRunKeys(), "resolved.run");
  expectSameValues(r.config, again);

  // An existing run folder is refused without overwrite, accepted with it.
  expectInputError([&] { talus::sim::Simulation(r.scene, r.config, "", talus::sim::OutputMode::New); }, {out, "--overwrite"});
  EXPECT_TRUE(fs::is_regular_file(out + "/summary.json")) << "a refused run must not touch the old outputs";
  EXPECT_NO_THROW(talus::sim::Simulation(r.scene, r.config, "", talus::sim::OutputMode::Overwrite));
}

TEST_F(Scene, PCRasterOutputWritesMapFiles) {
  writeMap("dem.tif", tiltedDem());
  writeMap("water.tif", tiltedWater());
  const std::string run = writeRun(
      "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\n"
      "End Time=0.02\nTimestep=1\nOutput Format=pcraster\nOutput Directory=pcr\n");
  const LibRun r = runScene(run);
  const std::string out = path("pcr");
  for (const char* f : {"hffinal", "hfmax", "vfmax", "tarrival", "series/hf_0000", "series/vf_0001"}) {
    SCOPED_TRACE(f);
    EXPECT_TRUE(fs::is_regular_file(out + "/" + f + ".map"));
    EXPECT_FALSE(fs::exists(out + "/" + f + ".tif"));
  }
  const Raster h = talus::io::readRaster(out + "/hffinal.map");
  EXPECT_TRUE(talus::sameGrid(h.grid, r.scene.dem.grid));
  const std::string json = slurp(out + "/summary.json");
  EXPECT_TRUE(contains(json, "\"precision\": \"float\"")) << json;
}

TEST_F(Scene, OutputDirectoryArgumentOverridesRunFile) {
  writeMap("dem.tif", tiltedDem());
  const std::string runFile = writeRun("DEM=dem.tif\nEnd Time=0.01\nTimestep=60\nReport Series=0\n");
  const RunConfig cfg = RunConfig::load(runFile, talusRunKeys());
  const talus::sim::Scene scene = talus::sim::loadScene(cfg);
  talus::sim::Simulation sim(scene, cfg, path("elsewhere"), talus::sim::OutputMode::New);
  const talus::sim::RunSummary s = sim.run();
  // Dry scene: nothing moves, so the run is one step straight to the end time.
  EXPECT_EQ(s.steps, 1);
  EXPECT_EQ(s.initialVolume, 0.0);
  EXPECT_EQ(s.volumeBalanceError, 0.0);
  EXPECT_TRUE(fs::is_regular_file(path("elsewhere/summary.json")));
  EXPECT_FALSE(fs::exists(path("output")));
  EXPECT_FALSE(fs::exists(path("elsewhere/series/hf_0000.tif"))) << "Report Series=0 writes no series";
}

TEST_F(Scene, NonZeroStartTimeReportsAbsoluteTimes) {
  // Start Time 1 min, End Time 1.1 min: reports at 60, 62.5, 65 s; arrival times are simulated times
  // like the series and diagnostics times, so water present at the start arrived at 60 s.
  writeMap("dem.tif", tiltedDem());
  writeMap("water.tif", tiltedWater());
  const std::string run = writeRun(
      "DEM=dem.tif\nInclude Initial Water=1\nInitial Fluid Height=water.tif\nPrecision=double\n"
      "Start Time=1\nEnd Time=1.1\nTimestep=2.5\nOutput Directory=late\n");
  const LibRun r = runScene(run);
  EXPECT_DOUBLE_EQ(r.summary.simulatedSeconds, 6.0);
  const std::string out = path("late");
  const auto index = readCsv(out + "/series/index.csv");
  ASSERT_EQ(index.size(), 4u);
  for (int n = 0; n < 3; ++n) EXPECT_EQ(std::stod(index[n + 1][1]), 60.0 + 2.5 * n);
  const auto diag = readCsv(out + "/diagnostics.csv");
  ASSERT_GT(diag.size(), 1u);
  EXPECT_GT(std::stod(diag[1][1]), 60.0);
  EXPECT_EQ(std::stod(diag.back()[1]), 66.0);
  const Raster arrival = talus::io::readRaster(out + "/tarrival.tif");
  // Every cell's arrival is checked; mismatches are counted and the first one is named.
  const Grid& g = arrival.grid;
  int wrongInitial = 0, wrongLater = 0;
  std::string firstWrong;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const std::size_t k = g.index(i, j);
      if (!arrival.valid[k]) continue;
      const double t = arrival.values[k];
      const bool ok = tiltedWet(i, j) ? t == 60.0 : (t > 60.0 && t <= 66.0);
      if (ok) continue;
      ++(tiltedWet(i, j) ? wrongInitial : wrongLater);
      if (firstWrong.empty())
        firstWrong = "cell (" + std::to_string(i) + ", " + std::to_string(j) + ") has arrival " + std::to_string(t);
    }
  EXPECT_EQ(wrongInitial, 0) << "cells wet at the start (Start Time 60 s) whose arrival is not 60 s; first: "
                             << firstWrong;
  EXPECT_EQ(wrongLater, 0) << "cells reached later whose arrival is outside (60, 66] s; first: " << firstWrong;
}

TEST_F(Scene, ParticlesMeetTheGridsBoundaries) {
  // The particles are held or let out by the same edges as the grid (issue 18: walls removed them).
  writeMap("dem.tif", loadingDem());
  for (const char* edge : {"wall", "open"})
    for (const char* nodata : {"wall", "open"}) {
      const talus::sim::Scene s = loadScene(writeRun(std::string("DEM=dem.tif\nBoundary Type=") + edge +
                                                     "\nNodata Boundary Type=" + nodata + "\n"));
      EXPECT_EQ(s.particles.settings.edgeWalls, std::string(edge) == "wall") << edge;
      EXPECT_EQ(s.particles.settings.nodataWalls, std::string(nodata) == "wall") << nodata;
    }
}
