// Options of the viewer and the form a desktop user reaches for (issue 17): the tilted view's
// vertical exaggeration (the relief drawn higher, the map view unchanged) and the Device key's picker
// (each listed OpenCL device, chosen from the menu, is the one its written name selects).
#include <gtest/gtest.h>

#include <QAction>
#include <QMenu>
#include <QTest>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"
#include "compute/Device.hpp"
#include "form/DevicePicker.hpp"
#include "form/KeyField.hpp"

using talus::gui::MainWindow;
using talus::gui::ViewCamera;
using namespace talus::guitest;

namespace {

/// Fraction of pixels that differ between two images of the same size.
double changedFraction(const QImage& a, const QImage& b) {
  if (a.size() != b.size()) return 1.0;
  long long changed = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) changed += (a.pixel(x, y) & 0xffffff) != (b.pixel(x, y) & 0xffffff);
  return double(changed) / (double(a.width()) * a.height());
}

}  // namespace

TEST(TiltedView, VerticalExaggerationRaisesTheReliefAndLeavesTheMapViewAlone) {
  const auto dir = scratchDir("exaggeration");
  MainWindow w;
  ASSERT_NO_FATAL_FAILURE(showExampleWindow(w, dir));
  auto& v = w.viewer();
  const QImage map1 = v.grabFramebuffer();
  v.setVerticalExaggeration(5);
  const QImage map5 = v.grabFramebuffer();
  EXPECT_EQ(changedFraction(map1, map5), 0.0) << "the map view is flat at any exaggeration";

  v.setMode(ViewCamera::Mode::Tilted);
  v.setVerticalExaggeration(1);
  const QImage tilted1 = v.grabFramebuffer();
  v.setVerticalExaggeration(5);
  EXPECT_DOUBLE_EQ(v.verticalExaggeration(), 5.0);
  const QImage tilted5 = v.grabFramebuffer();
  // The kot valley has ~700 m of relief over ~1 km: five times higher hides and moves most of the
  // drawn terrain (measured: 37 % of the pixels change); 5 % is far above rendering noise
  // (the same view drawn twice is identical).
  const QImage again = v.grabFramebuffer();
  EXPECT_EQ(changedFraction(tilted5, again), 0.0);
  const double changed = changedFraction(tilted1, tilted5);
  std::printf("[ tilted view, 1x vs 5x: %.1f %% of the pixels differ ]\n", 100 * changed);
  EXPECT_GT(changed, 0.05);
  v.setVerticalExaggeration(1000);
  EXPECT_DOUBLE_EQ(v.verticalExaggeration(), 50.0) << "clamped";
}

TEST(DevicePicker, EachListedDeviceWritesTheNameThatSelectsIt) {
  const auto dir = scratchDir("device_picker");
  MainWindow w;
  ASSERT_NO_FATAL_FAILURE(showExampleWindow(w, dir));
  talus::gui::KeyField* field = w.form().field("Device");
  ASSERT_NE(field, nullptr);
  auto* picker = field->findChild<talus::gui::DevicePicker*>();
  ASSERT_NE(picker, nullptr);
  picker->refresh();
  const auto actions = picker->menu()->actions();
  const auto devices = talus::compute::listDevices();
  ASSERT_FALSE(devices.empty()) << "the tests run on PoCL";
  ASSERT_EQ(actions.size(), int(devices.size()) + 1);  // "automatic" first
  for (std::size_t k = 0; k < devices.size(); ++k) {
    actions[int(k) + 1]->trigger();
    const QString chosen = field->value();
    EXPECT_EQ(chosen.toStdString(), devices[k].name);
    EXPECT_EQ(w.document()->value("Device"), devices[k].name) << "the form edits the run-file";
    // The name selects a device of that name (the first of identical ones).
    EXPECT_EQ(talus::compute::selectDevice(chosen.toStdString()).name, devices[k].name);
  }
  actions[0]->trigger();
  EXPECT_EQ(field->value(), QString());
}
