#include "run/LogPanel.hpp"

#include <QTime>

namespace talus::gui {

LogPanel::LogPanel(QWidget* parent) : QPlainTextEdit(parent) {
  setReadOnly(true);
  setMaximumBlockCount(5000);
  setFont(QFont("monospace"));
}

void LogPanel::append(const QString& line) {
  const QString stamp = QTime::currentTime().toString("HH:mm:ss");
  const QString body = line.toHtmlEscaped().replace("\n", "<br>&nbsp;&nbsp;");
  if (line.startsWith("error") || line.startsWith("run failed"))
    appendHtml(stamp + " <span style='color:#c0392b'>" + body + "</span>");
  else if (line.startsWith("warning"))
    appendHtml(stamp + " <span style='color:#d68910'>" + body + "</span>");
  else
    appendHtml(stamp + " " + body);
}

}  // namespace talus::gui
