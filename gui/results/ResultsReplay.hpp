// The views of an opened output folder: its terrain (the run's DEM), the catalogue of layers (each
// map of the folder, each series variable, the particle fields) and one ViewSnapshot per series
// frame, read through the engine's io library when asked for. A frame's snapshot holds the maps of
// the folder (maxima, final, arrival, ...) and the series variables and particles at that frame, so
// the viewer and the layer panel show it as they show a live run's snapshot.
#pragma once
#include <QPointF>
#include <QStringList>
#include <memory>
#include <vector>

#include "core/Grid.hpp"
#include "results/ResultsFolder.hpp"
#include "sim/ParticleView.hpp"
#include "sim/ViewFields.hpp"

namespace talus::gui {

class ResultsReplay {
 public:
  /// Reads the terrain and the folder's maps. Throws std::runtime_error naming the folder when no
  /// map of it can be read (nothing to show); maps that cannot be read or lie on another grid are
  /// left out and named in warnings().
  explicit ResultsReplay(ResultsFolder folder);

  const ResultsFolder& folder() const { return folder_; }
  const Grid& grid() const { return grid_; }
  const std::vector<float>& elevation() const { return elevation_; }
  const std::vector<sim::GridLayerInfo>& layers() const { return layers_; }
  const std::vector<sim::ParticleAttributeInfo>& particleAttributes() const { return attributes_; }
  /// Number of series frames (0: only the maps of the folder).
  int frameCount() const { return static_cast<int>(folder_.frameTimes.size()); }
  double frameTime(int frame) const;
  /// The snapshot of frame `frame` (clamped into range; without frames: the folder's maps and final
  /// particles). Reads the frame's files.
  std::shared_ptr<const sim::ViewSnapshot> snapshot(int frame);
  /// The values of a layer at cell k over every series frame, (frame time, value): a map of the
  /// folder is constant, a series variable reads only its own file per frame, any other layer (a
  /// difference) the frame's snapshot. NaN where a frame has no value.
  std::vector<QPointF> cellSeries(const std::string& layer, std::size_t k);
  /// Compares with another opened folder from now on: the difference layers of the maps and series
  /// both hold join the catalogue (ResultsComparison). Throws std::runtime_error naming both
  /// folders when their grids differ.
  void compareWith(std::unique_ptr<ResultsReplay> other);
  const ResultsReplay* comparison() const { return other_.get(); }
  /// Number of difference layers in layers() (0 without a comparison).
  std::size_t differenceCount() const { return layers_.size() - ownLayers_; }
  /// What was left out (unreadable maps, another grid, missing DEM).
  const QStringList& warnings() const { return warnings_; }

 private:
  /// The raster as floats on the run's grid (NaN where nodata), or false (with a warning).
  bool readLayer(const QString& path, std::vector<float>& out);
  void addParticles(sim::ViewSnapshot& s, const QString& path);

  ResultsFolder folder_;
  Grid grid_;
  std::vector<float> elevation_;
  std::vector<sim::GridLayerInfo> layers_;
  std::vector<sim::ParticleAttributeInfo> attributes_;
  std::vector<std::string> mapNames_;          ///< the folder's maps, read once
  std::vector<std::vector<float>> mapValues_;
  QStringList warnings_;
  std::size_t ownLayers_ = 0;  ///< layers_ before the differences
  std::unique_ptr<ResultsReplay> other_;
};

}  // namespace talus::gui
