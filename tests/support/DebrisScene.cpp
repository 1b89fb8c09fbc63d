// Scene builder, state read-back, stepping loop and host drag closure for the two-phase
// verification tests; see DebrisScene.hpp.
#include "support/DebrisScene.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/Constants.hpp"
#include "support/GranularAnalytic.hpp"

namespace talus::test {

flow::FlowSettings granularBetweenWalls(double k) {
  flow::FlowSettings s;
  s.twoPhase = true;
  s.edge = flow::Boundary::Wall;
  s.debris.earthPressure = flow::EarthPressure::Constant;
  s.debris.kConst = k;
  s.debris.deltaFromPhi = false;
  return s;
}

flow::FlowInput debrisInput(const Grid& grid, const SolidMaterial& mat, double manning) {
  const std::size_t n = grid.cells();
  flow::FlowInput in;
  in.mask.assign(n, 1);
  in.bed.assign(n, 0.0);
  in.manning.assign(n, manning);
  in.h.assign(n, 0.0);
  in.qx.assign(n, 0.0);
  in.qy.assign(n, 0.0);
  in.hs.assign(n, 0.0);
  in.qsx.assign(n, 0.0);
  in.qsy.assign(n, 0.0);
  in.phi.assign(n, mat.phi);
  in.rhoS.assign(n, mat.rhoS);
  in.grain.assign(n, mat.grain);
  in.delta.assign(n, mat.delta);
  in.cohesion.assign(n, mat.cohesion);
  return in;
}

namespace {

std::vector<double> ratio(const std::vector<double>& q, const std::vector<double>& h, double hDry) {
  std::vector<double> u(h.size(), 0.0);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (h[k] > hDry) u[k] = q[k] / h[k];
  return u;
}

double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

std::vector<double> DebrisState::usx(double hDry) const { return ratio(qsx, hs, hDry); }
std::vector<double> DebrisState::usy(double hDry) const { return ratio(qsy, hs, hDry); }
std::vector<double> DebrisState::ufx(double hDry) const { return ratio(qfx, hf, hDry); }
std::vector<double> DebrisState::ufy(double hDry) const { return ratio(qfy, hf, hDry); }

double DebrisState::maxSpeed(double hDry) const {
  double m = 0;
  for (const auto& u : {usx(hDry), usy(hDry), ufx(hDry), ufy(hDry)})
    for (double x : u) m = std::max(m, std::fabs(x));
  return m;
}

double DebrisState::volumeSolid(double dx) const { return sum(hs) * dx * dx; }
double DebrisState::volumeFluid(double dx) const { return sum(hf) * dx * dx; }

double DebrisState::solidCentroidX(const Grid& grid) const {
  double m = 0, mx = 0;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const double h = hs[grid.index(i, j)];
      m += h;
      mx += h * cellX(grid, i);
    }
  return mx / m;
}

DebrisState readState(const flow::FlowSolver& solver) {
  DebrisState s;
  s.hs = solver.hs();
  s.qsx = solver.qsx();
  s.qsy = solver.qsy();
  s.hf = solver.h();
  s.qfx = solver.qx();
  s.qfy = solver.qy();
  return s;
}

int advance(flow::FlowSolver& solver, const RunLimits& limits,
            const std::function<bool(const flow::FlowSolver&)>& onStep) {
  const double tEnd = limits.endTime;
  // Stop when what is left is a round-off sliver of the end time (no step of ~1e-16 s).
  const double sliver = std::isfinite(tEnd) ? 1e-12 * std::max(1.0, std::fabs(tEnd)) : 0.0;
  int steps = 0;
  while (steps < limits.maxSteps && solver.time() < tEnd - sliver) {
    const double stable = solver.stableDt();
    if (!std::isfinite(stable) || !(stable > 0))
      throw std::runtime_error("advance: no finite stable time step at t = " + std::to_string(solver.time()));
    solver.step(std::min(stable, tEnd - solver.time()));
    ++steps;
    if (onStep && !onStep(solver)) break;
  }
  return steps;
}

namespace drag {

double viscosity(const flow::DebrisSettings& s, double alphaS) { return s.viscA * std::exp(s.viscB * alphaS); }

double settlingVelocity(double d, double rhoS, double rhoF, double eta) {
  const double grain = std::max(d, 1e-7);
  const double nu = eta / rhoF;                            // kinematic viscosity [m^2/s]
  const double rel = std::max(0.0, rhoS / rhoF - 1.0);     // submerged specific gravity
  // Stokes (1851): U = R g d^2 / (18 nu).
  auto stokes = [&] { return rel * kGravity * grain * grain / (18.0 * nu); };
  // Zanke (1977): U = 10 nu / d (sqrt(1 + 0.01 R g d^3 / nu^2) - 1).
  auto zanke = [&] {
    const double dstar3 = rel * kGravity * grain * grain * grain / (nu * nu);
    return 10.0 * nu / grain * (std::sqrt(1.0 + 0.01 * dstar3) - 1.0);
  };
  constexpr double kFine = 1e-4, kCoarse = 1e-3;
  if (grain <= kFine) return stokes();
  if (grain >= kCoarse) return zanke();
  const double w = (grain - kFine) / (kCoarse - kFine);
  return stokes() + w * (zanke() - stokes());
}

double coefficient(const flow::DebrisSettings& s, double alphaS, double rhoS, double d) {
  if (s.drag == flow::DragLaw::Off) return 0.0;
  const double as = std::clamp(alphaS, 1e-6, 1.0 - 1e-6), af = 1.0 - as;
  const double gamma = s.fluidDensity / rhoS;
  const double eta = viscosity(s, as);
  const double ut = settlingVelocity(d, rhoS, s.fluidDensity, eta);
  const double rep = s.fluidDensity * d * ut / eta;                // particle Reynolds number
  const double F = gamma / 180.0 * std::pow(af / as, 3.0) * rep;   // solid-like (Richardson-Zaki) part
  const double G = std::pow(af, s.dragM - 1.0);                     // fluid-like part
  const double P = std::pow(as, s.dragPExponent);                   // interpolation P = alpha_s^m
  const double Sp = (P / as + (1.0 - P) / af) * s.dragKappa;       // smoothing function [m/s]
  const double denom = ut * (P * F + (1.0 - P) * G) + Sp;
  const int j = s.drag == flow::DragLaw::Quadratic ? 2 : 1;
  return s.dragMultiplier * as * af * (1.0 - gamma) * kGravity / std::pow(denom, j);
}

double virtualMassCoefficient(double alphaS) { return 0.5 * (1.0 + 2.0 * alphaS) / (1.0 - alphaS); }

double UniformLayer::rate() const { return analytic::linearDragRate(ms, mf, k, mvm); }

UniformLayer uniformLayer(const flow::DebrisSettings& s, double hs, double hf, double rhoS, double d) {
  const double H = hs + hf, as = hs / H;
  UniformLayer l;
  l.ms = rhoS * hs;
  l.mf = s.fluidDensity * hf;
  // dq_s/dt = H C w |w|^(j-1) per unit solid density: the force per area on the solids is rho_s H C.
  l.k = rhoS * H * coefficient(s, as, rhoS, d);
  l.mvm = s.virtualMass ? virtualMassCoefficient(as) * s.fluidDensity * hs : 0.0;
  return l;
}

}  // namespace drag

}  // namespace talus::test
