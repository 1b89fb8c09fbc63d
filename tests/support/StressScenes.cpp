// Randomised scenes and the invariant checker of the numerical stress suite; see StressScenes.hpp.
#include "support/StressScenes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/Constants.hpp"
#include "flow/SlopeGravity.hpp"
#include "support/FlowScene.hpp"
#include "support/GranularAnalytic.hpp"
#include "support/TestDevice.hpp"

namespace talus::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Draws from std::mt19937_64 with integer arithmetic on its raw output only (portable: the engine
/// is fully specified by the standard, the distributions are not).
class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  double unit() { return static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double a, double b) { return a + (b - a) * unit(); }
  /// Log-uniform in [a, b] (a, b > 0).
  double logUniform(double a, double b) { return a * std::exp(std::log(b / a) * unit()); }
  /// Integer in [a, b] (the modulo bias of 64 bits over ranges below 2^16 is irrelevant here).
  int integer(int a, int b) { return a + static_cast<int>(engine_() % static_cast<uint64_t>(b - a + 1)); }
  bool chance(double p) { return unit() < p; }

 private:
  std::mt19937_64 engine_;
};

/// splitmix64 finaliser: a bijective mix of a 64-bit value.
uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

const char* limiterName(flow::Limiter l) {
  switch (l) {
    case flow::Limiter::Minmod: return "minmod";
    case flow::Limiter::VanLeer: return "vanleer";
    case flow::Limiter::MC: return "mc";
    case flow::Limiter::None: return "none";
  }
  return "?";
}

/// Per-family probabilities and ranges of the generator.
struct Knobs {
  double pTinyGrid = 0.08;     // a 1x1 / 1xN / Nx1 / 2xN grid
  double slopeMin = 0.01, slopeMax = 2.0;  // target steepest gradient of the fractal DEM
  double pCliff = 0.25, pPit = 0.25, pRamp = 0.15;
  double pLake = 0.3, pBlock = 0.5, pSingle = 0.25, pEdge = 0.2, pFilm = 0.1, pNoise = 0.15;
  double depthMin = 1e-3, depthMax = 50.0;
  double pVelocity = 0.25, froudeMax = 2.0;
  double pNodata = 0.2;
  int maxBlobs = 4;
  double pWetBlob = 0.3;       // a blob grows from a wet cell
  double pHighBase = 0.15;     // DEM offset of 500-4000 m (float rounding of eta = h + b)
  double pExtremeManning = 0.3;
};

Knobs knobsFor(StressFamily f) {
  Knobs k;
  switch (f) {
    case StressFamily::Fractal: break;
    case StressFamily::Cliffs:
      k.slopeMax = 12.0, k.pCliff = 0.9, k.pPit = 0.6, k.pRamp = 0.6, k.pLake = 0.4, k.depthMax = 50.0;
      break;
    case StressFamily::ThinFilm:
      k.pFilm = 1.0, k.pBlock = 0.2, k.pLake = 0.1, k.pSingle = 0.2, k.pNoise = 0.05, k.depthMax = 0.05;
      break;
    case StressFamily::TinyGrid: k.pTinyGrid = 1.0; break;
    case StressFamily::EdgeRelease:
      k.pSingle = 0.8, k.pEdge = 0.9, k.pBlock = 0.2, k.pLake = 0.1, k.pVelocity = 0.4;
      break;
    case StressFamily::Nodata: k.pNodata = 1.0, k.maxBlobs = 12, k.pWetBlob = 0.6; break;
    case StressFamily::Friction: k.pExtremeManning = 1.0, k.pVelocity = 0.7, k.froudeMax = 3.0; break;
    case StressFamily::Chaos:
      k.pTinyGrid = 0.15, k.slopeMax = 12.0, k.pCliff = 0.5, k.pPit = 0.5, k.pRamp = 0.4, k.pLake = 0.4;
      k.pSingle = 0.5, k.pEdge = 0.5, k.pFilm = 0.3, k.pNoise = 0.4, k.pVelocity = 0.5, k.froudeMax = 3.0;
      k.pNodata = 0.5, k.maxBlobs = 8, k.pWetBlob = 0.5, k.pHighBase = 0.3, k.pExtremeManning = 0.5;
      break;
    case StressFamily::Debris: break;  // not drawn by seed % kStressFamilies (makeDebrisScene)
  }
  return k;
}

/// Steepest centred-difference gradient of a DEM on the full raster.
double maxGradient(const Grid& g, const std::vector<double>& b) {
  double m = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      auto d = [&](int di, int dj) {
        const int i0 = std::max(0, i - di), i1 = std::min(g.nx - 1, i + di);
        const int j0 = std::max(0, j - dj), j1 = std::min(g.ny - 1, j + dj);
        const int span = (i1 - i0) + (j1 - j0);
        return span ? (b[g.index(i1, j1)] - b[g.index(i0, j0)]) / (span * g.dx) : 0.0;
      };
      m = std::max(m, std::hypot(d(1, 0), d(0, 1)));
    }
  return m;
}

/// Spectral fractal: octaves o of wavelength L / 2^o, three waves each with random direction and
/// phase and amplitude persistence^o, scaled to the target steepest gradient.
std::vector<double> fractalDem(const Grid& g, Rng& r, double targetSlope, int& octavesOut) {
  const double L = std::max(g.nx, g.ny) * g.dx;
  const int octaves = r.integer(2, 7);
  const double persistence = r.uniform(0.35, 0.75);
  octavesOut = octaves;
  struct Wave { double kx, ky, phase, amp; };
  std::vector<Wave> waves;
  for (int o = 0; o < octaves; ++o)
    for (int w = 0; w < 3; ++w) {
      const double angle = r.uniform(0, 2 * kPi), k = 2 * kPi * std::pow(2.0, o) * r.uniform(0.7, 1.4) / L;
      waves.push_back({k * std::cos(angle), k * std::sin(angle), r.uniform(0, 2 * kPi),
                       std::pow(persistence, o) * r.uniform(0.5, 1.0)});
    }
  std::vector<double> b(g.cells(), 0.0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double x = cellX(g, i), y = cellY(g, j);
      double s = 0;
      for (const Wave& w : waves) s += w.amp * std::sin(w.kx * x + w.ky * y + w.phase);
      b[g.index(i, j)] = s;
    }
  const double m = maxGradient(g, b);
  const double scale = m > 0 ? targetSlope / m : targetSlope * g.dx;
  for (double& v : b) v *= scale;
  return b;
}

/// Signed distance of cell (i, j) to a random line through (px, py) with normal angle `a`.
struct Line {
  double px, py, nx, ny;
  double dist(const Grid& g, int i, int j) const { return (cellX(g, i) - px) * nx + (cellY(g, j) - py) * ny; }
};

Line randomLine(const Grid& g, Rng& r) {
  Line l;
  l.px = r.uniform(0, g.nx * g.dx);
  l.py = r.uniform(0, g.ny * g.dx);
  if (r.chance(0.5)) {  // grid-aligned: a vertical step exactly along cell faces
    const int q = r.integer(0, 3);
    l.nx = q == 0 ? 1 : q == 1 ? -1 : 0;
    l.ny = q == 2 ? 1 : q == 3 ? -1 : 0;
    // put the step on a cell face
    l.px = std::floor(l.px / g.dx) * g.dx;
    l.py = std::floor(l.py / g.dx) * g.dx;
  } else {
    const double a = r.uniform(0, 2 * kPi);
    l.nx = std::cos(a);
    l.ny = std::sin(a);
  }
  return l;
}

struct Rect { int i0, j0, i1, j1; };  // inclusive

Rect randomRect(const Grid& g, Rng& r, int maxSide) {
  const int w = r.integer(1, std::max(1, std::min(g.nx, maxSide)));
  const int h = r.integer(1, std::max(1, std::min(g.ny, maxSide)));
  const int i0 = r.integer(0, g.nx - w), j0 = r.integer(0, g.ny - h);
  return {i0, j0, i0 + w - 1, j0 + h - 1};
}

}  // namespace

const char* familyName(StressFamily f) {
  switch (f) {
    case StressFamily::Fractal: return "Fractal";
    case StressFamily::Cliffs: return "Cliffs";
    case StressFamily::ThinFilm: return "ThinFilm";
    case StressFamily::TinyGrid: return "TinyGrid";
    case StressFamily::EdgeRelease: return "EdgeRelease";
    case StressFamily::Nodata: return "Nodata";
    case StressFamily::Friction: return "Friction";
    case StressFamily::Chaos: return "Chaos";
    case StressFamily::Debris: return "Debris";
  }
  return "?";
}

uint64_t stressSeed(uint64_t base, uint64_t index, StressFamily family) {
  const uint64_t m = mix64(mix64(base) ^ (index * 0xD1B54A32D192ED03ull + static_cast<uint64_t>(family)));
  return m - m % kStressFamilies + static_cast<uint64_t>(family);
}

StressScene makeStressScene(uint64_t seed) {
  StressScene sc;
  sc.seed = seed;
  sc.family = static_cast<StressFamily>(seed % kStressFamilies);
  const Knobs k = knobsFor(sc.family);
  Rng r(seed);
  std::ostringstream d;

  // ---- grid
  int nx, ny;
  if (r.chance(k.pTinyGrid)) {
    const int n = r.integer(2, 96);
    switch (r.integer(0, 5)) {
      case 0: nx = 1, ny = 1; break;
      case 1: nx = 1, ny = n; break;
      case 2: nx = n, ny = 1; break;
      case 3: nx = 2, ny = n; break;
      case 4: nx = n, ny = 2; break;
      default: nx = r.integer(2, 4), ny = r.integer(2, 4); break;
    }
  } else {
    nx = static_cast<int>(std::lround(r.logUniform(3, 96)));
    ny = r.chance(0.3) ? nx : static_cast<int>(std::lround(r.logUniform(3, 96)));
  }
  const double dx = r.logUniform(0.1, 20.0);
  sc.grid = Grid::make(nx, ny, dx);
  const Grid& g = sc.grid;
  const std::size_t n = g.cells();

  // ---- settings and precision
  flow::FlowSettings& s = sc.settings;
  s.limiter = static_cast<flow::Limiter>(r.integer(0, 3));
  s.riemann = r.chance(0.5) ? flow::RiemannSolver::HLL : flow::RiemannSolver::HLLC;
  s.edge = r.chance(0.5) ? flow::Boundary::Open : flow::Boundary::Wall;
  s.nodata = r.chance(0.3) ? flow::Boundary::Open : flow::Boundary::Wall;
  s.slopeCorrection = r.chance(0.6);
  s.depthPressure = r.chance(0.3) ? flow::DepthPressure::Cos4 : flow::DepthPressure::Cos2;
  s.skipDryTiles = r.chance(0.8);
  {
    const double u = r.unit();
    // The CFL setting is valid in (0, 0.5] (positivity); the same draws as before keep seeds stable.
    s.cfl = u < 0.3 ? 0.5 : u < 0.85 ? r.uniform(0.05, 0.5) : r.uniform(0.25, 0.5);
  }
  s.hDry = r.chance(0.8) ? 1e-6 : r.logUniform(1e-9, 1e-4);
  sc.precision = r.chance(0.4) ? compute::Precision::Float : compute::Precision::Double;
  sc.dtFraction = r.chance(0.7) ? 1.0 : r.uniform(0.2, 1.0);

  // ---- DEM
  const double targetSlope = r.logUniform(k.slopeMin, k.slopeMax);
  int octaves = 0;
  std::vector<double> b = fractalDem(g, r, targetSlope, octaves);
  std::ostringstream dem;
  dem << "fractal(" << octaves << " oct, slope " << fmt("%.3g", targetSlope) << ")";
  const double base = r.chance(k.pHighBase) ? r.uniform(500, 4000) : r.uniform(-50, 100);
  for (double& v : b) v += base;
  dem << "+base " << fmt("%.1f", base) << "m";
  if (r.chance(k.pCliff)) {
    const int count = r.integer(1, 3);
    for (int c = 0; c < count; ++c) {
      const double height = r.chance(0.5) ? dx * r.uniform(1, 10) : r.uniform(5, 50);
      const Line l = randomLine(g, r);
      const bool ridge = r.chance(0.3);  // a thin wall (1-2 cells) instead of a terrace
      const double width = r.integer(1, 2) * dx;
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const double dd = l.dist(g, i, j);
          if (ridge ? (dd > 0 && dd <= width) : dd > 0) b[g.index(i, j)] += height;
        }
      dem << (ridge ? "+ridge " : "+cliff ") << fmt("%.2f", height) << "m";
    }
  }
  if (r.chance(k.pPit)) {
    const int count = r.integer(1, 6);
    for (int c = 0; c < count; ++c) {
      const int ci = r.integer(0, nx - 1), cj = r.integer(0, ny - 1), rad = r.chance(0.5) ? 0 : r.integer(1, 3);
      const double depth = r.chance(0.5) ? dx * r.uniform(1, 10) : r.uniform(0.5, 30);
      for (int j = std::max(0, cj - rad); j <= std::min(ny - 1, cj + rad); ++j)
        for (int i = std::max(0, ci - rad); i <= std::min(nx - 1, ci + rad); ++i)
          if ((i - ci) * (i - ci) + (j - cj) * (j - cj) <= rad * rad) b[g.index(i, j)] -= depth;
      dem << "+pit(r" << rad << "," << fmt("%.2f", depth) << "m)";
    }
  }
  if (r.chance(k.pRamp)) {
    const int count = r.integer(1, 2);
    for (int c = 0; c < count; ++c) {
      const double slope = r.uniform(3, 12), w = r.integer(1, 6) * dx;
      const Line l = randomLine(g, r);
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) b[g.index(i, j)] += slope * std::clamp(l.dist(g, i, j), 0.0, w);
      dem << "+ramp(grad " << fmt("%.1f", slope) << ", " << fmt("%.1f", w) << "m)";
    }
  }

  // ---- water
  std::vector<double> h(n, 0.0);
  std::ostringstream wat;
  auto depth = [&](double lo, double hi) { return r.logUniform(std::max(lo, 1e-3), std::max(hi, 1e-3)); };
  if (r.chance(k.pLake)) {
    std::vector<double> sorted = b;
    std::sort(sorted.begin(), sorted.end());
    const double q = r.uniform(0.05, 0.7);
    double level = sorted[static_cast<std::size_t>(q * (n - 1))] + depth(k.depthMin, k.depthMax);
    level = std::min(level, sorted.front() + k.depthMax);
    for (std::size_t c = 0; c < n; ++c) h[c] = std::max(0.0, level - b[c]);
    wat << "lake(q" << fmt("%.2f", q) << ")";
  }
  if (r.chance(k.pBlock)) {
    const int count = r.integer(1, 3);
    for (int c = 0; c < count; ++c) {
      const Rect rc = randomRect(g, r, std::max(1, std::max(nx, ny) / 2));
      const double dep = depth(k.depthMin, k.depthMax);
      const bool level = r.chance(0.4);
      double bmin = std::numeric_limits<double>::infinity();
      for (int j = rc.j0; j <= rc.j1; ++j)
        for (int i = rc.i0; i <= rc.i1; ++i) bmin = std::min(bmin, b[g.index(i, j)]);
      for (int j = rc.j0; j <= rc.j1; ++j)
        for (int i = rc.i0; i <= rc.i1; ++i) {
          const std::size_t q = g.index(i, j);
          h[q] += level ? std::max(0.0, bmin + dep - b[q]) : dep;
        }
      wat << "+block(" << (rc.i1 - rc.i0 + 1) << "x" << (rc.j1 - rc.j0 + 1) << "," << fmt("%.3g", dep) << "m"
          << (level ? ",level" : "") << ")";
    }
  }
  if (r.chance(k.pSingle)) {
    const int count = r.integer(1, 3);
    for (int c = 0; c < count; ++c) {
      const double dep = depth(k.depthMin, k.depthMax);
      h[g.index(r.integer(0, nx - 1), r.integer(0, ny - 1))] += dep;
      wat << "+single(" << fmt("%.3g", dep) << "m)";
    }
  }
  if (r.chance(k.pEdge)) {
    const int count = r.integer(1, 2);
    for (int c = 0; c < count; ++c) {
      Rect rc = randomRect(g, r, std::max(1, std::max(nx, ny) / 3));
      const int side = r.integer(0, 3);
      const int w = rc.i1 - rc.i0, hh = rc.j1 - rc.j0;
      if (side == 0) rc.i0 = 0, rc.i1 = w;
      if (side == 1) rc.i1 = nx - 1, rc.i0 = nx - 1 - w;
      if (side == 2) rc.j0 = 0, rc.j1 = hh;
      if (side == 3) rc.j1 = ny - 1, rc.j0 = ny - 1 - hh;
      const double dep = depth(k.depthMin, k.depthMax);
      for (int j = rc.j0; j <= rc.j1; ++j)
        for (int i = rc.i0; i <= rc.i1; ++i) h[g.index(i, j)] += dep;
      wat << "+edge(side " << side << "," << (w + 1) << "x" << (hh + 1) << "," << fmt("%.3g", dep) << "m)";
    }
  }
  if (r.chance(k.pFilm)) {
    // A 1 mm film over a large part of the domain (a half-plane or a big rectangle), dry elsewhere.
    const bool halfPlane = r.chance(0.5);
    const Line l = randomLine(g, r);
    const Rect rc = randomRect(g, r, std::max(nx, ny));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool in = halfPlane ? l.dist(g, i, j) > 0 : (i >= rc.i0 && i <= rc.i1 && j >= rc.j0 && j <= rc.j1);
        if (in) h[g.index(i, j)] += 1e-3;
      }
    wat << "+film(1mm," << (halfPlane ? "half-plane" : "rect") << ")";
  }
  if (r.chance(k.pNoise)) {
    const double dmax = depth(k.depthMin, k.depthMax), pDry = r.uniform(0.1, 0.8);
    for (double& v : h)
      if (!r.chance(pDry)) v += r.logUniform(1e-3, std::max(1e-3, dmax));
    wat << "+noise(" << fmt("%.3g", dmax) << "m, dry " << fmt("%.2f", pDry) << ")";
  }

  // ---- nodata holes
  std::vector<uint8_t> mask(n, 1);
  int blobs = 0, wetBlobs = 0;
  if (r.chance(k.pNodata) && n > 1) {
    blobs = r.integer(1, k.maxBlobs);
    std::vector<std::size_t> wet;
    for (std::size_t c = 0; c < n; ++c)
      if (h[c] > 0) wet.push_back(c);
    for (int c = 0; c < blobs; ++c) {
      std::size_t start;
      if (!wet.empty() && r.chance(k.pWetBlob)) {
        start = wet[static_cast<std::size_t>(r.integer(0, static_cast<int>(wet.size()) - 1))];
        ++wetBlobs;
      } else {
        start = g.index(r.integer(0, nx - 1), r.integer(0, ny - 1));
      }
      int i = static_cast<int>(start % nx), j = static_cast<int>(start / nx);
      const int len = r.integer(1, std::max(1, static_cast<int>(n) / 20));
      for (int st = 0; st < len; ++st) {
        mask[g.index(i, j)] = 0;
        const int dir = r.integer(0, 3);
        i = std::clamp(i + (dir == 0) - (dir == 1), 0, nx - 1);
        j = std::clamp(j + (dir == 2) - (dir == 3), 0, ny - 1);
      }
    }
  }

  // Keep at least one inside, wet cell.
  bool anyWet = false, anyInside = false;
  for (std::size_t c = 0; c < n; ++c) {
    anyInside = anyInside || mask[c];
    anyWet = anyWet || (mask[c] && h[c] > 0);
  }
  if (!anyInside) mask[g.index(nx / 2, ny / 2)] = 1;
  if (!anyWet) {
    std::vector<std::size_t> inside;
    for (std::size_t c = 0; c < n; ++c)
      if (mask[c]) inside.push_back(c);
    const double dep = depth(k.depthMin, k.depthMax);
    h[inside[static_cast<std::size_t>(r.integer(0, static_cast<int>(inside.size()) - 1))]] += dep;
    wat << "+single(" << fmt("%.3g", dep) << "m, fallback)";
  }
  for (std::size_t c = 0; c < n; ++c)
    if (!mask[c]) h[c] = 0.0;

  // ---- momentum
  std::vector<double> qx(n, 0.0), qy(n, 0.0);
  if (r.chance(k.pVelocity)) {
    const double froude = r.uniform(0.1, k.froudeMax);
    const bool uniformDir = r.chance(0.5);
    const double a0 = r.uniform(0, 2 * kPi);
    for (std::size_t c = 0; c < n; ++c) {
      const double a = uniformDir ? a0 : r.uniform(0, 2 * kPi);
      const double speed = froude * std::sqrt(kGravity * h[c]);
      qx[c] = h[c] * speed * std::cos(a);
      qy[c] = h[c] * speed * std::sin(a);
    }
    wat << "+velocity(Fr " << fmt("%.2f", froude) << (uniformDir ? ", one direction" : ", random directions")
        << ")";
  }

  // ---- Manning
  std::vector<double> manning(n, 0.0);
  std::string man;
  if (r.chance(k.pExtremeManning)) {
    switch (r.integer(0, 3)) {
      case 0: man = "n=0"; break;
      case 1: {
        const double v = r.uniform(0.5, 1.0);
        std::fill(manning.begin(), manning.end(), v);
        man = "n=" + fmt("%.3f", v);
        break;
      }
      case 2:
        for (double& v : manning) v = r.unit();
        man = "n random [0,1)";
        break;
      default: {
        const Line l = randomLine(g, r);
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i) manning[g.index(i, j)] = l.dist(g, i, j) > 0 ? 1.0 : 0.0;
        man = "n patches 0/1";
        break;
      }
    }
  } else {
    const double v = r.chance(0.3) ? 0.0 : r.logUniform(0.01, 0.15);
    std::fill(manning.begin(), manning.end(), v);
    man = "n=" + fmt("%.3f", v);
  }

  sc.input.mask = std::move(mask);
  sc.input.bed = std::move(b);
  sc.input.manning = std::move(manning);
  sc.input.h = std::move(h);
  sc.input.qx = std::move(qx);
  sc.input.qy = std::move(qy);

  // ---- steps: a few hundred, bounded by a cell-step budget so big grids stay within wall time
  const int want = r.integer(150, 400);
  constexpr double kCellStepBudget = 1.2e6;
  sc.steps = std::max(60, std::min(want, static_cast<int>(kCellStepBudget / static_cast<double>(n))));

  d << "seed=" << seed << " family=" << familyName(sc.family) << " grid=" << nx << "x" << ny
    << " dx=" << fmt("%.4g", dx) << " " << compute::precisionName(sc.precision) << " limiter="
    << limiterName(s.limiter) << " riemann=" << (s.riemann == flow::RiemannSolver::HLL ? "hll" : "hllc")
    << " edge=" << (s.edge == flow::Boundary::Open ? "open" : "wall")
    << " nodataBoundary=" << (s.nodata == flow::Boundary::Open ? "open" : "wall")
    << " slopeCorrection=" << (s.slopeCorrection ? "on" : "off")
    << " depthPressure=" << (s.depthPressure == flow::DepthPressure::Cos4 ? "cos4" : "cos2")
    << " skipDryTiles=" << (s.skipDryTiles ? 1 : 0) << " cfl=" << fmt("%.4g", s.cfl)
    << " hDry=" << fmt("%.3g", s.hDry) << " dtFraction=" << fmt("%.3g", sc.dtFraction) << " steps=" << sc.steps
    << " | dem: " << dem.str() << " | water: " << wat.str() << " | nodata: " << blobs << " blobs (" << wetBlobs
    << " from wet cells) | manning: " << man;
  sc.description = d.str();
  return sc;
}

// ------------------------------------------------------------------------------------------------
// Checker
// ------------------------------------------------------------------------------------------------
namespace {

/// Host-side totals of a state, all in double from the downloaded fields.
struct Totals {
  double volume = 0;     ///< sum h dx^2 [m^3]
  double kinetic = 0;    ///< sum h |u|^2 / 2 dx^2 [m^5/s^2] (per unit density, as the diagnostics)
  double potential = 0;  ///< sum h (b - bmin + h/2) dx^2 [m^4]: volume times centroid height
  double speed = 0;      ///< max (|u| + c) + (|v| + c), c = sqrt(g_p h), as the solver's CFL speed (split: max(|u|, |v|) + c)
  double speedFace = 0;  ///< the same with c from the largest g_p of the cell and its neighbours
  /// Upper bound of the rate at which the slope-corrected model can raise E_kin + g P (zero with
  /// slope correction off), [m^5/s^3]; see the energy tolerance in runStressScene.
  double slopeWorkRate = 0;
  int wetCells = 0;
  std::size_t speedCell = 0;  ///< where `speed` is reached
};

struct Frame {
  const Grid& grid;
  const std::vector<uint8_t>& mask;
  const std::vector<double>& bed;
  const std::vector<double>& gp;       ///< g_p as the device holds it (for the CFL speed)
  const std::vector<double>& gpHost;   ///< g_p and g_n in double (for the slope work)
  const std::vector<double>& gnHost;
  double bedMin;
  double hDry;  ///< the threshold as the device sees it (rounded to float in float runs)
  bool split = false;  ///< dimensionally split time scheme: the CFL speed is per direction
};

/// Upper bound of the rate at which the slope-corrected shallow-water terms of a layer h (velocity
/// q / h) over the bed b + under (under: the solids below a two-phase fluid, or none) can raise
/// E_kin + g P: sum (g - g_p) h (u . grad eta)^+ + (g_n - g_p) h (u . grad b)^- dx^2 [m^5/s^3], with
/// eta = b + under + h and centred differences (one-sided next to the boundary); see the energy
/// tolerance in runStressScene.
double slopeWorkRate(const Grid& g, const std::vector<uint8_t>& mask, const std::vector<double>& bed,
                     const std::vector<double>* under, const std::vector<double>& h, const std::vector<double>& qx,
                     const std::vector<double>& qy, const std::vector<double>& gp, const std::vector<double>& gn,
                     double hDry) {
  double rate = 0;
  const double area = g.dx * g.dx;
  auto inside = [&](int a, int c) { return a >= 0 && c >= 0 && a < g.nx && c < g.ny && mask[g.index(a, c)]; };
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      const double hk = h[k];
      if (!mask[k] || !(hk > 0)) continue;
      const double u = hk > hDry ? qx[k] / hk : 0.0, v = hk > hDry ? qy[k] / hk : 0.0;
      const double dgp = kGravity - gp[k], dgn = gn[k] - gp[k];
      if (!((dgp > 0 || dgn > 0) && (u != 0 || v != 0))) continue;
      auto grad = [&](int di, int dj, bool eta) {
        auto val = [&](int a, int c) {
          const std::size_t q = g.index(a, c);
          return bed[q] + (eta ? h[q] + (under ? (*under)[q] : 0.0) : 0.0);
        };
        const bool m = inside(i - di, j - dj), p = inside(i + di, j + dj);
        if (m && p) return 0.5 * (val(i + di, j + dj) - val(i - di, j - dj)) / g.dx;
        if (p) return (val(i + di, j + dj) - val(i, j)) / g.dx;
        if (m) return (val(i, j) - val(i - di, j - dj)) / g.dx;
        return 0.0;
      };
      const double ue = u * grad(1, 0, true) + v * grad(0, 1, true);
      const double ub = u * grad(1, 0, false) + v * grad(0, 1, false);
      rate += (dgp * hk * std::max(ue, 0.0) + dgn * hk * std::max(-ub, 0.0)) * area;
    }
  return rate;
}

Totals totals(const Frame& f, const std::vector<double>& h, const std::vector<double>& qx,
              const std::vector<double>& qy) {
  Totals t;
  // Sums in long double (64-bit mantissa on x86) so the host's totals are exact to far below the
  // device's rounding, whatever the summation order.
  long double volume = 0, kinetic = 0, potential = 0;
  const double area = f.grid.dx * f.grid.dx;
  const Grid& g = f.grid;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      if (!f.mask[k]) continue;
      const double hk = h[k];
      const double u = hk > f.hDry ? qx[k] / hk : 0.0, v = hk > f.hDry ? qy[k] / hk : 0.0;
      volume += static_cast<long double>(hk * area);
      kinetic += static_cast<long double>(0.5 * hk * (u * u + v * v) * area);
      potential += static_cast<long double>(hk * ((f.bed[k] - f.bedMin) + 0.5 * hk) * area);
      if (hk > 0) {
        ++t.wetCells;
        // The CFL speed (without the bed-slope speed w, which only makes the solver's larger):
        // over both directions' faces, or along one direction for the split scheme's sweeps.
        const auto cflSpeed = [&](double g) {
          return f.split ? std::max(std::fabs(u), std::fabs(v)) + std::sqrt(g * hk)
                         : std::fabs(u) + std::fabs(v) + 2 * std::sqrt(g * hk);
        };
        const double sk = cflSpeed(f.gp[k]);
        if (sk > t.speed) t.speed = sk, t.speedCell = k;
        double gmax = f.gp[k];
        const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
        for (int q = 0; q < 4; ++q) {
          const int a = i + di[q], c = j + dj[q];
          if (a >= 0 && c >= 0 && a < g.nx && c < g.ny && f.mask[g.index(a, c)]) gmax = std::max(gmax, f.gp[g.index(a, c)]);
        }
        t.speedFace = std::max(t.speedFace, cflSpeed(gmax));
      }
    }
  t.slopeWorkRate = slopeWorkRate(g, f.mask, f.bed, nullptr, h, qx, qy, f.gpHost, f.gnHost, f.hDry);
  t.volume = static_cast<double>(volume);
  t.kinetic = static_cast<double>(kinetic);
  t.potential = static_cast<double>(potential);
  return t;
}

std::string cellText(const Grid& g, std::size_t k) {
  return "cell (" + std::to_string(k % g.nx) + "," + std::to_string(k / g.nx) + ")";
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}


/// Marks `out` failed at `step` (time t) with the message `what`.
static void recordFailure(StressOutcome& out, int step, double t, const std::string& what) {
  out.ok = false;
  char head[160];
  std::snprintf(head, sizeof head, "step %d (t = %.6g s): ", step, t);
  out.failure = head + what;
}

}  // namespace

StressOutcome runDebrisScene(const StressScene& scene);

StressOutcome runStressScene(const StressScene& scene) {
  if (scene.settings.twoPhase) return runDebrisScene(scene);
  StressOutcome out;
  const Grid& g = scene.grid;
  const bool dbl = scene.precision == compute::Precision::Double;
  // Unit round-off of the kernels' arithmetic.
  const double eps = dbl ? std::numeric_limits<double>::epsilon() : static_cast<double>(std::numeric_limits<float>::epsilon());
  const double area = g.dx * g.dx;
  const auto start = std::chrono::steady_clock::now();

  const flow::FlowSettings& s = scene.settings;
  flow::FlowSolver solver(testContext(scene.precision), g, s);
  solver.setInput(scene.input);
  const std::vector<double> gp = solver.gp();
  const flow::SlopeGravity sg = flow::computeSlopeGravity(g, scene.input.bed, scene.input.mask, s);
  std::vector<double> bed = scene.input.bed;
  double bedMin = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < g.cells(); ++k)
    if (scene.input.mask[k]) bedMin = std::min(bedMin, bed[k]);
  const double hDry = dbl ? s.hDry : static_cast<double>(static_cast<float>(s.hDry));
  const Frame frame{g, scene.input.mask, bed, gp, sg.gp, sg.gn, bedMin, hDry, flow::sweeps(s.scheme)};

  std::vector<double> h = solver.h(), qx = solver.qx(), qy = solver.qy();
  const Totals t0 = totals(frame, h, qx, qy);
  double hMax0 = 0;
  for (double v : h) hMax0 = std::max(hMax0, v);
  std::vector<uint8_t> everWet(g.cells(), 0);
  int everWetCount = 0;
  for (std::size_t k = 0; k < g.cells(); ++k)
    if (h[k] > 0) everWet[k] = 1, ++everWetCount;

  // ---- tolerances
  //
  // Volume balance, |V(t) + sum of outflow - V(0)| <= relVol * V(0) + 4 eps hMax0 dx^2 * (cells ever
  // wet). Each interior face's mass flux is one value used with opposite signs by its two cells and
  // walls pass none, so the balance changes only by the rounding of each wet cell's h update (a few
  // operations per stage, each off by at most eps/2 of the cell's values) and by the clipping of a
  // round-off negative (the kernel's fmax(h, 0), a few eps of the neighbours' depths). Dry cells with
  // no wet neighbour are updated with exactly zero fluxes, so only cells that were ever wet count.
  //  - double: the rounding is ~1e-16 of the volume per step and mostly cancels between cells and
  //    steps (measured drift ~1e-15 over 300 steps, tests/verification/test_conservation.cpp);
  //    1e-11 relative is >= 1e4 times that and far below any real leak (a single clipped negative
  //    film of 1 um on one cell, or one face with a wrong sign, is many orders larger).
  //  - float: eps = 1.2e-7; the per-step error of a wet cell is a few eps/2 of its depth and
  //    accumulates like a random walk, so after S <= 400 steps the relative drift is about
  //    eps/2 * sqrt(4 S / N_wet) <= 2.4e-6 for one wet cell (less for more cells). 1e-5 relative
  //    leaves a factor > 4 over that, while a real positivity failure (a clipped negative depth of
  //    1e-5 of the release) still shows.
  const double relVol = dbl ? 1e-11 : 1e-5;
  // Diagnostics sums (device reductions in the kernels' precision) against the host's long-double
  // sums of the same fields (all terms non-negative): the device sums a tile as a tree (8 levels for
  // 16x16) and the tiles' partials with reduce_rows (a work-item loop over at most a few partials,
  // then a 7-level tree), so each term passes through fewer than 20 roundings and the relative error
  // is below ~20 eps (plus the per-cell products); 256 eps leaves a wide margin.
  const double relDiag = 256 * eps;
  // CFL: stableDt() = cfl dx / maxSpeed with the device's reduction of the same per-cell formula
  // that the host evaluates here; in double both are the same operations (a few ulps at most from
  // the order of the max and the division), in float the device speed is a float within a few
  // float ulps. 1e-12 and 1e-5 relative are comfortably above those and far below a real excess.
  const double relCfl = dbl ? 1e-12 : 1e-5;
  // Energy. With P = sum h (b - bmin + h/2) dx^2 (volume times centroid height above the lowest
  // bed cell), the shallow-water equations with one gravity g conserve E_kin + g P in smooth flow
  // and dissipate it at shocks, through Manning friction, and at open boundaries (outflow only, and
  // P >= 0 per cell, so water that leaves takes non-negative energy along). The scheme is built to
  // follow that (hydrostatic reconstruction with HLL/HLLC is entropy-satisfying for the first-order
  // scheme, the limiters are TVD, friction only removes momentum), so
  //   E_kin(t) <= E_kin(0) + g (P(0) - P(t)) + W(t) + slack.
  // W is the slope work, zero with slope correction off: with g_p, g_n < g the model is not
  // conservative for the g-weighted P: d(E_kin + g P)/dt = sum [(g - g_p) h u.grad(eta) +
  // (g_p - g_n) h u.grad(b)] dx^2 (plus dissipation), which is positive where water climbs a slope
  // (it loses speed at g_p but gains g-potential) or, with cos4, where g_p < g_n drives it downhill.
  // W integrates the positive parts of both terms from centred differences (rate at the start and
  // end of each step, the larger times dt), an upper bound of what the continuous model can add.
  // The slack covers:
  //  - the discretisation: the fully discrete entropy inequality of the hydrostatic reconstruction
  //    (Audusse, Bouchut, Bristeau & Saint-Marie 2016) has an O(dt^2) error term per step, and the
  //    second-order reconstruction has no proven inequality at all. Measured over 3000 soak scenes,
  //    the excess of the passing scenes stays below 0.13 of this slack (under 0.7 % of
  //    E_kin(0) + g |dP| + W), while each of the 55 scenes that broke it was traced to a mechanism by
  //    re-running it with one setting changed (dt / 20, Limiter=none, cfl 0.5, cos2 or slope
  //    correction off each makes it pass; see the regression cases in tests/stress/test_stress.cpp).
  //    After the fixes those mechanisms pointed to (bed-slope speed in the CFL condition, CFL <= 0.5,
  //    the subcell face bed and the minmod bed under the limited surface), every limiter is checked:
  //    frictionless thin water on near-vertical ramps resolved by a few coarse cells, which gained
  //    up to ~25 % with van Leer and MC through false face-bed rises (seeds 14493454552802392858,
  //    3610104951568155784, 8348562632382950745), now stays within (energy ratio 0 for all three).
  //    A 300-scene soak from base seed 777 still finds 3 MC / van Leer scenes of a few coarse cells
  //    over fractal pits and cliffs above the slack (docs/numerics.md, known limitations).
  //    The failures the check exists for exceeded the bound by factors of 10 to 1e10; kSlackRel =
  //    20 % sits well between;
  //  - rounding: P is a sum of h (b - bmin + h/2) whose h carry the kernels' rounding, so
  //    g (P(0) - P(t)) is noisy by ~eps g P(0) per step even for a lake at rest; 8 eps g P(0)
  //    sqrt(steps) (random walk, a factor 8 for the operations per step) bounds that noise.
  constexpr double kSlackRel = 0.20;

  double cumOut = 0;
  double slopeWork = 0;  // integral of the slope work rate, see the energy tolerance
  for (int st = 1; st <= scene.steps; ++st) {
    auto fail = [&](const std::string& what) { recordFailure(out, st, solver.time(), what); };
    const double stable = solver.stableDt();
    if (std::isnan(stable) || stable <= 0) {
      fail("stableDt() = " + num(stable));
      break;
    }
    const Totals before = totals(frame, h, qx, qy);
    if (std::isinf(stable)) {
      if (before.wetCells == 0) break;  // everything drained: nothing left to step
      fail("stableDt() is infinite with " + std::to_string(before.wetCells) + " wet cells");
      break;
    }
    const double dt = scene.dtFraction * stable * (std::getenv("TALUS_STRESS_DT_SCALE") ? std::atof(std::getenv("TALUS_STRESS_DT_SCALE")) : 1.0);
    // The step's CFL number on the state it starts from, with the host's speed.
    const double cfl = dt * before.speed / g.dx;
    out.cflUsed = std::max(out.cflUsed, cfl);
    out.cflFaceGravity = std::max(out.cflFaceGravity, dt * before.speedFace / g.dx);
    if (!(cfl <= s.cfl * (1 + relCfl))) {
      fail("CFL " + num(cfl) + " exceeds the setting " + num(s.cfl) + " (dt " + num(dt) + ", host speed " +
           num(before.speed) + ", diagnostics speed " + num(solver.diagnostics().maxSpeed) + ")");
      break;
    }

    solver.step(dt);
    ++out.steps;
    const flow::FlowDiagnostics& dg = solver.diagnostics();
    if (!std::isfinite(dg.volume) || !std::isfinite(dg.outflow) || !std::isfinite(dg.kinetic) ||
        !std::isfinite(dg.maxSpeed) || !std::isfinite(dg.minH)) {
      fail("non-finite diagnostics: volume " + num(dg.volume) + " outflow " + num(dg.outflow) + " kinetic " +
           num(dg.kinetic) + " maxSpeed " + num(dg.maxSpeed) + " minH " + num(dg.minH));
      break;
    }
    if (dg.outflow < 0) {
      fail("negative outflow " + num(dg.outflow) + " m^3: water entered through an open boundary");
      break;
    }
    cumOut += dg.outflow;

    const std::vector<double> hPrev = std::move(h);
    h = solver.h();
    qx = solver.qx();
    qy = solver.qy();
    std::string bad;
    for (std::size_t k = 0; k < g.cells() && bad.empty(); ++k) {
      if (!std::isfinite(h[k]) || !std::isfinite(qx[k]) || !std::isfinite(qy[k]))
        bad = "non-finite field at " + cellText(g, k) + ": h " + num(h[k]) + " qx " + num(qx[k]) + " qy " + num(qy[k]);
      else if (h[k] < 0)
        bad = "negative h " + num(h[k]) + " at " + cellText(g, k);
      else if (!scene.input.mask[k] && (h[k] != 0 || qx[k] != 0 || qy[k] != 0))
        bad = "water on nodata " + cellText(g, k) + ": h " + num(h[k]);
      else if (h[k] <= hDry && (qx[k] != 0 || qy[k] != 0))
        bad = "momentum on a dry " + cellText(g, k) + ": h " + num(h[k]) + " qx " + num(qx[k]) + " qy " + num(qy[k]);
      if (h[k] > 0 && !everWet[k]) everWet[k] = 1, ++everWetCount;
    }
    if (!bad.empty()) {
      fail(bad);
      break;
    }

    const Totals t = totals(frame, h, qx, qy);
    out.cflAfter = std::max(out.cflAfter, dt * t.speed / g.dx);
    // Where to look when the balance or the energy fails: the cell that gained the most depth in
    // this step and the cell with the largest CFL number after it (the step's dt on the new state).
    auto context = [&]() {
      std::size_t gain = 0;
      for (std::size_t k = 1; k < g.cells(); ++k)
        if (h[k] - hPrev[k] > h[gain] - hPrev[gain]) gain = k;
      const std::size_t c = t.speedCell;
      const double u = h[c] > hDry ? qx[c] / h[c] : 0.0, v = h[c] > hDry ? qy[c] / h[c] : 0.0;
      return "; largest depth gain in the step at " + cellText(g, gain) + ": h " + num(hPrev[gain]) + " -> " +
             num(h[gain]) + "; largest CFL after the step " + num(dt * t.speed / g.dx) + " at " + cellText(g, c) +
             " (h " + num(h[c]) + ", u " + num(u) + ", v " + num(v) + ", g_p " + num(gp[c]) + ", bed " +
             num(bed[c]) + ")";
    };

    // Volume balance.
    const double balance = t.volume + cumOut - t0.volume;
    const double volTol = relVol * t0.volume + 4 * eps * hMax0 * area * everWetCount;
    out.balanceRatio = std::max(out.balanceRatio, std::fabs(balance) / volTol);
    out.balanceRelative = std::max(out.balanceRelative, std::fabs(balance) / t0.volume);
    if (!(std::fabs(balance) <= volTol)) {
      fail("volume balance V + outflow - V0 = " + num(balance) + " m^3 (V " + num(t.volume) + ", outflow " +
           num(cumOut) + ", V0 " + num(t0.volume) + ", tolerance " + num(volTol) + ")" + context());
      break;
    }
    // The solver's own sums agree with the host's.
    const double diagTol = relDiag * std::max(t.volume, 1e-300) + 1e-300;
    if (!(std::fabs(dg.volume - t.volume) <= diagTol)) {
      fail("diagnostics volume " + num(dg.volume) + " differs from the fields' " + num(t.volume));
      break;
    }
    if (!(std::fabs(dg.kinetic - t.kinetic) <= relDiag * t.kinetic + 1e-300)) {
      fail("diagnostics kinetic energy " + num(dg.kinetic) + " differs from the fields' " + num(t.kinetic));
      break;
    }

    // Energy, for every scene and limiter (the compressive limiters' exemption on frictionless
    // steep terrain went with the minmod face bed of reconstruct_surface, flow_common.cl).
    slopeWork += dt * std::max(before.slopeWorkRate, t.slopeWorkRate);
    const double released = kGravity * (t0.potential - t.potential);
    const double slack = kSlackRel * (t0.kinetic + std::fabs(released) + slopeWork) +
                         8 * eps * kGravity * t0.potential * std::sqrt(static_cast<double>(st));
    const double excess = t.kinetic - t0.kinetic - released - slopeWork;
    out.energyRatio = std::max(out.energyRatio, excess / std::max(slack, 1e-300));
    const double budget = t0.kinetic + std::max(released, 0.0) + slopeWork;
    if (budget > 0) out.energyGainFraction = std::max(out.energyGainFraction, t.kinetic / budget);
    if (!(excess <= slack)) {
      fail("kinetic energy " + num(t.kinetic) + " exceeds E_kin(0) + g dP + slope work = " + num(t0.kinetic) +
           " + " + num(released) + " + " + num(slopeWork) + " by " + num(excess) + " (slack " + num(slack) +
           ") [per unit density, m^5/s^2]" + context());
      if (std::getenv("TALUS_STRESS_DUMP")) {
        for (std::size_t k = 0; k < g.cells(); ++k)
          std::printf("cell %s mask %d bed %.6g h0 %.6g | h %.9g q (%.6g %.6g) g_p %.6g\n", cellText(g, k).c_str(),
                      static_cast<int>(scene.input.mask[k]), bed[k], scene.input.h[k], h[k], qx[k], qy[k], gp[k]);
      }
      break;
    }
  }
  if (out.ok) {
    // Maxima maps: finite, and never below the final depth (they track every step's state).
    const std::vector<double> hMax = solver.hMax(), vMax = solver.vMax();
    for (std::size_t k = 0; k < g.cells(); ++k)
      if (scene.input.mask[k] && (!std::isfinite(hMax[k]) || !std::isfinite(vMax[k]) || hMax[k] < h[k] || vMax[k] < 0)) {
        out.ok = false;
        out.failure = "end of run: maxima maps at " + cellText(g, k) + ": hMax " + num(hMax[k]) + " < h " + num(h[k]) +
                      " or vMax " + num(vMax[k]) + " not finite and >= 0";
        break;
      }
  }
  out.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}


// ------------------------------------------------------------------------------------------------
// Two-phase (debris) scenes and their checker
// ------------------------------------------------------------------------------------------------

uint64_t debrisSeed(uint64_t base, uint64_t index) {
  // A sequence of its own (a different salt from stressSeed), so the single-phase sequences and
  // their seed -> scene mapping are untouched.
  return mix64(mix64(base ^ 0xDEB815F10Dull) ^ (index * 0x9E6C63D0676A9A99ull + 0x51ull));
}

StressScene makeDebrisScene(uint64_t seed) {
  Rng r(mix64(seed ^ 0xD0B1E5ull));
  // The grid, DEM, water, nodata, Manning map, numerics and precision of a single-phase Fractal or
  // Cliffs scene derived from the seed; the two-phase kernel is ~6x slower per cell, so grids above
  // 2500 cells are redrawn (at most 16 times: still a pure function of the seed).
  const StressFamily base = r.chance(0.5) ? StressFamily::Fractal : StressFamily::Cliffs;
  StressScene sc;
  for (uint64_t a = 0; a < 16; ++a) {
    sc = makeStressScene(stressSeed(seed, a, base));
    if (sc.grid.cells() <= 2500) break;
  }
  const uint64_t baseSeed = sc.seed;
  const std::string baseDescription = sc.description;
  sc.seed = seed;
  sc.family = StressFamily::Debris;
  const Grid& g = sc.grid;
  const std::size_t n = g.cells();
  flow::FlowInput& in = sc.input;
  flow::FlowSettings& s = sc.settings;
  s.twoPhase = true;
  flow::DebrisSettings& d = s.debris;
  std::ostringstream desc;
  auto deg = [](double v) { return v * kPi / 180.0; };

  // ---- settings
  d.drag = static_cast<flow::DragLaw>(r.integer(0, 2));
  {
    const double u = r.unit();
    d.dragMultiplier = u < 0.35 ? 1e-3 : u < 0.7 ? 1e6 : r.logUniform(1e-3, 1e6);
  }
  d.virtualMass = r.chance(0.5);
  // The bed's curvature along the material's path, on slope-corrected scenes (from the seed's bits, so
  // the random stream, and with it every other draw of the scene, is the same as without it).
  s.curvature = s.slopeCorrection && ((seed >> 11) & 1u);
  d.earthPressure = r.chance(0.5) ? flow::EarthPressure::SavageHutter : flow::EarthPressure::Constant;
  {
    const double u = r.unit();
    d.kConst = u < 0.2 ? 0.3 : u < 0.4 ? 3.0 : r.logUniform(0.3, 3.0);
  }
  {
    const double u = r.unit();
    d.poreB = u < 0.25 ? 0.0 : u < 0.5 ? 1.0 : r.unit();
  }
  d.deltaFromPhi = r.chance(0.5);
  d.fluidDensity = r.chance(0.7) ? 1000.0 : r.uniform(900, 1300);

  // ---- material fields
  const bool phiField = r.chance(0.4);
  const double phi0 = r.uniform(10, 45), delta0 = r.uniform(10, 45);
  in.phi.assign(n, deg(phi0));
  in.delta.assign(n, deg(delta0));
  if (phiField)
    for (std::size_t k = 0; k < n; ++k) in.phi[k] = deg(r.uniform(10, 45)), in.delta[k] = deg(r.uniform(10, 45));
  double cohesion;
  {
    const double u = r.unit();
    cohesion = u < 0.35 ? 0.0 : u < 0.55 ? 1e6 : r.logUniform(1.0, 1e6);
  }
  in.cohesion.assign(n, cohesion);
  const double rhoS = r.uniform(1500, 3000), grain = r.logUniform(1e-5, 0.2);
  in.rhoS.assign(n, rhoS);
  in.grain.assign(n, grain);

  // ---- split the water into solids and fluid
  const int mode = r.integer(0, 3);  // 0 solids only, 1 fluid only, 2 mixture, 3 mixture + pure cells
  const double pPure = mode == 3 ? r.uniform(0.2, 0.8) : 0.0;
  const bool solidMoves = r.chance(0.5);
  std::vector<double> hs(n, 0.0), qsx(n, 0.0), qsy(n, 0.0);
  int fluidOnly = 0, solidOnly = 0, mixed = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double H = in.h[k];
    if (!(H > 0)) continue;
    double alpha;  // solid fraction of the release
    if (mode == 0) alpha = 1;
    else if (mode == 1) alpha = 0;
    else if (mode == 3 && r.chance(pPure)) alpha = r.chance(0.5) ? 1.0 : 0.0;
    else alpha = r.uniform(0.05, 0.95);
    hs[k] = alpha * H;
    const double hf = H - hs[k];
    const double u = in.qx[k] / H, v = in.qy[k] / H;
    if (solidMoves) qsx[k] = hs[k] * u, qsy[k] = hs[k] * v;
    in.qx[k] = hf * u;
    in.qy[k] = hf * v;
    in.h[k] = alpha == 1 ? 0.0 : hf;
    if (alpha == 1) ++solidOnly;
    else if (alpha == 0) ++fluidOnly;
    else ++mixed;
  }
  in.hs = std::move(hs);
  in.qsx = std::move(qsx);
  in.qsy = std::move(qsy);

  // ---- steps: a cell-step budget (the two-phase stage is ~6x slower per cell than water only)
  constexpr double kCellStepBudget = 1.5e5;
  sc.steps = std::max(40, std::min(r.integer(80, 250), static_cast<int>(kCellStepBudget / static_cast<double>(n))));

  static const char* dragNames[] = {"off", "linear", "quadratic"};
  static const char* modeNames[] = {"solids only", "fluid only", "mixture", "mixture+pure cells"};
  desc << "debrisSeed=" << seed << " family=Debris steps=" << sc.steps << " | two-phase: drag="
       << dragNames[static_cast<int>(d.drag)] << " dragMultiplier=" << fmt("%.3g", d.dragMultiplier)
       << " virtualMass=" << (d.virtualMass ? 1 : 0) << " curvature=" << (s.curvature ? 1 : 0) << " earthPressure="
       << (d.earthPressure == flow::EarthPressure::Constant ? "constant K=" + fmt("%.3g", d.kConst) : std::string("savage-hutter"))
       << " poreB=" << fmt("%.3g", d.poreB) << " rhoF=" << fmt("%.4g", d.fluidDensity)
       << " phi=" << (phiField ? std::string("field 10-45") : fmt("%.1f", phi0)) << " delta="
       << (d.deltaFromPhi ? std::string("phi") : phiField ? std::string("field 10-45") : fmt("%.1f", delta0))
       << " cohesion=" << fmt("%.3g", cohesion) << "Pa rhoS=" << fmt("%.4g", rhoS) << " grain=" << fmt("%.3g", grain)
       << "m release=" << modeNames[mode] << " (" << solidOnly << " solid-only, " << fluidOnly << " fluid-only, " << mixed
       << " mixed cells)" << (solidMoves ? " solids moving" : " solids at rest") << " | base scene (seed " << baseSeed
       << "): " << baseDescription;
  sc.description = desc.str();
  return sc;
}

namespace {

/// Host totals of a two-phase state.
struct DebrisTotals {
  double volF = 0, volS = 0;  ///< [m^3]
  /// sum [rho_s h_s (b - bmin) + rho_s U_s / g + rho_f h_f (b - bmin + h_s + h_f/2)] dx^2 [kg m]
  /// (solidPressureEnergy: U_s per unit solid density)
  double potential = 0;
  int wetCells = 0;
};

/// The material constants of the solids' lateral pressure that the energy bound needs, per cell.
struct SolidPressureLaw {
  bool constantK = false;
  double kConst = 1, rhoF = 1000;
  /// No fluid in the scene: the dry granular model, whose energy is exact (runDebrisScene)
  bool dry = false;
  bool deltaFromPhi = true;
  const std::vector<double>* delta = nullptr;  ///< bed friction angle [rad] where !deltaFromPhi
  const std::vector<double>* gp = nullptr;     ///< pressure gravity per cell [m/s^2]
};

/// Internal energy per unit area and solid density [m^3/s^2] of a dry solid column of thickness h
/// under the model's lateral pressure (kernels/flow/debris_stage.cl, solid_side, without fluid):
/// p(h) = h Pi(h) with Pi = max(0, a h - c0), a = K g_p / 2, c0 = 2 c sqrt(K) / rho_s. For a
/// barotropic pressure the energy of a column is U = h int^h Pi(h') / h' dh' (then h U' - U = p), so
///   U = h (a (h - h0) - c0 ln(h / h0)) for h > h0 = c0 / a, and 0 below (cohesion holds it);
/// a h^2 without cohesion (g h^2 / 2 for water: the centroid term of hydrostatic pressure). K is the
/// smallest the law gives, the active Savage-Hutter value: the passive share a contraction adds is
/// work the contraction pays and the extension does not get back.
double solidPressureEnergy(double h, double K, double gp, double cohesion, double rhoS) {
  if (!(h > 0)) return 0;
  const double a = 0.5 * K * gp, c0 = 2 * cohesion * std::sqrt(std::max(K, 0.0)) / rhoS;
  if (!(a > 0)) return 0;
  if (!(c0 > 0)) return a * h * h;
  const double h0 = c0 / a;
  return h > h0 ? h * (a * (h - h0) - c0 * std::log(h / h0)) : 0.0;
}

DebrisTotals debrisTotals(const Grid& g, const std::vector<uint8_t>& mask, const std::vector<double>& bed, double bedMin,
                          const SolidPressureLaw& law, const std::vector<double>& h, const std::vector<double>& hs,
                          const std::vector<double>& rhoS, const std::vector<double>& phi,
                          const std::vector<double>& cohesion) {
  // phi and cohesion are read only where law.dry (the caller downloads them only then).
  long double vf = 0, vs = 0, pot = 0;
  const double area = g.dx * g.dx, rhoF = law.rhoF;
  DebrisTotals t;
  for (std::size_t k = 0; k < g.cells(); ++k) {
    if (!mask[k]) continue;
    const double z = bed[k] - bedMin;
    vf += static_cast<long double>(h[k] * area);
    vs += static_cast<long double>(hs[k] * area);
    // The solids' own energy: without fluid in the scene the model's lateral-pressure law (the dry
    // granular model conserves KE + g h b + U_s up to its dissipation); with fluid the hydrostatic
    // energy of the mixture column (see runDebrisScene).
    double u = 0.5 * kGravity * hs[k] * hs[k];
    if (law.dry && hs[k] > 0) {
      const double K = law.constantK ? law.kConst
                                     : analytic::earthPressure(phi[k], law.deltaFromPhi ? phi[k] : (*law.delta)[k], false);
      u = solidPressureEnergy(hs[k], K, (*law.gp)[k], cohesion[k], rhoS[k]);
    }
    pot += static_cast<long double>((rhoS[k] * (hs[k] * z + u / kGravity) + rhoF * h[k] * (z + hs[k] + 0.5 * h[k])) * area);
    if (h[k] > 0 || hs[k] > 0) ++t.wetCells;
  }
  t.volF = static_cast<double>(vf);
  t.volS = static_cast<double>(vs);
  t.potential = static_cast<double>(pot);
  return t;
}

}  // namespace

/// The two-phase checker. Per step: stableDt() positive (infinite only when everything drained),
/// the step's CFL number dt * maxSpeed / dx (maxSpeed: the solver's two-phase CFL speed, which
/// stableDt() is built from) within the setting, all diagnostics and fields finite, h_f >= 0 and
/// h_s >= 0, nodata cells empty, non-negative outflow of each phase, the volume balance of each phase
/// (V_p + tallied outflow_p - V_p(0), the single-phase tolerance per phase: no mass moves between the
/// phases, so each is conserved on its own), the solver's volume sums against the fields', and a
/// generous kinetic-energy bound.
///
/// Energy: the single-phase bound (E_kin <= E_kin(0) + g dP + slope work + 20 %) is not checked here.
/// The two-phase model is not conservative for one g-weighted potential: the phases exchange energy
/// through drag and buoyancy (-gamma g_p h_s grad H), whose work depends on both densities and on the
/// relative velocity, the fluid sees the mixture surface b + h_s + h_f while the solids feel
/// -g_n h_s grad b with a lateral pressure reduced by (1 - gamma) and by cohesion, and virtual mass
/// redistributes momentum with a density-dependent weight; an exact released-energy budget would need
/// all of those terms per cell. Instead a generous bound that still catches instabilities (which grow
/// energy by orders of magnitude):
///   E_kin(t) <= 2 (E_kin(0) + g max(0, P(0) - P(t)) + W_f) + tiny,
/// with E_kin the solver's kinetic energy in joules (both phases with their densities) and P the
/// potential of both phases with their densities (solids under the fluid). In a scene without fluid
/// the model is the dry granular one, which has an exact energy: P's solid column term is then the
/// energy of the model's own lateral pressure (solidPressureEnergy: K, g_p and cohesion), not the
/// hydrostatic h_s / 2. (With the hydrostatic term, material with little or no lateral pressure,
/// e.g. 1 MPa of cohesion, that slid down its bed onto a thicker column raised P while the model
/// released energy: soak seed 14007166592872737771 failed at KE 5.8 times "released", for any dt.)
/// With fluid the hydrostatic mixture term stays: the solids' pressure then grows with the fluid's
/// depth (Pi ~ K (1 - gamma) g_p (h_s + h_f) / 2) and has no potential. Drag, Coulomb friction,
/// Manning and shocks only dissipate, the exchange terms only move energy between the phases. W_f is
/// the fluid's slope work, rho_f times the single-phase check's W over the mixture surface
/// (slopeWorkRate): the work its g_p < g pressure and its (g_p - g_n) h_f grad b source can do
/// against the g-weighted P; with cos^4 it is what accelerates a lake on a slope (a lake at rest is
/// not an equilibrium of those equations, spec section 1; soak seeds 12860602142559376500 and
/// 8017601764101274024 exceeded the bound without it). The factor 2 covers the solids' slope
/// correction (g_n < g, bounded by the released energy on the DEMs used) and the first-order
/// splitting error of the stiff sources; tiny = 8 eps g P(0)
/// sqrt(step) is the rounding noise of P (as in the single-phase check).
StressOutcome runDebrisScene(const StressScene& scene) {
  StressOutcome out;
  const Grid& g = scene.grid;
  const bool dbl = scene.precision == compute::Precision::Double;
  const double eps = dbl ? std::numeric_limits<double>::epsilon() : static_cast<double>(std::numeric_limits<float>::epsilon());
  const double area = g.dx * g.dx;
  const auto start = std::chrono::steady_clock::now();
  const flow::FlowSettings& s = scene.settings;
  const double rhoF = s.debris.fluidDensity;
  flow::FlowSolver solver(testContext(scene.precision), g, s);
  solver.setInput(scene.input);
  const std::vector<uint8_t>& mask = scene.input.mask;
  const std::vector<double>& bed = scene.input.bed;
  double bedMin = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < g.cells(); ++k)
    if (mask[k]) bedMin = std::min(bedMin, bed[k]);
  const double hDry = dbl ? s.hDry : static_cast<double>(static_cast<float>(s.hDry));

  std::vector<double> h = solver.h(), hs = solver.hs(), qx = solver.qx(), qy = solver.qy(), qsx, qsy;
  const flow::SlopeGravity sg = flow::computeSlopeGravity(g, scene.input.bed, scene.input.mask, s);
  SolidPressureLaw law;
  law.constantK = s.debris.earthPressure == flow::EarthPressure::Constant;
  law.kConst = s.debris.kConst;
  law.rhoF = rhoF;
  law.dry = std::all_of(scene.input.h.begin(), scene.input.h.end(), [](double x) { return x == 0; });
  law.deltaFromPhi = s.debris.deltaFromPhi;
  law.delta = &scene.input.delta;
  law.gp = &sg.gp;
  const std::vector<double> none;
  auto totals = [&]() {
    return debrisTotals(g, mask, bed, bedMin, law, h, hs, solver.solidScalar(1), law.dry ? solver.solidScalar(0) : none,
                        law.dry ? solver.solidScalar(3) : none);
  };
  const DebrisTotals t0 = totals();
  const double ekin0 = solver.diagnostics().kinetic;
  // The fluid's slope work (as the single-phase check's W): its momentum has the pressure at g_p
  // over the mixture surface and (g_p - g_n) h_f grad b (debris_stage.cl), which with cos^4
  // (g_p < g_n) accelerates a lake on a slope: the spec's price of the slope-aligned pressure. The
  // rate of the state at the start of each step (the end of the one before) and at its end.
  auto fluidSlopeWorkRate = [&]() { return rhoF * slopeWorkRate(g, mask, bed, &hs, h, qx, qy, sg.gp, sg.gn, hDry); };
  double slopeWork = 0, rateBefore = fluidSlopeWorkRate();  // [J], [W]
  double hMaxF = 0, hMaxS = 0;
  for (std::size_t k = 0; k < g.cells(); ++k) hMaxF = std::max(hMaxF, h[k]), hMaxS = std::max(hMaxS, hs[k]);
  std::vector<uint8_t> everWet(g.cells(), 0);
  int everWetCount = 0;
  auto markWet = [&]() {
    for (std::size_t k = 0; k < g.cells(); ++k)
      if ((h[k] > 0 || hs[k] > 0) && !everWet[k]) everWet[k] = 1, ++everWetCount;
  };
  markWet();
  // Tolerances of the single-phase checker (see runStressScene), per phase.
  const double relVol = dbl ? 1e-11 : 1e-5;
  const double relDiag = 256 * eps;
  const double relCfl = dbl ? 1e-12 : 1e-5;

  double outF = 0, outS = 0;
  for (int st = 1; st <= scene.steps; ++st) {
    auto fail = [&](const std::string& what) { recordFailure(out, st, solver.time(), what); };
    const double stable = solver.stableDt();
    if (std::isnan(stable) || stable <= 0) {
      fail("stableDt() = " + num(stable));
      break;
    }
    if (std::isinf(stable)) {
      int wet = 0;
      for (std::size_t k = 0; k < g.cells(); ++k) wet += mask[k] && (h[k] > 0 || hs[k] > 0);
      if (wet == 0) break;
      fail("stableDt() is infinite with " + std::to_string(wet) + " wet cells");
      break;
    }
    const double dt = scene.dtFraction * stable *
                      (std::getenv("TALUS_STRESS_DT_SCALE") ? std::atof(std::getenv("TALUS_STRESS_DT_SCALE")) : 1.0);
    const double speed0 = solver.diagnostics().maxSpeed;
    const double cfl = dt * speed0 / g.dx;
    out.cflUsed = std::max(out.cflUsed, cfl);
    if (!(dt <= stable * (1 + relCfl)) && !std::getenv("TALUS_STRESS_DT_SCALE")) {
      fail("dt " + num(dt) + " exceeds stableDt() " + num(stable));
      break;
    }
    if (!(cfl <= s.cfl * (1 + relCfl))) {
      fail("CFL " + num(cfl) + " exceeds the setting " + num(s.cfl) + " (dt " + num(dt) + ", speed " + num(speed0) + ")");
      break;
    }

    solver.step(dt);
    ++out.steps;
    const flow::FlowDiagnostics& dg = solver.diagnostics();
    if (!std::isfinite(dg.volume) || !std::isfinite(dg.outflow) || !std::isfinite(dg.kinetic) ||
        !std::isfinite(dg.maxSpeed) || !std::isfinite(dg.minH) || !std::isfinite(dg.volumeSolid) ||
        !std::isfinite(dg.outflowSolid)) {
      fail("non-finite diagnostics: volume " + num(dg.volume) + " solid " + num(dg.volumeSolid) + " outflow " +
           num(dg.outflow) + " solid " + num(dg.outflowSolid) + " kinetic " + num(dg.kinetic) + " maxSpeed " +
           num(dg.maxSpeed));
      break;
    }
    if (dg.outflow < 0 || dg.outflowSolid < 0) {
      fail("negative outflow: fluid " + num(dg.outflow) + " solid " + num(dg.outflowSolid) + " m^3");
      break;
    }
    outF += dg.outflow;
    outS += dg.outflowSolid;
    out.cflAfter = std::max(out.cflAfter, dt * dg.maxSpeed / g.dx);

    h = solver.h(), qx = solver.qx(), qy = solver.qy();
    hs = solver.hs(), qsx = solver.qsx(), qsy = solver.qsy();
    std::string bad;
    for (std::size_t k = 0; k < g.cells() && bad.empty(); ++k) {
      const std::string vals = ": h_f " + num(h[k]) + " q_f (" + num(qx[k]) + ", " + num(qy[k]) + ") h_s " + num(hs[k]) +
                               " q_s (" + num(qsx[k]) + ", " + num(qsy[k]) + ")";
      if (!std::isfinite(h[k]) || !std::isfinite(qx[k]) || !std::isfinite(qy[k]) || !std::isfinite(hs[k]) ||
          !std::isfinite(qsx[k]) || !std::isfinite(qsy[k]))
        bad = "non-finite field at " + cellText(g, k) + vals;
      else if (h[k] < 0 || hs[k] < 0)
        bad = "negative thickness at " + cellText(g, k) + vals;
      else if (!mask[k] && (h[k] != 0 || qx[k] != 0 || qy[k] != 0 || hs[k] != 0 || qsx[k] != 0 || qsy[k] != 0))
        bad = "material on nodata " + cellText(g, k) + vals;
      else if (h[k] <= hDry && (qx[k] != 0 || qy[k] != 0))
        bad = "fluid momentum on a fluid-dry " + cellText(g, k) + vals;
    }
    if (!bad.empty()) {
      fail(bad);
      break;
    }
    markWet();
    const DebrisTotals t = totals();

    // Volume balance of each phase.
    const double balF = t.volF + outF - t0.volF, balS = t.volS + outS - t0.volS;
    const double tolF = relVol * t0.volF + 4 * eps * hMaxF * area * everWetCount;
    const double tolS = relVol * t0.volS + 4 * eps * hMaxS * area * everWetCount;
    out.balanceRatio = std::max({out.balanceRatio, tolF > 0 ? std::fabs(balF) / tolF : (balF != 0 ? 1e300 : 0.0),
                                 tolS > 0 ? std::fabs(balS) / tolS : (balS != 0 ? 1e300 : 0.0)});
    if (t0.volF > 0) out.balanceRelative = std::max(out.balanceRelative, std::fabs(balF) / t0.volF);
    if (t0.volS > 0) out.balanceRelative = std::max(out.balanceRelative, std::fabs(balS) / t0.volS);
    if (!(std::fabs(balF) <= tolF)) {
      fail("fluid volume balance V_f + outflow_f - V_f0 = " + num(balF) + " m^3 (V_f " + num(t.volF) + ", outflow " +
           num(outF) + ", V_f0 " + num(t0.volF) + ", tolerance " + num(tolF) + ")");
      break;
    }
    if (!(std::fabs(balS) <= tolS)) {
      fail("solid volume balance V_s + outflow_s - V_s0 = " + num(balS) + " m^3 (V_s " + num(t.volS) + ", outflow " +
           num(outS) + ", V_s0 " + num(t0.volS) + ", tolerance " + num(tolS) + ")");
      break;
    }
    if (!(std::fabs(dg.volume - t.volF) <= relDiag * t.volF + 1e-300) ||
        !(std::fabs(dg.volumeSolid - t.volS) <= relDiag * t.volS + 1e-300)) {
      fail("diagnostics volumes (fluid " + num(dg.volume) + ", solid " + num(dg.volumeSolid) + ") differ from the fields' (" +
           num(t.volF) + ", " + num(t.volS) + ")");
      break;
    }

    // Kinetic energy: the generous bound documented above.
    const double rateAfter = fluidSlopeWorkRate();
    slopeWork += dt * std::max(rateBefore, rateAfter);
    rateBefore = rateAfter;
    const double released = std::max(0.0, kGravity * (t0.potential - t.potential));
    const double bound = 2 * (ekin0 + released + slopeWork) +
                         8 * eps * kGravity * t0.potential * std::sqrt(static_cast<double>(st)) + 1e-300;
    out.energyRatio = std::max(out.energyRatio, dg.kinetic / bound);
    if (ekin0 + released + slopeWork > 0)
      out.energyGainFraction = std::max(out.energyGainFraction, dg.kinetic / (ekin0 + released + slopeWork));
    if (!(dg.kinetic <= bound)) {
      // Where: the cell with the largest kinetic energy density.
      std::size_t c = 0;
      double best = -1;
      for (std::size_t k = 0; k < g.cells(); ++k) {
        const double e = (h[k] > hDry ? (qx[k] * qx[k] + qy[k] * qy[k]) / h[k] : 0.0) * rhoF +
                         (hs[k] > hDry ? (qsx[k] * qsx[k] + qsy[k] * qsy[k]) / hs[k] : 0.0) * 2000.0;
        if (e > best) best = e, c = k;
      }
      fail("kinetic energy " + num(dg.kinetic) + " J exceeds 2 (E_kin(0) + g dP + W_f) + rounding = 2 (" + num(ekin0) + " + " +
           num(released) + " + " + num(slopeWork) + ") + ... = " + num(bound) + " J; most energetic " + cellText(g, c) + ": h_f " + num(h[c]) +
           " q_f (" + num(qx[c]) + ", " + num(qy[c]) + ") h_s " + num(hs[c]) + " q_s (" + num(qsx[c]) + ", " +
           num(qsy[c]) + ") bed " + num(bed[c]) + " (initial h_f " + num(scene.input.h[c]) + ", h_s " +
           num(scene.input.hs[c]) + ")");
      if (std::getenv("TALUS_STRESS_DUMP")) {
        for (std::size_t k = 0; k < g.cells(); ++k)
          std::printf("cell %s bed %.4f hs0 %.4g hf0 %.4g | hs %.6g qs (%.4g %.4g) hf %.6g qf (%.4g %.4g)\n",
                      cellText(g, k).c_str(), bed[k], scene.input.hs[k], scene.input.h[k], hs[k], qsx[k], qsy[k], h[k],
                      qx[k], qy[k]);
      }
      break;
    }
  }
  out.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace talus::test
