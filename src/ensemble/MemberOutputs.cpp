// Reading one member's outputs and deriving its figures (see MemberOutputs.hpp).
#include "ensemble/MemberOutputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/Error.hpp"
#include "ensemble/Json.hpp"

namespace talus::ensemble {
namespace fs = std::filesystem;

namespace {

std::string readText(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError("cannot read '" + path + "'");
  std::string s;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, n);
  std::fclose(f);
  return s;
}

/// The map `name` of the member folder as floats (invalid cells: `outside`), or empty when absent.
std::vector<float> readMap(const std::string& dir, const std::string& name, const Raster& dem,
                           io::RasterFormat format, float outside, bool required) {
  const std::string path = dir + "/" + name + (format == io::RasterFormat::PCRaster ? ".map" : ".tif");
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (required) throw InputError("member map '" + path + "' is missing");
    return {};
  }
  const Raster r = io::readRaster(path);
  io::requireSameGrid(dem, "DEM", r, path);
  std::vector<float> v(r.values.size(), outside);
  for (std::size_t k = 0; k < v.size(); ++k)
    if (r.valid[k] && dem.valid[k]) v[k] = static_cast<float>(r.values[k]);
  return v;
}

}  // namespace

MemberMaps readMemberMaps(const std::string& dir, const Raster& dem, io::RasterFormat format) {
  MemberMaps m;
  m.hmax = readMap(dir, "htmax", dem, format, 0.0f, false);
  if (m.hmax.empty()) m.hmax = readMap(dir, "hfmax", dem, format, 0.0f, true);
  m.vmax = readMap(dir, "vfmax", dem, format, 0.0f, true);
  const std::vector<float> vs = readMap(dir, "vsmax", dem, format, 0.0f, false);
  for (std::size_t k = 0; k < vs.size(); ++k) m.vmax[k] = std::max(m.vmax[k], vs[k]);
  m.arrival = readMap(dir, "tarrival", dem, format, -1.0f, true);
  return m;
}

MemberFigures memberFigures(long long member, const std::string& dir, const MemberMaps& maps, const Raster& dem,
                            double startTime, double affectedThreshold) {
  MemberFigures f;
  f.member = member;
  const std::string summaryPath = dir + "/summary.json";
  const JsonValue s = JsonValue::parse(readText(summaryPath), summaryPath);
  const JsonValue* status = s.find("status");
  f.status = status && status->type() == JsonValue::Type::String ? status->string() : "unknown";
  if (const JsonValue* v = s.at({"volume", "initial_m3"})) f.volumeInitialM3 = v->number();
  if (const JsonValue* v = s.at({"volume", "final_m3"})) f.volumeFinalM3 = v->number();

  const Grid& g = dem.grid;
  const double cellArea = g.dx * g.dx;
  long long affected = 0;
  std::size_t source = g.cells();
  const auto start = static_cast<float>(startTime);
  for (std::size_t k = 0; k < g.cells(); ++k) {
    if (!dem.valid[k]) continue;
    if (maps.hmax[k] > affectedThreshold) ++affected;
    const bool release = maps.arrival[k] >= 0.0f && maps.arrival[k] <= start;
    if (release && (source == g.cells() || dem.values[k] > dem.values[source])) source = k;
  }
  f.areaM2 = static_cast<double>(affected) * cellArea;
  if (source == g.cells() || affected == 0) return f;
  auto world = [&](std::size_t k, double& x, double& y) {
    x = g.cellX(static_cast<int>(k % static_cast<std::size_t>(g.nx)));
    y = g.cellY(static_cast<int>(k / static_cast<std::size_t>(g.nx)));
  };
  double sx = 0, sy = 0;
  world(source, sx, sy);
  double best = -1;
  for (std::size_t k = 0; k < g.cells(); ++k) {
    if (!dem.valid[k] || !(maps.hmax[k] > affectedThreshold)) continue;
    double x = 0, y = 0;
    world(k, x, y);
    const double d = std::hypot(x - sx, y - sy);
    if (d > best) {
      best = d;
      f.runoutX = x;
      f.runoutY = y;
    }
  }
  f.hasRunout = true;
  f.runoutM = best;
  return f;
}

}  // namespace talus::ensemble
