#include "plots/ProbePanel.hpp"

#include <QGridLayout>

namespace talus::gui {

ProbePanel::ProbePanel(QWidget* parent) : QWidget(parent) {
  caption_ = new QLabel("Tools > Time series at a point, or Tools > Profile along a line, then click on the map");
  caption_->setWordWrap(true);
  point_ = new TimeSeriesPlot("at a point", "-");
  profile_ = new TimeSeriesPlot("profile", "-");
  profile_->setXUnit("m");
  elevation_ = new TimeSeriesPlot("elevation along the profile", "m");
  elevation_->setXUnit("m");
  pointSeries_ = point_->addSeries("value", QColor(30, 110, 220));
  profileSeries_ = profile_->addSeries("value", QColor(200, 60, 40));
  elevationSeries_ = elevation_->addSeries("terrain", QColor(90, 90, 90));
  auto* grid = new QGridLayout(this);
  grid->addWidget(caption_, 0, 0, 1, 3);
  grid->addWidget(point_, 1, 0);
  grid->addWidget(profile_, 1, 1);
  grid->addWidget(elevation_, 1, 2);
}

void ProbePanel::setPointSeries(const QString& where, const QString& layer, const QString& unit,
                                const std::vector<QPointF>& points) {
  caption_->setText(layer + " at " + where);
  point_->setTitle(layer + " at a point", unit);
  point_->clear();
  for (const QPointF& p : points) point_->append(pointSeries_, p.x(), p.y());
}

void ProbePanel::appendPoint(double time, double value) {
  // A run's last state can arrive twice (its last step and its end): one point per time.
  const auto& points = point_->points(pointSeries_);
  if (!points.empty() && points.back().x() == time) return;
  point_->append(pointSeries_, time, value);
}

void ProbePanel::setProfile(const QString& layer, const QString& unit, const std::vector<QPointF>& values,
                            const std::vector<QPointF>& elevation) {
  profile_->setTitle(layer + " along the profile", unit);
  profile_->clear();
  elevation_->clear();
  for (const QPointF& p : values) profile_->append(profileSeries_, p.x(), p.y());
  for (const QPointF& p : elevation) elevation_->append(elevationSeries_, p.x(), p.y());
}

void ProbePanel::clear() {
  point_->clear();
  profile_->clear();
  elevation_->clear();
}

}  // namespace talus::gui
