// Unit tests of io/ParticleLayerIO: GeoPackage particle layers written from grid-frame positions and
// read back through OGR (readParticleLayer): feature count, world coordinates against the grid's own
// cell centres (offset origin, negative pixel height, a rotated geotransform), exact attribute values,
// the spatial reference, empty layers, NaN/Inf/non-finite positions, argument and file errors, atomic
// replacement. ParticleLayerIO.WriteTimeBenchmark prints the write time of 1e5 (and 1e6) particles
// when TALUS_BENCH=1.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "core/Error.hpp"
#include "core/Grid.hpp"
#include "io/ParticleLayerIO.hpp"

namespace fs = std::filesystem;
using talus::Grid;
using talus::InputError;
using talus::io::ParticleLayer;
using talus::io::ParticleRecords;

namespace {

/// EPSG:32633, WGS 84 / UTM zone 33N.
const char* kUtm33Wkt =
    "PROJCS[\"WGS 84 / UTM zone 33N\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,"
    "298.257223563,AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,"
    "AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],"
    "AUTHORITY[\"EPSG\",\"4326\"]],PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],"
    "PARAMETER[\"central_meridian\",15],PARAMETER[\"scale_factor\",0.9996],PARAMETER[\"false_easting\",500000],"
    "PARAMETER[\"false_northing\",0],UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]],AXIS[\"Easting\",EAST],"
    "AXIS[\"Northing\",NORTH],AUTHORITY[\"EPSG\",\"32633\"]]";

/// The attributes the simulation writes (docs/outputs.md, "Particle layers").
const std::vector<std::string> kNames = {"vx", "vy", "speed", "I1", "sqrtJ2", "cohesion_fraction",
                                         "f_sc", "f_fc", "plastic_strain", "mass", "thickness"};

/// A 9 x 6 grid of 2.5 m cells with a projected origin (top-left corner 512345.5, 5234567.25).
Grid makeGrid() {
  Grid g = Grid::make(9, 6, 2.5, 512345.5, 5234567.25 - 6 * 2.5);
  g.projectionWkt = kUtm33Wkt;
  return g;
}

/// An attribute value that is not a short binary fraction, so a float round trip would show.
double valueOf(std::size_t attribute, std::size_t particle) {
  return (static_cast<double>(attribute) + 1.0) * 1000.0 / 3.0 - std::sqrt(static_cast<double>(particle) + 2.0) * 1e-3;
}

/// One particle at every cell centre (row-major), with the attributes of kNames.
ParticleRecords cellCentreRecords(const Grid& g) {
  ParticleRecords r;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      r.x.push_back((i + 0.5) * g.dx);
      r.y.push_back((j + 0.5) * g.dx);
    }
  for (std::size_t a = 0; a < kNames.size(); ++a) {
    std::vector<double> v(r.size());
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = valueOf(a, k);
    r.add(kNames[a], std::move(v));
  }
  return r;
}

/// Runs fn, expects an InputError whose text holds every one of parts.
template <class Fn>
void expectInputError(Fn fn, const std::vector<std::string>& parts) {
  try {
    fn();
    ADD_FAILURE() << "expected talus::InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const std::string& part : parts) EXPECT_NE(what.find(part), std::string::npos) << what << "\nlacks: " << part;
  }
}

}  // namespace

/// Fixture: a fresh temporary folder per test, removed afterwards.
class ParticleLayerIO : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / ("talus_particlelayer_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  /// Names of the files in the folder (to see that no temporary file stayed behind).
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};

TEST_F(ParticleLayerIO, CellCentresMapToTheGridsWorldCoordinatesAndAttributesRoundTripExactly) {
  const Grid g = makeGrid();
  ASSERT_LT(g.geoTransform[5], 0.0);  // north-up: row 0 is the northern edge
  const ParticleRecords r = cellCentreRecords(g);
  talus::io::writeParticleLayer(file("p.gpkg"), g, r);
  EXPECT_EQ(listing(), std::vector<std::string>{"p.gpkg"});

  const ParticleLayer layer = talus::io::readParticleLayer(file("p.gpkg"));
  EXPECT_EQ(layer.layerName, "particles");
  EXPECT_FALSE(layer.spatialIndex);  // off by default
  ASSERT_EQ(layer.size(), static_cast<std::size_t>(g.nx * g.ny));
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      EXPECT_EQ(layer.worldX[k], g.cellX(i)) << "cell " << i << ", " << j;
      EXPECT_EQ(layer.worldY[k], g.cellY(j)) << "cell " << i << ", " << j;
    }
  // Row 0 is the northern one: its particles lie above those of the last row.
  EXPECT_GT(layer.worldY[g.index(0, 0)], layer.worldY[g.index(0, g.ny - 1)]);

  ASSERT_EQ(layer.attributes.size(), kNames.size());
  for (std::size_t a = 0; a < kNames.size(); ++a) {
    EXPECT_EQ(layer.attributes[a].name, kNames[a]);
    const std::vector<double>& v = layer.attributes[a].values;
    ASSERT_EQ(v.size(), r.size());
    for (std::size_t k = 0; k < v.size(); ++k) EXPECT_EQ(v[k], valueOf(a, k)) << kNames[a] << " of particle " << k;
  }
  EXPECT_EQ(layer.epsg, 32633);
  EXPECT_TRUE(talus::io::sameSpatialReference(layer.projectionWkt, g.projectionWkt)) << layer.projectionWkt;
}

TEST_F(ParticleLayerIO, OffCentrePositionsAndARotatedGeotransformFollowTheFullAffineMap) {
  Grid g = makeGrid();
  const std::vector<double> x = {0.0, 1.0, 22.5, 3.75}, y = {0.0, 2.0, 15.0, 14.9};
  ParticleRecords r;
  r.x = x;
  r.y = y;
  r.add("mass", {1, 2, 3, 4});
  talus::io::writeParticleLayer(file("plain.gpkg"), g, r);
  ParticleLayer a = talus::io::readParticleLayer(file("plain.gpkg"));
  ASSERT_EQ(a.size(), x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(a.worldX[k], 512345.5 + x[k]);
    EXPECT_EQ(a.worldY[k], 5234567.25 - y[k]);  // y counts rows down from the northern edge
  }

  // Vectors: a north-up grid flips the row axis (south) to north.
  EXPECT_EQ(talus::io::gridFrameVectorToWorld(g, 1.5, 2.0), std::make_pair(1.5, -2.0));

  // A rotated grid (30 degrees): world = origin + (x/dx) * column vector + (y/dx) * row vector.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6), dx = g.dx;
  g.geoTransform = {1000.0, dx * c, dx * s, 2000.0, dx * s, -dx * c};
  talus::io::writeParticleLayer(file("rotated.gpkg"), g, r);
  a = talus::io::readParticleLayer(file("rotated.gpkg"));
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_NEAR(a.worldX[k], 1000.0 + x[k] * c + y[k] * s, 1e-9);
    EXPECT_NEAR(a.worldY[k], 2000.0 + x[k] * s - y[k] * c, 1e-9);
  }
  const auto v = talus::io::gridFrameVectorToWorld(g, 1.0, 0.0);  // along a row: the column vector
  EXPECT_NEAR(v.first, c, 1e-15);
  EXPECT_NEAR(v.second, s, 1e-15);
}

TEST_F(ParticleLayerIO, AnEmptyLayerIsAValidGeoPackageWithItsFieldsAndProjection) {
  const Grid g = makeGrid();
  ParticleRecords r;
  for (const std::string& name : kNames) r.add(name, {});
  talus::io::writeParticleLayer(file("empty.gpkg"), g, r);
  const ParticleLayer layer = talus::io::readParticleLayer(file("empty.gpkg"));
  EXPECT_EQ(layer.size(), 0u);
  ASSERT_EQ(layer.attributes.size(), kNames.size());
  for (std::size_t a = 0; a < kNames.size(); ++a) EXPECT_EQ(layer.attributes[a].name, kNames[a]);
  EXPECT_EQ(layer.epsg, 32633);

  // No attributes and no projection at all is valid too.
  Grid plain = Grid::make(3, 3, 1.0);
  talus::io::writeParticleLayer(file("bare.gpkg"), plain, ParticleRecords{});
  const ParticleLayer bare = talus::io::readParticleLayer(file("bare.gpkg"));
  EXPECT_EQ(bare.size(), 0u);
  EXPECT_TRUE(bare.attributes.empty());
  EXPECT_TRUE(bare.projectionWkt.empty());
  EXPECT_EQ(bare.epsg, 0);
}

// NaN values are stored as NULL (read back as NaN); infinities are stored as they are; a particle
// with a non-finite position keeps its feature, with no geometry, so attributes stay aligned.
TEST_F(ParticleLayerIO, NanBecomesNullInfinityStaysAndANonFinitePositionHasNoGeometry) {
  const Grid g = makeGrid();
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  ParticleRecords r;
  r.x = {1.0, nan, 3.0};
  r.y = {1.0, 2.0, 3.0};
  r.add("I1", {nan, -5.0, inf});
  r.add("sqrtJ2", {1.0, 2.0, -inf});
  talus::io::writeParticleLayer(file("nan.gpkg"), g, r);
  const ParticleLayer layer = talus::io::readParticleLayer(file("nan.gpkg"));
  ASSERT_EQ(layer.size(), 3u);
  const std::vector<double>& i1 = *layer.find("I1");
  const std::vector<double>& j2 = *layer.find("sqrtJ2");
  EXPECT_TRUE(std::isnan(i1[0]));
  EXPECT_EQ(i1[1], -5.0);
  EXPECT_EQ(i1[2], inf);
  EXPECT_EQ(j2[2], -inf);
  EXPECT_TRUE(std::isnan(layer.worldX[1]) && std::isnan(layer.worldY[1]));
  EXPECT_DOUBLE_EQ(layer.worldX[2], 512345.5 + 3.0);
}

TEST_F(ParticleLayerIO, ReplacesAnExistingFileAtomically) {
  const Grid g = makeGrid();
  ParticleRecords r = cellCentreRecords(g);
  talus::io::writeParticleLayer(file("p.gpkg"), g, r);
  r.x.resize(5);
  r.y.resize(5);
  for (auto& a : r.attributes) a.values.assign(5, 7.0);
  talus::io::ParticleLayerOptions options;
  options.layerName = "step_2";
  options.spatialIndex = true;
  talus::io::writeParticleLayer(file("p.gpkg"), g, r, options);
  const ParticleLayer layer = talus::io::readParticleLayer(file("p.gpkg"));
  EXPECT_EQ(layer.layerName, "step_2");
  EXPECT_EQ(layer.size(), 5u);
  EXPECT_TRUE(layer.spatialIndex);
  EXPECT_EQ(listing(), std::vector<std::string>{"p.gpkg"});
}

TEST_F(ParticleLayerIO, UnwritablePathsAndBadFilesGiveClearErrors) {
  const Grid g = makeGrid();
  const ParticleRecords r = cellCentreRecords(g);
  const std::string missing = file("no/such/folder/p.gpkg");
  expectInputError([&] { talus::io::writeParticleLayer(missing, g, r); }, {missing, "does not exist"});
  { std::ofstream(file("plain.txt")) << "x"; }
  const std::string underFile = file("plain.txt/p.gpkg");
  expectInputError([&] { talus::io::writeParticleLayer(underFile, g, r); }, {underFile, "not a folder"});
  fs::create_directories(file("taken.gpkg"));
  expectInputError([&] { talus::io::writeParticleLayer(file("taken.gpkg"), g, r); },
                   {file("taken.gpkg"), "folder of that name"});
  Grid badProjection = g;
  badProjection.projectionWkt = "not a projection";
  expectInputError([&] { talus::io::writeParticleLayer(file("bad.gpkg"), badProjection, r); },
                   {file("bad.gpkg"), "projection"});
  EXPECT_FALSE(fs::exists(file("bad.gpkg")));

  expectInputError([&] { talus::io::readParticleLayer(file("absent.gpkg")); }, {file("absent.gpkg"), "does not exist"});
  expectInputError([&] { talus::io::readParticleLayer(file("plain.txt")); }, {file("plain.txt")});
  // Nothing but the files the test made itself is left in the folder.
  std::vector<std::string> names = listing();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"plain.txt", "taken.gpkg"}));
}

TEST_F(ParticleLayerIO, InconsistentRecordsAreProgrammingErrors) {
  const Grid g = makeGrid();
  ParticleRecords r;
  r.x = {1.0, 2.0};
  r.y = {1.0};
  EXPECT_THROW(talus::io::writeParticleLayer(file("a.gpkg"), g, r), std::invalid_argument);
  r.y = {1.0, 2.0};
  r.add("mass", {1.0});
  EXPECT_THROW(talus::io::writeParticleLayer(file("a.gpkg"), g, r), std::invalid_argument);
  r.attributes = {{"mass", {1.0, 2.0}}, {"MASS", {1.0, 2.0}}};
  EXPECT_THROW(talus::io::writeParticleLayer(file("a.gpkg"), g, r), std::invalid_argument);
  r.attributes = {{"", {1.0, 2.0}}};
  EXPECT_THROW(talus::io::writeParticleLayer(file("a.gpkg"), g, r), std::invalid_argument);
  EXPECT_TRUE(listing().empty());
}

TEST_F(ParticleLayerIO, WriteTimeBenchmark) {
  const char* bench = std::getenv("TALUS_BENCH");
  if (bench == nullptr || std::string(bench) != "1") GTEST_SKIP() << "set TALUS_BENCH=1 to time the writes";
  const Grid g = Grid::make(1000, 1000, 2.0, 500000.0, 5200000.0);
  for (const std::size_t n : {std::size_t(100000), std::size_t(1000000)}) {
    ParticleRecords r;
    r.x.resize(n);
    r.y.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      r.x[k] = std::fmod(k * 0.7548776662466927, 1.0) * 2000.0;
      r.y[k] = std::fmod(k * 0.5698402909980532, 1.0) * 2000.0;
    }
    for (std::size_t a = 0; a < kNames.size(); ++a) {
      std::vector<double> v(n);
      for (std::size_t k = 0; k < n; ++k) v[k] = valueOf(a, k);
      r.add(kNames[a], std::move(v));
    }
    for (const bool index : {false, true}) {
      talus::io::ParticleLayerOptions options;
      options.spatialIndex = index;
      const auto t0 = std::chrono::steady_clock::now();
      talus::io::writeParticleLayer(file("bench.gpkg"), g, r, options);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("writeParticleLayer: %zu particles, %zu attributes, spatial index %s: %.3f s (%.3g particles/s, %.1f MB)\n",
                  n, kNames.size(), index ? "on " : "off", s, n / s, fs::file_size(file("bench.gpkg")) / 1e6);
      EXPECT_EQ(talus::io::readParticleLayer(file("bench.gpkg")).size(), n);
    }
  }
}
