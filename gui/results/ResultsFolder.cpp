#include "results/ResultsFolder.hpp"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QRegularExpression>
#include <QTextStream>
#include <map>
#include <stdexcept>

#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"

namespace talus::gui {

namespace {

const QStringList kRasterFilters{"*.tif", "*.tiff", "*.map"};

[[noreturn]] void fail(const QString& message) { throw std::runtime_error(message.toStdString()); }

/// The status (and a failed run's diagnosis) from summary.json.
void readSummary(ResultsFolder& f) {
  QFile file(f.dir + "/summary.json");
  if (!file.open(QIODevice::ReadOnly)) fail("cannot read '" + file.fileName() + "': " + file.errorString());
  QJsonParseError error{};
  const QJsonDocument doc = QJsonDocument::fromJson(file.readAll(), &error);
  if (!doc.isObject())
    fail("'" + file.fileName() + "' is not a Talus summary (" +
         (error.error != QJsonParseError::NoError ? error.errorString() : QString("not a JSON object")) + ")");
  const QJsonObject summary = doc.object();
  if (!summary.contains("status")) fail("'" + file.fileName() + "' is not a Talus summary (no \"status\")");
  f.status = summary.value("status").toString();
  f.statusNote = summary.value("failure").toString();
}

/// The DEM named by the run's resolved run-file (every key with its value, absolute paths).
void findDem(ResultsFolder& f) {
  const QString runFile = f.dir + "/run.resolved.run";
  if (!QFileInfo::exists(runFile)) {
    f.warnings << "the folder has no run.resolved.run: the terrain is drawn flat";
    return;
  }
  try {
    const io::MapValue dem = io::RunConfig::load(runFile.toStdString(), sim::talusRunKeys()).map("DEM");
    f.demPath = QString::fromStdString(dem.file);
    f.demMultiplier = dem.multiplier;
  } catch (const std::exception& e) {
    f.warnings << QString("cannot read the DEM's name from '%1' (the terrain is drawn flat): %2").arg(runFile, e.what());
  }
}

/// Series frames "NAME_NNNN.ext" under series/ (or OpenLISEM's "NAMEdddddd.ddd" in the folder) and
/// particle frames under particles/, on the report indices of series/index.csv (whose times they
/// take; an index without a time gets its number).
void listFrames(ResultsFolder& f) {
  std::map<int, double> times;
  QFile index(f.dir + "/series/index.csv");
  if (index.open(QIODevice::ReadOnly | QIODevice::Text)) {
    QTextStream in(&index);
    in.readLine();  // header: index,time_s,...
    while (!in.atEnd()) {
      const QStringList cells = in.readLine().split(',');
      bool okIndex = false, okTime = false;
      const int k = cells.value(0).toInt(&okIndex);
      const double t = cells.value(1).toDouble(&okTime);
      if (okIndex && okTime) times[k] = t;
    }
  }
  std::map<QString, std::map<int, QString>> byName;
  const QRegularExpression seriesName("^([A-Za-z]+)_(\\d+)$");
  for (const QFileInfo& file : QDir(f.dir + "/series").entryInfoList(kRasterFilters, QDir::Files, QDir::Name)) {
    const QRegularExpressionMatch m = seriesName.match(file.completeBaseName());
    if (!m.hasMatch()) continue;
    const int k = m.captured(2).toInt();
    byName[m.captured(1)][k] = file.absoluteFilePath();
    if (!times.count(k)) times[k] = k;
  }
  // Series Names=openlisem: NAMEdddddd.ddd in the folder itself, the nine digits the report index.
  const QRegularExpression lisemName("^([A-Za-z]+)(\\d{6})\\.(\\d{3})$");
  for (const QFileInfo& file : QDir(f.dir).entryInfoList(QDir::Files, QDir::Name)) {
    const QRegularExpressionMatch m = lisemName.match(file.fileName());
    if (!m.hasMatch()) continue;
    const int k = (m.captured(2) + m.captured(3)).toInt();
    byName[m.captured(1)][k] = file.absoluteFilePath();
    if (!times.count(k)) times[k] = k;
  }
  std::map<int, QString> particles;
  const QRegularExpression particleName("^particles_(\\d+)$");
  for (const QFileInfo& file : QDir(f.dir + "/particles").entryInfoList({"*.gpkg"}, QDir::Files, QDir::Name)) {
    const QRegularExpressionMatch m = particleName.match(file.completeBaseName());
    if (!m.hasMatch()) continue;
    const int k = m.captured(1).toInt();
    particles[k] = file.absoluteFilePath();
    if (!times.count(k)) times[k] = k;
  }
  // Only indices that have a file: index.csv may list times whose files a cut-short run never wrote.
  std::vector<int> indices;
  for (const auto& [k, t] : times) {
    bool has = particles.count(k) > 0;
    for (const auto& [name, files] : byName) has = has || files.count(k) > 0;
    if (has) indices.push_back(k);
  }
  for (int k : indices) f.frameTimes.push_back(times[k]);
  for (const auto& [name, files] : byName) {
    ResultsSeries s{name, {}};
    for (int k : indices) s.files.push_back(files.count(k) ? files.at(k) : QString());
    f.series.push_back(std::move(s));
  }
  if (!particles.empty())
    for (int k : indices) f.particleFrames.push_back(particles.count(k) ? particles.at(k) : QString());
}

}  // namespace

ResultsFolder ResultsFolder::open(const QString& dir) {
  const QFileInfo info(dir);
  if (!info.exists()) fail("the results folder '" + dir + "' does not exist");
  if (!info.isDir()) fail("'" + dir + "' is not a folder: choose a Talus output folder");
  ResultsFolder f;
  f.dir = info.absoluteFilePath();
  if (!QFileInfo::exists(f.dir + "/summary.json"))
    fail("'" + f.dir + "' is not a Talus output folder (it has no summary.json)");
  readSummary(f);
  findDem(f);
  if (QFileInfo::exists(f.dir + "/diagnostics.csv")) f.diagnosticsPath = f.dir + "/diagnostics.csv";
  for (const QFileInfo& file : QDir(f.dir).entryInfoList(kRasterFilters, QDir::Files, QDir::Name))
    f.maps.push_back({file.completeBaseName(), file.absoluteFilePath()});
  if (QFileInfo::exists(f.dir + "/particles_final.gpkg")) f.particlesFinal = f.dir + "/particles_final.gpkg";
  listFrames(f);
  return f;
}

}  // namespace talus::gui
