// The log: time-stamped lines from the run (device, interop path, warnings, mass balance, errors).
#pragma once
#include <QPlainTextEdit>

namespace talus::gui {

class LogPanel : public QPlainTextEdit {
  Q_OBJECT

 public:
  explicit LogPanel(QWidget* parent = nullptr);
  /// Appends a line; lines starting with "error" or "warning" are highlighted.
  void append(const QString& line);
};

}  // namespace talus::gui
