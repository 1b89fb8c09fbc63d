// The main window fits laptop screens (1280x800) with its status bar in view, and remembers its
// geometry and dock layout between launches (QSettings, a scratch location in the tests: main.cpp).
#include <gtest/gtest.h>

#include <QDockWidget>
#include <QScreen>
#include <QStatusBar>
#include <QTest>

#include "GuiTestSupport.hpp"
#include "app/MainWindow.hpp"

using talus::gui::MainWindow;
using namespace talus::guitest;

namespace {

QDockWidget* dockNamed(MainWindow& w, const QString& name) { return w.findChild<QDockWidget*>(name); }

/// Shows the window at `size` in the top-left corner of the screen and waits until it is mapped.
void showAt(MainWindow& w, const QSize& size) {
  w.move(0, 0);
  w.resize(size);
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  waitFor([] { return false; }, 0.3);  // let the docks settle into the new size
}

}  // namespace

TEST(WindowLayout, MinimumSizeFitsA1280x800Screen) {
  MainWindow w;
  const QSize min = w.minimumSizeHint().expandedTo(w.minimumSize());
  EXPECT_LE(min.width(), 1260) << min.width() << "x" << min.height();
  EXPECT_LE(min.height(), 760) << min.width() << "x" << min.height();
}

TEST(WindowLayout, At1280x800TheStatusBarIsOnScreen) {
  MainWindow w;
  showAt(w, QSize(1280, 800));
  EXPECT_EQ(w.size(), QSize(1280, 800)) << "the window grew past the screen: " << w.width() << "x" << w.height();
  QStatusBar* bar = w.statusBar();
  ASSERT_TRUE(bar->isVisible());
  const QRect onScreen(bar->mapToGlobal(QPoint(0, 0)), bar->size());
  const QRect laptop(w.screen()->geometry().topLeft(), QSize(1280, 800));
  EXPECT_TRUE(laptop.contains(onScreen)) << "status bar at y " << onScreen.top() << ".." << onScreen.bottom();
  // Every panel keeps a usable share of the window.
  for (const char* name : {"Parameters", "Layers", "Plots"}) {
    QDockWidget* d = dockNamed(w, name);
    ASSERT_NE(d, nullptr) << name;
    EXPECT_TRUE(d->isVisible()) << name;
    EXPECT_GE(d->width(), 150) << name;
    EXPECT_GE(d->height(), 100) << name;
  }
  EXPECT_GE(w.viewer().width(), 320);
  EXPECT_GE(w.viewer().height(), 240);
}

TEST(WindowLayout, At1920x1080ThePanelsGrow) {
  MainWindow w;
  w.setMaximumSize(1920, 1080);  // the test screen is smaller; the layout is what is checked
  showAt(w, QSize(1920, 1080));
  ASSERT_EQ(w.size(), QSize(1920, 1080));
  const QRect barRect(w.statusBar()->mapTo(&w, QPoint(0, 0)), w.statusBar()->size());
  EXPECT_TRUE(w.rect().contains(barRect));
  EXPECT_GE(w.viewer().width(), 900);
  EXPECT_GE(w.viewer().height(), 500);
}

TEST(WindowLayout, GeometryAndDocksRestoredInTheNextWindow) {
  {
    MainWindow w;
    showAt(w, QSize(1100, 700));
    dockNamed(w, "Layers")->hide();
    dockNamed(w, "Log")->raise();
    ASSERT_TRUE(w.close());
  }
  MainWindow again;
  again.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&again));
  EXPECT_EQ(again.size(), QSize(1100, 700));
  EXPECT_FALSE(dockNamed(again, "Layers")->isVisible()) << "the hidden dock came back";
  EXPECT_TRUE(dockNamed(again, "Parameters")->isVisible());
  EXPECT_EQ(again.tabifiedDockWidgets(dockNamed(again, "Log")).value(0), dockNamed(again, "Plots"));
  // The layout is restored, not just kept: a window after another change shows that change.
  dockNamed(again, "Layers")->show();
  again.resize(1200, 760);
  ASSERT_TRUE(again.close());
  MainWindow third;
  third.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&third));
  EXPECT_EQ(third.size(), QSize(1200, 760));
  EXPECT_TRUE(dockNamed(third, "Layers")->isVisible());
}
