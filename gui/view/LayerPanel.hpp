// The viewer's layer controls: which grid layer is drawn (per phase, velocity, maxima, ...), its
// colour ramp, range (automatic or typed), dry threshold and opacity; which attribute colours the
// particles and its range; and the legends of both.
#pragma once
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSlider>
#include <QWidget>
#include <memory>
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
  /// Chooses the attribute that colours the particles (ignored when the run has no such attribute).
  void selectAttribute(const QString& name);
  /// Keeps the latest snapshot of the run and, with automatic ranges on, fits them to its values.
  /// The snapshot is kept so that choosing another layer or attribute later (a paused or ended run
  /// sends no more) fits that one's range instead of keeping the previous one's.
  void setSnapshot(std::shared_ptr<const sim::ViewSnapshot> snapshot);
  /// Forgets the catalogue and the snapshot of the previous scene (a run-file was opened).
  void clear();

  QString layer() const;
  /// The layer shown when a new catalogue lists it (the one last chosen or selected).
  QString preferredLayer() const { return preferred_; }
  /// The names of the layers offered, in list order ("(none)" left out).
  QStringList layerNames() const;
  QString layerUnit() const;
  LayerStyle layerStyle() const;
  QString layerRamp() const { return layerRamp_->currentText(); }
  ParticleStyle particleStyle() const;
  QString particleRamp() const { return particleRamp_->currentText(); }
  /// Unit of the attribute colouring the particles ("" when none).
  QString attributeUnit() const;

 signals:
  /// Something the viewer draws changed.
  void changed();

 private:
  void onLayerChosen();
  /// With automatic ranges on, fits both ranges to the kept snapshot (fractions: 0..1 always);
  /// true when a range changed. Emits nothing.
  bool refitRanges();
  void updateLegends();

  QString preferred_ = "h";  ///< the layer to show when a new catalogue arrives
  std::vector<sim::GridLayerInfo> layers_;
  std::vector<sim::ParticleAttributeInfo> attributes_;
  std::shared_ptr<const sim::ViewSnapshot> snapshot_;
  QComboBox *layer_, *layerRamp_, *attribute_, *particleRamp_;
  QDoubleSpinBox *min_, *max_, *emptyBelow_, *pMin_, *pMax_, *pointSize_;
  QCheckBox *autoRange_, *pAutoRange_, *showParticles_;
  QSlider* opacity_;
  LegendBar *legend_, *particleLegend_;
};

}  // namespace talus::gui
