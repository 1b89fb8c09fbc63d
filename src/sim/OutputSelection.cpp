#include "sim/OutputSelection.hpp"

#include <cstdio>

namespace talus::sim {

io::RasterFormat outputFormat(const io::RunConfig& cfg) {
  if (cfg.isDefault("Output Format") && !cfg.isDefault("Output GeoTIFF format"))
    return cfg.flag("Output GeoTIFF format") ? io::RasterFormat::GeoTiff : io::RasterFormat::PCRaster;
  return cfg.choice("Output Format") == "pcraster" ? io::RasterFormat::PCRaster : io::RasterFormat::GeoTiff;
}

SeriesSelection seriesSelection(const io::RunConfig& cfg) {
  SeriesSelection s;
  s.reportEvery = cfg.integer("Report every");
  s.lisemNames = cfg.choice("Series Names") == "openlisem";
  const bool lisem = cfg.isDefault("Report Series") && !cfg.isDefault("Output timeseries");
  if (!lisem) {
    s.any = cfg.flag("Report Series");
    return s;
  }
  // OpenLISEM: nothing unless Output timeseries is 1, then each variable its switch selects.
  s.any = cfg.flag("Output timeseries");
  s.hf = cfg.flag("Output timeseries of H");
  s.vf = cfg.flag("Output timeseries of V");
  s.hs = cfg.flag("Output timeseries of HS");
  s.vs = cfg.flag("Output timeseries of VS");
  s.sf = cfg.flag("Output timeseries of SFRAC");
  s.ht = cfg.flag("Output timeseries of HT (total height)");
  s.vt = cfg.flag("Output timeseries of HT (total averaged velocity)");
  return s;
}

std::string seriesName(const SeriesSelection& s, const std::string& prefix, int index) {
  char text[64];
  if (!s.lisemNames) {
    std::snprintf(text, sizeof text, "series/%s_%04d", prefix.c_str(), index);
    return text;
  }
  // OpenLISEM's WriteMapSeries (lisem/io/iogdal.h): the name padded with zeros to 7 characters, then
  // the step as 4 digits with a dot after the first (PCRaster's 8.3 series names).
  const long long step = static_cast<long long>(index) * s.reportEvery;
  std::string name = (prefix + "00000000").substr(0, 7);
  char digits[32];
  std::snprintf(digits, sizeof digits, "%04lld", step);
  std::string d = digits;
  d.insert(1, ".");
  return name + d;
}

}  // namespace talus::sim
