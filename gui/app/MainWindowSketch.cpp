// MainWindow's tools that draw on the map (Tools menu): a release area saved as the raster of an
// initial-thickness key, and the probes (a layer's time series at a cell, its profile along a line).
#include <QDir>
#include <QFileInfo>
#include <cmath>
#include <filesystem>

#include "app/MainWindow.hpp"
#include "core/Raster.hpp"
#include "form/ReleaseAreaFile.hpp"
#include "form/RunValidation.hpp"
#include "io/RasterIO.hpp"

namespace talus::gui {

namespace {

std::vector<MapPoint> worldPoints(const ViewerWidget& viewer, const std::vector<QPointF>& model) {
  std::vector<MapPoint> out;
  for (const QPointF& m : model) {
    const QPointF w = viewer.worldOf(m);
    out.push_back({w.x(), w.y()});
  }
  return out;
}

/// The value of a layer of a snapshot at cell k (NaN when it holds none there).
double layerValue(const sim::ViewSnapshot* s, const std::string& layer, std::size_t k) {
  const std::vector<float>* v = s ? s->layer(layer) : nullptr;
  return v && k < v->size() ? double((*v)[k]) : NAN;
}

}  // namespace

void MainWindow::startSketch(MapSketch::Tool tool) {
  if (tool == MapSketch::Tool::Polygon && !(doc_ && initial_)) {
    log_->append("error: open a run-file whose DEM can be read before drawing a release area");
    return;
  }
  const Grid* g = nullptr;
  const std::vector<float>* z = nullptr;
  const std::vector<sim::GridLayerInfo>* layers = nullptr;
  if (!sceneOnScreen(g, z, layers)) {
    log_->append("error: nothing to draw on: open a run-file or results first");
    return;
  }
  tilted_->setChecked(false);  // drawing is on the map view
  viewer_->sketch().start(tool);
  viewer_->setFocus();
}

void MainWindow::onSketchFinished(MapSketch::Tool tool, const std::vector<QPointF>& vertices) {
  const std::vector<MapPoint> world = worldPoints(*viewer_, vertices);
  switch (tool) {
    case MapSketch::Tool::Polygon: askReleaseArea(world); break;
    case MapSketch::Tool::Profile: probeProfile(world); break;
    case MapSketch::Tool::Point: {
      const Grid* g = nullptr;
      const std::vector<float>* z = nullptr;
      const std::vector<sim::GridLayerInfo>* layers = nullptr;
      int i = -1, j = -1;
      if (world.empty() || !sceneOnScreen(g, z, layers) || !cellOfPoint(*g, world.front(), i, j)) {
        log_->append("the point lies off the terrain: no time series");
        return;
      }
      probeCell(i, j);
      break;
    }
    case MapSketch::Tool::None: break;
  }
}

void MainWindow::askReleaseArea(const std::vector<MapPoint>& polygon) {
  const QString folder = doc_ ? QString::fromStdString(doc_->baseDir()) : QDir::currentPath();
  auto* dialog = new ReleaseAreaDialog(folder, polygonArea(polygon), this);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  connect(dialog, &QDialog::accepted, this, [this, dialog, polygon] {
    const QString problem = saveReleaseArea(polygon, dialog->material(), dialog->thickness(), dialog->path(),
                                            dialog->addToCurrentMap());
    if (!problem.isEmpty()) showMessageBox("Release area not saved", problem);
  });
  dialog->open();  // window-modal without a nested event loop
}

QString MainWindow::saveReleaseArea(const std::vector<MapPoint>& polygon, ReleaseAreaDialog::Material material,
                                    double thickness, const QString& path, bool addToCurrent) {
  auto fail = [this](const QString& why) {
    log_->append("error: " + why);
    return why;
  };
  if (!doc_ || !initial_ || initial_->elevation.empty())
    return fail("open a run-file whose DEM can be read before drawing a release area");
  if (run_->isActive()) return fail("a run is in progress: stop it before changing its release area");
  if (path.isEmpty()) return fail("release area: no file name given");
  const bool water = material == ReleaseAreaDialog::Material::Water;
  const std::string includeKey = water ? "Include Initial Water" : "Include Initial Solids";
  const std::string mapKey = water ? "Initial Fluid Height" : "Initial Solid Height";
  const Grid& grid = initial_->grid;
  // Where the run-file's maps resolve, and the key's current map (to add to).
  const ValidationResult valid = validateDocument(*doc_);
  std::string mapDir = doc_->baseDir();
  std::vector<double> base;
  if (valid.ok()) {
    mapDir = valid.config->directory("Map Directory");
    if (addToCurrent && valid.config->flag(includeKey)) {
      const io::MapValue current = valid.config->map(mapKey);
      try {
        base.assign(grid.cells(), current.constant * current.multiplier);
        if (current.isFile) {
          const Raster r = io::readRaster(current.file);
          if (!sameGrid(r.grid, grid))
            return fail(QString::fromStdString("release area: the current " + mapKey + " map (" + current.file +
                                               ") is not on the DEM's grid"));
          for (std::size_t k = 0; k < grid.cells(); ++k)
            base[k] = r.valid[k] ? r.values[k] * current.multiplier : 0.0;
        }
      } catch (const std::exception& e) {
        return fail(QString("release area: cannot add to the current map: %1").arg(e.what()));
      }
    }
  } else if (addToCurrent) {
    return fail("release area: the run-file has problems, so its current map cannot be read to add to");
  }
  const QString absolute = QFileInfo(path).isAbsolute() ? path : QDir(QString::fromStdString(mapDir)).filePath(path);
  ReleaseAreaWritten written;
  try {
    written = writeReleaseArea(grid, initial_->elevation, polygon, thickness, base, absolute.toStdString());
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  // The key names the file relative to the map folder when it lies inside it, else absolutely.
  namespace fs = std::filesystem;
  const fs::path file = fs::path(absolute.toStdString()).lexically_normal();
  const fs::path rel = file.lexically_relative(fs::path(mapDir).lexically_normal());
  const bool inside = !rel.empty() && *rel.begin() != "..";
  const std::string value = inside ? rel.generic_string() : file.generic_string();
  doc_->setValue(includeKey, "1");
  doc_->setValue(mapKey, value);
  form_->setDocument(doc_.get());
  const ValidationResult r = validateDocument(*doc_);
  form_->showErrors(r);
  log_->append(QString("release area: %1 cells (%2 m², polygon %3 m²) at %4 m, %5 m³ in the map; written to %6; %7=%8")
                   .arg(written.cells)
                   .arg(written.area, 0, 'f', 1)
                   .arg(written.polygonArea, 0, 'f', 1)
                   .arg(thickness)
                   .arg(written.volume, 0, 'f', 1)
                   .arg(absolute)
                   .arg(QString::fromStdString(mapKey))
                   .arg(QString::fromStdString(value)));
  if (r.ok()) {
    showTerrainOf(*r.config);
    layers_->selectLayer(water ? "initial water height" : "initial solid height");
  }
  updateActions();
  return {};
}

void MainWindow::probeCell(int i, int j) {
  probeI_ = i;
  probeJ_ = j;
  probedLayer_.clear();
  refreshProbes(true);
}

void MainWindow::probeProfile(const std::vector<MapPoint>& line) {
  profileLine_ = line;
  refreshProbes(false);
}

void MainWindow::refreshProbes(bool rereadSeries) {
  const Grid* g = nullptr;
  const std::vector<float>* z = nullptr;
  const std::vector<sim::GridLayerInfo>* catalogue = nullptr;
  if (!sceneOnScreen(g, z, catalogue)) return;
  const QString layer = layers_->layer();
  const std::string name = layer.toStdString();
  QString unit = "-";
  for (const auto& info : *catalogue)
    if (info.name == name) unit = QString::fromStdString(info.unit);
  const auto shown = viewer_->snapshot();

  if (probeI_ >= 0 && probeI_ < g->nx && probeJ_ >= 0 && probeJ_ < g->ny) {
    const std::size_t k = g->index(probeI_, probeJ_);
    if (rereadSeries || layer != probedLayer_) {
      // The whole series: every frame of opened results, else what is on screen now (a live run
      // appends its next snapshots below).
      std::vector<QPointF> points;
      if (results_ && results_->frameCount() > 0) {
        points = results_->cellSeries(name, k);
      } else if (shown) {
        points.emplace_back(shown->time, layerValue(shown.get(), name, k));
      }
      const QString where = QString("cell (%1, %2), x %3 y %4")
                                .arg(probeI_)
                                .arg(probeJ_)
                                .arg(g->cellX(probeI_), 0, 'f', 1)
                                .arg(g->cellY(probeJ_), 0, 'f', 1);
      probe_->setPointSeries(where, layer, unit, points);
      probedLayer_ = layer;
    } else if (run_->viewFields() && shown) {
      probe_->appendPoint(shown->time, layerValue(shown.get(), name, k));
    }
  }

  if (profileLine_.size() >= 2) {
    std::vector<QPointF> values, terrain;
    for (const ProfileSample& s : sampleProfile(*g, profileLine_, 0.5 * g->dx)) {
      if (s.i < 0) continue;
      const std::size_t k = g->index(s.i, s.j);
      values.emplace_back(s.distance, layerValue(shown.get(), name, k));
      if (k < z->size()) terrain.emplace_back(s.distance, double((*z)[k]));
    }
    probe_->setProfile(layer, unit, values, terrain);
  }
}

}  // namespace talus::gui
