#include "export/FrameExporter.hpp"

#include <QDir>
#include <QImage>

#include "view/ViewerWidget.hpp"

namespace talus::gui {

QString FrameExporter::saveScreenshot(ViewerWidget& viewer, const QString& path) {
  const QImage image = viewer.grabFramebuffer();
  if (image.isNull()) return "the viewer has no image yet";
  if (!image.save(path, "PNG")) return "cannot write '" + path + "'";
  return {};
}

QString FrameExporter::startSequence(const QString& folder) {
  if (!QDir().mkpath(folder)) return "cannot create folder '" + folder + "'";
  folder_ = folder;
  frames_ = 0;
  recording_ = true;
  return {};
}

QString FrameExporter::captureFrame(ViewerWidget& viewer) {
  if (!recording_) return {};
  const QString path = QDir(folder_).filePath(QString("frame_%1.png").arg(frames_, 5, 10, QChar('0')));
  const QString problem = saveScreenshot(viewer, path);
  if (!problem.isEmpty()) {
    recording_ = false;
    return problem;
  }
  ++frames_;
  return {};
}

}  // namespace talus::gui
