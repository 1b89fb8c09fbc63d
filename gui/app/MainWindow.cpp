#include "app/MainWindow.hpp"

#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QToolBar>
#include <cmath>

#include "app/RecentFiles.hpp"
#include "form/RunFilePaths.hpp"
#include "core/Error.hpp"
#include "io/RasterIO.hpp"
#include "sim/RunKeys.hpp"
#include "view/InitialScene.hpp"
#include "view/TerrainSlope.hpp"

namespace talus::gui {

namespace {
constexpr const char* kGeometryKey = "window/geometry";
constexpr const char* kStateKey = "window/state";
constexpr int kLayoutVersion = 2;  ///< raise when the docks change: an older saved layout is ignored

/// A panel in a scroll area, so that its dock can be made smaller than the panel's own minimum.
QScrollArea* scrollable(QWidget* panel) {
  auto* area = new QScrollArea;
  area->setWidget(panel);
  area->setWidgetResizable(true);
  area->setFrameShape(QFrame::NoFrame);
  return area;
}
}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setWindowTitle("Talus");
  setAcceptDrops(true);
  viewer_ = new ViewerWidget;
  setCentralWidget(viewer_);
  form_ = new ParameterForm(talusRunKeys());
  layers_ = new LayerPanel;
  log_ = new LogPanel;
  plots_ = new PlotPanel;
  probe_ = new ProbePanel;
  status_ = new RunStatusPanel;
  hover_ = new QLabel;
  run_ = new RunController(this);
  replay_ = new ReplayBar;
  statusBar()->addWidget(hover_, 1);
  statusBar()->addPermanentWidget(status_);
  buildActions();
  buildDocks();

  connect(form_, &ParameterForm::edited, this, [this] { updateActions(); });
  connect(layers_, &LayerPanel::changed, this, [this] { applyLayerStyle(); });
  connect(viewer_, &ViewerWidget::hovered, this, &MainWindow::onHover);
  connect(viewer_, &ViewerWidget::interopChosen, log_, &LogPanel::append);
  connect(viewer_, &ViewerWidget::sharedPathChosen, run_, &RunController::setDeviceSnapshots);
  connect(run_, &RunController::log, log_, &LogPanel::append);
  connect(run_, &RunController::stateChanged, this, [this](RunController::State s) {
    status_->showState(s);
    updateActions();
  });
  connect(run_, &RunController::prepared, this, &MainWindow::onPrepared);
  connect(run_, &RunController::prepareFailed, this, [this](const QString& message) {
    // Scene problems (rasters, grids) name their key: show them at the field.
    ValidationResult r;
    assignErrors(message.toStdString(), talusRunKeys(), r);
    form_->showErrors(r);
  });
  connect(run_, &RunController::progress, this, [this](const RunProgress& p) {
    status_->showProgress(p);
    plots_->addProgress(p, run_->scene() && run_->scene()->settings.twoPhase);
  });
  connect(run_, &RunController::snapshotReady, this, &MainWindow::onSnapshot);
  connect(replay_, &ReplayBar::frameChanged, this, &MainWindow::showResultsFrame);
  connect(&viewer_->sketch(), &MapSketch::finished, this, &MainWindow::onSketchFinished);
  connect(&viewer_->sketch(), &MapSketch::hint, log_, &LogPanel::append);
  applyLayerStyle();
  updateActions();
  resize(1400, 900);
  restoreLayout();
}

MainWindow::~MainWindow() = default;

void MainWindow::buildActions() {
  QMenu* file = menuBar()->addMenu("&File");
  open_ = file->addAction("&Open run-file...", this, &MainWindow::chooseAndOpen, QKeySequence::Open);
  openResults_ = file->addAction("Open res&ults...", this, &MainWindow::chooseAndOpenResults);
  compareResults_ = file->addAction("Co&mpare with results...", this, &MainWindow::chooseAndCompareResults);
  recent_ = new RecentFiles(file->addMenu("Open &recent"), this);
  connect(recent_, &RecentFiles::chosen, this, [this](const QString& f) {
    if (confirmDiscard()) openRunFile(f);
  });
  save_ = file->addAction("&Save", this, [this] {
    const QString problem = saveRunFile();
    if (!problem.isEmpty()) log_->append("error: " + problem);
  }, QKeySequence::Save);
  // Spelled out: QKeySequence::SaveAs is empty under some platforms' key schemes (Windows, bare X11).
  saveAs_ = file->addAction("Save &as...", this, &MainWindow::saveAs, QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S));
  file->addSeparator();
  shot_ = file->addAction("Export &screenshot (PNG)...", this, &MainWindow::screenshot);
  exportFigure_ = file->addAction("Export &figure...", this, &MainWindow::chooseAndExportFigure);
  exportLayer_ = file->addAction("Export &layer as GeoTIFF...", this, &MainWindow::chooseAndExportLayer);
  record_ = file->addAction("Record &frame sequence...");
  record_->setCheckable(true);
  connect(record_, &QAction::toggled, this, &MainWindow::toggleRecording);
  file->addSeparator();
  file->addAction("&Quit", this, &QWidget::close, QKeySequence::Quit);

  QMenu* runMenu = menuBar()->addMenu("&Run");
  start_ = runMenu->addAction("&Start", this, [this] { startRun(); }, QKeySequence("F5"));
  pause_ = runMenu->addAction("&Pause", this, [this] {
    if (run_->state() == RunController::State::Paused) run_->resume();
    else run_->pause();
  }, QKeySequence("F6"));
  step_ = runMenu->addAction("Single s&tep", this, [this] { run_->step(); }, QKeySequence("F7"));
  stop_ = runMenu->addAction("St&op", this, [this] { run_->stop(); }, QKeySequence("F8"));
  restart_ = runMenu->addAction("&Restart", this, [this] { restartRun(); });

  QMenu* view = menuBar()->addMenu("&View");
  tilted_ = view->addAction("&Tilted 3D view");
  tilted_->setCheckable(true);
  connect(tilted_, &QAction::toggled, this, [this](bool on) {
    viewer_->setMode(on ? ViewCamera::Mode::Tilted : ViewCamera::Mode::Map);
  });
  view->addAction("&Reset view", this, [this] { viewer_->resetView(); });
  QMenu* exaggeration = view->addMenu("&Vertical exaggeration (3D)");
  auto* factors = new QActionGroup(this);
  for (const double f : {1.0, 1.5, 2.0, 3.0, 5.0, 10.0}) {
    QAction* a = exaggeration->addAction(QString("%1\u00d7").arg(f), this, [this, f] {
      viewer_->setVerticalExaggeration(f);
      if (viewer_->mode() != ViewCamera::Mode::Tilted) tilted_->setChecked(true);
    });
    a->setCheckable(true);
    a->setChecked(f == 1.0);
    factors->addAction(a);
  }

  QMenu* tools = menuBar()->addMenu("&Tools");
  drawRelease_ = tools->addAction("Draw &release area", this, [this] { startSketch(MapSketch::Tool::Polygon); });
  probePoint_ = tools->addAction("Time series at a &point", this, [this] { startSketch(MapSketch::Tool::Point); });
  probeProfile_ = tools->addAction("&Profile along a line", this, [this] { startSketch(MapSketch::Tool::Profile); });

  QToolBar* bar = addToolBar("Run");
  bar->setObjectName("runToolbar");
  for (QAction* a : {open_, save_, start_, pause_, step_, stop_, restart_}) bar->addAction(a);
  bar->addSeparator();
  for (QAction* a : {tilted_, shot_, record_}) bar->addAction(a);
  QToolBar* replay = addToolBar("Results");
  replay->setObjectName("resultsToolbar");
  replay->addWidget(replay_);
}

void MainWindow::buildDocks() {
  auto dock = [this](const QString& title, QWidget* w, Qt::DockWidgetArea area) {
    auto* d = new QDockWidget(title, this);
    d->setObjectName(title);
    d->setWidget(w);
    addDockWidget(area, d);
    return d;
  };
  // The form scrolls itself; the layer controls and the plots scroll in their docks, and the log
  // and the plots share the bottom as tabs, so that the window fits a 1280x800 screen.
  QDockWidget* formDock = dock("Parameters", form_, Qt::LeftDockWidgetArea);
  dock("Layers", scrollable(layers_), Qt::RightDockWidgetArea);
  QDockWidget* plotDock = dock("Plots", scrollable(plots_), Qt::BottomDockWidgetArea);
  QDockWidget* logDock = dock("Log", log_, Qt::BottomDockWidgetArea);
  QDockWidget* probeDock = dock("Probe", scrollable(probe_), Qt::BottomDockWidgetArea);
  tabifyDockWidget(plotDock, logDock);
  tabifyDockWidget(plotDock, probeDock);
  plotDock->raise();
  resizeDocks({formDock}, {420}, Qt::Horizontal);
  resizeDocks({plotDock}, {260}, Qt::Vertical);
}

void MainWindow::saveLayout() const {
  QSettings settings;
  settings.setValue(kGeometryKey, saveGeometry());
  settings.setValue(kStateKey, saveState(kLayoutVersion));
}

void MainWindow::restoreLayout() {
  const QSettings settings;
  restoreGeometry(settings.value(kGeometryKey).toByteArray());
  restoreState(settings.value(kStateKey).toByteArray(), kLayoutVersion);
}

QMessageBox* MainWindow::reportProblems(const QString& title, const QString& problems) {
  for (const QString& line : problems.split('\n'))
    if (!line.trimmed().isEmpty()) log_->append("error: " + line);
  return showMessageBox(title, problems);
}

QMessageBox* MainWindow::showMessageBox(const QString& title, const QString& text) {
  if (!reportInDialogs_) return nullptr;
  auto* box = new QMessageBox(QMessageBox::Warning, title, text, QMessageBox::Ok, this);
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->setTextInteractionFlags(Qt::TextSelectableByMouse);
  box->open();  // window-modal, without a nested event loop: the program goes on
  return box;
}

void MainWindow::updateActions() {
  using S = RunController::State;
  const S s = run_->state();
  const bool active = s == S::Running || s == S::Paused || s == S::Preparing;
  start_->setEnabled(doc_ && !active);
  pause_->setEnabled(s == S::Running || s == S::Paused);
  pause_->setText(s == S::Paused ? "Resume" : "Pause");
  step_->setEnabled(s == S::Running || s == S::Paused);
  stop_->setEnabled(active);
  restart_->setEnabled(doc_ && (s == S::Running || s == S::Paused || s == S::Ended));
  save_->setEnabled(doc_ != nullptr);
  drawRelease_->setEnabled(doc_ && initial_ && !active);
  saveAs_->setEnabled(doc_ != nullptr);
  form_->setEnabled(doc_ && !active);
  open_->setEnabled(!active);
  openResults_->setEnabled(!active);
  compareResults_->setEnabled(results_ != nullptr);
  QString title = "Talus";
  if (results_)
    title = "results " + results_->folder().dir + (results_->folder().isPartial() ? " (partial)" : "") + " - Talus";
  else if (doc_) title = QFileInfo(QString::fromStdString(doc_->path())).fileName() + (doc_->isModified() ? " *" : "") + " - Talus";
  setWindowTitle(title);
}

bool MainWindow::openRunFile(const QString& path, QString* problems) {
  auto refuse = [&](const QString& why) {
    log_->append("error: " + why);
    if (problems) *problems = why;
    return false;
  };
  // The run's outputs and viewer belong to the open run-file: another one waits for its end.
  if (run_->isActive()) return refuse("a run is in progress: stop it before opening " + path);
  std::unique_ptr<RunFileDocument> doc;
  try {
    doc = std::make_unique<RunFileDocument>(RunFileDocument::load(path.toStdString(), talusRunKeys()));
  } catch (const std::exception& e) {
    return refuse(e.what());  // the open run-file and its scene stay
  }
  resetScene();
  doc_ = std::move(doc);
  form_->setDocument(doc_.get());
  recent_->add(path);
  log_->append("opened " + QFileInfo(path).absoluteFilePath());
  const ValidationResult r = validateDocument(*doc_);
  form_->showErrors(r);
  if (problems) *problems = QString::fromStdString(describeProblems(r));
  if (r.ok()) showTerrainOf(*r.config);
  else log_->append("warning: the run-file has problems; they are shown next to their fields");
  updateActions();
  return true;
}

void MainWindow::showTerrainOf(const io::RunConfig& config) {
  try {
    initial_ = std::make_unique<InitialScene>(InitialScene::read(config));
  } catch (const std::exception& e) {
    log_->append(QString("warning: cannot show the terrain: %1").arg(e.what()));
    return;
  }
  for (const std::string& w : initial_->warnings) log_->append("warning: " + QString::fromStdString(w));
  if (initial_->elevation.empty()) return;
  viewer_->setTerrain(initial_->grid, initial_->elevation);
  // The initial maps show as layers until the run's own snapshots replace them (the first is shown;
  // the layer preferred for the run stays as it was).
  const QString preferred = layers_->preferredLayer();
  layers_->setCatalogue(initial_->layers, {});
  layers_->selectLayer(preferred);
  layers_->setSnapshot(initial_->snapshot);
  viewer_->setSnapshot(initial_->snapshot);
  applyLayerStyle();
}

void MainWindow::resetScene() {
  run_->reset();
  results_.reset();
  initial_.reset();
  replay_->setFrames({});
  viewer_->clearScene();
  layers_->clear();
  plots_->clear();
  viewer_->sketch().start(MapSketch::Tool::None);
  probeI_ = probeJ_ = -1;
  profileLine_.clear();
  probedLayer_.clear();
  probe_->clear();
  status_->reset();
  hoverI_ = -1;
  hover_->clear();
}

std::optional<io::RunConfig> MainWindow::runConfig() {
  if (!doc_) return std::nullopt;
  const ValidationResult r = validateDocument(*doc_);
  form_->showErrors(r);
  if (!r.ok()) {
    log_->append("error: the run-file is not valid; nothing was started:\n" + QString::fromStdString(describeProblems(r)));
    return std::nullopt;
  }
  io::RunConfig config = *r.config;
  if (!outputOverride_.isEmpty()) {
    try {
      config.set("Output Directory=" + QFileInfo(outputOverride_).absoluteFilePath().toStdString());
    } catch (const std::exception& e) {
      log_->append(QString("error: %1").arg(e.what()));
      return std::nullopt;
    }
  }
  return config;
}

bool MainWindow::confirmReplace(const QString& out, const QString& question) {
  return !askBeforeOverwrite_ ||
         QMessageBox::question(this, "Replace results?", "The output folder\n" + out + "\n" + question) == QMessageBox::Yes;
}

bool MainWindow::startRun() {
  const std::optional<io::RunConfig> config = runConfig();
  if (!config) return false;
  const QString out = QString::fromStdString(config->directory("Output Directory"));
  const bool hasRun = QFileInfo::exists(out + "/summary.json") || QFileInfo::exists(out + "/diagnostics.csv");
  if (hasRun && !confirmReplace(out, "holds the results of an earlier run. Replace them?")) return false;
  if (results_) resetScene();  // the opened results' scene makes way for the run's
  plots_->clear();
  run_->start(*config, hasRun);
  return true;
}

bool MainWindow::restartRun() {
  if (!restart_->isEnabled()) return false;
  const std::optional<io::RunConfig> config = runConfig();
  if (!config) return false;
  const QString out = QString::fromStdString(config->directory("Output Directory"));
  if (!confirmReplace(out, run_->isActive() ? "receives the results of the run in progress. Stop it and start again?"
                                           : "holds the results of the last run. Replace them?"))
    return false;
  plots_->clear();
  run_->restart(*config);
  return true;
}

void MainWindow::onPrepared() {
  const sim::ViewFields* view = run_->viewFields();
  viewer_->setTerrain(view->grid(), view->elevation());
  sim::Simulation* sim = run_->simulation();
  viewer_->setDataSource(&sim->context().device(), sim->context().context(), sim->context().queue(),
                         QString::fromStdString(sim->context().glShareReason()));
  layers_->setCatalogue(view->gridLayers(), view->particleAttributes());
  applyLayerStyle();
}

void MainWindow::onSnapshot(std::shared_ptr<const sim::ViewSnapshot> s) {
  layers_->setSnapshot(s);
  viewer_->setSnapshot(s);
  plots_->addSnapshot(*s);
  refreshProbes(false);
  if (hoverI_ >= 0) hover_->setText(hoverText(hoverI_, hoverJ_));
  if (exporter_.isRecording()) {
    const QString problem = exporter_.captureFrame(*viewer_);
    if (!problem.isEmpty()) {
      log_->append("error: frame sequence stopped: " + problem);
      record_->setChecked(false);
    }
  }
}

void MainWindow::applyLayerStyle() {
  viewer_->setLayerRamp(layers_->layerRamp());
  viewer_->setLayer(layers_->layer(), layers_->layerStyle());
  viewer_->setParticleRamp(layers_->particleRamp());
  viewer_->setParticleStyle(layers_->particleStyle());
  if (layers_->layer() != probedLayer_) refreshProbes(false);
}

void MainWindow::onHover(int i, int j, bool inside) {
  hoverI_ = inside ? i : -1;
  hoverJ_ = j;
  hover_->setText(inside ? hoverText(i, j) : QString());
}

QString MainWindow::cursorReadout() const { return hover_->text(); }

QString MainWindow::hoverText(int i, int j) const {
  const auto s = viewer_->snapshot();
  QString text = QString("cell (%1, %2)").arg(i).arg(j);
  const Grid* grid = nullptr;
  const std::vector<float>* elevation = nullptr;
  const std::vector<sim::GridLayerInfo>* catalogue = nullptr;
  if (!sceneOnScreen(grid, elevation, catalogue)) return text;
  const Grid& g = *grid;
  const std::vector<float>& z = *elevation;
  const std::vector<sim::GridLayerInfo>& layers = *catalogue;
  if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) return text;
  const std::size_t k = g.index(i, j);
  text += QString("  x %1 y %2").arg(g.cellX(i), 0, 'f', 1).arg(g.cellY(j), 0, 'f', 1);
  text += QString("  elevation %1 m").arg(z[k], 0, 'f', 2);
  const double slope = slopeDegrees(g, z, i, j);
  if (std::isfinite(slope)) text += QString("  slope %1\u00b0").arg(slope, 0, 'f', 1);
  if (!s) return text;
  for (const auto& info : layers)
    if (const std::vector<float>* v = s->layer(info.name); v && k < v->size() && std::isfinite((*v)[k]))
      text += QString("  %1 %2 %3").arg(QString::fromStdString(info.name)).arg((*v)[k], 0, 'g', 4).arg(QString::fromStdString(info.unit));
  return text;
}

bool MainWindow::sceneOnScreen(const Grid*& grid, const std::vector<float>*& elevation,
                               const std::vector<sim::GridLayerInfo>*& layers) const {
  // The run's, else the opened results', else the run-file's initial one.
  const sim::ViewFields* view = run_->viewFields();
  const InitialScene* initial = initial_ && !initial_->elevation.empty() ? initial_.get() : nullptr;
  if (!view && !results_ && !initial) return false;
  grid = view ? &view->grid() : results_ ? &results_->grid() : &initial->grid;
  elevation = view ? &view->elevation() : results_ ? &results_->elevation() : &initial->elevation;
  layers = view ? &view->gridLayers() : results_ ? &results_->layers() : &initial->layers;
  return true;
}

QString MainWindow::saveRunFile(const QString& path) {
  if (!doc_) return "no run-file is open";
  const QString target = path.isEmpty() ? QString::fromStdString(doc_->path()) : path;
  if (target.isEmpty()) return "the run-file has no name yet: use Save as";
  // Saved elsewhere, the copy's relative input paths are rewritten to find the same maps; the open
  // document changes only once the copy is written (a failed save leaves it as it was).
  RunFileDocument copy = *doc_;
  rebaseInputPaths(copy, QFileInfo(target).absolutePath().toStdString());
  const bool rewritten = copy.text() != doc_->text();
  try {
    copy.save(target.toStdString());
  } catch (const std::exception& e) {
    return e.what();
  }
  *doc_ = std::move(copy);
  if (rewritten) {
    form_->setDocument(doc_.get());
    form_->showErrors(validateDocument(*doc_));
    log_->append("the relative paths of the maps were rewritten for the new folder");
  }
  recent_->add(target);
  log_->append("saved " + target);
  updateActions();
  return {};
}

void MainWindow::chooseAndOpen() {
  if (!confirmDiscard()) return;
  const QString path = QFileDialog::getOpenFileName(this, "Open run-file", {}, "Run-files (*.run);;All files (*)");
  if (!path.isEmpty()) openRunFile(path);
}

void MainWindow::saveAs() {
  const QString path = QFileDialog::getSaveFileName(this, "Save run-file as", QString::fromStdString(doc_->path()),
                                                    "Run-files (*.run)");
  if (path.isEmpty()) return;
  const QString problem = saveRunFile(path);
  if (!problem.isEmpty()) QMessageBox::warning(this, "Save failed", problem);
}

void MainWindow::screenshot() {
  const QString path = QFileDialog::getSaveFileName(this, "Export screenshot", "talus.png", "PNG images (*.png)");
  if (path.isEmpty()) return;
  // The map view gets the figure's frame, legend, scale bar and north arrow; the tilted view has
  // no single scale and is saved bare.
  const bool figure = viewer_->mode() == ViewCamera::Mode::Map && viewer_->snapshot();
  const QString problem = figure ? exportFigure(path) : FrameExporter::saveScreenshot(*viewer_, path);
  log_->append(problem.isEmpty() ? "screenshot saved to " + path : "error: " + problem);
}

void MainWindow::toggleRecording(bool on) {
  if (!on) {
    if (exporter_.isRecording())
      log_->append(QString("frame sequence: %1 frames in %2").arg(exporter_.framesWritten()).arg(exporter_.folder()));
    exporter_.stopSequence();
    return;
  }
  const QString folder = QFileDialog::getExistingDirectory(this, "Folder for the frames");
  const QString problem = folder.isEmpty() ? "no folder chosen" : exporter_.startSequence(folder);
  if (!problem.isEmpty()) {
    log_->append("frame sequence not started: " + problem);
    const QSignalBlocker block(record_);
    record_->setChecked(false);
    return;
  }
  log_->append("recording frames into " + folder + " (one per viewer update)");
}

bool MainWindow::confirmDiscard() {
  if (!doc_ || !doc_->isModified()) return true;
  return QMessageBox::question(this, "Discard changes?", "The run-file has unsaved changes. Discard them?") ==
         QMessageBox::Yes;
}

void MainWindow::dragEnterEvent(QDragEnterEvent* e) {
  if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* e) {
  const auto urls = e->mimeData()->urls();
  if (urls.isEmpty() || !urls.front().isLocalFile()) return;
  if (run_->state() == RunController::State::Running || run_->state() == RunController::State::Paused) return;
  const QString path = urls.front().toLocalFile();
  if (QFileInfo(path).isDir()) {  // an output folder: its results
    openResultsReporting(path);
    return;
  }
  if (confirmDiscard()) openRunFile(path);
}

void MainWindow::closeEvent(QCloseEvent* e) {
  // A run in progress would be cut short by quitting: its outputs are written up to the step it
  // stops at, but an accidental Ctrl+Q should not end an hour-long run.
  const bool stopRun = run_->isActive();
  if (!confirmDiscard() ||
      (stopRun && QMessageBox::question(this, "Stop the run?",
                                        "A run is in progress. Stop it (its outputs so far are written) and quit?") !=
                      QMessageBox::Yes)) {
    e->ignore();
    return;
  }
  run_->stop();
  saveLayout();
  e->accept();
}

}  // namespace talus::gui
