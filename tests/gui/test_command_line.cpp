// talus-gui started from a terminal with a run-file it cannot use: a missing one ends the program
// with an error naming the file on stderr; an invalid one is reported on stderr (file, line, key)
// and opened with the errors at the fields, as File > Open opens it.
#include <gtest/gtest.h>

#include <QProcess>
#include <filesystem>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"

using talus::gui::MainWindow;
using namespace talus::guitest;
namespace fs = std::filesystem;

TEST(GuiCommandLine, MissingRunFileIsReportedOnStderrAndExitsNonZero) {
  const fs::path dir = scratchDir("cli_missing");
  const QString missing = QString::fromStdString((dir / "nope.run").string());
  QProcess gui;
  gui.start(TALUS_GUI_BINARY, {missing});
  ASSERT_TRUE(gui.waitForFinished(60000)) << "talus-gui did not end for a missing run-file";
  const QString err = QString::fromLocal8Bit(gui.readAllStandardError());
  EXPECT_EQ(gui.exitStatus(), QProcess::NormalExit);
  EXPECT_NE(gui.exitCode(), 0);
  EXPECT_TRUE(err.contains("cannot read run-file '" + missing + "'")) << err.toStdString();
  EXPECT_TRUE(err.contains("No such file")) << err.toStdString();
}

TEST(GuiCommandLine, InvalidRunFileIsReportedOnStderrAndOpenedWithTheErrorsAtTheFields) {
  const fs::path dir = scratchDir("cli_invalid");
  const QString runFile = QString::fromStdString(writeExampleRunFile(dir, "CFL=5\n"));
  QProcess gui;
  gui.start(TALUS_GUI_BINARY, {runFile});
  QString err;
  const bool reported = waitFor([&] {
    err += QString::fromLocal8Bit(gui.readAllStandardError());
    return err.contains("key 'CFL'") || gui.state() == QProcess::NotRunning;
  }, 60);
  // The line of the key is named (file:line: key 'CFL': ...), and the window stays open.
  EXPECT_TRUE(reported && err.contains(runFile + ":")) << err.toStdString();
  EXPECT_TRUE(err.contains("key 'CFL'") && err.contains("outside the valid range")) << err.toStdString();
  waitFor([] { return false; }, 1.0);
  EXPECT_EQ(gui.state(), QProcess::Running) << "the window closed: " << err.toStdString();
  gui.kill();
  gui.waitForFinished(10000);

  // In the window: the same problems, at the field, as File > Open shows them.
  MainWindow w;
  QString problems;
  ASSERT_TRUE(w.openRunFile(runFile, &problems));
  EXPECT_TRUE(problems.contains("key 'CFL'")) << problems.toStdString();
  EXPECT_TRUE(w.form().field("CFL")->error().contains("outside the valid range"));
  QString none;
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("cli_valid"))), &none));
  EXPECT_TRUE(none.isEmpty()) << none.toStdString();
}
