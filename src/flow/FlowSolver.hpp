// The shallow-water grid solver on the device (spec §4 with h_s = 0, numerics in docs/numerics.md).
// One step is a short list of named phases:
//   stage 1: U1 = U0 + dt L(U0)                   (flow_stage: reconstruction, fluxes, update)
//   stage 2: U0 = U0/2 + (U1 + dt L(U1))/2        (SSP-RK2)
//   friction (semi-implicit Manning) -> sources (rain, infiltration) -> maxima -> diagnostics and
//   next active tiles.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "compute/Reducer.hpp"
#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"

namespace talus::flow {

/// The fields that define a shallow-water scene (all on `grid`, row-major, SI units).
struct FlowInput {
  std::vector<uint8_t> mask;    ///< 1 inside the domain, 0 nodata
  std::vector<double> bed;      ///< b [m]
  std::vector<double> manning;  ///< n [s m^-1/3]
  std::vector<double> h;        ///< vertical fluid thickness [m]
  std::vector<double> qx, qy;   ///< fluid discharge per unit width [m^2/s] (empty: at rest)
  // Two-phase model only (FlowSettings::twoPhase); empty vectors mean zero / defaults.
  std::vector<double> hs;          ///< vertical solid thickness alpha_s H [m]
  std::vector<double> qsx, qsy;    ///< solid discharge [m^2/s] (empty: at rest)
  std::vector<double> phi;         ///< internal friction angle [rad]
  std::vector<double> rhoS;        ///< solid density [kg/m^3]
  std::vector<double> grain;       ///< grain size [m]
  std::vector<double> delta;       ///< bed friction angle [rad] (used unless DebrisSettings::deltaFromPhi)
  std::vector<double> cohesion;    ///< cohesion [Pa] of the solids there (Bell's reduction of the lateral
                                   ///< pressure), carried with them as they flow
  /// Entrainment only (FlowSettings::entrainment): vertical depth of bed material the flow can take
  /// up [m] (empty: none).
  std::vector<double> erodible;
};

/// Reduced quantities after the last step (or after setInput).
struct FlowDiagnostics {
  double maxSpeed = 0;   ///< max over cells of (|u| + c) + (|v| + c) [m/s]
  double volume = 0;     ///< [m^3]
  double outflow = 0;    ///< volume that left through boundary faces in the last step [m^3]
  double kinetic = 0;    ///< kinetic energy per unit density, sum h |u|^2 / 2 dx^2 [m^5/s^2]
  double minH = 0;       ///< smallest thickness inside the domain (active tiles) [m]
  double volumeSolid = 0;   ///< two-phase: solid volume [m^3]
  double outflowSolid = 0;  ///< two-phase: solid volume out in the last step [m^3]
  double potential = 0;     ///< two-phase: g sum m z_centroid over both phases [J]
  double kineticVertical = 0;  ///< two-phase: sum m (u.grad b)^2 / 2, the vertical motion along the bed [J]
  double maxFlowSpeed = 0;     ///< max material speed |u| (either phase) of layers above Minimum Flow Height [m/s]
  double maxWaveSpeedWet = 0;  ///< maxSpeed over cells with a layer above Minimum Flow Height [m/s]
  double rain = 0;             ///< rain volume added in the last step [m^3] (docs/sources.md)
  double infiltrated = 0;      ///< volume infiltrated in the last step [m^3]
  double erodible = 0;         ///< entrainment: erodible bed volume left [m^3]
  /// two-phase: the kinetic energy that the last step's stiff sources (the solids' basal law and the
  /// drag, solved together; the basal viscous terms; Manning on the fluid) took from the grid phases
  /// [J]: the work of friction and drag (negative where a moving particle bed drives the solids)
  double sourceWork = 0;
};

/// Running maxima of the two-phase model (spec §8).
struct DebrisMaxima {
  std::vector<double> hf, vf, hs, vs, h, solidFraction, impactPressure;
};

class FlowSolver {
 public:
  FlowSolver(compute::Context& ctx, const Grid& grid, const FlowSettings& settings);

  /// Uploads a scene, sets the time to `startTime` [s], resets maxima and arrival (cells wet at the
  /// start arrive at startTime) and computes the first diagnostics.
  void setInput(const FlowInput& in, double startTime = 0.0);
  /// The CFL time step of the current state (infinite when everything is at rest and dry).
  double stableDt() const;
  /// The CFL time step of a film at rest on every domain cell: cfl dx / (2 w_max), w_max the largest
  /// slope speed sqrt(g |grad b| dx) of the bed (the wave speed of any wet cell at rest includes
  /// 2 w). Infinite on a flat bed. A step in which rain wets dry ground keeps within it, so the
  /// rain's first step is not a whole report interval without runoff.
  double filmStableDt() const;
  /// Advances by dt (caller keeps dt <= stableDt()); `rainDepth` [m] is the uniform rain depth that
  /// falls on every domain cell during the step (the step's integral of the intensity), added after
  /// the flux update together with the infiltration of setInfiltration() (docs/sources.md).
  void step(double dt, double rainDepth = 0.0);
  /// Constant-rate infiltration capacity per cell [m/s] (empty: none). Single-phase model only.
  void setInfiltration(const std::vector<double>& rate);
  bool hasInfiltration() const { return hasInfiltration_; }
  /// Only the sources phase of step() (rain depth [m], infiltration over dt [s]) on the current
  /// state, then the diagnostics; the time does not advance (for tests of the source kernel).
  void applySources(double dt, double rainDepth);

  double time() const { return time_; }
  void setTime(double t) { time_ = t; }
  const FlowDiagnostics& diagnostics() const { return diag_; }
  const Grid& grid() const { return grid_; }
  const FlowSettings& settings() const { return settings_; }
  /// Number of tiles the next step will update, and the total number of tiles.
  int activeTiles() const { return activeTiles_; }
  int tileCount() const { return tilesX_ * tilesY_; }

  std::vector<double> h() const { return h_.download(); }
  std::vector<double> qx() const { return qx_.download(); }
  std::vector<double> qy() const { return qy_.download(); }
  std::vector<double> hMax() const { return hMax_.download(); }
  std::vector<double> vMax() const { return vMax_.download(); }
  std::vector<double> arrival() const { return arrival_.download(); }
  bool twoPhase() const { return settings_.twoPhase; }
  /// Two-phase only: solid thickness and discharge, the transported friction angle, density, grain
  /// size (per cell, defaults where no solids are), and the maxima.
  std::vector<double> hs() const;
  std::vector<double> qsx() const;
  std::vector<double> qsy() const;
  /// h_s w: the solids' lift-off speed (curvature term, kernels/flow/solid_bed.cl point 5) times h_s [m^2/s].
  std::vector<double> hsLiftOff() const { return solidComponent(7); }
  std::vector<double> solidScalar(int which) const;  ///< 0 phi, 1 rho_s, 2 grain size, 3 cohesion [Pa]
  DebrisMaxima debrisMaxima() const;
  /// The evolving state as the device holds it (h, qx, qy, maxima, arrival; raw bytes of the run's
  /// precision) and the time, for checkpoints. restoreState() after setInput() of the same scene
  /// continues bitwise as if the run had not stopped.
  std::vector<char> saveState() const;
  void restoreState(const std::vector<char>& bytes, double time);
  /// An edit of the device fields h, qx, qy from outside the solver.
  using FluidEdit = std::function<void(compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy)>;
  /// Adds fluid from outside the grid (water released by particles, spec §5 P.27-P.28); then the
  /// diagnostics and the active tiles are recomputed over every tile (the new fluid may lie in tiles
  /// that were dry). The outflow of the last step stays what it was.
  void addFluid(const FluidEdit& add);
  /// Changes only the discharge of wet cells (drag with particles); the diagnostics are recomputed
  /// over the active tiles.
  void changeDischarge(const FluidEdit& change);
  /// Recomputes the diagnostics (the next time step) over the active tiles, after an input they
  /// depend on changed outside the solver (the particle bed restored from a checkpoint).
  void refreshDiagnostics() { computeDiagnostics(); }
  /// Hybrid mode (FlowSettings::particleBed): the particles' confined phase as the grid sees it,
  /// 3 x cells (H_c [m], then u_c and v_c [m/s]), written by the particle run before each step; and
  /// the impulse the grid phases gave it in the last step, 2 x cells (x, y, momentum per area
  /// [kg m^-1 s^-1]). Placeholders of one value in grid mode.
  compute::RealBuffer& particleBed() { return particleBed_; }
  const compute::RealBuffer& bedImpulse() const { return bedImpulse_; }
  /// The device fields a viewer may read without a host copy (sim::ViewFields::setDeviceFields):
  /// "h", "qx", "qy", "hMax", "vMax", "arrival", one `real` per cell. The two-phase solid state is one
  /// interleaved buffer and is not listed (its layers are read through the host).
  std::map<std::string, cl_mem> viewBuffers() const;
  /// Slope-corrected gravities as uploaded (for tests).
  std::vector<double> gp() const { return gp_.download(); }
  std::vector<double> gn() const { return gn_.download(); }
  /// Bed elevation [m], as the solver holds it (lowered by entrainment).
  std::vector<double> bed() const { return bed_.download(); }
  /// Entrainment: the bed change so far (negative where eroded) and the erodible depth left [m];
  /// zeros without entrainment.
  std::vector<double> bedChange() const;
  std::vector<double> erodibleDepth() const;
  bool entrainment() const { return settings_.entrainment.enabled; }
  /// Recomputes the bed's slope fields on the device over every tile (as after a bed change; for
  /// tests of kernels/flow/bed_geometry.cl against flow/SlopeGravity.cpp): g_n, g_p, the slope
  /// speed and the bed slope (2 n).
  void recomputeBedGeometry();
  std::vector<double> slopeSpeed() const { return slopeSpeed_.download(); }
  std::vector<double> bedSlope() const { return bedSlope_.download(); }

 private:
  void enqueueStage(const compute::RealBuffer& hSt, const compute::RealBuffer& qxSt, const compute::RealBuffer& qySt,
                     compute::RealBuffer& hOut, compute::RealBuffer& qxOut, compute::RealBuffer& qyOut, double dt,
                     double a, bool firstStage, int directions);
  static constexpr int kDirX = 1, kDirY = 2;  ///< the stage kernel's dir_mask bits
  void enqueueFriction(double dt);
  void enqueueTrackMaxima();
  /// Rain and infiltration over the whole grid (kernels/flow/water_sources.cl); with rain, lists
  /// every tile as active (rain wets dry tiles). Returns the infiltrated volume [m^3].
  double enqueueSources(double dt, double rainDepth);
  void computeDiagnostics();
  /// Lists every tile as active, so the next diagnostics find the wet tiles anywhere.
  void activateAllTiles();
  // Two-phase model (FlowSolverDebris.cpp).
  void buildDebris();
  void setDebrisInput(const FlowInput& in, const std::vector<double>& h);
  void enqueueDebrisStage(bool first, double dt);
  void enqueueDebrisTrack();
  void enqueueDebrisDiagnostics();
  std::vector<double> solidComponent(int c) const;
  // Entrainment (FlowSolverEntrainment.cpp).
  void buildEntrainment();
  void setEntrainmentInput(const FlowInput& in);
  /// Takes up bed material after the step's stages, then refreshes the bed's slope fields where
  /// something was taken; the erodible volume left goes to diag_ with the diagnostics.
  void enqueueEntrainment(double dt);
  void enqueueBedGeometry();

  compute::Context& ctx_;
  Grid grid_;
  FlowSettings settings_;
  int tilesX_, tilesY_;
  double time_ = 0.0;
  FlowDiagnostics diag_;

  compute::RawBuffer params_;
  compute::Buffer<uint8_t> mask_;
  compute::Buffer<int> tileActive_, tileWet_, tileList_, tileCount_;
  int activeTiles_ = 0;
  /// Steps taken with the split scheme: its parity chooses the sweep order (checkpointed).
  std::uint64_t splitStep_ = 0;
  double maxSlopeSpeed_ = 0;  ///< max slope speed over the domain [m/s]
  bool hasInfiltration_ = false;
  std::size_t domainCells_ = 0;  ///< cells inside the domain (the rain volume is rainDepth x these x dx^2)
  bool hasFriction_ = true;  ///< false when Manning's n is zero everywhere: friction is not launched
  compute::RealBuffer bed_, gp_, gn_, manning_, slopeSpeed_;
  /// The water level outside a `level` edge (Boundary::Level), per cell: its initial surface b + h
  /// (its bed where it starts dry). Only edge cells read it (kernels/flow/riemann.cl, open_ghost); it
  /// follows from the input, so a resumed run sets it again from its scene.
  compute::RealBuffer farLevel_;
  compute::RealBuffer bedSlope_;  ///< bed slope b_x, b_y (2 n values, flow/SlopeGravity.hpp): Manning, two-phase diagnostics
  compute::RealBuffer h_, qx_, qy_, h1_, qx1_, qy1_;
  compute::RealBuffer outStep_, partial_;
  compute::RealBuffer hMax_, vMax_, arrival_;
  compute::RealBuffer infiltration_, sink_;  ///< capacity [m/s] and the last step's infiltrated depth [m]
  compute::Reducer reducer_;
  // Two-phase model: solid state (8 components, see kernels/flow/debris_stage.cl) at the start of
  // the step and after stage 1, static-solid flags, static maps, maxima.
  compute::RawBuffer debrisParams_;
  compute::RealBuffer solid0_, solid1_, delta_, maxima_;
  compute::RealBuffer particleBed_, bedImpulse_;
  compute::Buffer<uint8_t> lock0_, lock1_;
  compute::Kernel debrisStage_, debrisTrack_, debrisDiagnostics_;
  // Entrainment: erodible depth left and bed change (per cell), the erodible volume left [m^3].
  compute::RealBuffer erodible_, bedChange_;
  compute::Buffer<int> erodedFlag_;  ///< set by the entrainment kernel where it took anything
  compute::Kernel entrain_, bedSlopeFields_;
  double erodibleVolume_ = 0;
  compute::Kernel stage_, friction_, track_, diagnostics_, compact_, sources_;
  /// Global range covering the active tiles: one work-group of kTile x kTile per tile.
  compute::Range tileRange() const;
};

}  // namespace talus::flow
