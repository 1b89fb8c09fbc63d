// The viewer's layer controls: which grid layer is drawn (per phase, velocity, maxima, ...), its
// colour ramp, range (automatic or typed), dry threshold and opacity; which attribute colours the
// particles and its range; and the legends of both.
#pragma once
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSlider>
#include <QWidget>
#include <vector>

#include "render/TerrainRenderer.hpp"
#include "sim/ViewFields.hpp"
#include "view/LegendBar.hpp"
#include "view/ViewerWidget.hpp"

namespace talus::gui {

class LayerPanel : public QWidget {
  Q_OBJECT

 public:
  explicit LayerPanel(QWidget* parent = nullptr);

  /// The layers and particle attributes of a new run (keeps the chosen layer when it still exists).
  void setCatalogue(const std::vector<sim::GridLayerInfo>& layers, const std::vector<sim::ParticleAttributeInfo>& attributes);
  /// Chooses the layer by name ("" = none); remembered for runs whose catalogue comes later.
  void selectLayer(const QString& name);
  /// With automatic ranges on, fits them to the values of a new snapshot.
  void fitRanges(const sim::ViewSnapshot& snapshot);

  QString layer() const;
  QString layerUnit() const;
  LayerStyle layerStyle() const;
  QString layerRamp() const { return layerRamp_->currentText(); }
  ParticleStyle particleStyle() const;
  QString particleRamp() const { return particleRamp_->currentText(); }

 signals:
  /// Something the viewer draws changed.
  void changed();

 private:
  void onLayerChosen();
  void updateLegends();

  QString preferred_ = "h";  ///< the layer to show when a new catalogue arrives
  std::vector<sim::GridLayerInfo> layers_;
  std::vector<sim::ParticleAttributeInfo> attributes_;
  QComboBox *layer_, *layerRamp_, *attribute_, *particleRamp_;
  QDoubleSpinBox *min_, *max_, *emptyBelow_, *pMin_, *pMax_, *pointSize_;
  QCheckBox *autoRange_, *pAutoRange_, *showParticles_;
  QSlider* opacity_;
  LegendBar *legend_, *particleLegend_;
};

}  // namespace talus::gui
