#include "core/MapGeometry.hpp"

#include <algorithm>
#include <cmath>

namespace talus {

double polygonArea(const std::vector<MapPoint>& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return 0.0;
  double twice = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const MapPoint& a = polygon[k];
    const MapPoint& b = polygon[(k + 1) % n];
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * std::fabs(twice);
}

std::vector<uint8_t> cellsInsidePolygon(const Grid& grid, const std::vector<MapPoint>& polygon) {
  std::vector<uint8_t> inside(grid.cells(), 0);
  const std::size_t n = polygon.size();
  if (n < 3) return inside;
  std::vector<double> crossings;
  for (int j = 0; j < grid.ny; ++j) {
    // One scanline through the row's centres: the x where each edge crosses it, by the half-open
    // rule (an edge counts when one end is above the line and the other at or below it), which is
    // the even-odd point test of every centre on the row at once.
    const double y = grid.cellY(j);
    crossings.clear();
    for (std::size_t k = 0; k < n; ++k) {
      // Each edge from its lower end, so an edge shared by two polygons gives both the same x.
      MapPoint a = polygon[k], b = polygon[(k + 1) % n];
      if (a.y > b.y) std::swap(a, b);
      if ((a.y > y) != (b.y > y)) crossings.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    std::sort(crossings.begin(), crossings.end());
    // Centres at or right of one crossing and strictly left of the next are inside. The first and
    // the last such column come from the division, then are moved by the exact comparison, so a
    // centre on a crossing is decided by the same rule whatever the division's rounding.
    for (std::size_t c = 0; c + 1 < crossings.size(); c += 2) {
      const double x0 = crossings[c], x1 = crossings[c + 1];
      auto column = [&](double x) {
        const double f = std::ceil((x - grid.geoTransform[0]) / grid.dx - 0.5);
        return int(std::min(double(grid.nx), std::max(0.0, f)));
      };
      int first = column(x0), end = column(x1);  // [first, end)
      while (first > 0 && grid.cellX(first - 1) >= x0) --first;
      while (first < grid.nx && grid.cellX(first) < x0) ++first;
      while (end > 0 && grid.cellX(end - 1) >= x1) --end;
      while (end < grid.nx && grid.cellX(end) < x1) ++end;
      for (int i = first; i < end; ++i) inside[grid.index(i, j)] = 1;
    }
  }
  return inside;
}

bool cellOfPoint(const Grid& grid, MapPoint p, int& i, int& j) {
  const double fi = (p.x - grid.geoTransform[0]) / grid.geoTransform[1];
  const double fj = (p.y - grid.geoTransform[3]) / grid.geoTransform[5];
  if (!(fi >= 0 && fj >= 0 && fi < grid.nx && fj < grid.ny)) {
    i = j = -1;
    return false;
  }
  i = int(fi);
  j = int(fj);
  return true;
}

std::vector<ProfileSample> sampleProfile(const Grid& grid, const std::vector<MapPoint>& line, double spacing) {
  std::vector<ProfileSample> out;
  if (line.size() < 2 || !(spacing > 0)) return out;
  auto add = [&](double distance, MapPoint p) {
    ProfileSample s;
    s.distance = distance;
    s.point = p;
    cellOfPoint(grid, p, s.i, s.j);
    out.push_back(s);
  };
  double start = 0;  // distance of the current segment's first vertex
  double next = 0;   // distance of the next sample
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const MapPoint a = line[k], b = line[k + 1];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    // Samples on this segment: next, next + spacing, ... while before its end.
    for (; next < start + length; next = double(out.size()) * spacing) {
      const double f = length > 0 ? (next - start) / length : 0.0;
      add(next, {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)});
    }
    start += length;
  }
  if (out.empty() || out.back().distance < start) add(start, line.back());
  return out;
}

}  // namespace talus
