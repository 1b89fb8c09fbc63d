// bench_viewer: frames per second of the live viewer on a synthetic scene, by default 10^6 cells
// (1000 x 1000) with a flow layer and 10^5 particles, in the map view and the tilted 3D view, both
// redrawing only and with new data (layer + particles uploaded) every frame. Run it on a display
// (xvfb-run -a build/gui/bench_viewer). Options: --side N, --particles N, --frames N, --png PATH.
#include <QApplication>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QSurfaceFormat>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "render/GlSetup.hpp"
#include "compute/Context.hpp"
#include "render/ClGlInterop.hpp"
#include "view/ViewerWidget.hpp"

using namespace talus;

namespace {

/// Elevation of the synthetic terrain at (x, y) metres from its top-left corner.
float hillAt(double x, double y) {
  return float(200 * std::sin(x / 900.0) * std::cos(y / 700.0) + 40 * std::sin(x / 97.0 + y / 131.0) + 0.05 * (x + y));
}

/// A synthetic scene: rolling hills, a flow blob, particles scattered over the blob.
std::shared_ptr<sim::ViewSnapshot> syntheticSnapshot(int side, std::size_t particles, double dx, int frame) {
  auto s = std::make_shared<sim::ViewSnapshot>();
  s->grid = Grid::make(side, side, dx);
  s->time = frame;
  std::vector<float> h(s->grid.cells());
  const double c = side / 2.0 + 0.1 * side * std::sin(0.1 * frame), r = side / 5.0;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const double d2 = ((i - c) * (i - c) + (j - c) * (j - c)) / (r * r);
      h[s->grid.index(i, j)] = d2 < 1 ? float(5 * (1 - d2)) : 0.0f;
    }
  s->layerNames = {"h"};
  s->layers = {std::move(h)};
  std::mt19937 rng(42 + frame);
  std::normal_distribution<float> spread(0.0f, float(r * dx / 2));
  s->particleCount = particles;
  s->particlePositions.resize(3 * particles);
  std::vector<float> speed(particles);
  const auto& gt = s->grid.geoTransform;
  for (std::size_t p = 0; p < particles; ++p) {
    const float x = float(gt[0] + c * dx) + spread(rng), y = float(gt[3] - c * dx) + spread(rng);
    s->particlePositions[3 * p] = x;
    s->particlePositions[3 * p + 1] = y;
    s->particlePositions[3 * p + 2] = hillAt(x - gt[0], gt[3] - y) + 2.0f;  // just above the ground
    speed[p] = std::fabs(spread(rng)) / float(r * dx);
  }
  s->particleAttributeNames = {"velocity"};
  s->particleAttributes = {std::move(speed)};
  return s;
}

std::vector<float> hills(int side, double dx) {
  std::vector<float> z(std::size_t(side) * side);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i)
      z[std::size_t(j) * side + i] = hillAt((i + 0.5) * dx, (j + 0.5) * dx);
  return z;
}

/// Frames per second over `frames` repaints; with `newData` every frame gets a fresh snapshot.
double measure(gui::ViewerWidget& viewer, int frames, bool newData, int side, std::size_t particles, double dx) {
  std::vector<std::shared_ptr<sim::ViewSnapshot>> data;
  if (newData)
    for (int k = 0; k < 4; ++k) data.push_back(syntheticSnapshot(side, particles, dx, k));
  viewer.repaint();
  QElapsedTimer clock;
  clock.start();
  const long long before = viewer.framesDrawn();
  for (int f = 0; f < frames; ++f) {
    if (newData) viewer.setSnapshot(data[std::size_t(f) % data.size()]);
    viewer.repaint();
    QCoreApplication::processEvents();
  }
  viewer.makeCurrent();
  viewer.context()->functions()->glFinish();
  viewer.doneCurrent();
  const double seconds = clock.nsecsElapsed() * 1e-9;
  return (viewer.framesDrawn() - before) / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  talus::gui::requestCoreProfile33();
  QApplication app(argc, argv);
  QCommandLineParser cli;
  const QCommandLineOption sideOpt("side", "cells along each side", "N", "1000");
  const QCommandLineOption particlesOpt("particles", "number of particles", "N", "100000");
  const QCommandLineOption framesOpt("frames", "frames per measurement", "N", "30");
  const QCommandLineOption pngOpt("png", "save the last frame of each view as PATH-map.png, PATH-tilted.png", "PATH");
  cli.addOptions({sideOpt, particlesOpt, framesOpt, pngOpt});
  cli.addHelpOption();
  cli.process(app);
  const int side = cli.value(sideOpt).toInt(), frames = cli.value(framesOpt).toInt();
  const std::size_t particles = cli.value(particlesOpt).toULongLong();
  const double dx = 5.0;

  // The run's device decides the interop path, as in the application.
  const auto device = compute::Context::create("", compute::Precision::Float);
  gui::ViewerWidget viewer;
  viewer.resize(1280, 800);
  viewer.show();
  viewer.setDataSource(&device->device(), device->context(), device->queue());
  viewer.setTerrain(Grid::make(side, side, dx), hills(side, dx));
  viewer.setSnapshot(syntheticSnapshot(side, particles, dx, 0));
  gui::LayerStyle style;
  style.visible = true;
  style.min = 0;
  style.max = 5;
  style.emptyBelow = 0.001f;
  viewer.setLayer("h", style);
  gui::ParticleStyle ps;
  ps.attribute = "velocity";
  ps.min = 0;
  ps.max = 1.5f;
  ps.pointSize = 3;
  viewer.setParticleStyle(ps);
  QCoreApplication::processEvents();

  viewer.makeCurrent();
  const QString renderer = reinterpret_cast<const char*>(viewer.context()->functions()->glGetString(GL_RENDERER));
  viewer.doneCurrent();
  std::printf("bench_viewer: %d x %d cells (%.3g), %zu particles, viewport %d x %d, %s\n", side, side,
              double(side) * side, particles, viewer.width(), viewer.height(), renderer.toUtf8().constData());
  for (auto mode : {gui::ViewCamera::Mode::Map, gui::ViewCamera::Mode::Tilted}) {
    viewer.setMode(mode);
    const char* name = mode == gui::ViewCamera::Mode::Map ? "map" : "tilted";
    const double redraw = measure(viewer, frames, false, side, particles, dx);
    const double fresh = measure(viewer, frames, true, side, particles, dx);
    std::printf("  %-6s view: %6.1f frames/s redrawing, %6.1f frames/s with new layer + particle data each frame\n",
                name, redraw, fresh);
    if (cli.isSet(pngOpt)) viewer.grabFramebuffer().save(cli.value(pngOpt) + "-" + name + ".png");
  }
  if (const gui::InteropChoice* c = viewer.interopChoice())
    std::printf("  data path: %s (%s)\n", gui::interopPathName(c->path).toUtf8().constData(),
                c->reason.toUtf8().constData());
  return 0;
}
