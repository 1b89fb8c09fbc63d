// Host reference of the particle-grid transfers (see ParticleGridReference.hpp).
#include "support/ParticleGridReference.hpp"

#include <algorithm>
#include <cmath>

namespace talus::test {

double referenceBSpline(double d) {
  const double a = std::fabs(d);
  if (a < 1) return 2.0 / 3.0 - a * a + 0.5 * a * a * a;
  if (a < 2) return (2 - a) * (2 - a) * (2 - a) / 6.0;
  return 0;
}

std::vector<std::pair<std::size_t, double>> referenceCellWeights(const Grid& g, double x, double y) {
  // Every cell centre within 2 dx, found from the nearest centre; more candidates than needed are harmless.
  auto axis = [&](double p, int n) {
    std::vector<std::pair<int, double>> w;
    const double near = std::floor(p / g.dx);
    for (int s = -3; s <= 3; ++s) {
      const double k = near + s;  // virtual cell, may lie beyond the raster
      const double wk = referenceBSpline((p - (k + 0.5) * g.dx) / g.dx);
      if (wk == 0) continue;
      const int folded = static_cast<int>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
      auto it = std::find_if(w.begin(), w.end(), [&](const auto& e) { return e.first == folded; });
      if (it == w.end()) w.emplace_back(folded, wk);
      else it->second += wk;
    }
    return w;
  };
  std::vector<std::pair<std::size_t, double>> out;
  for (const auto& [j, wy] : axis(y, g.ny))
    for (const auto& [i, wx] : axis(x, g.nx)) out.emplace_back(g.index(i, j), wx * wy);
  return out;
}

namespace {

bool used(const std::vector<char>& use, std::size_t p) { return use.empty() || use[p]; }

}  // namespace

ReferenceConfined referenceConfinedToGrid(const Grid& g, const std::vector<double>& x, const std::vector<double>& y,
                                          const std::vector<double>& volume, const std::vector<double>& mass,
                                          const std::vector<double>& vx, const std::vector<double>& vy,
                                          const std::vector<char>& use) {
  ReferenceConfined r;
  r.thickness.assign(g.cells(), 0.0);
  r.mass.assign(g.cells(), 0.0);
  r.momentumX.assign(g.cells(), 0.0);
  r.momentumY.assign(g.cells(), 0.0);
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (!used(use, p)) continue;
    for (const auto& [c, w] : referenceCellWeights(g, x[p], y[p])) {
      r.thickness[c] += w * volume[p] / (g.dx * g.dx);
      r.mass[c] += w * mass[p];
      r.momentumX[c] += w * mass[p] * vx[p];
      r.momentumY[c] += w * mass[p] * vy[p];
    }
  }
  return r;
}

std::vector<double> referenceFieldToGrid(const Grid& g, const std::vector<double>& x, const std::vector<double>& y,
                                         const std::vector<double>& q, const std::vector<double>& f, bool mean,
                                         const std::vector<char>& use) {
  std::vector<double> sq(g.cells(), 0.0), sqf(g.cells(), 0.0);
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (!used(use, p)) continue;
    for (const auto& [c, w] : referenceCellWeights(g, x[p], y[p])) {
      sq[c] += w * q[p];
      sqf[c] += w * q[p] * f[p];
    }
  }
  if (mean)
    for (std::size_t c = 0; c < sq.size(); ++c) sqf[c] = sq[c] != 0 ? sqf[c] / sq[c] : 0.0;
  return sqf;
}

std::vector<double> referenceGridToParticles(const Grid& g, const std::vector<double>& field,
                                             const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> out(x.size(), 0.0);
  for (std::size_t p = 0; p < x.size(); ++p)
    for (const auto& [c, w] : referenceCellWeights(g, x[p], y[p])) out[p] += w * field[c];
  return out;
}

}  // namespace talus::test
