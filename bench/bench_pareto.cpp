// Accuracy against run time (issue 6, item 3; not a test): sweeps the numerical settings of the
// shallow-water / two-phase grid solver on the analytic cases of the verification suite, and the
// stiffness (Young's modulus E or Sound Speed) and particles per cell of the particle mode, and
// prints / writes per run the error, the wall time and the throughput. tools/validation/
// plot_pareto.py draws error against wall time with the Pareto front; the findings are in
// docs/validation_parts/pareto.md.
//
//   bench_pareto [--quick] [--csv FILE] [--cases ritter,stoker,thacker,mangeney,particles]
//                [--limiters minmod,vanleer,mc,none] [--precision float,double] [--cfl 0.25,0.4,0.5]
//                [--levels N] [--E 1e9,1e8,...] [--sound-speed C,...] [--ppc 4,1]
//                [--particle-precision double] [--particle-time T] [--particle-cfl 0.2,0.1]
//   device: TALUS_DEVICE (index or name substring, as for the tests; support/TestDevice.hpp)
//
// Cost on two shared PoCL cores: the default sweep (4 grid cases x 4 limiters x 2 precisions x
// 3 CFLs x 3 to 5 grids = 432 runs, then the particle dam break at 4 and 1 particles per cell for
// E = 1e9 ... 1e5 Pa) about 8 + 5 min; --quick (2 grids, E = 1e8 ... 1e6 Pa at 4 per cell for 1 s)
// about 1 min. 9 per cell is expensive (4750 particles): --cases particles --ppc 9
// --E 1e8,1e7,1e6,1e5 takes about 8 min.
//
// Grid cases (scenes, end times and error norms exactly as in the verification tests; the analytic
// solutions come from tests/support, linked as talus_test_support):
//  - ritter:   tests/verification/test_dambreak.cpp, 1D dam break onto a dry bed (SWASHES 4.1.1),
//              domain [0, 100] m, dam at 50 m, hL = 1 m, t = 4 s; L1 = sum |h_i - hbar_i| dx [m^2]
//              against exact cell averages (analytic::cellAverage1D), whole domain.
//  - stoker:   the same with hR = 0.1 m (SWASHES 4.1.2).
//  - thacker:  tests/verification/test_thacker.cpp, planar oscillation in a paraboloid (SWASHES
//              4.2.2), [0, 4]^2 m, one period; L1 = sum |h_ij - h_exact(x_ij)| dx^2 [m^3].
//  - mangeney: tests/verification/test_granular.cpp, two-phase model in its dry granular limit, dam
//              break on a 35-degree plane, delta 22 deg, K = 1, cos^2 pressure, t = 3 s; L1 over the
//              window [17, 50] m against exact cell averages (MangeneyDamBreak::integralH) [m^2].
// Each also reports the relative L1 (divided by the exact mass in the compared region).
// Wall time: the stepping loop only, after a warm-up run of the same case, precision and limiter
// (PoCL compiles kernels lazily at their first launch, which must not be charged to one run).
//
// Particle case (stiffness trade-off): the cohesionless particle dam break of
// tests/verification/test_particle_dambreak.cpp (Mangeney set-up on a 30 m wide strip, E swept,
// nu = 0.3, phi = 1 deg, c = 0, K = 1, t = 3 s, dx = 1 m) with 1, 4 or 9 particles per cell. Per run:
// L1 of the middle band's column thickness against Mangeney over [17, 50] m (as the test), the front
// (largest x of the band's particles), and the P2G thickness field on the grid; relative to the
// stiffest run of the same particles-per-cell: the front change |dx_f| / (x_f - x0) (the runout past
// the dam) and the thickness-field change sum |H - H_ref| / sum H_ref. The particle sub-step is
// dt_p = cfl h / (c + |v|max) with c the elastic P-wave speed sqrt((K + 4G/3) / rho) of E and nu,
// or the Sound Speed when given (ParticleSettings::soundSpeed), so dt_p ~ E^-1/2. A second particle
// CFL (--particle-cfl 0.2,0.1) at the same E measures the sensitivity of these changes to the time
// step alone (the floor below which a change says nothing about the stiffness).
#include "bench_args.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "compute/Context.hpp"
#include "compute/Precision.hpp"
#include "core/Constants.hpp"
#include "core/Error.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/FlowSolver.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSolver.hpp"
#include "support/Analytic.hpp"
#include "support/DebrisScene.hpp"
#include "support/FlowScene.hpp"
#include "support/GranularAnalytic.hpp"
#include "support/ParticleDamBreakScene.hpp"
#include "support/TestDevice.hpp"

using namespace talus;
namespace an = talus::analytic;
namespace fl = talus::flow;
namespace pa = talus::particles;
using compute::Precision;
using talus::bench::split;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// One row of the CSV (grid or particle run).
struct Row {
  std::string kind, name;  // "grid" / "particles"; case name
  int n = 0;               // cells along x (grid) or particles per cell (particles)
  double dx = 0;
  std::string limiter = "", precision = "";
  double cfl = 0;
  double E = 0, waveSpeed = 0;  // particles only
  int ppc = 0;
  std::size_t cells = 0, particles = 0;
  double l1 = 0, relL1 = 0;
  double front = 0, frontExact = 0;
  double frontChange = std::nan(""), fieldChange = std::nan("");  // particles: relative to the stiffest run
  long long steps = 0;       // grid steps or particle sub-steps
  double wall = 0;
  double rate = 0;           // cell-updates/s or particle-updates/s
};

// ------------------------------------------------------------------------------------------------
// Grid cases

struct GridResult {
  double l1 = 0, mass = 0;
  int steps = 0;
  double wall = 0;
  std::size_t cells = 0;
  double dx = 0;
};

/// Runs `solver` to tEnd with dt = min(stableDt, tEnd - t) (or at most maxSteps), timing the loop.
template <class Solver>
std::pair<int, double> timedAdvance(compute::Context& ctx, Solver& solver, double tEnd, int maxSteps) {
  const auto t0 = std::chrono::steady_clock::now();
  const int steps = talus::test::advance(solver, maxSteps > 0 ? talus::test::RunLimits::steps(maxSteps)
                                                              : talus::test::RunLimits::until(tEnd));
  ctx.finish();
  return {steps, seconds(t0)};
}

fl::FlowSettings classicalSettings(fl::Limiter lim, double cfl) {
  fl::FlowSettings s;
  s.limiter = lim;
  s.riemann = fl::RiemannSolver::HLLC;
  s.cfl = cfl;
  s.edge = fl::Boundary::Wall;
  s.slopeCorrection = false;  // the exact solutions are for classical SWE with g
  return s;
}

// Dam breaks (test_dambreak.cpp).
constexpr double kDbLength = 100.0, kDbDam = 50.0, kDbHL = 1.0, kDbT = 4.0;

GridResult runDamBreak(int nx, double hR, fl::Limiter lim, Precision prec, double cfl, int maxSteps) {
  const double dx = kDbLength / nx;
  const Grid grid = Grid::make(nx, 1, dx);
  const auto input = talus::test::makeInput(
      grid, [](double, double) { return 0.0; }, [&](double x, double) { return x < kDbDam ? kDbHL : hR; });
  compute::Context& ctx = talus::test::testContext(prec);
  fl::FlowSolver solver(ctx, grid, classicalSettings(lim, cfl));
  solver.setInput(input);
  GridResult r;
  std::tie(r.steps, r.wall) = timedAdvance(ctx, solver, kDbT, maxSteps);
  if (maxSteps > 0) return r;
  const std::vector<double> h = solver.h();
  std::vector<double> ref(nx);
  for (int i = 0; i < nx; ++i) {
    ref[i] = an::cellAverage1D([&](double x) { return an::stoker(x, kDbT, kDbDam, kDbHL, hR, kGravity).h; },
                               talus::test::cellX(grid, i), dx);
    r.mass += ref[i] * dx;
  }
  r.l1 = an::l1(h, ref, dx);
  r.cells = grid.cells();
  r.dx = dx;
  return r;
}

// Thacker (test_thacker.cpp).
GridResult runThacker(int n, fl::Limiter lim, Precision prec, double cfl, int maxSteps) {
  const an::ThackerPlanar th;
  const double dx = 4.0 / n;
  const Grid grid = Grid::make(n, n, dx);
  const double u0 = th.u(0.0), v0 = th.v(0.0);
  const auto input = talus::test::makeInput(
      grid, [&](double x, double y) { return th.bed(x, y); }, [&](double x, double y) { return th.h(x, y, 0.0); },
      [&](double x, double y) { return th.h(x, y, 0.0) * u0; }, [&](double x, double y) { return th.h(x, y, 0.0) * v0; });
  compute::Context& ctx = talus::test::testContext(prec);
  fl::FlowSolver solver(ctx, grid, classicalSettings(lim, cfl));
  solver.setInput(input);
  GridResult r;
  const double T = th.period();
  std::tie(r.steps, r.wall) = timedAdvance(ctx, solver, T, maxSteps);
  if (maxSteps > 0) return r;
  const std::vector<double> h = solver.h();
  std::vector<double> ref(grid.cells());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) ref[grid.index(i, j)] = th.h(talus::test::cellX(grid, i), talus::test::cellY(grid, j), T);
  r.l1 = an::l1(h, ref, dx * dx);
  r.mass = th.volume();
  r.cells = grid.cells();
  r.dx = dx;
  return r;
}

// Mangeney (test_granular.cpp): two-phase model, dry granular limit.
constexpr double kMgTheta = 35.0, kMgDelta = 22.0, kMgH0 = 1.0, kMgX0 = 20.0, kMgL = 50.0, kMgT = 3.0;
constexpr double kMgWindow = 17.0;

GridResult runMangeney(int nx, fl::Limiter lim, Precision prec, double cfl, int maxSteps) {
  const double theta = kMgTheta * kDeg, delta = kMgDelta * kDeg, dx = kMgL / nx;
  const Grid grid = Grid::make(nx, 1, dx);
  talus::test::SolidMaterial mat;
  mat.phi = mat.delta = delta;
  mat.cohesion = 0.0;
  mat.grain = 1e-6;
  fl::FlowInput in = talus::test::debrisInput(grid, mat);
  for (int i = 0; i < nx; ++i) {
    const double x = talus::test::cellX(grid, i);
    in.bed[i] = -std::tan(theta) * x;
    in.hs[i] = x < kMgX0 ? kMgH0 : 0.0;
  }
  fl::FlowSettings s;
  s.limiter = lim;
  s.cfl = cfl;
  s.twoPhase = true;
  s.edge = fl::Boundary::Wall;
  s.debris.earthPressure = fl::EarthPressure::Constant;
  s.debris.kConst = 1.0;
  s.debris.deltaFromPhi = false;
  s.debris.filmThickness = 0.0;  // continuum solution down to h = 0 (see test_granular.cpp, "Film")
  compute::Context& ctx = talus::test::testContext(prec);
  fl::FlowSolver solver(ctx, grid, s);
  solver.setInput(in);
  GridResult r;
  std::tie(r.steps, r.wall) = timedAdvance(ctx, solver, kMgT, maxSteps);
  if (maxSteps > 0) return r;
  const auto st = talus::test::readState(solver);
  const an::MangeneyDamBreak d = an::mangeneyFromSlope(kMgH0, theta, delta, 1.0, false, kMgX0);
  for (int i = 0; i < nx; ++i) {
    const double xl = i * dx, xr = xl + dx;
    if (xl < kMgWindow - 1e-9) continue;
    const double exact = d.integralH(xl, xr, kMgT);
    r.l1 += std::fabs(st.hs[i] * dx - exact);
    r.mass += exact;
  }
  r.cells = grid.cells();
  r.dx = dx;
  return r;
}

using GridRunner = std::function<GridResult(int, fl::Limiter, Precision, double, int)>;

struct GridCase {
  std::string name;
  std::vector<int> levels;
  int defaultLevels;  ///< levels run unless --levels (or --quick) says otherwise
  GridRunner run;
};

// ------------------------------------------------------------------------------------------------
// Particle dam break (test_particle_dambreak.cpp)

struct ParticleResult {
  double l1 = 0, mass = 0, front = 0, frontExact = 0, wall = 0, waveSpeed = 0;
  long long subSteps = 0;
  std::size_t particles = 0;
  std::vector<double> thickness;  // P2G thickness on the grid at T
};

ParticleResult runParticleDamBreak(double E, double soundSpeed, double ppc, Precision prec, double T, double cfl) {
  const talus::test::ParticleDamBreakScene scene = talus::test::makeParticleDamBreak(ppc);
  const double theta = scene.theta, delta = scene.delta, H0 = scene.H0, x0 = scene.x0, dx = scene.dx;
  const int nx = scene.nx, ny = scene.ny;
  const Grid& g = scene.grid;
  pa::ParticleSettings ps;
  ps.youngModulus = E;
  ps.soundSpeed = soundSpeed;
  if (cfl > 0) ps.cfl = cfl;
  ps.earthPressure = pa::ParticleEarthPressure::Constant;
  ps.kConst = 1.0;
  compute::Context& ctx = talus::test::testContext(prec);
  pa::ParticleSolver solver(ctx, g, scene.terrain, ps);
  solver.setParticles(scene.seeded, scene.material);
  ParticleResult r;
  const double rho = 2000.0;
  r.waveSpeed = soundSpeed > 0 ? soundSpeed
                               : std::sqrt(ps.inPlaneWaveModulus() / rho);
  const auto t0 = std::chrono::steady_clock::now();
  constexpr int kOuter = 30;  // as the test: 30 outer steps of T / 30, sub-stepped by the solver
  for (int k = 0; k < kOuter; ++k) {
    solver.step(T / kOuter);
    r.subSteps += solver.diagnostics().subSteps;
  }
  ctx.finish();
  r.wall = seconds(t0);
  const pa::ParticleState s = solver.state();
  r.particles = s.size();
  const double yc = 0.5 * ny * dx, band = 3.0;
  std::vector<double> column(nx, 0.0);
  for (std::size_t q = 0; q < s.size(); ++q) {
    if (std::fabs(s.y[q] - yc) > band || !(s.x[q] >= 0)) continue;
    r.front = std::max(r.front, s.x[q]);
    const int i = static_cast<int>(s.x[q] / dx);
    if (i < nx) column[i] += s.mass[q] / rho;
  }
  const an::MangeneyDamBreak exact = an::mangeneyFromSlope(H0, theta, delta, 1.0, false, x0);
  for (int i = 17; i < nx; ++i) {
    const double h = column[i] / (2 * band * dx);
    const double hbar = exact.integralH(i * dx, (i + 1) * dx, T) / dx;
    r.l1 += std::fabs(h - hbar) * dx;
    r.mass += hbar * dx;
  }
  r.frontExact = exact.front(T);
  r.thickness = solver.gridFields().thickness;
  return r;
}

// ------------------------------------------------------------------------------------------------
// Output

void printRow(const Row& r) {
  if (r.kind == "grid")
    std::printf("%-9s n %4d  %-7s %-6s cfl %.2f  L1 %.4e (rel %.3e)  %6d steps  %8.3f s  %10.4g cell-updates/s\n",
                r.name.c_str(), r.n, r.limiter.c_str(), r.precision.c_str(), r.cfl, r.l1, r.relL1,
                static_cast<int>(r.steps), r.wall, r.rate);
  else
    std::printf("%-9s ppc %d  E %.0e Pa  c %8.1f m/s  %-6s  %5zu particles  L1 %.4f (rel %.3f)  front %.2f m "
                "(exact %.2f)  dfront %.2e  dfield %.2e  %7lld sub-steps  %8.2f s  %10.4g particle-updates/s\n",
                r.name.c_str(), r.ppc, r.E, r.waveSpeed, r.precision.c_str(), r.particles, r.l1, r.relL1, r.front,
                r.frontExact, r.frontChange, r.fieldChange, r.steps, r.wall, r.rate);
  std::fflush(stdout);
}

void writeCsv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  if (!f) {
    std::fprintf(stderr, "bench_pareto: cannot write %s\n", path.c_str());
    return;
  }
  f << "kind,case,n,dx_m,limiter,precision,cfl,E_Pa,wave_speed_m_s,ppc,cells,particles,l1,rel_l1,front_m,"
       "front_exact_m,front_change,field_change,steps,wall_s,updates_per_s\n";
  char buf[1024];
  for (const Row& r : rows) {
    std::snprintf(buf, sizeof buf, "%s,%s,%d,%.6g,%s,%s,%.3g,%.6g,%.6g,%d,%zu,%zu,%.8g,%.8g,%.6g,%.6g,%.6g,%.6g,%lld,%.6g,%.6g\n",
                  r.kind.c_str(), r.name.c_str(), r.n, r.dx, r.limiter.c_str(), r.precision.c_str(), r.cfl, r.E,
                  r.waveSpeed, r.ppc, r.cells, r.particles, r.l1, r.relL1, r.front, r.frontExact, r.frontChange,
                  r.fieldChange, r.steps, r.wall, r.rate);
    f << buf;
  }
}

void usage() {
  std::fprintf(stderr,
               "usage: bench_pareto [--quick] [--csv FILE] [--cases ritter,stoker,thacker,mangeney,particles]\n"
               "                    [--limiters minmod,vanleer,mc,none] [--precision float,double] [--cfl 0.25,0.4,0.5]\n"
               "                    [--levels N] [--E 1e10,1e9,1e8,1e7,1e6] [--sound-speed C1,C2,...] [--ppc 1,4,9]\n"
               "                    [--particle-precision double] [--particle-time T] [--particle-cfl 0.2,0.1]\n");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string csv;
  std::vector<std::string> cases = {"ritter", "stoker", "thacker", "mangeney", "particles"};
  std::vector<std::string> limiters = {"minmod", "vanleer", "mc", "none"}, precisions = {"float", "double"};
  std::vector<std::string> cfls = {"0.25", "0.4", "0.5"};
  std::vector<std::string> Es = {"1e9", "1e8", "1e7", "1e6", "1e5"}, sounds, ppcs = {"4", "1"};
  std::string particlePrecision = "double";
  std::vector<std::string> particleCfls = {"0.2"};
  double particleT = 3.0;
  int levels = 0;  // 0: each case's default
  bool setE = false, setPpc = false, setLevels = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool more = a + 1 < argc;
    if (arg == "--quick") quick = true;
    else if (arg == "--csv" && more) csv = argv[++a];
    else if (arg == "--cases" && more) cases = split(argv[++a]);
    else if (arg == "--limiters" && more) limiters = split(argv[++a]);
    else if (arg == "--precision" && more) precisions = split(argv[++a]);
    else if (arg == "--cfl" && more) cfls = split(argv[++a]);
    else if (arg == "--levels" && more) levels = std::atoi(argv[++a]), setLevels = true;
    else if (arg == "--E" && more) Es = split(argv[++a]), setE = true;
    else if (arg == "--sound-speed" && more) sounds = split(argv[++a]);
    else if (arg == "--ppc" && more) ppcs = split(argv[++a]), setPpc = true;
    else if (arg == "--particle-precision" && more) particlePrecision = argv[++a];
    else if (arg == "--particle-time" && more) particleT = std::atof(argv[++a]);
    else if (arg == "--particle-cfl" && more) particleCfls = split(argv[++a]);
    else {
      usage();
      return 1;
    }
  }
  if (quick) {
    if (!setLevels) levels = 2;
    if (!setPpc && !setE) particleT = 1.0;
    if (!setE) Es = {"1e8", "1e7", "1e6"};
    if (!setPpc) ppcs = {"4"};
  }
  // Finest level last; the dam breaks and Mangeney are 1D (one row of cells).
  std::vector<GridCase> gridCases = {
      {"ritter", {100, 200, 400, 800, 1600}, 5,
       [](int n, fl::Limiter l, Precision p, double c, int m) { return runDamBreak(n, 0.0, l, p, c, m); }},
      {"stoker", {100, 200, 400, 800, 1600}, 5,
       [](int n, fl::Limiter l, Precision p, double c, int m) { return runDamBreak(n, 0.1, l, p, c, m); }},
      // 200^2 costs 30 to 60 s per run on two PoCL cores: only with --levels 4.
      {"thacker", {25, 50, 100, 200}, 3, runThacker},
      {"mangeney", {100, 200, 400, 800, 1600}, 5, runMangeney},
  };
  std::vector<Row> rows;
  const auto start = std::chrono::steady_clock::now();
  try {
    std::printf("device: %s\n\n", talus::test::testDevice().describe().c_str());
    for (GridCase& gc : gridCases) {
      if (std::find(cases.begin(), cases.end(), gc.name) == cases.end()) continue;
      const int want = levels > 0 ? levels : gc.defaultLevels;
      const int nl = std::max(1, std::min(want, static_cast<int>(gc.levels.size())));
      gc.levels.resize(nl);
      for (const std::string& pn : precisions) {
        const Precision prec = compute::parsePrecision(pn);
        for (const std::string& ln : limiters) {
          const fl::Limiter lim = fl::parseLimiter(ln);
          gc.run(gc.levels.front(), lim, prec, 0.5, 0);  // warm-up: kernel builds and PoCL's lazy compiles
          for (const int n : gc.levels)
            for (const std::string& cn : cfls) {
              const double cfl = std::atof(cn.c_str());
              const GridResult g = gc.run(n, lim, prec, cfl, 0);
              Row r;
              r.kind = "grid";
              r.name = gc.name;
              r.n = n;
              r.dx = g.dx;
              r.limiter = ln;
              r.precision = compute::precisionName(prec);
              r.cfl = cfl;
              r.cells = g.cells;
              r.l1 = g.l1;
              r.relL1 = g.mass > 0 ? g.l1 / g.mass : std::nan("");
              r.steps = g.steps;
              r.wall = g.wall;
              r.rate = static_cast<double>(g.cells) * g.steps / g.wall;
              printRow(r);
              rows.push_back(r);
            }
        }
      }
      std::printf("\n");
    }
    if (std::find(cases.begin(), cases.end(), "particles") != cases.end()) {
      const Precision prec = compute::parsePrecision(particlePrecision);
      // Stiffness axis: E values (Sound Speed 0), then Sound Speed values at the first E.
      struct Stiff {
        double E, c, cfl;
      };
      std::vector<Stiff> stiff;
      for (const std::string& pc : particleCfls) {
        const double cfl = std::atof(pc.c_str());
        for (const std::string& e : Es) stiff.push_back({std::atof(e.c_str()), 0.0, cfl});
        for (const std::string& c : sounds)
          stiff.push_back({Es.empty() ? 1e7 : std::atof(Es.front().c_str()), std::atof(c.c_str()), cfl});
      }
      runParticleDamBreak(1e6, 0.0, 1, prec, 0.05, 0.0);  // warm-up
      for (const std::string& pc : ppcs) {
        const int ppc = std::atoi(pc.c_str());
        std::vector<ParticleResult> res;
        for (const Stiff& s : stiff) {
          res.push_back(runParticleDamBreak(s.E, s.c, ppc, prec, particleT, s.cfl));
          const ParticleResult& p = res.back();
          std::printf("  (ppc %d, E %.0e, c %.1f, particle CFL %.3g: %.2f s, %lld sub-steps)\n", ppc, s.E, p.waveSpeed,
                      s.cfl, p.wall, p.subSteps);
          std::fflush(stdout);
        }
        // Reference: the stiffest run (largest wave speed; of those, the smallest particle CFL).
        std::size_t ref = 0;
        for (std::size_t k = 1; k < res.size(); ++k)
          if (res[k].waveSpeed > res[ref].waveSpeed ||
              (res[k].waveSpeed == res[ref].waveSpeed && stiff[k].cfl < stiff[ref].cfl))
            ref = k;
        double refSum = 0;
        for (double v : res[ref].thickness) refSum += v;
        for (std::size_t k = 0; k < res.size(); ++k) {
          const ParticleResult& p = res[k];
          Row r;
          r.kind = "particles";
          r.name = stiff[k].c > 0 ? "particle_dambreak_c" : "particle_dambreak";
          r.n = ppc;
          r.ppc = ppc;
          r.dx = 1.0;
          r.precision = compute::precisionName(prec);
          r.cfl = stiff[k].cfl;
          r.E = stiff[k].E;
          r.waveSpeed = p.waveSpeed;
          r.particles = p.particles;
          r.cells = p.thickness.size();
          r.l1 = p.l1;
          r.relL1 = p.l1 / p.mass;
          r.front = p.front;
          r.frontExact = p.frontExact;
          r.frontChange = std::fabs(p.front - res[ref].front) / (res[ref].front - 20.0);
          double d = 0;
          for (std::size_t c = 0; c < p.thickness.size(); ++c) d += std::fabs(p.thickness[c] - res[ref].thickness[c]);
          r.fieldChange = d / refSum;
          r.steps = p.subSteps;
          r.wall = p.wall;
          r.rate = static_cast<double>(p.particles) * p.subSteps / p.wall;
          printRow(r);
          rows.push_back(r);
        }
        std::printf("\n");
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pareto: %s\n", e.what());
    if (!csv.empty()) writeCsv(csv, rows);
    return 1;
  }
  if (!csv.empty()) writeCsv(csv, rows);
  std::printf("sweep: %zu runs, %.1f s in all\n", rows.size(), seconds(start));
  return 0;
}
