// The main window: the parameter form (left), the live viewer with its layer panel (centre, right),
// the log and the plots (bottom), run controls in a toolbar and the progress in the status bar. It
// wires the parts together; each part lives in its own file.
#pragma once
#include <QAction>
#include <QLabel>
#include <QMainWindow>
#include <QMessageBox>
#include <memory>
#include <optional>

#include "core/MapGeometry.hpp"
#include "export/FrameExporter.hpp"
#include "form/ParameterForm.hpp"
#include "form/ReleaseAreaDialog.hpp"
#include "form/RunFileDocument.hpp"
#include "plots/PlotPanel.hpp"
#include "plots/ProbePanel.hpp"
#include "results/ReplayBar.hpp"
#include "results/ResultsReplay.hpp"
#include "run/LogPanel.hpp"
#include "run/RunController.hpp"
#include "run/RunStatusPanel.hpp"
#include "view/InitialScene.hpp"
#include "view/LayerPanel.hpp"
#include "view/ViewerWidget.hpp"

namespace talus::gui {

class RecentFiles;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  /// Opens a run-file into the form (and shows its terrain). Returns false (and logs why) when it
  /// cannot be read. `problems`, when given, receives why it cannot be read, or else the problems
  /// validation found (each naming the file, line and key where it can; "" when valid), so that
  /// a caller without the window in view (the command line) can report them.
  bool openRunFile(const QString& path, QString* problems = nullptr);
  /// Opens a finished output folder of `talus run` for replay: the DEM's hillshade, each map of
  /// the folder in the layer list, the series frames on the time slider, diagnostics.csv in the
  /// plots. Returns false (the reason, naming the folder, in the log and in `problems`) when the
  /// folder is missing, not a Talus output (no summary.json) or has nothing readable. A run that did
  /// not complete opens as partial: true, and `problems` says so.
  bool openResults(const QString& dir, QString* problems = nullptr);
  /// Compares the opened results with those in `dir` (same grid): a difference layer "NAME-diff"
  /// (opened minus `dir`) joins the layer list for each map and series both hold. False (the
  /// reason in the log and in `problems`) when no results are open or `dir` cannot be opened or
  /// is on another grid.
  bool compareResults(const QString& dir, QString* problems = nullptr);
  /// The opened output folder (nullptr when none is open).
  ResultsReplay* results() { return results_.get(); }
  ReplayBar& replayBar() { return *replay_; }
  /// Validates the form and starts a run; false (errors shown next to their fields) when invalid.
  bool startRun();
  /// Stops the run (if any) and starts the open run-file again, as it is now in the form, after
  /// asking whether to replace the results (unless setAskBeforeOverwrite(false)). False when not
  /// restarted (declined, invalid, or no run of this run-file to restart).
  bool restartRun();
  /// Saves the run-file (to `path`, or its own path when empty). Returns "" or the problem.
  QString saveRunFile(const QString& path = {});
  /// Whether to ask before a run replaces the outputs of an earlier run (off: replace silently).
  void setAskBeforeOverwrite(bool ask) { askBeforeOverwrite_ = ask; }
  /// Shows problems the user should read now (a command line's invalid run-file): in the log and,
  /// unless setReportInDialogs(false), in a message box over the window that does not block the
  /// program (returned; deleted when closed). Returns nullptr when no box was opened.
  QMessageBox* reportProblems(const QString& title, const QString& problems);
  /// The message box of reportProblems, without the log (nullptr when dialogs are off).
  QMessageBox* showMessageBox(const QString& title, const QString& text);
  /// Whether reportProblems opens a message box (off: tests and scripts without anyone to read it).
  void setReportInDialogs(bool on) { reportInDialogs_ = on; }
  /// Runs write into `dir` instead of the run-file's Output Directory (as `talus run --out`).
  void setOutputOverride(const QString& dir) { outputOverride_ = dir; }

  ParameterForm& form() { return *form_; }
  ViewerWidget& viewer() { return *viewer_; }
  LayerPanel& layers() { return *layers_; }
  RunController& controller() { return *run_; }
  PlotPanel& plots() { return *plots_; }
  RunStatusPanel& status() { return *status_; }
  RunFileDocument* document() { return doc_.get(); }
  FrameExporter& exporter() { return exporter_; }
  QString logText() const { return log_->toPlainText(); }
  /// Writes a figure of the map view (legend, time, scale bar, north arrow, coordinate ticks) as
  /// PNG. Returns "" or the problem.
  QString exportFigure(const QString& path);
  /// Writes the layer the viewer shows (its current values) as a GeoTIFF. Returns "" or the problem.
  QString exportShownLayer(const QString& path);
  /// What the status bar says about the cell under the cursor ("" when it is outside the terrain).
  QString cursorReadout() const;

  /// Starts drawing on the map (switches to the map view): a release area (Polygon), a profile
  /// (Profile) or the cell of a time series (Point). A finished polygon asks what it releases
  /// (ReleaseAreaDialog, window-modal) and then calls saveReleaseArea.
  void startSketch(MapSketch::Tool tool);
  /// Writes a release area drawn as `polygon` (world coordinates) to the raster `path` and sets the
  /// open run-file's keys to it (Include Initial Water / Initial Fluid Height, or the solids'
  /// pair); the scene then shows the new map. With `addToCurrent` the cells outside the polygon keep
  /// the key's current map. Returns "" or the problem (also in the log).
  QString saveReleaseArea(const std::vector<MapPoint>& polygon, ReleaseAreaDialog::Material material,
                          double thickness, const QString& path, bool addToCurrent);
  /// Shows the time series of the shown layer at cell (i, j) (-1: none) in the Probe panel: over the
  /// frames of opened results, from a live run's snapshots as they come, or the scene's one value.
  void probeCell(int i, int j);
  /// Shows the shown layer's profile along `line` (world coordinates, empty: none), sampled every
  /// half cell, with the terrain along it; it follows the frame and the layer shown.
  void probeProfile(const std::vector<MapPoint>& line);
  ProbePanel& probe() { return *probe_; }

 protected:
  void dragEnterEvent(QDragEnterEvent* e) override;
  void dropEvent(QDropEvent* e) override;
  void closeEvent(QCloseEvent* e) override;

 private:
  void buildActions();
  void buildDocks();
  /// Remembers the window's geometry and dock layout (QSettings) for the next launch.
  void saveLayout() const;
  void restoreLayout();
  void updateActions();
  void applyLayerStyle();
  void showTerrainOf(const io::RunConfig& config);
  /// Clears what the previous run-file's scene left: its run, viewer, layers, plots and status.
  void resetScene();
  /// The validated configuration of the open run-file (with the output override), or nullopt with
  /// the errors shown at the fields and in the log.
  std::optional<io::RunConfig> runConfig();
  /// Whether replacing the results in `out` is fine (asked unless askBeforeOverwrite_ is off).
  bool confirmReplace(const QString& out, const QString& question);
  void onPrepared();
  void onSnapshot(std::shared_ptr<const sim::ViewSnapshot> s);
  void onHover(int i, int j, bool inside);
  void chooseAndOpen();
  void chooseAndOpenResults();
  void chooseAndCompareResults();
  /// openResults, with a message box for a refusal or partial results.
  void openResultsReporting(const QString& dir);
  /// Shows series frame `frame` of the opened results.
  void showResultsFrame(int frame);
  void saveAs();
  void screenshot();
  void chooseAndExportLayer();
  void chooseAndExportFigure();
  void toggleRecording(bool on);
  bool confirmDiscard();
  QString hoverText(int i, int j) const;
  /// The scene on screen (the run's, else the opened results', else the run-file's initial one):
  /// its grid, elevation and layer catalogue; false when there is none.
  bool sceneOnScreen(const Grid*& grid, const std::vector<float>*& elevation,
                     const std::vector<sim::GridLayerInfo>*& layers) const;
  void onSketchFinished(MapSketch::Tool tool, const std::vector<QPointF>& vertices);
  void askReleaseArea(const std::vector<MapPoint>& polygon);
  /// Recomputes the probes for the layer and snapshot now shown (the point series only when the
  /// layer changed or `rereadSeries`).
  void refreshProbes(bool rereadSeries);

  std::unique_ptr<RunFileDocument> doc_;
  ParameterForm* form_;
  ViewerWidget* viewer_;
  LayerPanel* layers_;
  LogPanel* log_;
  PlotPanel* plots_;
  ProbePanel* probe_;
  RunStatusPanel* status_;
  QLabel* hover_;
  RunController* run_;
  RecentFiles* recent_ = nullptr;
  std::unique_ptr<ResultsReplay> results_;
  std::unique_ptr<InitialScene> initial_;  ///< the open run-file's scene before it runs
  ReplayBar* replay_;
  FrameExporter exporter_;
  bool askBeforeOverwrite_ = true;
  bool reportInDialogs_ = true;
  QString outputOverride_;
  int hoverI_ = -1, hoverJ_ = -1;
  int probeI_ = -1, probeJ_ = -1;  ///< the time series' cell
  QString probedLayer_;            ///< the layer the time series was read for
  std::vector<MapPoint> profileLine_;
  QAction *open_, *openResults_, *compareResults_, *save_, *saveAs_, *start_, *pause_, *step_, *stop_, *restart_, *tilted_, *shot_, *record_, *exportLayer_, *exportFigure_;
  QAction *drawRelease_, *probePoint_, *probeProfile_;
};

}  // namespace talus::gui
