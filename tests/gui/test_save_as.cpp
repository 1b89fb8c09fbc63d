// Save as into another folder: the copy's relative map paths are rewritten, so that it reads the
// same maps as the original; the original file is left as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "form/RunFileDocument.hpp"
#include "form/RunValidation.hpp"
#include "sim/RunKeys.hpp"

using talus::gui::MainWindow;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

/// A scene folder holding its own maps (dem.tif, water.tif) and a run-file `text`; returns its path.
fs::path sceneWithMaps(const std::string& name, const std::string& text) {
  const fs::path dir = scratchDir(name) / "site";
  fs::create_directories(dir / "maps");
  for (const char* map : {"dem.tif", "water.tif"})
    fs::copy_file(fs::path(TALUS_TEST_DATA_DIR) / "kot_dambreak" / map, dir / "maps" / map);
  std::ofstream(dir / "scene.run") << text;
  return dir / "scene.run";
}

/// The value of `key` in run-file text.
std::string valueIn(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + "=", 0) == 0) return line.substr(key.size() + 1);
  return "(not given)";
}

/// The saved run-file validated where it lies (the test fails with its problems when it is not
/// valid, e.g. a map not found): the map files it reads.
talus::io::RunConfig validateSaved(const fs::path& file) {
  const auto doc = talus::gui::RunFileDocument::load(file.string(), talus::talusRunKeys());
  const talus::gui::ValidationResult r = talus::gui::validateDocument(doc);
  if (!r.ok()) throw std::runtime_error("the saved run-file is not valid: " + talus::gui::describeProblems(r));
  return *r.config;
}

const std::string kRest = "Include Initial Water=1\nEnd Time=0.05\n[Output]\nOutput Directory=out\n";

}  // namespace

TEST(SaveAs, ARelativeMapDirectoryIsRewrittenForTheNewFolder) {
  const fs::path original = sceneWithMaps("saveas_dir", "[Input]\nMap Directory=maps\nDEM=dem.tif\n"
                                                        "Initial Fluid Height=water.tif=0.5\nManning=0.05\n" + kRest);
  const std::string before = readText(original);
  const fs::path copy = original.parent_path().parent_path() / "elsewhere" / "deeper" / "copy.run";
  fs::create_directories(copy.parent_path());
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(original.string())));
  ASSERT_EQ(w.saveRunFile(QString::fromStdString(copy.string())), "");

  const std::string saved = readText(copy);
  EXPECT_EQ(valueIn(saved, "Map Directory"), "../../site/maps") << saved;
  EXPECT_EQ(valueIn(saved, "DEM"), "dem.tif");  // relative to the Map Directory, which moved
  EXPECT_EQ(valueIn(saved, "Output Directory"), "out");  // the copy's outputs go next to it
  const talus::io::RunConfig config = validateSaved(copy);
  EXPECT_TRUE(fs::equivalent(config.map("DEM").file, original.parent_path() / "maps" / "dem.tif"));
  EXPECT_TRUE(fs::equivalent(config.map("Initial Fluid Height").file, original.parent_path() / "maps" / "water.tif"));
  EXPECT_DOUBLE_EQ(config.map("Initial Fluid Height").multiplier, 0.5);
  EXPECT_EQ(readText(original), before);
  // The window now edits the copy, with the rewritten folder in its field.
  EXPECT_EQ(w.document()->path(), copy.string());
  EXPECT_EQ(w.form().field("Map Directory")->value(), "../../site/maps");
  EXPECT_FALSE(w.document()->isModified());
}

TEST(SaveAs, TheExampleWithMapDirectoryDotFindsItsMapsFromAnotherFolder) {
  const fs::path example = fs::path(TALUS_TEST_DATA_DIR) / "kot_dambreak" / "kot_dambreak.run";
  ASSERT_EQ(valueIn(readText(example), "Map Directory"), ".");
  const fs::path copy = scratchDir("saveas_example") / "copy.run";
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(example.string())));
  ASSERT_EQ(w.saveRunFile(QString::fromStdString(copy.string())), "");
  EXPECT_NE(valueIn(readText(copy), "Map Directory"), ".");
  const talus::io::RunConfig config = validateSaved(copy);
  EXPECT_TRUE(fs::equivalent(config.map("DEM").file, example.parent_path() / "dem.tif"));
}

TEST(SaveAs, WithoutAMapDirectoryTheRelativeMapFilesAreRewritten) {
  const fs::path original = sceneWithMaps("saveas_files", "[Input]\nDEM=maps/dem.tif\n"
                                                          "Initial Fluid Height=maps\\water.tif=0.5\nManning=0.05\n" + kRest);
  const fs::path copy = original.parent_path().parent_path() / "other" / "copy.run";
  fs::create_directories(copy.parent_path());
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(original.string())));
  ASSERT_EQ(w.saveRunFile(QString::fromStdString(copy.string())), "");
  const std::string saved = readText(copy);
  EXPECT_EQ(valueIn(saved, "DEM"), "../site/maps/dem.tif") << saved;
  EXPECT_EQ(valueIn(saved, "Initial Fluid Height"), "../site/maps/water.tif=0.5") << saved;
  EXPECT_EQ(valueIn(saved, "Manning"), "0.05");  // a uniform value, not a file
  EXPECT_EQ(valueIn(saved, "Map Directory"), "(not given)");
  const talus::io::RunConfig config = validateSaved(copy);
  EXPECT_TRUE(fs::equivalent(config.map("DEM").file, original.parent_path() / "maps" / "dem.tif"));
  EXPECT_DOUBLE_EQ(config.map("Initial Fluid Height").multiplier, 0.5);
}

TEST(SaveAs, AbsolutePathsAndTheSameFolderAreLeftAsTheyAre) {
  const fs::path dir = scratchDir("saveas_abs");
  const std::string original = writeExampleRunFile(dir);  // Map Directory is absolute
  const std::string mapDir = valueIn(readText(original), "Map Directory");
  ASSERT_TRUE(fs::path(mapDir).is_absolute());
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(original)));
  fs::create_directories(dir / "sub");
  ASSERT_EQ(w.saveRunFile(QString::fromStdString((dir / "sub" / "copy.run").string())), "");
  EXPECT_EQ(valueIn(readText(dir / "sub" / "copy.run"), "Map Directory"), mapDir);
  validateSaved(dir / "sub" / "copy.run");

  // Into the run-file's own folder with a relative Map Directory: written as it was.
  const fs::path local = sceneWithMaps("saveas_same", "[Input]\nMap Directory=maps\nDEM=dem.tif\n" + kRest);
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(local.string())));
  ASSERT_EQ(w.saveRunFile(QString::fromStdString((local.parent_path() / "again.run").string())), "");
  EXPECT_EQ(readText(local.parent_path() / "again.run"), readText(local));
}
