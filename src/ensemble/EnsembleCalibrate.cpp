// Ranking of members against observations (see EnsembleCalibrate.hpp for the measures).
#include "ensemble/EnsembleCalibrate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/Error.hpp"
#include "core/FileWrite.hpp"
#include "ensemble/EnsembleRun.hpp"
#include "ensemble/Json.hpp"
#include "ensemble/Sampling.hpp"

namespace talus::ensemble {
namespace {

std::string num(double v, int digits = 10) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace

MemberFit fitMask(const std::vector<unsigned char>& modelled, const std::vector<unsigned char>& observed,
                  const std::vector<unsigned char>& domain) {
  MemberFit f;
  for (std::size_t k = 0; k < domain.size(); ++k) {
    if (!domain[k]) continue;
    const bool m = modelled[k] != 0, o = observed[k] != 0;
    if (m && o) ++f.tp;
    else if (m) ++f.fp;
    else if (o) ++f.fn;
    else ++f.tn;
  }
  const auto d = [](long long a, long long b) { return b > 0 ? static_cast<double>(a) / static_cast<double>(b) : 0.0; };
  f.jaccard = d(f.tp, f.tp + f.fp + f.fn);
  f.tpr = d(f.tp, f.tp + f.fn);
  f.fpr = d(f.fp, f.fp + f.tn);
  f.d2pc = std::sqrt((1 - f.tpr) * (1 - f.tpr) + f.fpr * f.fpr);
  f.auroc = (1 + f.tpr - f.fpr) / 2;
  f.foc = d(f.tp + f.fp, f.tp + f.fn);
  return f;
}

std::vector<unsigned char> agreementMap(const std::vector<unsigned char>& modelled,
                                        const std::vector<unsigned char>& observed,
                                        const std::vector<unsigned char>& domain) {
  std::vector<unsigned char> a(domain.size(), 255);
  for (std::size_t k = 0; k < domain.size(); ++k)
    if (domain[k]) a[k] = static_cast<unsigned char>((modelled[k] ? 1 : 0) + (observed[k] ? 2 : 0));
  return a;
}

std::vector<MemberFit> calibrate(const EnsembleSpec& spec, const Raster& dem, const std::vector<MemberMaps>& maps,
                                 const std::vector<MemberFigures>& figures, const std::string& dir,
                                 io::RasterFormat format) {
  const std::size_t cells = dem.grid.cells();
  std::vector<unsigned char> domain(dem.valid.begin(), dem.valid.end()), observed(cells, 0);
  const bool haveMap = !spec.observedMap.empty();
  if (haveMap) {
    const Raster obs = io::readRaster(spec.observedMap);
    io::requireSameGrid(dem, "DEM", obs, spec.observedMap);
    for (std::size_t k = 0; k < cells; ++k) {
      domain[k] = dem.valid[k] && obs.valid[k];  // observed nodata: unknown, not compared
      observed[k] = domain[k] && obs.values[k] > spec.observedThreshold;
    }
  }
  auto modelledMask = [&](const MemberMaps& m) {
    std::vector<unsigned char> mask(cells, 0);
    for (std::size_t k = 0; k < cells; ++k) mask[k] = domain[k] && m.hmax[k] > spec.affectedThreshold;
    return mask;
  };
  std::vector<MemberFit> fits;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    MemberFit f = haveMap ? fitMask(modelledMask(maps[i]), observed, domain) : MemberFit{};
    f.member = figures[i].member;
    if (spec.hasObservedRunout && figures[i].hasRunout) {
      f.hasDistance = true;
      f.runoutDistanceM = std::hypot(figures[i].runoutX - spec.observedX, figures[i].runoutY - spec.observedY);
    }
    fits.push_back(f);
  }
  // Rank: the better measure first, ties by member index (stable over the index-ordered list).
  const double inf = std::numeric_limits<double>::infinity();
  auto key = [&](const MemberFit& f) {
    if (spec.rankBy == "jaccard") return -f.jaccard;
    if (spec.rankBy == "d2pc") return f.d2pc;
    return f.hasDistance ? f.runoutDistanceM : inf;
  };
  std::stable_sort(fits.begin(), fits.end(), [&](const MemberFit& a, const MemberFit& b) { return key(a) < key(b); });

  std::ostringstream csv;
  csv << "rank,member,name";
  for (const Parameter& p : spec.parameters) csv << "," << p.key;
  csv << ",tp,fp,fn,tn,jaccard,tpr,fpr,d2pc,auroc,foc,runout_distance_m\n";
  for (std::size_t r = 0; r < fits.size(); ++r) {
    const MemberFit& f = fits[r];
    csv << r + 1 << "," << f.member << "," << memberName(f.member);
    for (double v : memberValues(spec, f.member)) csv << "," << num(v, 17);
    csv << "," << f.tp << "," << f.fp << "," << f.fn << "," << f.tn << "," << num(f.jaccard) << "," << num(f.tpr)
        << "," << num(f.fpr) << "," << num(f.d2pc) << "," << num(f.auroc) << "," << num(f.foc) << ","
        << (f.hasDistance ? num(f.runoutDistanceM) : "") << "\n";
  }
  writeFileAtomically(dir + "/calibration.csv", csv.str());

  const MemberFit& best = fits.front();
  std::ostringstream js;
  js << "{\n  \"rank_by\": " << jsonQuote(spec.rankBy) << ",\n  \"best_member\": " << best.member
     << ",\n  \"name\": " << jsonQuote(memberName(best.member)) << ",\n  \"parameters\": {";
  const std::vector<double> values = memberValues(spec, best.member);
  for (std::size_t k = 0; k < values.size(); ++k)
    js << (k ? ", " : "") << jsonQuote(spec.parameters[k].key) << ": " << num(values[k], 17);
  js << "},\n";
  if (haveMap)
    js << "  \"jaccard\": " << num(best.jaccard) << ",\n  \"tpr\": " << num(best.tpr) << ",\n  \"fpr\": "
       << num(best.fpr) << ",\n  \"d2pc\": " << num(best.d2pc) << ",\n  \"auroc\": " << num(best.auroc)
       << ",\n  \"foc\": " << num(best.foc) << ",\n";
  js << "  \"runout_distance_m\": " << (best.hasDistance ? num(best.runoutDistanceM) : "null") << "\n}\n";
  writeFileAtomically(dir + "/calibration.json", js.str());

  if (haveMap) {
    std::size_t bestIndex = 0;
    while (figures[bestIndex].member != best.member) ++bestIndex;
    const std::vector<unsigned char> codes = agreementMap(modelledMask(maps[bestIndex]), observed, domain);
    Raster r(dem.grid, 0.0);
    r.nodata = 255;
    for (std::size_t k = 0; k < cells; ++k) {
      r.valid[k] = codes[k] != 255;
      r.values[k] = codes[k];
    }
    io::writeRaster(dir + "/agreement" + (format == io::RasterFormat::PCRaster ? ".map" : ".tif"), r, format);
  }
  return fits;
}

}  // namespace talus::ensemble
