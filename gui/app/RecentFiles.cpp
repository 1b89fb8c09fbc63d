#include "app/RecentFiles.hpp"

#include <QFileInfo>
#include <QSettings>

namespace talus::gui {

namespace {
constexpr const char* kKey = "recentRunFiles";
}

RecentFiles::RecentFiles(QMenu* menu, QObject* parent) : QObject(parent), menu_(menu) { rebuild(); }

QStringList RecentFiles::files() const { return QSettings().value(kKey).toStringList(); }

void RecentFiles::add(const QString& path) {
  const QString abs = QFileInfo(path).absoluteFilePath();
  QStringList list = files();
  list.removeAll(abs);
  list.prepend(abs);
  while (list.size() > kMax) list.removeLast();
  QSettings().setValue(kKey, list);
  rebuild();
}

void RecentFiles::rebuild() {
  menu_->clear();
  const QStringList list = files();
  for (const QString& f : list)
    menu_->addAction(f, this, [this, f] { emit chosen(f); });
  menu_->setEnabled(!list.isEmpty());
}

}  // namespace talus::gui
