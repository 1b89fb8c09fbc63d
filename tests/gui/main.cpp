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
  // Settings (recent files, window layout) go to a scratch folder, emptied at each start, never to
  // the user's own: every test run starts from no saved layout.
  const std::filesystem::path settings = std::filesystem::temp_directory_path() / "talus_gui_test_settings";
  std::filesystem::remove_all(settings);
  QSettings::setDefaultFormat(QSettings::IniFormat);
  QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, QString::fromStdString(settings.string()));
  return RUN_ALL_TESTS();
}
