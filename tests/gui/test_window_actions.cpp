// Keyboard and window actions of the main window: Ctrl+Shift+S saves as (through the dialog), and
// closing the window during a run asks first.
#include <gtest/gtest.h>

#include <QApplication>
#include <QFileDialog>
#include <QMessageBox>
#include <QTest>
#include <filesystem>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"

using talus::gui::MainWindow;
using talus::gui::RunController;
using namespace talus::guitest;
namespace fs = std::filesystem;

TEST(WindowActions, CtrlShiftSSavesAsThroughTheDialog) {
  const fs::path dir = scratchDir("shortcut_saveas");
  const std::string original = writeExampleRunFile(dir);
  const fs::path copy = dir / "copy.run";
  QApplication::setAttribute(Qt::AA_DontUseNativeDialogs);  // the Qt dialog, which the test can answer
  MainWindow w;
  w.show();
  w.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&w)) << "the window is not active: shortcuts would not reach it";
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(original)));
  w.document()->setValue("CFL", "0.3");

  bool dialogSeen = false;
  onNextModal([&](QWidget* modal) {
    auto* dialog = qobject_cast<QFileDialog*>(modal);
    if (!dialog) {
      modal->close();
      return;
    }
    dialogSeen = dialog->acceptMode() == QFileDialog::AcceptSave;
    chooseInFileDialog(dialog, copy);
  });
  QTest::keyClick(&w, Qt::Key_S, Qt::ControlModifier | Qt::ShiftModifier);
  waitFor([&] { return fs::exists(copy); }, 10);
  EXPECT_TRUE(dialogSeen) << "no save dialog opened";
  ASSERT_TRUE(fs::exists(copy));
  EXPECT_NE(readText(copy).find("CFL=0.3"), std::string::npos) << readText(copy);
  EXPECT_EQ(w.document()->path(), copy.string());
  EXPECT_EQ(readText(original).find("CFL=0.3"), std::string::npos);  // the original is untouched
}

TEST(WindowActions, ClosingDuringARunAsksFirst) {
  MainWindow w;
  w.setAskBeforeOverwrite(false);
  w.show();
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(scratchDir("close_run"), "End Time=30\n"))));
  ASSERT_TRUE(w.startRun());
  ASSERT_TRUE(waitFor([&] { return w.controller().state() == RunController::State::Running; }, 120));

  auto asked = answerNextMessageBox(QMessageBox::No);
  EXPECT_FALSE(w.close());
  EXPECT_TRUE(asked->contains("run is in progress")) << asked->toStdString();
  EXPECT_TRUE(w.isVisible());
  EXPECT_EQ(w.controller().state(), RunController::State::Running);

  asked = answerNextMessageBox(QMessageBox::Yes);
  EXPECT_TRUE(w.close());
  EXPECT_FALSE(asked->isEmpty());
  ASSERT_TRUE(waitFor([&] { return w.controller().state() == RunController::State::Ended; }, 120));
  EXPECT_TRUE(w.logText().contains("run stopped")) << w.logText().toStdString();

  // Without a run, closing asks nothing (a question would be answered No and keep it open).
  MainWindow idle;
  idle.show();
  asked = answerNextMessageBox(QMessageBox::No, 1.0);
  EXPECT_TRUE(idle.close());
  waitFor([] { return false; }, 1.2);
  EXPECT_TRUE(asked->isEmpty()) << asked->toStdString();
}
