// Merged maps and member table of an ensemble (see EnsembleMerge.hpp).
#include "ensemble/EnsembleMerge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/Error.hpp"
#include "core/FileWrite.hpp"
#include "ensemble/EnsembleCalibrate.hpp"
#include "ensemble/EnsembleRun.hpp"
#include "ensemble/MemberOutputs.hpp"
#include "ensemble/Sampling.hpp"
#include "io/RasterIO.hpp"
#include "sim/Scene.hpp"

namespace talus::ensemble {
namespace fs = std::filesystem;

namespace {

std::string num(double v, int digits = 10) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

/// Writes one merged map of per-cell values; cells outside the DEM's domain are nodata.
class MapSink {
 public:
  MapSink(const Raster& dem, std::string dir, io::RasterFormat format, MergeReport& report)
      : dem_(dem), dir_(std::move(dir)), format_(format), report_(report) {}
  void write(const std::string& name, const std::vector<double>& values) {
    Raster r(dem_.grid, 0.0);
    r.valid = dem_.valid;
    for (std::size_t k = 0; k < values.size(); ++k) r.values[k] = dem_.valid[k] ? values[k] : r.nodata;
    const std::string path = dir_ + "/" + name + (format_ == io::RasterFormat::PCRaster ? ".map" : ".tif");
    io::writeRaster(path, r, format_);
    report_.files.push_back(path);
  }

 private:
  const Raster& dem_;
  std::string dir_;
  io::RasterFormat format_;
  MergeReport& report_;
};

/// Fraction of members whose value passes `test`, per cell (count / n, exact in any order).
template <class Test>
std::vector<double> probability(const std::vector<MemberMaps>& maps, std::size_t cells,
                                std::vector<float> MemberMaps::*field, Test test) {
  std::vector<double> p(cells, 0.0);
  for (std::size_t k = 0; k < cells; ++k) {
    long long count = 0;
    for (const MemberMaps& m : maps) count += test((m.*field)[k]) ? 1 : 0;
    p[k] = static_cast<double>(count) / static_cast<double>(maps.size());
  }
  return p;
}

std::vector<double> percentileMap(const std::vector<MemberMaps>& maps, std::size_t cells,
                                  std::vector<float> MemberMaps::*field, double q) {
  std::vector<double> out(cells, 0.0);
  std::vector<float> column(maps.size());
  for (std::size_t k = 0; k < cells; ++k) {
    for (std::size_t i = 0; i < maps.size(); ++i) column[i] = (maps[i].*field)[k];
    std::sort(column.begin(), column.end());
    out[k] = percentile(column, q);
  }
  return out;
}

}  // namespace

double percentile(const std::vector<float>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q / 100.0;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  if (lo + 1 >= sorted.size()) return sorted.back();
  return sorted[lo] + (h - static_cast<double>(lo)) * (static_cast<double>(sorted[lo + 1]) - sorted[lo]);
}

std::string thresholdName(double t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", t);
  return buf;
}

MergeReport mergeEnsemble(const EnsembleSpec& spec, const io::RunConfig& base) {
  std::vector<std::string> missing;
  for (long long m = 0; m < spec.members; ++m)
    if (!memberComplete(spec, m)) missing.push_back(memberName(m));
  if (!missing.empty()) {
    std::string list;
    for (std::size_t k = 0; k < missing.size() && k < 20; ++k) list += (k ? ", " : "") + missing[k];
    if (missing.size() > 20) list += ", ...";
    throw InputError("cannot merge '" + spec.outputDir + "': " + std::to_string(missing.size()) + " of " +
                     std::to_string(spec.members) + " members are not complete (" + list +
                     "); run `talus ensemble " + spec.file + "` to finish them");
  }
  // The DEM as the runs saw it (unit conversion included) gives the grid, georeference and mask.
  const sim::Scene scene = sim::loadScene(base);
  const Raster& dem = scene.dem;
  const std::size_t cells = dem.grid.cells();
  std::vector<MemberMaps> maps;
  std::vector<MemberFigures> figures;
  for (long long m = 0; m < spec.members; ++m) {
    checkMemberRecord(spec, m, memberAssignments(spec, base, m));
    const std::string dir = memberDir(spec, m);
    maps.push_back(readMemberMaps(dir, dem, scene.format));
    figures.push_back(memberFigures(m, dir, maps.back(), dem, scene.startTime, spec.affectedThreshold));
  }
  MergeReport report;
  report.members = spec.members;
  const std::string dir = (fs::path(spec.outputDir) / "merged").string();
  fs::create_directories(dir);
  MapSink sink(dem, dir, scene.format, report);
  for (double t : spec.thicknessThresholds)
    sink.write("p_hmax_gt_" + thresholdName(t), probability(maps, cells, &MemberMaps::hmax, [t](float v) { return v > t; }));
  for (double t : spec.speedThresholds)
    sink.write("p_vmax_gt_" + thresholdName(t), probability(maps, cells, &MemberMaps::vmax, [t](float v) { return v > t; }));
  for (double t : spec.arrivalTimes)
    sink.write("p_arrival_le_" + thresholdName(t),
               probability(maps, cells, &MemberMaps::arrival, [t](float v) { return v >= 0 && v <= t; }));
  for (double q : spec.percentiles) {
    sink.write("hmax_p" + thresholdName(q), percentileMap(maps, cells, &MemberMaps::hmax, q));
    sink.write("vmax_p" + thresholdName(q), percentileMap(maps, cells, &MemberMaps::vmax, q));
  }
  // The member table.
  std::ostringstream csv;
  csv << "member,name";
  for (const Parameter& p : spec.parameters) csv << "," << p.key;
  csv << ",status,area_m2,runout_m,runout_x,runout_y,volume_initial_m3,volume_final_m3\n";
  for (const MemberFigures& f : figures) {
    csv << f.member << "," << memberName(f.member);
    for (double v : memberValues(spec, f.member)) csv << "," << num(v, 17);
    csv << "," << f.status << "," << num(f.areaM2) << ",";
    if (f.hasRunout) csv << num(f.runoutM) << "," << num(f.runoutX, 12) << "," << num(f.runoutY, 12);
    else csv << ",,";
    csv << "," << num(f.volumeInitialM3) << "," << num(f.volumeFinalM3) << "\n";
  }
  writeFileAtomically(dir + "/members.csv", csv.str());
  report.files.push_back(dir + "/members.csv");
  if (!spec.rankBy.empty()) {
    const std::vector<MemberFit> fits = calibrate(spec, dem, maps, figures, dir, scene.format);
    report.files.push_back(dir + "/calibration.csv");
    report.files.push_back(dir + "/calibration.json");
    const MemberFit& b = fits.front();
    std::ostringstream line;
    line << "best member by " << spec.rankBy << ": " << memberName(b.member);
    const std::vector<double> values = memberValues(spec, b.member);
    for (std::size_t k = 0; k < values.size(); ++k) line << "  " << spec.parameters[k].key << "=" << num(values[k]);
    if (!spec.observedMap.empty()) line << "  (Jaccard " << num(b.jaccard, 4) << ", D2PC " << num(b.d2pc, 4) << ")";
    if (b.hasDistance) line << "  (runout " << num(b.runoutDistanceM, 4) << " m from the observed point)";
    report.best = line.str();
  }
  return report;
}

}  // namespace talus::ensemble
