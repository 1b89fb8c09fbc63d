// The most recently opened run-files, kept in QSettings and shown as a menu.
#pragma once
#include <QMenu>
#include <QObject>
#include <QStringList>

namespace talus::gui {

class RecentFiles : public QObject {
  Q_OBJECT

 public:
  /// Fills `menu` (owned by the caller) with the stored list.
  explicit RecentFiles(QMenu* menu, QObject* parent = nullptr);
  /// Puts `path` first (absolute), keeps at most kMax entries.
  void add(const QString& path);
  QStringList files() const;

  static constexpr int kMax = 10;

 signals:
  void chosen(const QString& path);

 private:
  void rebuild();
  QMenu* menu_;
};

}  // namespace talus::gui
