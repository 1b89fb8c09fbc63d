// GUI test runner: GoogleTest inside a QApplication with an OpenGL 3.3 core default format. Run it
// on a display (xvfb-run -a in CI). Listing the tests (ctest discovery) needs no display.
#include <gtest/gtest.h>

#include <QApplication>
#include <QSurfaceFormat>
#include <cstring>

#include "render/GlSetup.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
  talus::gui::requestCoreProfile33();
  QApplication app(argc, argv);
  QApplication::setOrganizationName("TalusTests");
  QApplication::setApplicationName("talus-gui-tests");
  return RUN_ALL_TESTS();
}
