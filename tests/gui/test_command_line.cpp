// talus-gui started from a terminal with a run-file it cannot use: a missing one ends the program
// with an error naming the file on stderr; an invalid one is reported on stderr (file, line, key)
// and opened with the errors at the fields, as File > Open opens it.
#include <gtest/gtest.h>

#include <QAbstractButton>
#include <QApplication>
#include <QMessageBox>
#include <QPointer>
#include <QProcess>
#include <QTest>
#include <filesystem>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"

using talus::gui::MainWindow;
using namespace talus::guitest;
namespace fs = std::filesystem;

namespace {

/// Starts talus-gui with `args`; its settings (recent files, window layout) go to a scratch folder,
/// not the user's.
void startGui(QProcess& gui, const QStringList& args) {
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("XDG_CONFIG_HOME", QString::fromStdString(scratchDir("cli_settings").string()));
  gui.setProcessEnvironment(env);
  gui.start(TALUS_GUI_BINARY, args);
}

}  // namespace

TEST(GuiCommandLine, MissingRunFileIsReportedOnStderrAndExitsNonZero) {
  const fs::path dir = scratchDir("cli_missing");
  const QString missing = QString::fromStdString((dir / "nope.run").string());
  QProcess gui;
  startGui(gui, {missing});
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
  startGui(gui, {runFile});
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
  // Started from a desktop nobody reads stderr: a message box over the window says it too
  // (looked for among the display's windows, by its title).
  QProcess windows;
  windows.start("xwininfo", {"-root", "-tree"});
  if (windows.waitForFinished(10000) && windows.exitCode() == 0) {
    QString tree;
    waitFor([&] {
      QProcess again;
      again.start("xwininfo", {"-root", "-tree"});
      again.waitForFinished(10000);
      tree = QString::fromLocal8Bit(again.readAllStandardOutput());
      return tree.contains("\"Run-file not valid\"");
    }, 10);
    EXPECT_TRUE(tree.contains("\"Run-file not valid\"")) << "no message box among the windows:\n" << tree.toStdString();
  } else {
    ADD_FAILURE() << "xwininfo (x11-utils) is needed to look for the message box";
  }
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

TEST(GuiCommandLine, ProblemsAreShownInAMessageBoxThatDoesNotBlock) {
  const QString runFile = QString::fromStdString(writeExampleRunFile(scratchDir("cli_box"), "CFL=5\n"));
  MainWindow w;
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  QString problems;
  ASSERT_TRUE(w.openRunFile(runFile, &problems));
  ASSERT_FALSE(problems.isEmpty());
  QMessageBox* box = w.reportProblems("Run-file not valid", problems);
  ASSERT_NE(box, nullptr);
  // reportProblems returned with the box open: nothing waits for it to be answered.
  EXPECT_TRUE(waitFor([&] { return box->isVisible(); }, 5));
  EXPECT_TRUE(box->text().contains("key 'CFL'")) << box->text().toStdString();
  EXPECT_EQ(QApplication::activeModalWidget(), box);
  EXPECT_TRUE(w.logText().contains("error: ")) << w.logText().toStdString();
  QPointer<QMessageBox> gone(box);
  box->button(QMessageBox::Ok)->click();
  EXPECT_TRUE(waitFor([&] { return gone.isNull() || !gone->isVisible(); }, 5)) << "the answered box stays";

  // Switched off (tests, scripts): the log only.
  w.setReportInDialogs(false);
  EXPECT_EQ(w.reportProblems("Run-file not valid", problems), nullptr);
  waitFor([] { return false; }, 0.2);
  EXPECT_EQ(QApplication::activeModalWidget(), nullptr);
}
