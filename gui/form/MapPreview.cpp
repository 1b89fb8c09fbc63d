#include "form/MapPreview.hpp"

#include <QDateTime>
#include <QFileInfo>
#include <QImage>
#include <QPixmap>
#include <algorithm>
#include <cmath>

#include "core/Error.hpp"
#include "io/RasterIO.hpp"

namespace talus::gui {

namespace {
constexpr int kSide = 160;                     ///< preview size [pixels]
constexpr std::size_t kMaxCells = 25'000'000;  ///< larger rasters get no preview (too slow to read here)
}  // namespace

MapPreview::MapPreview(QWidget* parent) : QLabel(parent) { setVisible(false); }

void MapPreview::showMessage(const QString& text) {
  setPixmap({});
  setWordWrap(true);  // a long reason wraps
  setText(text);
}

void MapPreview::showRaster(const QString& path) {
  const QFileInfo info(path);
  const QString stamp = path + "@" + info.lastModified().toString(Qt::ISODateWithMs);
  if (stamp == shown_) return;
  shown_ = stamp;
  if (path.isEmpty()) {
    setVisible(false);
    return;
  }
  setVisible(true);
  if (!info.isFile()) {
    showMessage("(no preview: file not found)");
    return;
  }
  if (static_cast<std::size_t>(info.size()) > kMaxCells * 8) {
    showMessage("(no preview: large file)");
    return;
  }
  try {
    const Raster r = io::readRaster(path.toStdString());
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (std::size_t k = 0; k < r.values.size(); ++k)
      if (r.valid[k]) {
        lo = std::min(lo, r.values[k]);
        hi = std::max(hi, r.values[k]);
      }
    const double scale = double(kSide) / std::max(r.grid.nx, r.grid.ny);
    const int w = std::max(1, int(r.grid.nx * scale)), h = std::max(1, int(r.grid.ny * scale));
    QImage img(w, h, QImage::Format_RGB32);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int i = std::min(r.grid.nx - 1, int(x / scale)), j = std::min(r.grid.ny - 1, int(y / scale));
        const std::size_t k = r.grid.index(i, j);
        if (!r.valid[k]) {
          img.setPixel(x, y, qRgb(255, 240, 240));
          continue;
        }
        const int g = hi > lo ? int(std::lround(255 * (r.values[k] - lo) / (hi - lo))) : 128;
        img.setPixel(x, y, qRgb(g, g, g));
      }
    // Word wrap off for a picture: a word-wrapping label asks its layout for a height for its width,
    // which a picture does not give (-1), and the preview was laid out 0 px high.
    setWordWrap(false);
    setPixmap(QPixmap::fromImage(img));
    setToolTip(QString("%1 x %2 cells of %3 m, values %4 .. %5 (black .. white); nodata pink")
                   .arg(r.grid.nx)
                   .arg(r.grid.ny)
                   .arg(r.grid.dx)
                   .arg(lo)
                   .arg(hi));
  } catch (const std::exception& e) {
    showMessage(QString("(no preview: %1)").arg(e.what()));
  }
}

}  // namespace talus::gui
