#include "view/LayerPanel.hpp"

#include <QFormLayout>
#include <QGroupBox>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "render/ColorRamp.hpp"

namespace talus::gui {

namespace {

QDoubleSpinBox* rangeBox(double value) {
  auto* b = new QDoubleSpinBox;
  b->setDecimals(4);
  b->setRange(-1e12, 1e12);
  b->setValue(value);
  b->setKeyboardTracking(false);
  return b;
}

/// Smallest and largest finite value (above `above` when given), or false (and 0..1) when none.
bool valueRange(const std::vector<float>& v, double& lo, double& hi, double above = -HUGE_VAL) {
  lo = HUGE_VAL;
  hi = -HUGE_VAL;
  for (float x : v)
    if (std::isfinite(x) && x > above) {
      lo = std::min(lo, double(x));
      hi = std::max(hi, double(x));
    }
  if (lo > hi) {
    lo = 0;  // no value: the boxes' initial range
    hi = 1;
    return false;
  }
  return true;
}

/// Dimensionless shares (solid fraction, cohesion fraction) lie in 0..1 by definition: a fixed
/// range lets a colour mean the same share in every frame and every run, instead of stretching
/// whatever spread the flow has now over the whole ramp.
bool isFraction(const QString& name, const QString& unit) { return unit == "-" && name.contains("fraction"); }

/// Sets an automatic range into its boxes (without their signals); true when that changed them.
bool setRange(QDoubleSpinBox& min, QDoubleSpinBox& max, double lo, double hi) {
  if (hi <= lo) hi = lo + 1e-6;  // a flat field still needs a range to colour
  const double oldMin = min.value(), oldMax = max.value();
  const QSignalBlocker b1(min), b2(max);
  min.setValue(lo);
  max.setValue(hi);
  return min.value() != oldMin || max.value() != oldMax;  // as the boxes round them
}

}  // namespace

LayerPanel::LayerPanel(QWidget* parent) : QWidget(parent) {
  auto* grid = new QGroupBox("Grid layer");
  auto* gf = new QFormLayout(grid);
  layer_ = new QComboBox;
  layerRamp_ = new QComboBox;
  layerRamp_->addItems(ColorRamp::names());
  autoRange_ = new QCheckBox("automatic");
  autoRange_->setChecked(true);
  min_ = rangeBox(0);
  max_ = rangeBox(1);
  emptyBelow_ = rangeBox(0.001);
  emptyBelow_->setToolTip("cells whose value is at or below this are not coloured (dry cells)");
  opacity_ = new QSlider(Qt::Horizontal);
  opacity_->setRange(0, 100);
  opacity_->setValue(85);
  legend_ = new LegendBar;
  gf->addRow("layer", layer_);
  gf->addRow("colours", layerRamp_);
  gf->addRow("range", autoRange_);
  gf->addRow("minimum", min_);
  gf->addRow("maximum", max_);
  gf->addRow("hide at or below", emptyBelow_);
  gf->addRow("opacity", opacity_);
  gf->addRow(legend_);

  auto* parts = new QGroupBox("Particles");
  auto* pf = new QFormLayout(parts);
  showParticles_ = new QCheckBox("show");
  showParticles_->setChecked(true);
  attribute_ = new QComboBox;
  particleRamp_ = new QComboBox;
  particleRamp_->addItems(ColorRamp::names());
  particleRamp_->setCurrentText("heat");
  pAutoRange_ = new QCheckBox("automatic");
  pAutoRange_->setChecked(true);
  pMin_ = rangeBox(0);
  pMax_ = rangeBox(1);
  pointSize_ = rangeBox(4);
  pointSize_->setRange(1, 32);
  pointSize_->setDecimals(0);
  particleLegend_ = new LegendBar;
  pf->addRow(showParticles_);
  pf->addRow("colour by", attribute_);
  pf->addRow("colours", particleRamp_);
  pf->addRow("range", pAutoRange_);
  pf->addRow("minimum", pMin_);
  pf->addRow("maximum", pMax_);
  pf->addRow("point size [px]", pointSize_);
  pf->addRow(particleLegend_);

  auto* v = new QVBoxLayout(this);
  v->addWidget(grid);
  v->addWidget(parts);
  v->addStretch(1);

  auto emitChanged = [this] {
    refitRanges();  // automatic switched on, or another attribute: its range, not the last one
    min_->setEnabled(!autoRange_->isChecked());
    max_->setEnabled(!autoRange_->isChecked());
    pMin_->setEnabled(!pAutoRange_->isChecked());
    pMax_->setEnabled(!pAutoRange_->isChecked());
    updateLegends();
    emit changed();
  };
  connect(layer_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this] { onLayerChosen(); });
  for (QComboBox* c : {layerRamp_, attribute_, particleRamp_})
    connect(c, QOverload<int>::of(&QComboBox::currentIndexChanged), this, emitChanged);
  for (QDoubleSpinBox* b : {min_, max_, emptyBelow_, pMin_, pMax_, pointSize_})
    connect(b, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, emitChanged);
  for (QCheckBox* c : {autoRange_, pAutoRange_, showParticles_}) connect(c, &QCheckBox::toggled, this, emitChanged);
  connect(opacity_, &QSlider::valueChanged, this, emitChanged);
  emitChanged();
}

void LayerPanel::setCatalogue(const std::vector<sim::GridLayerInfo>& layers,
                              const std::vector<sim::ParticleAttributeInfo>& attributes) {
  const QString previous = preferred_;
  snapshot_.reset();  // the previous run's
  layers_ = layers;
  attributes_ = attributes;
  {
    const QSignalBlocker block(layer_);
    layer_->clear();
    layer_->addItem("(none)", QString());
    for (const auto& l : layers)
      layer_->addItem(QString::fromStdString(l.label) + " [" + QString::fromStdString(l.unit) + "]",
                      QString::fromStdString(l.name));
    const int keep = layer_->findData(previous);
    layer_->setCurrentIndex(keep >= 0 ? keep : std::min(1, layer_->count() - 1));
  }
  {
    const QSignalBlocker block(attribute_);
    attribute_->clear();
    for (const auto& a : attributes)
      attribute_->addItem(QString::fromStdString(a.name) + " [" + QString::fromStdString(a.unit) + "]",
                          QString::fromStdString(a.name));
  }
  attribute_->setEnabled(!attributes.empty());
  onLayerChosen();
}

QStringList LayerPanel::layerNames() const {
  QStringList names;
  for (int k = 0; k < layer_->count(); ++k)
    if (!layer_->itemData(k).toString().isEmpty()) names << layer_->itemData(k).toString();
  return names;
}

void LayerPanel::selectLayer(const QString& name) {
  preferred_ = name;
  const int k = layer_->findData(name);
  if (k >= 0) layer_->setCurrentIndex(k);
}

void LayerPanel::selectAttribute(const QString& name) {
  const int k = attribute_->findData(name);
  if (k >= 0) attribute_->setCurrentIndex(k);
}

void LayerPanel::onLayerChosen() {
  if (!layer().isEmpty()) preferred_ = layer();
  const QSignalBlocker block(layerRamp_);
  layerRamp_->setCurrentText(ColorRamp::defaultFor(layerUnit()));
  const QString unit = layerUnit();
  // Thickness layers hide dry cells; other layers hide only cells without value (and 0 where 0 is empty).
  const sim::GridLayerInfo* info = nullptr;
  for (const auto& l : layers_)
    if (QString::fromStdString(l.name) == layer()) info = &l;
  {
    const QSignalBlocker b2(emptyBelow_);
    emptyBelow_->setValue(!info ? 0.0 : !info->zeroIsEmpty ? -1e12 : unit == "m" ? 0.001 : 1e-6);
  }
  refitRanges();  // the range of this layer, also when no new snapshot comes (paused or ended run)
  updateLegends();
  emit changed();
}

QString LayerPanel::layer() const { return layer_->currentData().toString(); }

QString LayerPanel::layerUnit() const {
  for (const auto& l : layers_)
    if (QString::fromStdString(l.name) == layer()) return QString::fromStdString(l.unit);
  return {};
}

LayerStyle LayerPanel::layerStyle() const {
  LayerStyle s;
  s.visible = !layer().isEmpty();
  s.min = float(min_->value());
  s.max = float(max_->value());
  s.emptyBelow = float(emptyBelow_->value());
  s.opacity = opacity_->value() / 100.0f;
  return s;
}

ParticleStyle LayerPanel::particleStyle() const {
  ParticleStyle s;
  s.attribute = attribute_->currentData().toString();
  s.min = float(pMin_->value());
  s.max = float(pMax_->value());
  s.pointSize = float(pointSize_->value());
  s.visible = showParticles_->isChecked();
  return s;
}

void LayerPanel::setSnapshot(std::shared_ptr<const sim::ViewSnapshot> snapshot) {
  snapshot_ = std::move(snapshot);
  if (refitRanges()) {
    updateLegends();
    emit changed();
  }
}

void LayerPanel::clear() {
  setCatalogue({}, {});
}

bool LayerPanel::refitRanges() {
  bool changedRange = false;
  if (autoRange_->isChecked()) {
    const std::vector<float>* v = snapshot_ ? snapshot_->layer(layer().toStdString()) : nullptr;
    double lo = 0, hi = 1;
    if (!isFraction(layer(), layerUnit()) && v && valueRange(*v, lo, hi, emptyBelow_->value()) && layerUnit() != "s")
      lo = std::min(lo, 0.0);  // amounts start at zero; times at the first arrival
    changedRange = setRange(*min_, *max_, lo, hi) || changedRange;
  }
  if (pAutoRange_->isChecked()) {
    const QString name = particleStyle().attribute;
    const std::vector<float>* v = snapshot_ ? snapshot_->particleAttribute(name.toStdString()) : nullptr;
    double lo = 0, hi = 1;
    if (!isFraction(name, attributeUnit()) && v) valueRange(*v, lo, hi);
    changedRange = setRange(*pMin_, *pMax_, lo, hi) || changedRange;
  }
  return changedRange;
}

QString LayerPanel::attributeUnit() const {
  for (const auto& a : attributes_)
    if (QString::fromStdString(a.name) == particleStyle().attribute) return QString::fromStdString(a.unit);
  return {};
}

void LayerPanel::updateLegends() {
  legend_->setLegend(layer_->currentText().section(" [", 0, 0), layerUnit(), layerRamp(), min_->value(), max_->value());
  particleLegend_->setLegend(attributes_.empty() ? "particles (none in this run)" : attribute_->currentText().section(" [", 0, 0),
                             attributeUnit(), particleRamp(), pMin_->value(), pMax_->value());
}

}  // namespace talus::gui
