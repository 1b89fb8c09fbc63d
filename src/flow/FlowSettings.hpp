// Numerical and physical options of the shallow-water solver, with their run-file defaults.
#pragma once
#include <array>
#include <string>

#include "flow/Rheology.hpp"

namespace talus::flow {

/// Slope limiter of the MUSCL reconstruction; None gives the first-order scheme (for comparisons).
enum class Limiter { Minmod = 0, VanLeer = 1, MC = 2, None = 3 };
enum class RiemannSolver { HLL = 0, HLLC = 1 };
/// What lies beyond the raster edge or a nodata cell: a wall; an open edge (outflow only, the outside
/// a continuation of the inside: zero-gradient ghost); or a level edge (outflow only, the outside
/// water at rest at the edge cell's initial surface, dry outside a free overfall: characteristic
/// ghost, kernels/flow/riemann.cl open_ghost; single-phase model).
enum class Boundary { Wall = 0, Open = 1, Level = 2 };
enum class DepthPressure { Cos2, Cos4 };
/// Time integration of the water: SSP-RK2 over both directions' faces at once (CFL over the sum of
/// the two directions' wave speeds), or dimensionally split sweeps, one SSP-RK2 per direction with
/// the order alternated between steps (CFL per direction, up to 1; kernels/flow/stage.cl), or the
/// same sweeps with one MUSCL-Hancock stage each (half the flux evaluations of Split and less
/// dissipation at Courant numbers near 1; flow_common.cl, hancock_predict).
enum class TimeScheme { Unsplit = 0, Split = 1, Hancock = 2 };
/// Whether the scheme works in dimensionally split sweeps (per-direction CFL up to 1, draining time).
inline bool sweeps(TimeScheme s) { return s != TimeScheme::Unsplit; }

enum class EarthPressure { SavageHutter = 0, Constant = 1 };
enum class DragLaw { Off = 0, Linear = 1, Quadratic = 2 };

/// Options of the two-phase (solids + fluid) grid model, spec §4.
struct DebrisSettings {
  EarthPressure earthPressure = EarthPressure::SavageHutter;
  double kConst = 1.0;           ///< earth-pressure coefficient when constant
  double fluidDensity = 1000.0;  ///< rho_f [kg/m^3]
  double poreB = 1.0;            ///< basal pore-pressure factor B (P.39)
  /// Solid volume fraction of the saturated skeleton: fluid thinner than its pore volume
  /// h_s (1 - packing) / packing submerges the solids only partly (kernels/flow/debris_closures.cl)
  double packing = 0.6;
  DragLaw drag = DragLaw::Linear;
  double dragMultiplier = 1.0;
  double dragPExponent = 1.0;    ///< m in P = alpha_s^m
  double dragM = 2.4;            ///< M in G = alpha_f^(M-1)
  double dragKappa = 10.0;       ///< K of the smoothing function S_p [m/s]
  double viscA = 0.001;          ///< O'Brien-Julien a [Pa s]
  double viscB = 10.0;           ///< O'Brien-Julien b [-]
  bool virtualMass = true;
  bool deltaFromPhi = true;      ///< bed friction angle = internal friction angle
  double filmThickness = 1e-4;   ///< [m] solid films thinner than this get desingularised velocities
  double reynolds = 0;           ///< N_R of the fluid's Newtonian stress (P.30); 0: off
  double reynoldsInterfacial = 0;  ///< N_RA of the interfacial (non-Newtonian) stress; 0: off
  double chi = 0;                ///< vertical shear factor of the basal viscous term
  double xi = 0;                 ///< vertical solid-fraction factor of the basal interfacial term
  /// Basal law of the solids (kernels/flow/basal_rheology.cl); Coulomb uses the delta map.
  Rheology rheology = Rheology::Coulomb;
  std::array<double, 4> rheologyParams{};  ///< its kernel parameters (Rheology.hpp, RheologyLaw::params)
  bool viscous() const { return reynolds > 0 || reynoldsInterfacial > 0; }
};

/// Entrainment of an erodible bed layer into the solids (kernels/flow/entrainment.cl).
struct EntrainmentSettings {
  bool enabled = false;
  double growthRate = 0.0;  ///< E of McDougall & Hungr (2005): dV/dt = E V |U| [1/m]
};

struct FlowSettings {
  Limiter limiter = Limiter::MC;  // on the accuracy-per-cost front (docs/validation_parts/pareto.md)
  RiemannSolver riemann = RiemannSolver::HLLC;
  TimeScheme scheme = TimeScheme::Unsplit;  ///< water only; the two-phase model is unsplit
  /// dt = cfl * dx / max((|u| + c + w) + (|v| + c + w)), at most 0.5; split: cfl * dx / max(max(|u|, |v|)
  /// + c + w), at most 1 (positive by the draining time, kernels/flow/stage.cl)
  double cfl = 0.5;
  double hDry = 1e-6;               ///< [m] below this, velocities are zero
  double arrivalH = 0.01;           ///< [m] thickness that marks arrival
  Boundary edge = Boundary::Open;   ///< raster edge
  Boundary nodata = Boundary::Wall; ///< faces to nodata cells
  bool skipDryTiles = true;         ///< skip tiles with no water within one tile
  bool slopeCorrection = true;      ///< g_n = g cos^2(theta) (spec §1); off: g everywhere
  /// Solids: the bed's curvature in g_n (terrain-following gravity, kernels/flow/solid_bed.cl); the
  /// run-file key's default is on, this struct's default (for tests that build settings) is off
  bool curvature = false;
  DepthPressure depthPressure = DepthPressure::Cos2;  ///< g_p = g cos^2 (default) or g cos^4
  bool twoPhase = false;            ///< solids on the grid (grid mode of spec §3); false: water only
  /// Hybrid mode (two-phase only): the particles' confined phase is part of both phases' bed and
  /// takes the reaction of the grid's bed forces (FlowSolver::particleBed(), bedImpulse()).
  bool particleBed = false;
  DebrisSettings debris;
  EntrainmentSettings entrainment;  ///< two-phase only
};

Limiter parseLimiter(const std::string& name);
RiemannSolver parseRiemann(const std::string& name);
Boundary parseBoundary(const std::string& name);
DepthPressure parseDepthPressure(const std::string& name);
EarthPressure parseEarthPressure(const std::string& name);
DragLaw parseDragLaw(const std::string& name);
TimeScheme parseTimeScheme(const std::string& name);

}  // namespace talus::flow
