// MainWindow's replay of a finished output folder (File > Open results, talus-gui --results DIR).
#include <QFileDialog>
#include <QFileInfo>
#include <algorithm>

#include "app/MainWindow.hpp"
#include "results/DiagnosticsTable.hpp"
#include "results/ResultsComparison.hpp"

namespace talus::gui {

namespace {
bool lists(const std::vector<sim::GridLayerInfo>& layers, const std::string& name) {
  return std::any_of(layers.begin(), layers.end(), [&](const sim::GridLayerInfo& l) { return l.name == name; });
}
}  // namespace

bool MainWindow::openResults(const QString& dir, QString* problems) {
  auto refuse = [&](const QString& why) {
    log_->append("error: " + why);
    if (problems) *problems = why;
    return false;
  };
  if (run_->isActive()) return refuse("a run is in progress: stop it before opening the results in " + dir);
  std::unique_ptr<ResultsReplay> replay;
  try {
    replay = std::make_unique<ResultsReplay>(ResultsFolder::open(dir));
  } catch (const std::exception& e) {
    return refuse(e.what());  // the scene shown stays
  }
  resetScene();
  results_ = std::move(replay);
  const ResultsFolder& f = results_->folder();
  viewer_->setTerrain(results_->grid(), results_->elevation());
  layers_->setCatalogue(results_->layers(), results_->particleAttributes());
  // A series shows first (what the slider moves), else the maximum thickness.
  const std::vector<sim::GridLayerInfo>& all = results_->layers();
  QString preferred = f.series.empty() ? QString() : f.series.front().name;
  for (const char* name : {"hfmax", "hsmax", "htmax"})
    if (preferred.isEmpty() && lists(all, name)) preferred = name;
  if (!preferred.isEmpty()) layers_->selectLayer(preferred);
  replay_->setFrames(f.frameTimes);
  showResultsFrame(0);
  if (!f.diagnosticsPath.isEmpty()) {
    try {
      plots_->setDiagnostics(DiagnosticsTable::read(f.diagnosticsPath));
    } catch (const std::exception& e) {
      log_->append(QString("warning: %1").arg(e.what()));
    }
  }
  log_->append(QString("opened results %1: %2 maps, %3 series over %4 frames%5, status \"%6\"")
                   .arg(f.dir)
                   .arg(f.maps.size())
                   .arg(f.series.size())
                   .arg(f.frameTimes.size())
                   .arg(f.hasParticles() ? ", particles" : "")
                   .arg(f.status));
  for (const QString& w : results_->warnings()) log_->append("warning: " + w);
  QString partial;
  if (f.isPartial()) {
    partial = "the run in '" + f.dir + "' is incomplete (status \"" + f.status + "\"" +
              (f.statusNote.isEmpty() ? QString() : ": " + f.statusNote) +
              "): what it wrote is shown, marked as partial";
    log_->append("warning: " + partial);
  }
  if (problems) *problems = partial;
  status_->showResults(f.status, f.isPartial());
  updateActions();
  return true;
}

bool MainWindow::compareResults(const QString& dir, QString* problems) {
  auto refuse = [&](const QString& why) {
    log_->append("error: cannot compare: " + why);
    if (problems) *problems = why;
    return false;
  };
  if (!results_) return refuse("no results are open (File > Open results first)");
  try {
    results_->compareWith(std::make_unique<ResultsReplay>(ResultsFolder::open(dir)));
  } catch (const std::exception& e) {
    return refuse(e.what());  // the results shown stay as they were
  }
  const std::vector<sim::GridLayerInfo>& all = results_->layers();
  const QString shown = layers_->layer();
  layers_->setCatalogue(all, results_->particleAttributes());
  const std::string difference = differenceLayerName(shown.toStdString());
  if (lists(all, difference)) layers_->selectLayer(QString::fromStdString(difference));
  showResultsFrame(replay_->frame());
  log_->append(QString("comparing with the results in %1: %2 difference layers (opened minus compared)")
                   .arg(results_->comparison()->folder().dir)
                   .arg(results_->differenceCount()));
  if (problems) problems->clear();
  return true;
}

void MainWindow::showResultsFrame(int frame) {
  if (!results_) return;
  const auto s = results_->snapshot(frame);
  layers_->setSnapshot(s);
  viewer_->setSnapshot(s);
  refreshProbes(false);
  if (hoverI_ >= 0) hover_->setText(hoverText(hoverI_, hoverJ_));
}

void MainWindow::chooseAndOpenResults() {
  const QString dir = QFileDialog::getExistingDirectory(this, "Open results (a Talus output folder)");
  if (dir.isEmpty()) return;
  openResultsReporting(dir);
}

void MainWindow::openResultsReporting(const QString& dir) {
  QString problems;
  if (!openResults(dir, &problems) || !problems.isEmpty())
    showMessageBox(results_ ? "Partial results" : "Cannot open results", problems);  // the log has it
}

void MainWindow::chooseAndCompareResults() {
  const QString dir = QFileDialog::getExistingDirectory(this, "Compare with results (another Talus output folder)");
  if (dir.isEmpty()) return;
  QString problems;
  if (!compareResults(dir, &problems)) showMessageBox("Cannot compare results", problems);  // the log has it
}

}  // namespace talus::gui
