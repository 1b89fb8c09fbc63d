#include "view/InitialScene.hpp"

#include <cmath>
#include <exception>

#include "io/RasterIO.hpp"

namespace talus::gui {

namespace {
/// The initial maps and the flag that switches each on.
struct InitialMap {
  const char* include;
  const char* key;
  const char* name;
  const char* label;
};
constexpr InitialMap kInitialMaps[] = {
    {"Include Initial Water", "Initial Fluid Height", "initial water height", "initial water height (Initial Fluid Height)"},
    {"Include Initial Solids", "Initial Solid Height", "initial solid height", "initial solid thickness (Initial Solid Height)"},
};

/// The map's values on `grid` (times its multiplier; NaN where the DEM or the map has none).
std::vector<float> mapValues(const io::MapValue& m, const Grid& grid, const std::vector<float>& dem, const std::string& demPath) {
  std::vector<float> v(grid.cells(), static_cast<float>(m.constant * m.multiplier));
  if (m.isFile) {
    const Raster r = io::readRaster(m.file);
    Raster reference;
    reference.grid = grid;
    io::requireSameGrid(reference, demPath, r, m.file);
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = r.valid[k] ? static_cast<float>(r.values[k] * m.multiplier) : NAN;
  }
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!std::isfinite(dem[k])) v[k] = NAN;
  return v;
}
}  // namespace

InitialScene InitialScene::read(const io::RunConfig& config) {
  InitialScene s;
  const io::MapValue dem = config.map("DEM");
  if (dem.isFile) {
    const Raster r = io::readRaster(dem.file);
    s.grid = r.grid;
    s.elevation.resize(r.values.size());
    for (std::size_t k = 0; k < r.values.size(); ++k)
      s.elevation[k] = r.valid[k] ? static_cast<float>(r.values[k] * dem.multiplier) : NAN;
  }
  s.snapshot = std::make_shared<sim::ViewSnapshot>();
  s.snapshot->grid = s.grid;
  if (s.elevation.empty()) return s;
  for (const InitialMap& m : kInitialMaps) {
    if (!config.flag(m.include)) continue;
    try {
      s.snapshot->layers.push_back(mapValues(config.map(m.key), s.grid, s.elevation, dem.file));
    } catch (const std::exception& e) {
      s.warnings.push_back(std::string("cannot show ") + m.key + ": " + e.what());
      continue;
    }
    s.snapshot->layerNames.push_back(m.name);
    s.layers.push_back({m.name, m.label, "m", true});
  }
  return s;
}

}  // namespace talus::gui
