#include "GuiTestSupport.hpp"

#include <gtest/gtest.h>
#include <QTest>

#include "app/MainWindow.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

#include <QAbstractButton>
#include <QApplication>
#include <QCoreApplication>
#include <QMessageBox>
#include <QTimer>
#include <QElapsedTimer>
#include <QLineEdit>
#include <QThread>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace talus::guitest {

namespace fs = std::filesystem;

fs::path scratchDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("talus_gui_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string writeExampleRunFile(const fs::path& dir, const std::string& extraLines) {
  const std::string data = std::string(TALUS_TEST_DATA_DIR) + "/kot_dambreak";
  std::ifstream in(data + "/kot_dambreak.run");
  std::ostringstream text;
  std::string line;
  // Replaced keys are dropped from the original; the extra lines follow the [Output] section.
  std::set<std::string> replaced;
  std::istringstream extras(extraLines);
  for (std::string e; std::getline(extras, e);)
    if (e.find('=') != std::string::npos) replaced.insert(e.substr(0, e.find('=')));
  while (std::getline(in, line)) {
    const std::string key = line.substr(0, line.find('='));
    if (key == "Map Directory") line = "Map Directory=" + data;
    if (key == "Output Directory") line = "Output Directory=" + (dir / "out").string();
    if (replaced.count(key)) continue;
    text << line << "\n";
  }
  text << extraLines;
  const std::string path = (dir / "scene.run").string();
  std::ofstream(path) << text.str();
  return path;
}

fs::path writeExampleResults(const fs::path& dir, const std::string& extraLines) {
  const std::string runFile = writeExampleRunFile(dir, "End Time=0.05\nTimestep=1\nReport Series=1\n" + extraLines);
  const io::RunConfig config = io::RunConfig::load(runFile, sim::talusRunKeys());
  const sim::Scene scene = sim::loadScene(config);
  sim::Simulation(scene, config, (dir / "out").string(), sim::OutputMode::New).run();
  return dir / "out";
}

std::string readText(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool waitFor(const std::function<bool()>& done, double seconds) {
  QElapsedTimer clock;
  clock.start();
  while (!done()) {
    if (clock.elapsed() > seconds * 1000) return false;
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(5);
  }
  return true;
}

void onNextModal(const std::function<void(QWidget*)>& act, double seconds) {
  // A modal dialog runs its own event loop (QMessageBox::question, QFileDialog::getSaveFileName
  // block): a timer reaches into it.
  auto* timer = new QTimer;
  auto clock = std::make_shared<QElapsedTimer>();
  clock->start();
  QObject::connect(timer, &QTimer::timeout, [timer, clock, act, seconds] {
    if (QWidget* modal = QApplication::activeModalWidget()) act(modal);
    else if (clock->elapsed() < seconds * 1000) return;
    timer->stop();
    timer->deleteLater();
  });
  timer->start(20);
}

std::shared_ptr<QString> answerNextMessageBox(int button, double seconds) {
  auto seen = std::make_shared<QString>();
  onNextModal([seen, button](QWidget* modal) {
    auto* box = qobject_cast<QMessageBox*>(modal);
    if (!box) {  // not the question expected: close it, the test then fails on what it checks
      modal->close();
      return;
    }
    *seen = box->text();
    if (QAbstractButton* b = box->button(QMessageBox::StandardButton(button))) b->click();
    else box->reject();
  }, seconds);
  return seen;
}

void chooseInFileDialog(QFileDialog* dialog, const std::filesystem::path& file) {
  dialog->setDirectory(QString::fromStdString(file.parent_path().string()));
  if (auto* name = dialog->findChild<QLineEdit*>("fileNameEdit")) name->setText(QString::fromStdString(file.filename().string()));
  else dialog->selectFile(QString::fromStdString(file.string()));
  QMetaObject::invokeMethod(dialog, "accept");  // a protected override of QDialog's slot
}

void showExampleWindow(talus::gui::MainWindow& w, const std::filesystem::path& dir, int width, int height) {
  w.setReportInDialogs(false);
  w.resize(width, height);
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  ASSERT_TRUE(w.openRunFile(QString::fromStdString(writeExampleRunFile(dir))));
  waitFor([] { return false; }, 0.3);
}

std::map<std::string, double> lastDiagnosticsRow(const fs::path& csv) {
  std::istringstream in(readText(csv));
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::map<std::string, double> row;
  if (last.empty()) return row;
  std::istringstream h(header), r(last);
  for (std::string key, value; std::getline(h, key, ',') && std::getline(r, value, ',');) row[key] = std::stod(value);
  return row;
}

int distinctColours(const QImage& image) {
  std::set<QRgb> colours;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) colours.insert(image.pixel(x, y) & 0xffffff);
  return static_cast<int>(colours.size());
}

double greyDeviation(const QImage& image) {
  double sum = 0, sum2 = 0;
  const double n = double(image.width()) * image.height();
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const double g = qGray(image.pixel(x, y));
      sum += g;
      sum2 += g * g;
    }
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sum2 / n - mean * mean));
}

}  // namespace talus::guitest
