// Helpers for the verification tests of the two-phase (solids + fluid) grid model
// (FlowSettings::twoPhase, kernels/flow/debris_stage.cl, spec section 4):
//  - a FlowInput with every two-phase map filled (mask 1, flat bed, no material, uniform solid
//    properties), which the tests then edit cell by cell;
//  - the two-phase state read back from a solver, with phase velocities and reductions (volume,
//    momentum, centroid, largest speed);
//  - a CFL stepping loop (dt = min(stableDt, T - t)) with a per-step callback;
//  - an independent host implementation of the drag closure of Pudasaini (2012) that the kernels
//    use (kernels/flow/debris_closures.cl), so a test can predict the exact drag coefficient C and
//    the relaxation rate of the phase velocities of a uniform layer.
//
// Coordinates follow support/FlowScene.hpp: x = (i + 1/2) dx along columns, y = (j + 1/2) dx along
// rows, in the solver's frame.
#pragma once
#include <functional>
#include <vector>

#include "compute/Precision.hpp"
#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/FlowSolver.hpp"
#include "support/FlowScene.hpp"

namespace talus::test {

/// Uniform solid properties of a scene (each becomes a full map of the FlowInput).
struct SolidMaterial {
  double phi = 0.5235987755982988;    ///< internal friction angle [rad] (30 degrees)
  double delta = 0.5235987755982988;  ///< bed friction angle [rad] (used when deltaFromPhi is off)
  double rhoS = 2500.0;               ///< solid density [kg/m^3]
  double grain = 0.01;                ///< grain size [m]
  double cohesion = 0.0;              ///< [Pa]
};

/// A two-phase FlowInput on `grid` with every map present: mask 1, bed 0, Manning `manning`, no
/// material (h = h_s = 0, at rest) and the uniform material `mat`.
flow::FlowInput debrisInput(const Grid& grid, const SolidMaterial& mat = {}, double manning = 0.0);

/// Settings of a dry granular test: the two-phase model between walls on every raster edge, the
/// constant earth-pressure coefficient `k`, the bed friction angle from the delta map.
flow::FlowSettings granularBetweenWalls(double k);

/// The two-phase state of a solver (downloaded).
struct DebrisState {
  std::vector<double> hs, qsx, qsy;  ///< solids [m], [m^2/s]
  std::vector<double> hf, qfx, qfy;  ///< fluid [m], [m^2/s]

  /// q / h where h > hDry, else 0 (the solver's velocity).
  std::vector<double> usx(double hDry) const;
  std::vector<double> usy(double hDry) const;
  std::vector<double> ufx(double hDry) const;
  std::vector<double> ufy(double hDry) const;
  /// Largest |u|, |v| of either phase over wet cells [m/s].
  double maxSpeed(double hDry) const;
  /// Sums of h_s and h_f times the cell area [m^3].
  double volumeSolid(double dx) const;
  double volumeFluid(double dx) const;
  /// Centroid sum x h_s / sum h_s of the solids along x [m] (cell centres of the solver's frame).
  double solidCentroidX(const Grid& grid) const;
};

DebrisState readState(const flow::FlowSolver& solver);

/// Steps `solver` with dt = min(stableDt, endTime - t) until `limits` (support/FlowScene.hpp),
/// calling `onStep` after every step (may be empty; returning false stops the loop). Returns the
/// number of steps. Throws std::runtime_error when the time step is not finite and positive.
int advance(flow::FlowSolver& solver, const RunLimits& limits,
            const std::function<bool(const flow::FlowSolver&)>& onStep = {});

/// Host implementation of the drag closure of the two-phase model (Pudasaini 2012, JGR 117,
/// F03010, eqs. 11-15; OpenLISEM Hazard P.31-P.35, P.72, P.73), written independently of the
/// kernels from those formulas, with the regularisations the kernels document
/// (kernels/flow/debris_closures.cl): alpha_s clamped to [1e-6, 1 - 1e-6] and the grain size to at
/// least 1e-7 m; settling velocity by Stokes for d <= 0.1 mm, Zanke (1977) for d >= 1 mm and a linear
/// blend in between.
namespace drag {

/// O'Brien-Julien viscosity a exp(b alpha_s) [Pa s].
double viscosity(const flow::DebrisSettings& s, double alphaS);
/// Settling velocity U_T of a grain of size d [m/s] in a fluid of density rhoF and viscosity eta.
double settlingVelocity(double d, double rhoS, double rhoF, double eta);
/// Drag coefficient C of dq_s/dt = H C (u_f - u_s) |u_f - u_s|^(j-1) (j = 1 linear: [1/s];
/// j = 2 quadratic: [1/m]); 0 when the drag law is Off.
double coefficient(const flow::DebrisSettings& s, double alphaS, double rhoS, double d);
/// Virtual-mass coefficient C_vm = (1 + 2 alpha_s) / (2 alpha_f) (P.35, alpha_u = alpha_f).
double virtualMassCoefficient(double alphaS);

/// The uniform layer h_s, h_f as seen by analytic::linearDragRelaxation / quadraticDragRelaxation
/// (support/GranularAnalytic.hpp): areal masses, the drag force coefficient k (force per area
/// k w |w|^(j-1) on the solids, k = rho_s H C) and the virtual mass mvm = C_vm rho_f h_s (0 when
/// virtual mass is off).
struct UniformLayer {
  double ms = 0, mf = 0, k = 0, mvm = 0;
  /// Decay rate of w = u_f - u_s: [1/s] (linear) or k' of dw/dt = -k' |w| w [1/m] (quadratic).
  double rate() const;
};
UniformLayer uniformLayer(const flow::DebrisSettings& s, double hs, double hf, double rhoS, double d);

}  // namespace drag

}  // namespace talus::test
