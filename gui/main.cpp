// talus-gui: the desktop application.
//   talus-gui [RUNFILE] [--results DIR] [--run] [--out DIR] [--overwrite] [--capture-at SECONDS:PATH] [--tilted] [--layer NAME]
// --run starts the run-file at once; --out writes the results into DIR instead of the run-file's
// Output Directory; --overwrite replaces earlier results without asking;
// --results opens a finished output folder of `talus run` for replay (time slider, maps, plots);
// --capture-at saves a picture of the whole window once the simulated time reaches SECONDS (or the
// run ends; with --results: the first series frame at or after SECONDS) and quits (used for the
// README screenshot under Xvfb).
#include <QApplication>
#include <QCommandLineParser>
#include <QSurfaceFormat>
#include <QTimer>
#include <algorithm>
#include <cstdio>

#include "render/GlSetup.hpp"
#include "app/MainWindow.hpp"
#include "sim/Simulation.hpp"

using talus::gui::MainWindow;

int main(int argc, char** argv) {
  // OpenGL 3.3 core for every GL widget; must be set before the application object exists.
  talus::gui::requestCoreProfile33();
  QApplication app(argc, argv);
  QApplication::setOrganizationName("Talus");
  QApplication::setApplicationName("talus-gui");

  QCommandLineParser cli;
  cli.setApplicationDescription("Talus desktop application: edit run-files, run them and watch the flow.");
  cli.addHelpOption();
  cli.addPositionalArgument("runfile", "run-file to open");
  const QCommandLineOption runOpt("run", "start the run at once");
  const QCommandLineOption outOpt("out", "write results into DIR (overrides the Output Directory)", "DIR");
  const QCommandLineOption overwriteOpt("overwrite", "replace earlier results without asking");
  const QCommandLineOption captureOpt("capture-at", "save a window picture at simulated time SECONDS to PATH and quit",
                                      "SECONDS:PATH");
  const QCommandLineOption tiltedOpt("tilted", "start in the tilted 3D view");
  const QCommandLineOption layerOpt("layer", "grid layer to show (h, velocity, hmax, arrival, ...)", "NAME");
  const QCommandLineOption resultsOpt("results", "open the finished output folder DIR for replay", "DIR");
  cli.addOptions({resultsOpt, runOpt, outOpt, overwriteOpt, captureOpt, tiltedOpt, layerOpt});
  cli.process(app);

  MainWindow window;
  window.setAskBeforeOverwrite(!cli.isSet(overwriteOpt));
  if (cli.isSet(outOpt)) window.setOutputOverride(cli.value(outOpt));
  const QStringList files = cli.positionalArguments();
  bool valid = true;
  QString invalid;  // the problems of an invalid run-file, shown in the window too
  QString partial;  // why the results opened are incomplete, shown in the window too
  if (!files.isEmpty()) {
    // The terminal is where a command line's mistakes are read: a run-file that cannot be read
    // ends here, before any window appears; an invalid one is reported and then opened with its
    // errors at the fields, as File > Open shows it, so that it can be fixed there.
    QString problems;
    if (!window.openRunFile(files.front(), &problems)) {
      std::fprintf(stderr, "talus-gui: %s\n", qPrintable(problems));
      return 2;
    }
    valid = problems.isEmpty();
    if (!valid) {
      std::fprintf(stderr, "talus-gui: run-file '%s' is not valid (the errors are shown at their fields):\n%s\n",
                   qPrintable(files.front()), qPrintable(problems));
      invalid = problems;
    }
  }
  if (cli.isSet(resultsOpt)) {
    // As for a run-file: a folder that is no output ends here; an incomplete run opens as partial.
    const QString dir = cli.value(resultsOpt);
    QString problems;
    if (!window.openResults(dir, &problems)) {
      std::fprintf(stderr, "talus-gui: %s\n", qPrintable(problems));
      return 2;
    }
    if (!problems.isEmpty()) {
      std::fprintf(stderr, "talus-gui: warning: %s\n", qPrintable(problems));
      partial = problems;
    }
  }
  window.show();
  if (cli.isSet(tiltedOpt)) window.viewer().setMode(talus::gui::ViewCamera::Mode::Tilted);
  if (cli.isSet(layerOpt)) window.layers().selectLayer(cli.value(layerOpt));
  // A picture of a run that cannot start would never be taken: fail instead of waiting forever.
  if (!valid && cli.isSet(captureOpt)) return 2;
  if (cli.isSet(runOpt)) {
    if (!valid) {
      std::fprintf(stderr, "talus-gui: nothing was started\n");
      invalid += "\nNothing was started (--run).";
    } else if (!window.startRun()) {
      return 2;
    }
  }
  // Started from a desktop, nobody reads stderr: the window says it too (without blocking).
  if (!invalid.isEmpty())
    window.reportProblems("Run-file not valid", "The run-file '" + files.front() +
                                                    "' is not valid; the errors are shown at their fields:\n" + invalid);

  if (!partial.isEmpty()) window.showMessageBox("Partial results", partial);  // the log has it

  if (cli.isSet(captureOpt)) {
    const QString spec = cli.value(captureOpt);
    const double at = spec.section(':', 0, 0).toDouble();
    const QString path = spec.section(':', 1);
    auto capture = [&window, path] {
      window.grab().save(path, "PNG");
      QApplication::quit();
    };
    if (window.results() && !cli.isSet(runOpt)) {
      // Replaying results: the first frame at or after SECONDS (the last when none is).
      talus::gui::ReplayBar& bar = window.replayBar();
      int frame = bar.frameCount() - 1;
      for (int k = 0; k < bar.frameCount(); ++k)
        if (window.results()->frameTime(k) >= at) {
          frame = k;
          break;
        }
      bar.setFrame(std::max(frame, 0));
      QTimer::singleShot(800, &window, capture);
    }
    QObject::connect(&window.controller(), &talus::gui::RunController::snapshotReady, &window,
                     [&window, at, capture](std::shared_ptr<const talus::sim::ViewSnapshot> s) {
                       // Let the viewer draw the snapshot before the picture is taken.
                       if (s->time >= at) QTimer::singleShot(300, &window, capture);
                     });
    QObject::connect(&window.controller(), &talus::gui::RunController::prepareFailed, &app, [] { QApplication::exit(2); });
  }
  return app.exec();
}
