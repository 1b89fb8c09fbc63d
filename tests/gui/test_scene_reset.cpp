// Opening a run-file replaces the previous scene: its run, viewer, plots and status go, also when
// the new run-file is invalid; Restart runs the open run-file as it is now, after asking.
#include <gtest/gtest.h>

#include <QMessageBox>
#include <filesystem>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"

using talus::gui::MainWindow;
using talus::gui::RunController;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

/// Runs the open run-file of `w` to its end (End Time short) with a snapshot in the viewer.
void runToEnd(MainWindow& w) {
  ASSERT_TRUE(w.startRun()) << w.logText().toStdString();
  ASSERT_TRUE(waitFor([&] { return w.controller().state() == RunController::State::Ended; }, 120))
      << w.logText().toStdString();
  ASSERT_TRUE(waitFor([&] { return w.viewer().snapshot() != nullptr; }, 30));
}

}  // namespace

TEST(SceneReset, OpeningAnInvalidRunFileLeavesNothingOfThePreviousScene) {
  MainWindow w;
  w.setAskBeforeOverwrite(false);
  w.resize(1200, 800);
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("reset_a"), "End Time=0.05\n"))));
  runToEnd(w);
  // What the finished run shows: terrain and flow, plots, the time reached.
  EXPECT_GT(distinctColours(w.viewer().grabFramebuffer()), 200);
  EXPECT_GT(w.plots().volumePlot().size(0), 0u);
  EXPECT_TRUE(w.status().text().contains("t = ")) << w.status().text().toStdString();
  EXPECT_EQ(w.layers().layer(), "h");

  const std::string invalid = writeExampleRunFile(scratchDir("reset_b"), "CFL=5\n");
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(invalid)));
  waitFor([] { return false; }, 0.5);  // anything the old run still had queued would arrive now
  EXPECT_EQ(w.controller().state(), RunController::State::Idle);
  EXPECT_EQ(w.controller().viewFields(), nullptr);
  EXPECT_EQ(w.viewer().snapshot(), nullptr);
  EXPECT_EQ(w.plots().volumePlot().size(0), 0u);
  EXPECT_FALSE(w.status().text().contains("t = ")) << w.status().text().toStdString();
  EXPECT_TRUE(w.status().text().startsWith("idle")) << w.status().text().toStdString();
  EXPECT_EQ(w.layers().layer(), "");
  EXPECT_FALSE(w.restartRun());  // nothing of this run-file has run
  // The viewer draws the background alone: no terrain of the old scene.
  EXPECT_EQ(distinctColours(w.viewer().grabFramebuffer()), 1);
  EXPECT_FALSE(w.form().field("CFL")->error().isEmpty());

  // A valid one shows its own terrain and initial maps, still without results.
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("reset_c")))));
  EXPECT_GT(distinctColours(w.viewer().grabFramebuffer()), 200);
  const auto initial = w.viewer().snapshot();
  ASSERT_NE(initial, nullptr);
  EXPECT_EQ(initial->steps, 0);
  EXPECT_EQ(initial->time, 0.0);
  EXPECT_EQ(initial->layerNames, std::vector<std::string>{"initial water height"});
  EXPECT_EQ(w.plots().volumePlot().size(0), 0u);
}

TEST(SceneReset, NoRunFileOpensDuringARun) {
  MainWindow w;
  w.setAskBeforeOverwrite(false);
  w.show();
  const QString first = QString::fromStdString(writeExampleRunFile(scratchDir("reset_busy"), "End Time=30\n"));
  ASSERT_TRUE(w.openRunFile(first));
  ASSERT_TRUE(w.startRun());
  ASSERT_TRUE(waitFor([&] { return w.controller().state() == RunController::State::Running; }, 120));
  QString problems;
  EXPECT_FALSE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("reset_other"))), &problems));
  EXPECT_TRUE(problems.contains("run is in progress")) << problems.toStdString();
  EXPECT_EQ(QString::fromStdString(w.document()->path()), first);
  EXPECT_EQ(w.controller().state(), RunController::State::Running);
  w.controller().stop();
  ASSERT_TRUE(waitFor([&] { return w.controller().state() == RunController::State::Ended; }, 120));
}

TEST(SceneReset, RestartAsksAndRunsTheOpenRunFileAsItIsNow) {
  const fs::path dir = scratchDir("restart");
  MainWindow w;  // asks before replacing results
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir, "End Time=0.05\n"))));
  runToEnd(w);  // the first run into an empty folder asks nothing
  EXPECT_DOUBLE_EQ(w.controller().lastProgress().endTime, 3.0);  // End Time is in minutes
  w.document()->setValue("End Time", "0.1");

  // Declined: nothing starts, the results stay.
  auto asked = answerNextMessageBox(QMessageBox::No);
  EXPECT_FALSE(w.restartRun());
  EXPECT_TRUE(asked->contains(QString::fromStdString((dir / "out").string()))) << asked->toStdString();
  EXPECT_EQ(w.controller().state(), RunController::State::Ended);
  EXPECT_DOUBLE_EQ(w.controller().lastProgress().endTime, 3.0);
  EXPECT_GT(w.plots().volumePlot().size(0), 0u);

  // Accepted: the run-file as edited runs again.
  asked = answerNextMessageBox(QMessageBox::Yes);
  ASSERT_TRUE(w.restartRun());
  EXPECT_FALSE(asked->isEmpty());
  ASSERT_TRUE(waitFor([&] { return w.controller().state() == RunController::State::Ended; }, 120));
  EXPECT_DOUBLE_EQ(w.controller().lastProgress().endTime, 6.0);
  EXPECT_NEAR(w.controller().lastProgress().time, 6.0, 1e-9);
}

TEST(SceneReset, RestartDuringARunStopsItAndStartsTheEditedRunFile) {
  MainWindow w;
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("restart_busy"), "End Time=30\n"))));
  ASSERT_TRUE(w.startRun());
  ASSERT_TRUE(waitFor([&] { return w.controller().lastProgress().steps >= 5; }, 120));
  w.document()->setValue("End Time", "0.05");
  auto asked = answerNextMessageBox(QMessageBox::Yes);
  ASSERT_TRUE(w.restartRun());
  EXPECT_TRUE(asked->contains("in progress")) << asked->toStdString();
  // The stopped run ends first; the restart then runs to the new end.
  ASSERT_TRUE(waitFor([&] {
    return w.controller().state() == RunController::State::Ended && w.controller().lastProgress().endTime == 3.0;
  }, 120)) << w.logText().toStdString();
  EXPECT_NEAR(w.controller().lastProgress().time, 3.0, 1e-9);
  EXPECT_TRUE(w.logText().contains("run stopped")) << w.logText().toStdString();
}
