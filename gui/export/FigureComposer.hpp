// A figure of the viewer's map view for reports (File > Export figure): the view framed by
// coordinate ticks, with a legend (colour bar, layer name and unit), the simulated time, a scale
// bar and a north arrow, in the manner of the engine's `talus render` (drawn here with QPainter).
#pragma once
#include <QImage>
#include <QRect>
#include <QString>

namespace talus::gui {

struct FigureContent {
  QImage view;                    ///< the viewer's image (map view: north up)
  double x0 = 0, y0 = 0;          ///< world coordinates of the view image's top-left corner
  double metresPerPixel = 1;      ///< of the view image
  QString layer, unit, ramp;      ///< the layer shown ("" = none: no colour bar)
  double min = 0, max = 1;        ///< its colour range
  double time = 0;                ///< simulated [s]
};

/// Where the parts of a figure for a view of `viewSize` pixels lie.
struct FigureLayout {
  QSize size;       ///< the whole figure
  QRect view;       ///< the view image
  QRect colourBar;  ///< the legend's ramp (bottom: min, top: max)
  QRect scaleBar;   ///< the scale bar and its label, over the view's bottom-left corner
  QRect northArrow; ///< over the view's top-right corner
  static FigureLayout of(QSize viewSize);
};

/// The figure (white background).
QImage composeFigure(const FigureContent& content);

}  // namespace talus::gui
