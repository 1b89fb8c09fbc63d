// Run-file parsing: syntax, defaults, maps, path resolution, every error message, echo and --set.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/Error.hpp"
#include "io/KeyRegistry.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"

namespace fs = std::filesystem;
using talus::InputError;
using talus::io::KeyRegistry;
using talus::io::KeySpec;
using talus::io::KeyType;
using talus::io::RunConfig;
using talus::sim::talusRunKeys;

namespace {

/// A fresh temporary folder per test, removed afterwards.
class RunFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_runfile_" + std::string(info->name()) + "_" +
                                        std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes a file under the temp folder (creating folders) and returns its absolute path.
  std::string write(const std::string& rel, const std::string& text = "raster") {
    const fs::path p = dir_ / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
  std::string dir() const { return dir_.string(); }

  /// The message of the InputError fromText throws (fails the test when none is thrown).
  std::string errorOf(const std::string& text, const std::string& name = "case.run") {
    try {
      RunConfig::fromText(text, dir(), talusRunKeys(), name);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
  }

  fs::path dir_;
};

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_F(RunFile, ParsesValidFile) {
  write("dem.tif");
  const std::string text =
      "[openLISEM runfile version 6.0]\n"
      "\n"
      "[Input]\n"
      "# a comment\n"
      "; another comment\n"
      "DEM=dem.tif\n"
      "  include   initial WATER = yes \r\n"
      "[Time]\n"
      "start time=5\n"
      "END TIME = 30\n"
      "Timestep=60=0.5\n"
      "[Flow]\n"
      "Manning = 0.05 = 2\n"
      "Limiter=MC\n"
      "Device= NVIDIA H100 \n";
  const RunConfig c = RunConfig::fromText(text, dir(), talusRunKeys(), "valid.run");
  EXPECT_TRUE(c.flag("Include Initial Water"));
  EXPECT_DOUBLE_EQ(c.real("Start Time"), 5);
  EXPECT_DOUBLE_EQ(c.real("End Time"), 30);
  EXPECT_DOUBLE_EQ(c.real("Timestep"), 30);  // value times multiplier
  EXPECT_DOUBLE_EQ(c.map("Manning").constant, 0.05);
  EXPECT_DOUBLE_EQ(c.map("Manning").multiplier, 2);
  EXPECT_EQ(c.choice("limiter"), "mc");
  EXPECT_EQ(c.text("Device"), "NVIDIA H100");
  EXPECT_EQ(c.origin("End Time"), "valid.run:10");
  EXPECT_FALSE(c.isDefault("End Time"));
  EXPECT_EQ(c.sourceName(), "valid.run");
  EXPECT_TRUE(contains(c.echo(), "[openLISEM runfile version 6.0]"));
}

TEST_F(RunFile, DefaultsApplyToKeysNotGiven) {
  const RunConfig c = RunConfig::fromText("DEM=100\n", dir(), talusRunKeys());
  EXPECT_TRUE(c.isDefault("CFL"));
  EXPECT_EQ(c.origin("CFL"), "default");
  EXPECT_DOUBLE_EQ(c.real("CFL"), 0.5);
  EXPECT_DOUBLE_EQ(c.real("Start Time"), 0);
  EXPECT_DOUBLE_EQ(c.real("End Time"), 1);
  EXPECT_DOUBLE_EQ(c.real("Timestep"), 10);
  EXPECT_DOUBLE_EQ(c.real("Minimum Flow Height"), 1e-6);
  EXPECT_DOUBLE_EQ(c.real("Arrival Threshold"), 0.01);
  EXPECT_EQ(c.choice("Limiter"), "mc");
  EXPECT_EQ(c.choice("Riemann Solver"), "hllc");
  EXPECT_EQ(c.choice("Precision"), "float");
  EXPECT_EQ(c.choice("Boundary Type"), "open");
  EXPECT_EQ(c.choice("Nodata Boundary Type"), "wall");
  EXPECT_EQ(c.choice("Depth Pressure"), "cos2");
  EXPECT_EQ(c.choice("Output Format"), "geotiff");
  EXPECT_TRUE(c.flag("Slope Correction"));
  EXPECT_TRUE(c.flag("Report Series"));
  EXPECT_FALSE(c.flag("Include Initial Water"));
  EXPECT_EQ(c.text("Device"), "");
  EXPECT_DOUBLE_EQ(c.map("Manning").constant, 0.01);
  EXPECT_FALSE(c.map("Initial Fluid Height").isFile);
  EXPECT_EQ(c.directory("Map Directory"), dir());
  EXPECT_EQ(c.directory("Output Directory"), (dir_ / "output").string());
  EXPECT_EQ(c.baseDir(), dir());
}

TEST_F(RunFile, MapIsFileOrNumber) {
  const std::string dem = write("dem.tif");
  write("h0.tif");
  const RunConfig c =
      RunConfig::fromText("DEM=dem.tif\nInitial Fluid Height=h0.tif=0.5\nManning=0.03\n", dir(), talusRunKeys());
  EXPECT_TRUE(c.map("DEM").isFile);
  EXPECT_EQ(c.map("DEM").file, dem);
  EXPECT_TRUE(c.map("Initial Fluid Height").isFile);
  EXPECT_DOUBLE_EQ(c.map("Initial Fluid Height").multiplier, 0.5);
  EXPECT_FALSE(c.map("Manning").isFile);
  EXPECT_DOUBLE_EQ(c.map("Manning").constant, 0.03);
  EXPECT_DOUBLE_EQ(c.map("Manning").multiplier, 1);
}

TEST_F(RunFile, ResolvesPathsAgainstMapDirectoryAndRunFileFolder) {
  const std::string dem = write("case/maps/dem.tif");
  const std::string abs = write("elsewhere/h.tif");
  const std::string run = write("case/sim.run",
                                "Output Directory=results\nDEM=dem.tif\nMap Directory=maps\n"
                                "Initial Fluid Height=" + abs + "\n");
  const RunConfig c = RunConfig::load(run, talusRunKeys());
  EXPECT_EQ(c.baseDir(), (dir_ / "case").string());
  EXPECT_EQ(c.directory("Map Directory"), (dir_ / "case/maps").string());
  EXPECT_EQ(c.map("DEM").file, dem);  // relative to the Map Directory, given after the map
  EXPECT_EQ(c.map("Initial Fluid Height").file, abs);  // absolute paths are kept
  EXPECT_EQ(c.directory("Output Directory"), (dir_ / "case/results").string());  // run-file folder
  EXPECT_EQ(c.origin("DEM"), run + ":2");
  // Backslashes (Windows run-files) read as separators; '..' is normalised away.
  const RunConfig w = RunConfig::fromText("DEM=case\\maps\\..\\maps\\dem.tif\n", dir(), talusRunKeys());
  EXPECT_EQ(w.map("DEM").file, dem);
}

TEST_F(RunFile, UnknownKeySuggestsClosestName) {
  const std::string msg = errorOf("DEM=1\n\nManing=0.1\n", "case.run");
  EXPECT_TRUE(contains(msg, "case.run:3: key 'Maning'")) << msg;
  EXPECT_TRUE(contains(msg, "did you mean 'Manning'")) << msg;
  EXPECT_TRUE(contains(errorOf("DEM=1\nFrobnicate=3\n"), "case.run:2: key 'Frobnicate': unknown key"));
  EXPECT_EQ(talusRunKeys().suggestions("maning").at(0), "Manning");
  EXPECT_TRUE(talusRunKeys().suggestions("Frobnicate").empty());
}

TEST_F(RunFile, KeyGivenTwiceNamesBothLines) {
  const std::string msg = errorOf("DEM=1\nCFL=0.4\n# x\ncfl=0.3\n");
  EXPECT_TRUE(contains(msg, "case.run:4: key 'CFL'")) << msg;
  EXPECT_TRUE(contains(msg, "given twice, at case.run:2 and again at case.run:4")) << msg;
}

TEST_F(RunFile, LineWithoutEquals) {
  const std::string msg = errorOf("DEM=1\nCFL 0.4\n");
  EXPECT_TRUE(contains(msg, "case.run:2: key 'CFL 0.4'")) << msg;
  EXPECT_TRUE(contains(msg, "no '='")) << msg;
}

TEST_F(RunFile, BadNumbers) {
  for (const char* bad : {"abc", "nan", "inf", "-inf", "1e999", "0.5x", ""}) {
    const std::string msg = errorOf(std::string("DEM=1\nCFL=") + bad + "\n");
    EXPECT_TRUE(contains(msg, "case.run:2: key 'CFL'")) << bad << ": " << msg;
  }
  EXPECT_TRUE(contains(errorOf("DEM=1\nCFL=abc\n"), "bad number 'abc'"));
  EXPECT_TRUE(contains(errorOf("DEM=1\nManning=nan\n"), "case.run:2: key 'Manning': bad number"));
}

TEST_F(RunFile, ValueOutOfRangeStatesRangeAndUnit) {
  const std::string msg = errorOf("DEM=1\nCFL=2\n");
  EXPECT_TRUE(contains(msg, "case.run:2: key 'CFL'")) << msg;
  EXPECT_TRUE(contains(msg, "[0.01, 1]")) << msg;
  const std::string h = errorOf("DEM=1\nInitial Fluid Height=-1\n");
  EXPECT_TRUE(contains(h, "case.run:2: key 'Initial Fluid Height'")) << h;
  EXPECT_TRUE(contains(h, "[0, 10000] m")) << h;
  // The range applies to value times multiplier.
  EXPECT_TRUE(contains(errorOf("DEM=1\nManning=0.5=3\n"), "[0, 1] s/m^(1/3)"));
  EXPECT_NO_THROW(RunConfig::fromText("DEM=1\nManning=2=0.25\n", dir(), talusRunKeys()));
}

TEST_F(RunFile, BadChoiceListsChoices) {
  const std::string msg = errorOf("DEM=1\nLimiter=superbee\n");
  EXPECT_TRUE(contains(msg, "case.run:2: key 'Limiter'")) << msg;
  EXPECT_TRUE(contains(msg, "minmod, vanleer, mc")) << msg;
}

TEST_F(RunFile, Flags) {
  const std::string msg = errorOf("DEM=1\nReport Series=maybe\n");
  EXPECT_TRUE(contains(msg, "case.run:2: key 'Report Series'")) << msg;
  EXPECT_TRUE(contains(msg, "maybe")) << msg;
  const RunConfig c =
      RunConfig::fromText("DEM=1\nReport Series=FALSE\nSlope Correction=no\nInclude Initial Water=true\n", dir(),
                          talusRunKeys());
  EXPECT_FALSE(c.flag("Report Series"));
  EXPECT_FALSE(c.flag("Slope Correction"));
  EXPECT_TRUE(c.flag("Include Initial Water"));
}

TEST_F(RunFile, MissingMapFileNamesResolvedPath) {
  const std::string msg = errorOf("Map Directory=maps\nDEM=nothere.tif\n");
  EXPECT_TRUE(contains(msg, "case.run:2: key 'DEM'")) << msg;
  EXPECT_TRUE(contains(msg, (dir_ / "maps/nothere.tif").string())) << msg;
  EXPECT_TRUE(contains(msg, "does not exist")) << msg;
}

TEST_F(RunFile, BadMultiplier) {
  const std::string msg = errorOf("DEM=1\nManning=0.1=x\n");
  EXPECT_TRUE(contains(msg, "case.run:2: key 'Manning': bad multiplier 'x'")) << msg;
  EXPECT_TRUE(contains(errorOf("DEM=1\nCFL=0.5=1=2\n"), "bad multiplier"));
  EXPECT_TRUE(contains(errorOf("DEM=1\nCFL=0.5=inf\n"), "bad multiplier"));
  EXPECT_TRUE(contains(errorOf("DEM=1\nLimiter=mc=2\n"), "case.run:2: key 'Limiter': a multiplier"));
}

TEST_F(RunFile, MissingRequiredKey) {
  const std::string msg = errorOf("# nothing\nCFL=0.4\n", "empty.run");
  EXPECT_TRUE(contains(msg, "empty.run: required key 'DEM' is missing")) << msg;
}

TEST_F(RunFile, UnreadableRunFileIsNamed) {
  const std::string missing = (dir_ / "absent.run").string();
  try {
    RunConfig::load(missing, talusRunKeys());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), missing)) << e.what();
  }
  EXPECT_THROW(RunConfig::load(dir(), talusRunKeys()), InputError);  // a folder
}

TEST_F(RunFile, CollectsAllErrorsOnePerLine) {
  const std::string msg = errorOf("Maning=1\nCFL=9\nLimiter=x\n");
  EXPECT_TRUE(contains(msg, "case.run:1: key 'Maning'")) << msg;
  EXPECT_TRUE(contains(msg, "\ncase.run:2: key 'CFL'")) << msg;
  EXPECT_TRUE(contains(msg, "\ncase.run:3: key 'Limiter'")) << msg;
  EXPECT_TRUE(contains(msg, "\ncase.run: required key 'DEM' is missing")) << msg;
}

TEST_F(RunFile, EndTimeMustExceedStartTime) {
  const std::string msg = errorOf("DEM=1\nEnd Time=5\nStart Time=5\n");
  EXPECT_TRUE(contains(msg, "case.run:3: key 'Start Time'")) << msg;  // the later of the two lines
  EXPECT_TRUE(contains(msg, "End Time")) << msg;
  const std::string d = errorOf("DEM=1\nStart Time=3\n");  // against the default End Time of 1 min
  EXPECT_TRUE(contains(d, "case.run:2: key 'Start Time'")) << d;
  RunConfig c = RunConfig::fromText("DEM=1\nEnd Time=10\n", dir(), talusRunKeys());
  try {
    c.set("Start Time=20");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "command line --set: key 'Start Time'")) << e.what();
    EXPECT_TRUE(contains(e.what(), "End Time")) << e.what();
  }
}

TEST_F(RunFile, EchoRoundTripsToIdenticalValues) {
  write("maps/dem.tif");
  write("maps/h.tif");
  const RunConfig a = RunConfig::fromText(
      "[openLISEM runfile version 6.0]\nMap Directory=maps\nDEM=dem.tif\nInitial Fluid Height=h.tif=1.5\n"
      "Include Initial Water=yes\nManning=0.2=0.5\nEnd Time=7.25\nTimestep=0.1\nLimiter=MinMod\n"
      "Device=1\nOutput Directory=out dir\nReport Series=0\n",
      dir(), talusRunKeys(), "a.run");
  const std::string echoed = a.echo();
  EXPECT_TRUE(contains(echoed, "[Numerics]")) << echoed;
  EXPECT_TRUE(contains(echoed, "[min] (from a.run:7)")) << echoed;
  EXPECT_TRUE(contains(echoed, "(default)")) << echoed;
  const RunConfig b = RunConfig::fromText(echoed, "/", talusRunKeys(), "echo.run");  // paths are absolute
  for (const KeySpec& k : talusRunKeys().keys()) {
    SCOPED_TRACE(k.name);
    switch (k.type) {
      case KeyType::Flag: EXPECT_EQ(a.flag(k.name), b.flag(k.name)); break;
      case KeyType::Integer:
      case KeyType::Real: EXPECT_EQ(a.real(k.name), b.real(k.name)); break;
      case KeyType::Choice: EXPECT_EQ(a.choice(k.name), b.choice(k.name)); break;
      case KeyType::Text: EXPECT_EQ(a.text(k.name), b.text(k.name)); break;
      case KeyType::Directory: EXPECT_EQ(a.directory(k.name), b.directory(k.name)); break;
      case KeyType::Map: {
        const auto ma = a.map(k.name), mb = b.map(k.name);
        EXPECT_EQ(ma.isFile, mb.isFile);
        EXPECT_EQ(ma.file, mb.file);
        EXPECT_EQ(ma.constant, mb.constant);
        EXPECT_EQ(ma.multiplier, mb.multiplier);
        break;
      }
    }
  }
}

TEST_F(RunFile, SetOverridesAndValidates) {
  RunConfig c = RunConfig::fromText("DEM=1\nCFL=0.4\n", dir(), talusRunKeys());
  c.set("cfl = 0.3");
  EXPECT_DOUBLE_EQ(c.real("CFL"), 0.3);
  EXPECT_EQ(c.origin("CFL"), "command line");
  c.set("Limiter=MC");
  EXPECT_EQ(c.choice("Limiter"), "mc");
  EXPECT_FALSE(c.isDefault("Limiter"));
  c.set("Manning=0.1=0.5");
  EXPECT_DOUBLE_EQ(c.map("Manning").multiplier, 0.5);
  c.set("Output Directory=res");
  EXPECT_EQ(c.directory("Output Directory"), (dir_ / "res").string());
  auto messageOf = [&c](const std::string& assignment) {
    try {
      c.set(assignment);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string range = messageOf("CFL=5");
  EXPECT_TRUE(contains(range, "command line --set: key 'CFL'")) << range;
  EXPECT_TRUE(contains(range, "[0.01, 1]")) << range;
  EXPECT_DOUBLE_EQ(c.real("CFL"), 0.3);  // unchanged after a rejected override
  EXPECT_TRUE(contains(messageOf("Maning=0.1"), "did you mean 'Manning'"));
  EXPECT_TRUE(contains(messageOf("CFL"), "command line --set"));
  EXPECT_TRUE(contains(messageOf("DEM=missing.tif"), "command line --set: key 'DEM'"));
  EXPECT_TRUE(contains(messageOf("Precision=half"), "float, double"));
}

TEST_F(RunFile, AccessorsRejectUndeclaredKeysAndWrongTypes) {
  const RunConfig c = RunConfig::fromText("DEM=1\n", dir(), talusRunKeys());
  EXPECT_THROW(c.real("Not A Key"), std::logic_error);
  EXPECT_THROW(c.origin("Not A Key"), std::logic_error);
  EXPECT_THROW(c.flag("CFL"), std::logic_error);
  EXPECT_THROW(c.real("Limiter"), std::logic_error);
  EXPECT_THROW(c.integer("CFL"), std::logic_error);
  EXPECT_THROW(c.map("Output Directory"), std::logic_error);
  EXPECT_THROW(c.directory("Device"), std::logic_error);
}

TEST_F(RunFile, RegistryIntegerKeysRulesAndTable) {
  KeyRegistry r;
  KeySpec n;
  n.name = "Particle Count";
  n.type = KeyType::Integer;
  n.defaultValue = "10";
  n.unit = "-";
  n.min = 0;
  n.max = 1000;
  n.help = "particles";
  n.section = "Misc";
  r.add(n);
  EXPECT_THROW(r.add(n), std::logic_error);  // declared twice
  KeySpec bad;
  bad.name = "Bad";
  bad.type = KeyType::Choice;
  bad.defaultValue = "x";
  bad.choices = {"a"};
  EXPECT_THROW(r.add(bad), std::logic_error);  // default not among the choices
  const RunConfig c = RunConfig::fromText("particle count=20=2\n", dir(), r);
  EXPECT_EQ(c.integer("Particle Count"), 40);
  EXPECT_DOUBLE_EQ(c.real("Particle Count"), 40);
  std::string msg;
  try {
    RunConfig::fromText("Particle Count=2.5\n", dir(), r);
  } catch (const InputError& e) {
    msg = e.what();
  }
  EXPECT_TRUE(contains(msg, "<text>:1: key 'Particle Count': value 2.5 is not an integer")) << msg;
  const std::string table = talusRunKeys().markdownTable();
  EXPECT_EQ(talus::io::describeKeys(talusRunKeys()).rfind(table, 0), 0u);  // the OpenLISEM table follows
  EXPECT_TRUE(contains(table, "### Numerics")) << table;
  EXPECT_TRUE(contains(table, "| `DEM` | map | (required) | m |")) << table;
  EXPECT_TRUE(contains(table, "| `CFL` | real | 0.5 | - | [0.01, 1] |")) << table;
  for (const char* name : {"Map Directory", "DEM", "Include Initial Water", "Initial Fluid Height", "Manning",
                           "Start Time", "End Time", "Timestep", "CFL", "Limiter", "Riemann Solver", "Precision",
                           "Device", "Boundary Type", "Nodata Boundary Type", "Slope Correction",
                           "Depth Pressure", "Minimum Flow Height", "Arrival Threshold", "Output Directory",
                           "Output Format", "Report Series"})
    EXPECT_NE(talusRunKeys().find(name), nullptr) << name;
}
