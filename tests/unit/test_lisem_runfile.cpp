// Run-files in OpenLISEM Hazard 2.x's own format load in Talus unchanged. The generator below
// writes what OpenLISEM's GUI saves (ParameterManager::SaveToRunFile: the header
// "[SPHAZARD RUNFILE VERSION 0.1a]", a "[Label]" line per label, "Name=Value" per key and
// "Name=Value=Multiplier" for maps and files that carry a multiplier), with every key of its
// parameter list at its default. The list is written here from OpenLISEM's source
// (bastianvandenbout/LISEM, lisem/model/parameters/parametermanager.h, InitParameters), not
// from Talus's registry, so that a key Talus forgets shows up as an unknown key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/Error.hpp"
#include "core/Grid.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "io/RunFileConvert.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"
#include "support/ExpectInputError.hpp"

namespace fs = std::filesystem;
using talus::io::RunConfig;
using talus::sim::talusRunKeys;
using talus::test::contains;
using talus::test::expectInputError;

namespace {

/// One line of OpenLISEM's parameter list: a label (section) when key is empty.
struct LisemLine {
  const char* label;
  const char* key;
  const char* value;
  bool mult;  // written as Name=Value=1
};

// In the GUI's order, values as QString::number writes the defaults. "<maps>", "<res>" and
// "<time>" stand for GetSite() + "/maps/" etc.
const std::vector<LisemLine> kLisemParameters = {
    {"Settings", "", "", false}, {"Time", "", "", false},
    {"", "Start Time", "0", false}, {"", "End Time", "100", false}, {"", "Timestep", "10", false},
    {"", "Timestep Flow", "1", false}, {"", "Timestep Particle Flow", "0.001", false},
    {"TimeInput Directory", "", "", false}, {"", "TimeInput Directory", "<time>", false},
    {"Map Directory", "", "", false}, {"", "Map Directory", "<maps>", false},
    {"Output Directory", "", "", false}, {"", "Output Directory", "<res>", false},
    {"Processes", "", "", false},
    {"", "Include Rainfall", "0", false}, {"", "Include Infiltration", "0", false}, {"", "Include Hydrology", "0", false},
    {"", "Custom Infiltration", "0", false}, {"", "Include Evapotranspiration", "0", false},
    {"", "Include GroundWater Flow", "0", false}, {"", "Include Channel", "0", false}, {"", "Include Erosion", "0", false},
    {"", "Include Loose Material Layer", "0", false}, {"", "Include Slope Stability", "0", false},
    {"", "Include Slope Failure", "0", false}, {"", "Include Initial Stability", "0", false},
    {"", "Include Initial Water", "0", false}, {"", "Include Initial Solids", "0", false},
    {"", "Include Seismic Trigger", "0", false}, {"", "Include Rigid-Body Phyisics", "0", false},
    {"Flow Settings", "", "", false}, {"", "Use Material Point Method", "0", false},
    {"Compute Settings", "", "", false}, {"", "Use CPU", "0", false}, {"", "Limit Memory Usage", "0", false},
    {"", "Simulate Subsection", "0", false}, {"", "SubSection Value", "1", false},
    {"Parameters", "", "", false}, {"Water Flow", "", "", false},
    {"", "Drag coefficient multiplier", "1", false}, {"", "Reynolds Number Multiplier", "1", false},
    {"", "Custom Channel Slope", "1", false},
    {"Solid Flow", "", "", false}, {"", "Initial Stability Margin", "0.005", false},
    {"", "Elastic Modulus", "1e+13", false}, {"", "Shear Modulus", "1e+12", false},
    {"", "Particle Fractional Dimension", "0.2", false},
    {"Numerical", "", "", false}, {"Time Input", "", "", false}, {"Climate Input", "", "", false},
    {"", "Rainfall", "rain", true}, {"", "Temperature", "temp", true}, {"", "Radiation", "rad", true},
    {"", "Wind", "wind", true}, {"", "Vapor Pressure", "vap", true}, {"", "ndvi", "ndvi", true},
    {"Input Maps", "", "", false}, {"Topography", "", "", false},
    {"", "DEM", "dem.map", false}, {"", "MASK", "mask.map", false},
    {"Channels", "", "", false}, {"", "Channel", "channelldd.map", false},
    {"", "Channel Width", "channelwidth.map", true}, {"", "Channel Depth", "channeldepth.map", true},
    {"", "Channel Slope", "channelslope.map", true},
    {"Surface", "", "", false}, {"", "Manning", "n.map", true}, {"", "Building Cover", "buildingcover.map", true},
    {"", "Road Width", "buildingcover.map", true}, {"", "Vegetation Height", "vegheight.map", true},
    {"", "Vegetation Cover", "vegcover.map", true}, {"", "SMAX Surface", "smaxsurface.map", true},
    {"", "SMAX Canopy", "smaxcanopy.map", true}, {"", "CropF", "cropf.map", true},
    {"", "Tree Density", "treedens.map", true}, {"", "Tree Length", "treelength.map", true},
    {"", "Tree Radius", "treeradius.map", true}, {"", "Tree Count", "treecount.map", true},
    {"SubSurface", "", "", false}, {"", "KSatSimple", "ksatsimple.map", true}, {"", "KSatBottom", "ksatbottom.map", true},
    {"", "Clay", "clay.map", true}, {"", "Sand", "sand.map", true}, {"", "Gravel", "gravel.map", true},
    {"", "Organic", "om.map", true}, {"", "Density", "density.map", true}, {"", "MatricSuction", "psi.map", true},
    {"", "Porosity", "thetas.map", true}, {"", "A", "a.map", true}, {"", "B", "b.map", true},
    {"", "Soil Depth", "soildepth.map", true}, {"", "Ground Water Height", "gwh.map", true},
    {"", "Theta Initial", "thetaieff.map", true}, {"", "Cohesion Top", "cohtop.map", true},
    {"", "Cohesion Channel", "cohch.map", true}, {"", "Aggregate Stability", "aggrst.map", true},
    {"", "Internal Friction Angle", "ifa.map", true}, {"", "Cohesion Bottom", "coh.map", true},
    {"", "Density Bottom", "densityb.map", true}, {"", "Rocksize", "rocksize.map", true},
    {"", "Material Depth", "materialdepth.map", true}, {"", "Material Internal Friction Angle", "materialifa.map", true},
    {"", "Material Density Bottom", "materialdensity.map", true}, {"", "Material Rocksize", "materialrocksize.map", true},
    {"Boundary Conditions", "", "", false}, {"", "Initial Fluid Height", "initialfh.map", true},
    {"", "Initial Solid Height", "initialsh.map", true}, {"", "Initial Solid Density", "initialsd.map", true},
    {"", "Initial Solid IFA", "initialsifa.map", true}, {"", "Initial Solid Rocksize", "initialsrocksize.map", true},
    {"", "Initial Cohesion", "initialscohesion.map", true},
    {"Seismic", "", "", false}, {"", "Peak Ground Accaleration", "pga.map", true},
    {"Rigid Elements", "", "", false}, {"Scene", "", "", false}, {"Density Instancing", "", "", false},
    {"", "Tree Instancing", "0", false}, {"", "Friction Coefficient", "0.005", false},
    {"Output", "", "", false}, {"Output", "", "", false},
    {"", "Output GeoTIFF format", "0", false}, {"", "Calculate Max per sub-step", "0", false},
    {"", "Output Max Height/Vel only", "0", false}, {"", "Output totals", "0", false},
    {"", "Output hydrographs", "0", false},
    {"Timeseries", "", "", false}, {"", "Output timeseries", "0", false}, {"", "Report every", "1", false},
    {"", "Report particles every", "1000", false}, {"", "Output timeseries of H", "0", false},
    {"", "Output timeseries of HS", "0", false}, {"", "Output timeseries of HT (total height)", "0", false},
    {"", "Output timeseries of SFRAC", "0", false}, {"", "Output timeseries of V", "0", false},
    {"", "Output timeseries of VS", "0", false}, {"", "Output timeseries of HT (total averaged velocity)", "0", false},
    {"", "Output timeseries of Infil", "0", false}, {"", "Output timeseries of GWH", "0", false},
    {"", "Output timeseries of Soil Loss", "0", false}, {"", "Output timeseries of Sediment Load", "0", false},
};

/// An OpenLISEM Hazard run-file with every key at its default except those in `changes`; the
/// site folders are `site` + "/maps/" etc., as the GUI writes them (trailing slash).
std::string lisemRunFile(const std::string& site, const std::map<std::string, std::string>& changes) {
  std::string out = "[SPHAZARD RUNFILE VERSION 0.1a]\n";
  for (const auto& p : kLisemParameters) {
    if (*p.key == '\0') {
      out += "\n[" + std::string(p.label) + "]\n";
      continue;
    }
    std::string value = p.value;
    for (const char* dir : {"maps", "res", "time"})
      if (value == "<" + std::string(dir) + ">") value = site + "/" + dir + "/";
    const auto it = changes.find(p.key);
    if (it != changes.end()) value = it->second;
    out += std::string(p.key) + "=" + value + (p.mult ? "=1" : "") + "\n";
  }
  return out;
}

class LisemRunFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("talus_lisem_" + std::to_string(::getpid()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "maps");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// PCRaster maps under OpenLISEM's default names: a 12 x 10 plane of 2 m cells tilted 0.2 in x
  /// with a 1 m solid block in its upper part.
  void writeMaps() const {
    talus::Grid g = talus::Grid::make(12, 10, 2.0, 0.0, 0.0);
    auto write = [&](const std::string& name, auto f) {
      talus::Raster r(g, 0.0);
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) r.at(i, j) = f(i, j);
      talus::io::writeRaster(path("maps/" + name), r, talus::io::RasterFormat::PCRaster);
    };
    write("dem.map", [](int i, int) { return 10.0 - 0.4 * i; });
    write("n.map", [](int, int) { return 0.05; });
    write("initialsh.map", [](int i, int j) { return i >= 2 && i < 5 && j >= 3 && j < 7 ? 1.0 : 0.0; });
    write("initialsd.map", [](int, int) { return 2000.0; });
    write("initialsifa.map", [](int, int) { return 0.3; });
    write("initialsrocksize.map", [](int, int) { return 0.1; });
    write("initialscohesion.map", [](int, int) { return 0.0; });
  }

  /// Writes the OpenLISEM run-file (site = the test folder) and returns its path.
  std::string writeRun(const std::map<std::string, std::string>& changes, const std::string& name = "lisem.run") const {
    std::ofstream(path(name)) << lisemRunFile(dir_.string(), changes);
    return path(name);
  }

  RunConfig load(const std::map<std::string, std::string>& changes) const {
    return RunConfig::load(writeRun(changes), talusRunKeys());
  }

  /// Only the initial solids on, run for 2 s in steps of 1 s.
  std::map<std::string, std::string> solidsOn() const {
    return {{"Include Initial Solids", "1"}, {"End Time", "0.0333333"}, {"Timestep", "1"}};
  }

  static std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
  }

  fs::path dir_;
};

TEST_F(LisemRunFile, ParameterListHas113Keys) {
  // The count in the issue and in OpenLISEM's InitParameters (Clay2 ... Soil Depth2 are commented out).
  int keys = 0;
  for (const auto& p : kLisemParameters) keys += *p.key != '\0';
  EXPECT_EQ(keys, 113);
  int declared = 0;
  for (const auto& k : talusRunKeys().keys()) declared += k.fromLisem;
  EXPECT_EQ(declared, 113) << "every OpenLISEM key is declared once with fromLisem";
  for (const auto& p : kLisemParameters) {
    if (*p.key == '\0') continue;
    const auto* spec = talusRunKeys().find(p.key);
    ASSERT_TRUE(spec) << p.key;
    EXPECT_TRUE(spec->fromLisem) << p.key;
    if (std::string(p.value).front() != '<') {
      EXPECT_EQ(spec->lisemDefault, p.value) << p.key;
    }
  }
}

TEST_F(LisemRunFile, FullRunFileWithInitialSolidsLoadsAndRuns) {
  writeMaps();
  const RunConfig cfg = load(solidsOn());
  // OpenLISEM's meanings: Timestep is the model step, Report every the steps per report.
  EXPECT_DOUBLE_EQ(cfg.real("Timestep"), 1.0);
  EXPECT_EQ(cfg.integer("Report every"), 1);
  EXPECT_EQ(cfg.directory("Map Directory"), path("maps"));
  EXPECT_EQ(cfg.map("Manning").file, path("maps/n.map"));
  EXPECT_DOUBLE_EQ(cfg.map("Manning").multiplier, 1.0);
  const std::string notes = joined(cfg.warnings());
  // The maps of processes that are off are OpenLISEM's boilerplate: no warning about them, one
  // line for the settings without effect and one for the output switches.
  EXPECT_FALSE(contains(notes, "Initial Fluid Height")) << notes;
  EXPECT_FALSE(contains(notes, "Building Cover")) << notes;
  EXPECT_TRUE(contains(notes, "5 OpenLISEM Hazard settings have no effect in Talus (it chooses its own steps and device): 5 more at "
                                   "OpenLISEM's defaults")) << notes;
  // 9: the format and series switches are honoured (sim/OutputSelection.hpp), the hydrograph,
  // totals and particle-report switches and the series of processes Talus lacks are not.
  EXPECT_TRUE(contains(notes, "9 OpenLISEM Hazard output switches are not honoured yet")) << notes;
  EXPECT_EQ(cfg.warnings().size(), 2u) << notes;

  const talus::sim::Scene scene = talus::sim::loadScene(cfg);
  EXPECT_DOUBLE_EQ(scene.reportInterval, 1.0);
  EXPECT_TRUE(scene.settings.twoPhase);
  // OpenLISEM's defaults Output GeoTIFF format=0 and Output timeseries=0: PCRaster maps, no series.
  EXPECT_EQ(scene.format, talus::io::RasterFormat::PCRaster);
  EXPECT_FALSE(scene.series.any);
  talus::sim::Simulation sim(scene, cfg, "", talus::sim::OutputMode::New);
  const talus::sim::RunSummary s = sim.run();
  EXPECT_NEAR(s.simulatedSeconds, 2.0, 1e-9);
  EXPECT_LT(s.volumeBalanceError, 1e-4);
  EXPECT_TRUE(fs::exists(path("res/summary.json")));
  EXPECT_TRUE(fs::exists(path("res/hsfinal.map")));
  EXPECT_TRUE(fs::exists(path("res/vsfinal.map")));
  EXPECT_FALSE(fs::exists(path("res/series/hs_0000.map")));
}

// OpenLISEM's series switches select the variables, and Series Names=openlisem names them as its
// WriteMapSeries does (lisem/io/iogdal.h: prefix padded to 7 characters, the model step with a dot
// after its first digit): at Timestep 0.5 s and Report every 2, report 1 is step 2, hs000000.002.
TEST_F(LisemRunFile, OutputSwitchesSelectTheSeriesAndTheirNames) {
  writeMaps();
  auto changes = solidsOn();
  changes["Output timeseries"] = "1";
  changes["Output timeseries of HS"] = "1";
  changes["Output timeseries of VS"] = "1";
  changes["Output timeseries of HT (total height)"] = "1";
  changes["Output GeoTIFF format"] = "1";
  changes["Timestep"] = "0.5";
  changes["Report every"] = "2";
  RunConfig cfg = load(changes);
  cfg.set("Series Names=openlisem");
  const talus::sim::Scene scene = talus::sim::loadScene(cfg);
  EXPECT_EQ(scene.format, talus::io::RasterFormat::GeoTiff);
  ASSERT_TRUE(scene.series.any);
  EXPECT_TRUE(scene.series.hs && scene.series.vs && scene.series.ht);
  EXPECT_FALSE(scene.series.hf || scene.series.vf || scene.series.sf || scene.series.vt);
  EXPECT_EQ(talus::sim::seriesName(scene.series, "hs", 1), "hs000000.002");
  EXPECT_EQ(talus::sim::seriesName(scene.series, "vs", 500), "vs000001.000");
  talus::sim::Simulation sim(scene, cfg, "", talus::sim::OutputMode::New);
  sim.run();
  for (const char* f : {"res/hs000000.000", "res/vs000000.002", "res/ht000000.004", "res/hsfinal.tif"})
    EXPECT_TRUE(fs::exists(path(f))) << f;
  EXPECT_FALSE(fs::exists(path("res/hf000000.002")));
  // ht is the total thickness: on this dry scene it equals hs at every cell.
  const talus::Raster hs = talus::io::readRaster(path("res/hs000000.002"));
  const talus::Raster ht = talus::io::readRaster(path("res/ht000000.002"));
  for (std::size_t k = 0; k < hs.values.size(); ++k) EXPECT_EQ(hs.values[k], ht.values[k]) << k;
}

TEST_F(LisemRunFile, ReportEveryMultipliesTheTimestep) {
  writeMaps();
  auto changes = solidsOn();
  changes["Timestep"] = "0.5";
  changes["Report every"] = "4";
  const talus::sim::Scene scene = talus::sim::loadScene(load(changes));
  EXPECT_DOUBLE_EQ(scene.reportInterval, 2.0);  // 4 steps of 0.5 s (modelreport.cpp: m_Step % every)
}

TEST_F(LisemRunFile, OpenLisemElasticityAndParticleFraction) {
  // OpenLISEM's defaults K = 1e13 Pa (Elastic Modulus, its bulk modulus) and G = 1e12 Pa give
  // nu = (3K - 2G) / (2 (3K + G)) = 28/62 and E = 9KG / (3K + G) = 9e25 / 3.1e13, not a refusal.
  writeMaps();
  auto changes = solidsOn();
  changes["Use Material Point Method"] = "1";
  const talus::sim::Scene scene = talus::sim::loadScene(load(changes));
  EXPECT_NEAR(scene.particles.settings.poisson, 28.0 / 62.0, 1e-12);
  EXPECT_NEAR(scene.particles.settings.youngModulus / (9e25 / 3.1e13), 1.0, 1e-12);
  // Particle Fractional Dimension 0.2 of a 2 m cell: particles of 0.2 * 8 m^3.
  EXPECT_NEAR(scene.particles.spacing.volume, 1.6, 1e-12);
}

TEST_F(LisemRunFile, ProcessSwitchedOnIsRefusedNamingTheProcess) {
  writeMaps();
  auto changes = solidsOn();
  changes["Include Slope Failure"] = "1";
  changes["Include Hydrology"] = "1";
  expectInputError([&] { load(changes); },
                   {"key 'Include Slope Failure': slope failure is not modelled by Talus (OpenLISEM",
                    "key 'Include Hydrology': hydrology (infiltration and surface storage) is not modelled by Talus yet",
                    "set 'Include Hydrology=0' to run without it"});
}

TEST_F(LisemRunFile, RainfallAndInfiltrationAreReadWithOpenLisemsNamesAndUnits) {
  // OpenLISEM's defaults: Rainfall=rain=1 in TimeInput Directory, KSatSimple=ksatsimple.map=1 (mm/h).
  writeMaps();
  fs::create_directories(dir_ / "time");
  std::ofstream(path("time/rain")) << "rain gauge\n2\ntime [min]\nintensity [mm/h]\n0 0\n10 72\n20 0\n";
  {
    talus::Grid g = talus::Grid::make(12, 10, 2.0, 0.0, 0.0);
    talus::io::writeRaster(path("maps/ksatsimple.map"), talus::Raster(g, 18.0), talus::io::RasterFormat::PCRaster);
  }
  std::map<std::string, std::string> changes = {{"Include Rainfall", "1"}, {"Include Infiltration", "1"},
                                                {"End Time", "30"}};
  const talus::sim::Scene scene = talus::sim::loadScene(load(changes));
  ASSERT_EQ(scene.rainfall.times().size(), 3u);
  EXPECT_EQ(scene.rainfall.times()[1], 600.0);
  EXPECT_EQ(scene.rainfall.intensities()[1], 72.0);
  EXPECT_NEAR(scene.rainfall.depth(0, 1800), 0.012, 1e-15);  // 72 mm/h for 10 min
  ASSERT_EQ(scene.infiltration.size(), 120u);
  EXPECT_NEAR(scene.infiltration[0], 18.0 / 3.6e6, 1e-20);  // mm/h -> m/s
  // Rain alone is something to move: the dry scene is accepted.
  EXPECT_NO_THROW(talus::sim::requireMaterial(scene, load(changes)));
  // A multiplier on the file scales its intensities, as OpenLISEM's GetMapMult does.
  {
    std::string text = lisemRunFile(dir_.string(), changes);
    const std::size_t at = text.find("Rainfall=rain=1\n");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::string("Rainfall=rain=1").size(), "Rainfall=rain=0.5");
    std::ofstream(path("half.run")) << text;
    const RunConfig half = RunConfig::load(path("half.run"), talusRunKeys());
    EXPECT_EQ(talus::sim::loadScene(half).rainfall.intensities()[1], 36.0);
  }
  // Rainfall Intensity (Talus's key, added to OpenLISEM's file) replaces the file; the switch off
  // reads neither file nor map.
  auto withIntensity = [&](const std::map<std::string, std::string>& c) {
    std::ofstream(path("intensity.run")) << lisemRunFile(dir_.string(), c) << "Rainfall Intensity=5\n";
    return RunConfig::load(path("intensity.run"), talusRunKeys());
  };
  EXPECT_EQ(talus::sim::loadScene(withIntensity(changes)).rainfall.intensity(1e5), 5.0);
  fs::remove(path("time/rain"));
  fs::remove(path("maps/ksatsimple.map"));
  const talus::sim::Scene off = talus::sim::loadScene(load(solidsOn()));
  EXPECT_TRUE(off.rainfall.empty());
  EXPECT_TRUE(off.infiltration.empty());
  // Missing file with the switch on: named.
  changes["Include Infiltration"] = "0";
  expectInputError([&] { talus::sim::loadScene(load(changes)); }, {"rainfall file '" + path("time/rain") + "'"});
  // With solids (the two-phase model) the rain falls into the fluid phase.
  auto solids = solidsOn();
  solids["Include Rainfall"] = "1";
  const talus::sim::Scene wetSolids = talus::sim::loadScene(withIntensity(solids));
  EXPECT_TRUE(wetSolids.settings.twoPhase);
  EXPECT_EQ(wetSolids.rainfall.intensity(0.0), 5.0);
}

TEST_F(LisemRunFile, NoEffectSettingsGivenOtherwiseAreNamed) {
  writeMaps();
  auto changes = solidsOn();
  changes["Use CPU"] = "1";
  const std::string notes = joined(load(changes).warnings());
  EXPECT_TRUE(contains(notes, "have no effect in Talus (it chooses its own steps and device): Use CPU=1 (and 4 more"))
      << notes;
}

TEST_F(LisemRunFile, UnknownKeysGetSensibleSuggestions) {
  writeMaps();
  std::ofstream(path("typo.run")) << "DEM=maps/dem.map\nInclude Initial Stabilty=0\ncoh=1\nManing=0.05\n";
  const std::string msg = expectInputError([&] { RunConfig::load(path("typo.run"), talusRunKeys()); },
                                           {"'Include Initial Stabilty': unknown key; did you mean 'Include Initial Stability'?",
                                            "'Maning': unknown key; did you mean 'Manning'?"});
  EXPECT_FALSE(contains(msg, "'CFL'")) << msg;  // 'coh' is two of three letters from 'CFL': no misspelling
  EXPECT_FALSE(contains(msg, "Include Initial Solids")) << msg;
  // A known key of either dialect is never "corrected".
  std::ofstream(path("known.run")) << "DEM=maps/dem.map\nInclude Initial Stability=0\nReport every=2\n";
  EXPECT_NO_THROW(RunConfig::load(path("known.run"), talusRunKeys()));
}

TEST_F(LisemRunFile, WindowsDrivePathsResolveInsideTheRunFilesFolders) {
  writeMaps();
  auto changes = solidsOn();
  changes["Map Directory"] = "C:/lisemcourse/maps/";
  changes["Output Directory"] = "D:\\data\\res\\";
  changes["DEM"] = "C:\\lisemcourse\\maps\\dem.map";
  const RunConfig cfg = load(changes);
  EXPECT_EQ(cfg.directory("Map Directory"), path("maps"));  // the run-file's maps/ exists
  EXPECT_EQ(cfg.directory("Output Directory"), path("res"));
  EXPECT_EQ(cfg.map("DEM").file, path("maps/dem.map"));
  const std::string notes = joined(cfg.warnings());
  EXPECT_TRUE(contains(notes, "Windows path 'C:/lisemcourse/maps/' taken as '" + path("maps") + "'")) << notes;
  EXPECT_TRUE(contains(notes, "Windows path 'C:\\lisemcourse\\maps\\dem.map' taken as '" + path("maps/dem.map") + "'"))
      << notes;
}

TEST_F(LisemRunFile, MapNamesMatchIgnoringCaseWithANote) {
  writeMaps();
  fs::rename(path("maps/dem.map"), path("maps/DEM.MAP"));
  const RunConfig cfg = load(solidsOn());
  EXPECT_EQ(cfg.map("DEM").file, path("maps/DEM.MAP"));
  EXPECT_TRUE(contains(joined(cfg.warnings()), "same name but for letter case")) << joined(cfg.warnings());
}

TEST_F(LisemRunFile, DecimalCommasAreReadOrRefused) {
  writeMaps();
  auto changes = solidsOn();
  changes["Manning"] = "0,05";  // written as Manning=0,05=1
  changes["Drag coefficient multiplier"] = "1,5";
  const RunConfig cfg = load(changes);
  EXPECT_FALSE(cfg.map("Manning").isFile);
  EXPECT_DOUBLE_EQ(cfg.map("Manning").constant, 0.05);
  EXPECT_DOUBLE_EQ(cfg.real("Drag coefficient multiplier"), 1.5);
  EXPECT_TRUE(contains(joined(cfg.warnings()), "'0,05' has a decimal comma: read as the uniform value 0.05"));
  // 1,000 is 1.0 with a decimal comma or 1000 with a thousands separator: refused, not guessed.
  changes["Drag coefficient multiplier"] = "1,000";
  expectInputError([&] { load(changes); }, {"'1,000': a decimal comma or a thousands separator?"});
  changes["Drag coefficient multiplier"] = "1,2,3";
  expectInputError([&] { load(changes); }, {"bad number '1,2,3': expected one number with a decimal point"});
}

TEST_F(LisemRunFile, DayMinuteTimesAndBeginTime) {
  writeMaps();
  auto changes = solidsOn();
  changes["Start Time"] = "001:0000";  // day 1, minute 0 = 1440 min (openLISEM getTimefromString)
  changes["End Time"] = "001:0001";
  const RunConfig cfg = load(changes);
  EXPECT_DOUBLE_EQ(cfg.real("Start Time"), 1440);
  EXPECT_DOUBLE_EQ(cfg.real("End Time"), 1441);
  EXPECT_TRUE(contains(joined(cfg.warnings()), "'001:0001' read as OpenLISEM's day:minute time, 1441 min"));
  changes["End Time"] = "1:x";
  expectInputError([&] { load(changes); }, {"expected minutes (e.g. 90) or OpenLISEM's day:minute (ddd:mmmm"});
  // openLISEM 6 names the start "Begin time".
  std::ofstream(path("v6.run")) << "DEM=maps/dem.map\nBegin time=5\nEnd time=6\n";
  const RunConfig v6 = RunConfig::load(path("v6.run"), talusRunKeys());
  EXPECT_DOUBLE_EQ(v6.real("Start Time"), 5);
  EXPECT_DOUBLE_EQ(v6.real("End Time"), 6);
}

TEST_F(LisemRunFile, ConvertWritesATalusRunFileAndListsWhatItDropped) {
  writeMaps();
  auto changes = solidsOn();
  changes["Use CPU"] = "1";
  changes["Manning"] = "0,05";
  const std::string in = writeRun(changes);
  const talus::io::Conversion c = talus::io::convertRunFile(in, talusRunKeys());
  EXPECT_TRUE(contains(c.text, "Include Initial Solids=1\n")) << c.text;
  EXPECT_TRUE(contains(c.text, "Manning=0.05=1\n")) << c.text;
  EXPECT_FALSE(contains(c.text, "Use CPU")) << c.text;
  EXPECT_FALSE(contains(c.text, "Building Cover")) << c.text;
  const std::string report = joined(c.report);
  EXPECT_TRUE(contains(report, "dropped 'Use CPU=1'")) << report;
  EXPECT_TRUE(contains(report, "changed 'Manning'")) << report;
  // The converted file loads to the same configuration of the keys Talus uses.
  std::ofstream(path("talus.run")) << c.text;
  const RunConfig a = RunConfig::load(in, talusRunKeys());
  const RunConfig b = RunConfig::load(path("talus.run"), talusRunKeys());
  for (const auto& k : talusRunKeys().keys())
    if (k.role == talus::io::KeyRole::Used && (k.enabledBy.empty() || a.flag(k.enabledBy))) {
      EXPECT_EQ(a.valueText(k.name), b.valueText(k.name)) << k.name;
    }
  EXPECT_TRUE(b.warnings().empty()) << joined(b.warnings());
}

}  // namespace
