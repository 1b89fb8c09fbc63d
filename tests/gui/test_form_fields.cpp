// The run-file form: dependent fields are disabled while they do not matter, angles are typed in
// degrees (the file keeps radians), cohesion in Pa (the file keeps OpenLISEM's kPa), and only the
// sections of processes that are on start expanded.
#include <gtest/gtest.h>

#include <QCheckBox>
#include <QTest>
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"

using talus::gui::KeyField;
using talus::gui::MainWindow;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

/// Clicks a flag field's check box, as the user would.
void clickFlag(KeyField* flag) {
  ASSERT_NE(flag, nullptr);
  auto* box = flag->findChild<QCheckBox*>();
  ASSERT_NE(box, nullptr);
  box->click();
}

}  // namespace

TEST(FormFields, BedFrictionAngleDisabledWhileItEqualsTheIfa) {
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(
      scratchDir("form_dependent"), "Include Initial Solids=1\nBed Friction Equals IFA=1\n"))));
  KeyField* angle = w.form().field("Bed Friction Angle");
  ASSERT_NE(angle, nullptr);
  EXPECT_FALSE(angle->isEnabled()) << "Bed Friction Angle editable although it equals the IFA";
  EXPECT_TRUE(angle->toolTip().contains("not used now"));
  clickFlag(w.form().field("Bed Friction Equals IFA"));
  EXPECT_EQ(w.document()->value("Bed Friction Equals IFA"), "0");
  EXPECT_TRUE(angle->isEnabled());
  clickFlag(w.form().field("Bed Friction Equals IFA"));
  EXPECT_FALSE(angle->isEnabled());
}

TEST(FormFields, ProcessMapsAndOtherPairsFollowTheirSwitch) {
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("form_pairs")))));
  // A map of a process that is off (KeySpec::enabledBy).
  KeyField* solids = w.form().field("Initial Solid Height");
  EXPECT_FALSE(solids->isEnabled());
  clickFlag(w.form().field("Include Initial Solids"));
  EXPECT_TRUE(solids->isEnabled());
  EXPECT_TRUE(w.form().field("Initial Fluid Height")->isEnabled());  // Include Initial Water=1
  clickFlag(w.form().field("Include Initial Water"));
  EXPECT_FALSE(w.form().field("Initial Fluid Height")->isEnabled());
  // Young Modulus is read while Elastic Modulus (the bulk modulus) is 0.
  KeyField* young = w.form().field("Young Modulus");
  EXPECT_TRUE(young->isEnabled());
  w.form().field("Elastic Modulus")->typeText("1e9");
  EXPECT_EQ(w.document()->value("Elastic Modulus"), "1e9");
  EXPECT_FALSE(young->isEnabled());
  w.form().field("Elastic Modulus")->typeText("0");
  EXPECT_TRUE(young->isEnabled());
  // A basal law's parameters only with that law.
  EXPECT_FALSE(w.form().field("Voellmy Mu")->isEnabled());  // Solid Rheology=coulomb (default)
  // The time scheme is a choice of water-only runs: solids make the run two-phase (unsplit).
  // Include Initial Solids was switched on above.
  EXPECT_FALSE(w.form().field("Time Scheme")->isEnabled());
  clickFlag(w.form().field("Include Initial Solids"));
  EXPECT_TRUE(w.form().field("Time Scheme")->isEnabled());
}

TEST(FormFields, AnglesInDegreesInTheFormRadiansInTheFile) {
  const fs::path dir = scratchDir("form_degrees");
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(
      dir, "Include Initial Solids=1\nBed Friction Equals IFA=0\nBed Friction Angle=0.5\n"))));
  KeyField* angle = w.form().field("Bed Friction Angle");
  EXPECT_EQ(angle->unitText(), "deg");
  EXPECT_EQ(angle->shownText(), "28.6479");  // 0.5 rad
  angle->typeText("30");
  EXPECT_EQ(w.saveRunFile(), "");
  const std::string saved = readText(dir / "scene.run");
  EXPECT_NE(saved.find("Bed Friction Angle=0.523599\n"), std::string::npos) << saved;

  MainWindow again;
  ASSERT_TRUE(again.openRunFile(QString::fromStdString((dir / "scene.run").string())));
  EXPECT_EQ(again.form().field("Bed Friction Angle")->shownText(), "30");
  EXPECT_EQ(again.form().field("Bed Friction Angle")->value(), "0.523599");
  // A map of angles given as a file keeps the file's unit (radians in the raster).
  KeyField* ifa = again.form().field("Initial Solid IFA");
  ifa->typeText("ifa.tif");
  EXPECT_EQ(ifa->unitText(), "rad");
  EXPECT_EQ(again.document()->value("Initial Solid IFA"), "ifa.tif");
  ifa->typeText("35");
  EXPECT_EQ(ifa->unitText(), "deg");
  EXPECT_EQ(again.document()->value("Initial Solid IFA"), "0.610865");
}

TEST(FormFields, CohesionInPaInTheFormKpaInTheFile) {
  const fs::path dir = scratchDir("form_cohesion");
  MainWindow w;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir, "Include Initial Solids=1\nInitial Cohesion=2.5\n"))));
  KeyField* c = w.form().field("Initial Cohesion");
  EXPECT_EQ(c->unitText(), "Pa");  // as the cohesion layer and the other stresses (Yield Stress)
  EXPECT_EQ(w.form().field("Yield Stress")->unitText(), "Pa");
  EXPECT_EQ(c->shownText(), "2500");
  c->typeText("4000");
  EXPECT_EQ(w.saveRunFile(), "");
  const std::string saved = readText(dir / "scene.run");
  EXPECT_NE(saved.find("Initial Cohesion=4\n"), std::string::npos) << saved;
}

TEST(FormFields, WaterOnlyRunFileCollapsesTheSolidsSections) {
  MainWindow w;
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("form_sections")))));
  for (const char* off : {"Solids", "Entrainment", "Particles", "Rain and infiltration", "OpenLISEM Hazard inputs"})
    EXPECT_FALSE(w.form().sectionExpanded(off)) << off << " expanded in a water-only run-file";
  for (const char* on : {"Input", "Time", "Flow", "Numerics", "Output"})
    EXPECT_TRUE(w.form().sectionExpanded(on)) << on;
  EXPECT_FALSE(w.form().field("Initial Solid Height")->isVisible());
  EXPECT_FALSE(w.form().field("Particles Per Cell")->isVisible());
  EXPECT_TRUE(w.form().field("CFL")->isVisible());

  // A run-file with solids shows their section; one with rain its own.
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(
      writeExampleRunFile(scratchDir("form_sections_solids"), "Include Initial Solids=1\nInclude Infiltration=1\n"))));
  EXPECT_TRUE(w.form().sectionExpanded("Solids"));
  EXPECT_TRUE(w.form().field("Initial Solid Height")->isVisible());
  EXPECT_TRUE(w.form().sectionExpanded("Rain and infiltration"));
  EXPECT_FALSE(w.form().sectionExpanded("Particles"));
}

TEST(FormFields, AProblemInACollapsedSectionOpensIt) {
  MainWindow w;
  w.setAskBeforeOverwrite(false);
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("form_section_error")))));
  ASSERT_FALSE(w.form().sectionExpanded("Solids"));
  w.document()->setValue("Drag M", "50");  // outside 1..10
  EXPECT_FALSE(w.startRun());
  EXPECT_FALSE(w.form().field("Drag M")->error().isEmpty());
  EXPECT_TRUE(w.form().sectionExpanded("Solids")) << "the problem stays hidden in a collapsed section";

  // Opening a run-file with a problem there shows it too.
  MainWindow again;
  again.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("form_section_error2"), "Include Slope Failure=1\n")));
  EXPECT_FALSE(again.form().field("Include Slope Failure")->error().isEmpty());
  EXPECT_TRUE(again.form().sectionExpanded("OpenLISEM Hazard processes and settings"));
}

TEST(FormFields, CohesionOfTheFormMatchesTheCohesionLayer) {
  // The form and the cohesion layer of a two-phase run show the same number in the same unit.
  const fs::path dir = scratchDir("form_cohesion_layer");
  MainWindow w;
  w.setAskBeforeOverwrite(false);
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(
      dir, "Include Initial Solids=1\nInitial Solid Height=water.tif\nInitial Cohesion=2.5\nEnd Time=20\n"))));
  const KeyField* c = w.form().field("Initial Cohesion");
  ASSERT_TRUE(w.startRun()) << w.logText().toStdString();
  talus::gui::RunController& run = w.controller();
  ASSERT_TRUE(waitFor([&] { return run.lastProgress().steps >= 2; }, 120)) << w.logText().toStdString();
  run.pause();
  run.requestSnapshot();
  ASSERT_TRUE(waitFor([&] { return w.viewer().snapshot() && w.viewer().snapshot()->steps == run.lastProgress().steps; }, 30));
  w.layers().selectLayer("cohesion");
  ASSERT_EQ(w.layers().layer(), "cohesion") << "no cohesion layer";
  EXPECT_EQ(w.layers().layerUnit(), c->unitText());
  const std::vector<float>* values = w.viewer().snapshot()->layer("cohesion");
  ASSERT_NE(values, nullptr);
  float most = 0;
  for (float v : *values)
    if (std::isfinite(v)) most = std::max(most, v);
  EXPECT_NEAR(most, c->shownText().toDouble(), 1e-3 * c->shownText().toDouble()) << "layer " << most << " form "
                                                                                 << c->shownText().toStdString();
  run.stop();
  ASSERT_TRUE(waitFor([&] { return run.state() == talus::gui::RunController::State::Ended; }, 120));
}
