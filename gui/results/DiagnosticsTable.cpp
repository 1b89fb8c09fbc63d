#include "results/DiagnosticsTable.hpp"

#include <QFile>
#include <QTextStream>
#include <stdexcept>

namespace talus::gui {

const std::vector<double>* DiagnosticsTable::column(const QString& name) const {
  const int k = names.indexOf(name);
  return k < 0 ? nullptr : &columns[static_cast<std::size_t>(k)];
}

DiagnosticsTable DiagnosticsTable::read(const QString& path) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly | QIODevice::Text))
    throw std::runtime_error(("cannot read '" + path + "': " + file.errorString()).toStdString());
  QTextStream in(&file);
  DiagnosticsTable t;
  t.names = in.readLine().trimmed().split(',');
  if (t.names.size() < 2) throw std::runtime_error(("'" + path + "' has no diagnostics header").toStdString());
  t.columns.resize(static_cast<std::size_t>(t.names.size()));
  while (!in.atEnd()) {
    const QStringList cells = in.readLine().trimmed().split(',');
    if (cells.size() != t.names.size()) break;
    for (int c = 0; c < cells.size(); ++c) t.columns[static_cast<std::size_t>(c)].push_back(cells[c].toDouble());
  }
  return t;
}

}  // namespace talus::gui
