// GUI test runner: GoogleTest inside a QApplication with an OpenGL 3.3 core default format. Run it
// on a display (xvfb-run -a in CI). Listing the tests (ctest discovery) needs no display.
#include <gtest/gtest.h>

#include <QApplication>
#include <QSettings>
#include <QSurfaceFormat>
#include <cstring>
#include <filesystem>

#include "render/GlSetup.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
  talus::gui::requestCoreProfile33();
  QApplication app(argc, argv);
  QApplication::setOrganizationName("TalusTests");
  QApplication::setApplicationName("talus-gui-tests");
  // Settings (recent files, window layout) go to a scratch folder, of its own per run, never to
  // the user's own: every test run starts from no saved layout. Programs the tests start get their
  // own (XDG_CONFIG_HOME, test_command_line.cpp).
  // One folder per test process (ctest -j runs several at once), removed when it ends.
  const std::filesystem::path settings = std::filesystem::temp_directory_path() /
      ("talus_gui_test_settings_" + std::to_string(QCoreApplication::applicationPid()));
  std::filesystem::remove_all(settings);
  // Both formats: Qt's own settings (QFileDialog's history, organisation QtProject) use the native one.
  for (QSettings::Format f : {QSettings::NativeFormat, QSettings::IniFormat})
    QSettings::setPath(f, QSettings::UserScope, QString::fromStdString(settings.string()));
  const int result = RUN_ALL_TESTS();
  std::filesystem::remove_all(settings);
  return result;
}
