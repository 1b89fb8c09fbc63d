#include "particles/ParticleBedSurface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus::particles {
namespace {

/// The cell-centre elevations of the particles' bed surface (particle_common.cl, bed_gradient):
/// the DEM's, and in each nodata cell the mean of its nearest domain cells (rings of 4-neighbours, filled
/// outwards), so the surface near a nodata hole or edge continues flat instead of falling to a placeholder.
std::vector<double> surfaceElevations(const Grid& g, const std::vector<double>& bed, const std::vector<uint8_t>& mask) {
  std::vector<double> z(g.cells(), 0.0);
  std::vector<uint8_t> known(g.cells(), 0);
  std::vector<std::size_t> front;
  for (std::size_t k = 0; k < g.cells(); ++k)
    if (mask[k]) z[k] = bed[k], known[k] = 1, front.push_back(k);
  const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
  while (!front.empty()) {
    std::vector<std::size_t> next;
    for (std::size_t k : front) {
      const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
      for (int d = 0; d < 4; ++d) {
        const int a = i + di[d], b = j + dj[d];
        if (a < 0 || b < 0 || a >= g.nx || b >= g.ny || known[g.index(a, b)]) continue;
        known[g.index(a, b)] = 2;  // in this ring: its value is the mean of its known neighbours
        next.push_back(g.index(a, b));
      }
    }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    for (std::size_t k : next) {
      const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
      double sum = 0;
      int count = 0;
      for (int d = 0; d < 4; ++d) {
        const int a = i + di[d], b = j + dj[d];
        if (a >= 0 && b >= 0 && a < g.nx && b < g.ny && known[g.index(a, b)] == 1) sum += z[g.index(a, b)], ++count;
      }
      z[k] = sum / count;
    }
    for (std::size_t k : next) known[k] = 1;
    front.swap(next);
  }
  return z;
}

}  // namespace

ParticleBedSurface::ParticleBedSurface(const Grid& grid, const std::vector<double>& bed, const std::vector<uint8_t>& mask,
                                       const std::vector<double>& slopeX, const std::vector<double>& slopeY,
                                       bool edgeWalls, bool nodataWalls)
    : grid_(grid), mask_(mask), bed_(bed), edgeWalls_(edgeWalls), nodataWalls_(nodataWalls) {
  const std::size_t n = grid.cells();
  for (std::size_t k = 0; k < n; ++k)
    if (!mask[k]) bed_[k] = 0.0;  // never read: a nodata face is a wall or an outlet (face_rise)
  slope_ = slopeX;
  slope_.insert(slope_.end(), slopeY.begin(), slopeY.end());
  // The patches in double: a plane then has the same gradient to the last bit everywhere, and the
  // kernels take no difference of two large elevations in float.
  z_ = surfaceElevations(grid, bed, mask);
  const std::vector<double>& z = z_;
  patch_.assign(3 * n, 0.0);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      const bool east = i + 1 < grid.nx, north = j + 1 < grid.ny;
      const double b00 = z[k], b10 = east ? z[grid.index(i + 1, j)] : b00, b01 = north ? z[grid.index(i, j + 1)] : b00;
      const double b11 = east && north ? z[grid.index(i + 1, j + 1)] : east ? b10 : b01;
      patch_[k] = (b10 - b00) / grid.dx;
      patch_[n + k] = (b01 - b00) / grid.dx;
      patch_[2 * n + k] = (b11 - b10 - b01 + b00) / grid.dx;
    }
}

std::array<double, 2> ParticleBedSurface::gradient(double x, double y) const {
  const std::size_t n = grid_.cells();
  const double fx = x / grid_.dx - 0.5, fy = y / grid_.dx - 0.5;
  const int i0 = std::clamp(static_cast<int>(std::floor(fx)), 0, std::max(grid_.nx - 2, 0));
  const int j0 = std::clamp(static_cast<int>(std::floor(fy)), 0, std::max(grid_.ny - 2, 0));
  const std::size_t k = grid_.index(i0, j0);
  const double t = patch_[2 * n + k];
  return {patch_[k] + t * (fy - j0), patch_[n + k] + t * (fx - i0)};
}

double ParticleBedSurface::faceRise(int here, int a, int b, int axis, int d) const {
  const double inf = std::numeric_limits<double>::infinity();
  if (a < 0 || b < 0 || a >= grid_.nx || b >= grid_.ny) return edgeWalls_ ? inf : 0.0;
  const std::size_t nb = grid_.index(a, b), n = grid_.cells();
  if (!mask_[nb]) return nodataWalls_ ? inf : 0.0;
  const double hw = 0.5 * grid_.dx * d;
  return (bed_[nb] - hw * slope_[axis * n + nb]) - (bed_[here] + hw * slope_[axis * n + here]);
}

ParticleBedSurface::WalledPatch ParticleBedSurface::walledPatch(double x, double y, double column) const {
  WalledPatch w;
  if (grid_.nx < 2 || grid_.ny < 2) return w;
  const double dx = grid_.dx;
  const double fx = x / dx - 0.5, fy = y / dx - 0.5;
  const int i0 = std::clamp(static_cast<int>(std::floor(fx)), 0, grid_.nx - 2);
  const int j0 = std::clamp(static_cast<int>(std::floor(fy)), 0, grid_.ny - 2);
  w.u = fx - i0;
  w.v = fy - j0;
  const int ci = std::clamp(static_cast<int>(std::floor(x / dx)), i0, i0 + 1);
  const int cj = std::clamp(static_cast<int>(std::floor(y / dx)), j0, j0 + 1);
  const int oi = ci == i0 ? i0 + 1 : i0, oj = cj == j0 ? j0 + 1 : j0;
  const int sx = oi - ci, sy = oj - cj;
  const int own = static_cast<int>(grid_.index(ci, cj)), acrossX = static_cast<int>(grid_.index(oi, cj)),
            acrossY = static_cast<int>(grid_.index(ci, oj));
  const bool wallX = faceRise(own, oi, cj, 0, sx) > column, wallY = faceRise(own, ci, oj, 1, sy) > column;
  const bool wallD = !wallX && !wallY &&
                     ((mask_[acrossX] && faceRise(acrossX, oi, oj, 1, sy) > column) ||
                      (mask_[acrossY] && faceRise(acrossY, oi, oj, 0, sx) > column));
  w.walls = wallX || wallY || wallD;
  if (!w.walls) return w;
  const std::size_t n = grid_.cells(), k = grid_.index(i0, j0);
  const double ex = patch_[k] * dx, ey = patch_[n + k] * dx, tw = patch_[2 * n + k] * dx;
  const double c[4] = {0.0, ex, ey, ex + ey + tw};
  const int a = ci - i0, b = cj - j0;
  const int kOwn = a + 2 * b, kX = (1 - a) + 2 * b, kY = a + 2 * (1 - b), kD = (1 - a) + 2 * (1 - b);
  const double gx = sx * dx * slope_[own], gy = sy * dx * slope_[n + own];
  const double nX = wallX ? c[kOwn] + gx : c[kX], nY = wallY ? c[kOwn] + gy : c[kY];
  const double nD = wallX && wallY ? c[kOwn] + gx + gy : wallX ? c[kY] + gx : wallY ? c[kX] + gy : c[kX] + c[kY] - c[kOwn];
  w.d[kX] = nX - c[kX];
  w.d[kY] = nY - c[kY];
  w.d[kD] = nD - c[kD];
  return w;
}

std::array<double, 2> ParticleBedSurface::walledGradient(double x, double y, double column) const {
  const std::array<double, 2> plain = gradient(x, y);
  const WalledPatch w = walledPatch(x, y, column);
  if (!w.walls) return plain;
  return {plain[0] + ((w.d[1] - w.d[0]) * (1 - w.v) + (w.d[3] - w.d[2]) * w.v) / grid_.dx,
          plain[1] + ((w.d[2] - w.d[0]) * (1 - w.u) + (w.d[3] - w.d[1]) * w.u) / grid_.dx};
}

double ParticleBedSurface::walledOffset(double x, double y, double column) const {
  const WalledPatch w = walledPatch(x, y, column);
  const double u = w.u, v = w.v;
  return w.d[0] * (1 - u) * (1 - v) + w.d[1] * u * (1 - v) + w.d[2] * (1 - u) * v + w.d[3] * u * v;
}

double ParticleBedSurface::elevation(double x, double y) const {
  const std::size_t n = grid_.cells();
  const double fx = x / grid_.dx - 0.5, fy = y / grid_.dx - 0.5;
  const int i0 = std::clamp(static_cast<int>(std::floor(fx)), 0, std::max(grid_.nx - 2, 0));
  const int j0 = std::clamp(static_cast<int>(std::floor(fy)), 0, std::max(grid_.ny - 2, 0));
  const std::size_t k = grid_.index(i0, j0);
  const double u = fx - i0, v = fy - j0;
  return z_[k] + grid_.dx * (patch_[k] * u + patch_[n + k] * v + patch_[2 * n + k] * u * v);
}

}  // namespace talus::particles
