#include "results/ResultsReplay.hpp"

#include <QFileInfo>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/Raster.hpp"
#include "io/ParticleLayerIO.hpp"
#include "io/RasterIO.hpp"
#include "results/ResultsComparison.hpp"
#include "results/ResultsLayerNames.hpp"

namespace talus::gui {

namespace {

std::vector<float> toFloats(const Raster& r, double multiplier = 1) {
  std::vector<float> v(r.values.size());
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = r.valid[k] ? float(r.values[k] * multiplier) : NAN;
  return v;
}

}  // namespace

ResultsReplay::ResultsReplay(ResultsFolder folder) : folder_(std::move(folder)) {
  warnings_ = folder_.warnings;
  // The grid: the DEM's, or else the first map's (the terrain then flat).
  if (!folder_.demPath.isEmpty()) {
    try {
      const Raster dem = io::readRaster(folder_.demPath.toStdString());
      grid_ = dem.grid;
      elevation_ = toFloats(dem, folder_.demMultiplier);
    } catch (const std::exception& e) {
      warnings_ << QString("cannot read the DEM (the terrain is drawn flat): %1").arg(e.what());
    }
  }
  for (const ResultsMap& m : folder_.maps) {
    std::vector<float> v;
    if (!readLayer(m.path, v)) continue;
    mapNames_.push_back(m.name.toStdString());
    mapValues_.push_back(std::move(v));
    layers_.push_back(resultsLayerInfo(m.name, false));
  }
  for (const ResultsSeries& s : folder_.series) layers_.push_back(resultsLayerInfo(s.name, true));
  if (grid_.nx == 0)
    throw std::runtime_error(("no map of the results folder '" + folder_.dir + "' could be read").toStdString());
  if (elevation_.empty()) elevation_.assign(grid_.cells(), 0.0f);
  ownLayers_ = layers_.size();
  // The particle fields, from the first layer written.
  QString first = folder_.particlesFinal;
  for (const QString& f : folder_.particleFrames)
    if (!f.isEmpty()) {
      first = f;
      break;
    }
  if (!first.isEmpty()) {
    try {
      for (const io::ParticleAttribute& a : io::readParticleLayer(first.toStdString()).attributes)
        attributes_.push_back({a.name, resultsParticleUnit(QString::fromStdString(a.name)).toStdString()});
    } catch (const std::exception& e) {
      warnings_ << QString("cannot read the particles: %1").arg(e.what());
    }
  }
}

double ResultsReplay::frameTime(int frame) const {
  if (folder_.frameTimes.empty()) return 0;
  return folder_.frameTimes[static_cast<std::size_t>(std::clamp(frame, 0, frameCount() - 1))];
}

bool ResultsReplay::readLayer(const QString& path, std::vector<float>& out) {
  try {
    const Raster r = io::readRaster(path.toStdString());
    if (grid_.nx == 0) grid_ = r.grid;
    if (!sameGrid(r.grid, grid_)) {
      warnings_ << "'" + path + "' is on another grid than the DEM: left out";
      return false;
    }
    out = toFloats(r);
    return true;
  } catch (const std::exception& e) {
    warnings_ << QString("cannot read '%1': %2").arg(path, e.what());
    return false;
  }
}

void ResultsReplay::addParticles(sim::ViewSnapshot& s, const QString& path) {
  io::ParticleLayer layer;
  try {
    layer = io::readParticleLayer(path.toStdString());
  } catch (const std::exception& e) {
    warnings_ << QString("cannot read the particles: %1").arg(e.what());
    return;
  }
  // Points stand on the terrain (the DEM's cell under them; north-up geotransform).
  const auto& gt = grid_.geoTransform;
  for (std::size_t p = 0; p < layer.size(); ++p) {
    const double x = layer.worldX[p], y = layer.worldY[p];
    const int i = int(std::floor((x - gt[0]) / gt[1])), j = int(std::floor((y - gt[3]) / gt[5]));
    float z = 0;
    if (i >= 0 && j >= 0 && i < grid_.nx && j < grid_.ny && std::isfinite(elevation_[grid_.index(i, j)]))
      z = elevation_[grid_.index(i, j)];
    s.particlePositions.insert(s.particlePositions.end(), {float(x), float(y), z});
  }
  s.particleCount = layer.size();
  for (const sim::ParticleAttributeInfo& a : attributes_) {
    s.particleAttributeNames.push_back(a.name);
    const std::vector<double>* v = layer.find(a.name);
    s.particleAttributes.emplace_back(layer.size(), NAN);
    if (v) std::transform(v->begin(), v->end(), s.particleAttributes.back().begin(), [](double d) { return float(d); });
  }
}

std::shared_ptr<const sim::ViewSnapshot> ResultsReplay::snapshot(int frame) {
  auto s = std::make_shared<sim::ViewSnapshot>();
  s->grid = grid_;
  s->layerNames = mapNames_;
  s->layers = mapValues_;
  const bool hasFrames = frameCount() > 0;
  frame = hasFrames ? std::clamp(frame, 0, frameCount() - 1) : 0;
  s->time = frameTime(frame);
  s->steps = frame;
  for (const ResultsSeries& series : folder_.series) {
    std::vector<float> v;
    const QString& file = series.files[static_cast<std::size_t>(frame)];
    if (file.isEmpty() || !readLayer(file, v)) v.assign(grid_.cells(), NAN);
    s->layerNames.push_back(series.name.toStdString());
    s->layers.push_back(std::move(v));
  }
  const QString particles = hasFrames && !folder_.particleFrames.empty()
                                ? folder_.particleFrames[static_cast<std::size_t>(frame)]
                                : folder_.particlesFinal;
  if (!particles.isEmpty()) addParticles(*s, particles);
  if (other_) {
    // The other run's frame at the same report time; without one its series have no values here.
    int otherFrame = hasFrames ? -1 : 0;
    for (int k = 0; hasFrames && k < other_->frameCount(); ++k)
      if (std::abs(other_->frameTime(k) - s->time) <= 1e-6 * std::max(1.0, std::abs(s->time))) otherFrame = k;
    if (otherFrame >= 0) {
      addDifferenceLayers(*s, *other_->snapshot(otherFrame));
    } else {
      sim::ViewSnapshot mapsOnly;
      mapsOnly.layerNames = other_->mapNames_;
      mapsOnly.layers = other_->mapValues_;
      for (const ResultsSeries& series : other_->folder_.series) {
        mapsOnly.layerNames.push_back(series.name.toStdString());
        mapsOnly.layers.emplace_back(grid_.cells(), NAN);
      }
      addDifferenceLayers(*s, mapsOnly);
    }
  }
  return s;
}

std::vector<QPointF> ResultsReplay::cellSeries(const std::string& layer, std::size_t k) {
  const auto map = std::find(mapNames_.begin(), mapNames_.end(), layer);
  const ResultsSeries* series = nullptr;
  for (const ResultsSeries& s : folder_.series)
    if (s.name.toStdString() == layer) series = &s;
  std::vector<QPointF> out;
  for (int f = 0; f < frameCount(); ++f) {
    double v = NAN;
    if (map != mapNames_.end()) {
      v = mapValues_[static_cast<std::size_t>(map - mapNames_.begin())][k];
    } else if (series) {
      std::vector<float> values;
      const QString& file = series->files[static_cast<std::size_t>(f)];
      if (!file.isEmpty() && readLayer(file, values)) v = values[k];
    } else if (const std::vector<float>* l = snapshot(f)->layer(layer)) {
      v = (*l)[k];
    }
    out.emplace_back(frameTime(f), v);
  }
  return out;
}

void ResultsReplay::compareWith(std::unique_ptr<ResultsReplay> other) {
  if (!sameGrid(other->grid_, grid_))
    throw std::runtime_error(("the results in '" + other->folder_.dir + "' are on another grid than those in '" +
                              folder_.dir + "': they cannot be compared").toStdString());
  other->other_.reset();  // a comparison of the other run is not this one's
  other->layers_.resize(other->ownLayers_);
  other_ = std::move(other);
  layers_.resize(ownLayers_);
  const std::vector<sim::GridLayerInfo> own(layers_.begin(), layers_.end());
  const QString otherName = QFileInfo(other_->folder_.dir).fileName();
  for (sim::GridLayerInfo& d : differenceCatalogue(own, other_->layers_, otherName)) layers_.push_back(std::move(d));
}

}  // namespace talus::gui
