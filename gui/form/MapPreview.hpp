// A small grey-scale picture of a raster map, shown under a map field of the parameter form.
#pragma once
#include <QLabel>
#include <QString>

namespace talus::gui {

class MapPreview : public QLabel {
  Q_OBJECT

 public:
  explicit MapPreview(QWidget* parent = nullptr);
  /// Shows the raster at `path` (absolute), or a line saying why there is no preview; an empty
  /// path hides the preview (a uniform value instead of a file).
  void showRaster(const QString& path);

 private:
  void showMessage(const QString& text);  ///< a line saying why there is no picture
  QString shown_;
};

}  // namespace talus::gui
