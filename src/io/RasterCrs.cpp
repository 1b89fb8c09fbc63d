#include "io/RasterCrs.hpp"

#include <ogr_spatialref.h>

#include <cmath>

namespace talus::io::detail {
namespace {

/// A unit factor within a part per billion of 1 is the metre (WKT writers round it differently).
double snapMetre(double f) { return std::fabs(f - 1.0) < 1e-9 ? 1.0 : f; }

}  // namespace

CrsUnits inspectCrs(const std::string& wkt) {
  CrsUnits u;
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) {
    u.none = true;
    return u;
  }
  const char* name = srs.GetName();
  u.description = name != nullptr && *name != '\0' ? name : "unnamed CRS";
  // The authority code of the whole CRS: for a compound CRS, of the compound, else of its root.
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority != nullptr && code != nullptr) u.description += std::string(", ") + authority + ":" + code;
  if (srs.IsGeographic()) {
    u.geographic = true;
    const char* unit = nullptr;
    srs.GetAngularUnits(&unit);
    u.horizontalUnit = unit != nullptr ? unit : "degree";
    return u;
  }
  const char* unit = nullptr;
  u.horizontalToMetre = snapMetre(srs.GetLinearUnits(&unit));
  if (unit != nullptr) u.horizontalUnit = unit;
  u.verticalUnit = u.horizontalUnit;
  u.verticalToMetre = u.horizontalToMetre;
  if (srs.IsCompound()) {
    const char* vunit = nullptr;
    const double f = srs.GetTargetLinearUnits("VERT_CS", &vunit);
    if (f > 0) {
      u.verticalToMetre = snapMetre(f);
      u.verticalUnit = vunit != nullptr ? vunit : "unnamed unit";
    }
  }
  return u;
}

}  // namespace talus::io::detail
