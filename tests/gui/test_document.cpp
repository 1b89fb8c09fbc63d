// Run-file documents edited by the form: values read as written, edits saved in run-file syntax
// with comments and order kept, and new keys placed in their section; RunConfig reads the result.
#include <gtest/gtest.h>

#include <filesystem>

#include "GuiTestSupport.hpp"
#include "form/RunFileDocument.hpp"
#include "form/RunValidation.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"

using namespace talus;

TEST(RunFileDocument, EditsAreSavedInRunFileSyntax) {
  const auto dir = guitest::scratchDir("document");
  const std::string text =
      "[Talus run file]\n# a comment that must survive\n[Input]\nMap Directory=" + std::string(TALUS_TEST_DATA_DIR) +
      "/kot_dambreak\nDEM=dem.tif\n\n[Numerics]\nCFL=0.5\n\n[Output]\nOutput Directory=out\n";
  gui::RunFileDocument doc = gui::RunFileDocument::fromText(text, (dir / "a.run").string(), talusRunKeys());
  EXPECT_EQ(doc.value("cfl"), "0.5");
  EXPECT_EQ(doc.value("Manning"), "0.01");  // the default
  EXPECT_FALSE(doc.isGiven("Manning"));
  doc.setValue("CFL", "0.4");
  doc.setValue("Limiter", "mc");  // equals the default: adds nothing
  doc.setValue("Arrival Threshold", "0.05");
  doc.setValue("Manning", "0.03");  // its [Flow] section does not exist yet
  EXPECT_TRUE(doc.isModified());
  const std::string saved = doc.text();
  EXPECT_NE(saved.find("# a comment that must survive\n"), std::string::npos);
  EXPECT_NE(saved.find("CFL=0.4\n"), std::string::npos);
  EXPECT_EQ(saved.find("Limiter"), std::string::npos);
  EXPECT_LT(saved.find("[Output]"), saved.find("Arrival Threshold=0.05"));
  EXPECT_LT(saved.find("[Flow]"), saved.find("Manning=0.03"));
  const std::string path = (dir / "saved.run").string();
  doc.save(path);
  EXPECT_FALSE(doc.isModified());
  const io::RunConfig cfg = io::RunConfig::load(path, talusRunKeys());
  EXPECT_DOUBLE_EQ(cfg.real("CFL"), 0.4);
  EXPECT_DOUBLE_EQ(cfg.real("Arrival Threshold"), 0.05);
  EXPECT_DOUBLE_EQ(cfg.map("Manning").constant, 0.03);
}

TEST(RunValidation, ProblemsGoToTheFieldsTheyName) {
  const auto dir = guitest::scratchDir("validation");
  gui::RunFileDocument doc = gui::RunFileDocument::fromText(
      "[Input]\nDEM=nothing.tif\n[Numerics]\nCFL=2\nLimiter=superbee\nFoo=1\n", (dir / "b.run").string(),
      talusRunKeys());
  const gui::ValidationResult r = gui::validateDocument(doc);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.fieldErrors.count("cfl"), 1u);
  EXPECT_EQ(r.fieldErrors.count("limiter"), 1u);
  EXPECT_EQ(r.fieldErrors.count("dem"), 1u);
  ASSERT_EQ(r.generalErrors.size(), 1u);
  EXPECT_NE(r.generalErrors[0].find("unknown key"), std::string::npos);
  EXPECT_NE(r.fieldErrors.at("cfl").find("b.run:4"), std::string::npos) << r.fieldErrors.at("cfl");
}
