// A plain C++ (double precision, single-threaded) reference of one FlowSolver::step, written from
// the equations stated in the headers of kernels/flow/*.cl, for comparing the device solver with
// on small random scenes. It never touches OpenCL.
//
// What one step does (the same sequence as FlowSolver::step):
//   U1 = U0 + dt L(U0)                      (then the dry-cell rule)
//   U  = U0 / 2 + (U1 + dt L(U1)) / 2       (SSP-RK2, Shu & Osher 1988; then the dry-cell rule)
//   (split scheme: the same per direction, L with that direction's faces only, x first on even
//   steps; each stage limits the fluxes out of draining cells, see rkStage; Hancock scheme: those
//   sweeps with one stage U = U0 + dt L(U0) each, L from the faces advanced by the predictor, and
//   friction over dt/2 before the sweeps and dt/2 after them)
//   semi-implicit Manning friction, time += dt, running maxima / arrival, diagnostics.
// L(U) is the finite-volume residual: MUSCL reconstruction of h, eta = h + b, u, v (limited slopes,
// zero next to outside cells), hydrostatic reconstruction (Audusse et al. 2004), an HLL or HLLC
// flux with the pressure part scaled by each cell's own g_p, the well-balanced centred bed source,
// and the (g_p - g_n) h db/dx term of the cos^4 depth-pressure option. Outside cells (nodata or
// off the raster) are ghost cells: mirrored with the normal velocity reversed at walls; at open and
// level boundaries outflow only, copied at open ones, from characteristics against water at rest at
// the edge cell's initial surface at level ones (kernels/flow/riemann.cl, open_ghost). The dry-cell rule: h <= h_dry sets the momentum to zero and h to max(h, 0).
// Velocities are q / h above h_dry and zero below; Manning friction uses g (as friction.cl states).
// Like FlowSolver::setInput, the constructor discards input momentum on dry and outside cells.
//
// Tiles are ignored: every inside cell is updated every step, which equals the device only when
// all tiles are active (or when the skipped tiles are dry, as they are by construction).
#pragma once
#include <vector>

#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/FlowSolver.hpp"

namespace talus::test {

class CpuFlowReference {
 public:
  /// Takes the scene as FlowSolver::setInput does: outside cells get h = 0 and b = 0, g_n and g_p
  /// come from talus::flow::computeSlopeGravity, maxima start at the initial state, time at 0.
  CpuFlowReference(const Grid& grid, const flow::FlowSettings& settings, const flow::FlowInput& input);

  /// One full solver step of size dt.
  void step(double dt);
  /// cfl * dx / max over wet cells of (|u| + c + w) + (|v| + c + w) (split scheme: max(|u|, |v|) +
  /// c + w; w the slope speed), infinite when nothing moves.
  double stableDt() const;

  double time() const { return time_; }
  /// Volume, outflow of the last step [m^3], kinetic energy, wave speed and smallest thickness.
  const flow::FlowDiagnostics& diagnostics() const { return diag_; }
  const std::vector<double>& h() const { return h_; }
  const std::vector<double>& qx() const { return qx_; }
  const std::vector<double>& qy() const { return qy_; }
  const std::vector<double>& hMax() const { return hMax_; }
  const std::vector<double>& vMax() const { return vMax_; }
  const std::vector<double>& arrival() const { return arrival_; }
  const std::vector<double>& gp() const { return gp_; }
  const std::vector<double>& gn() const { return gn_; }
  bool inside(int i, int j) const;
  /// Volume [m^3] the dry-cell rule created in the last step by raising negative thicknesses to 0.
  /// Zero when the scheme stays positive; then volume(before) - volume(after) == outflow.
  double clampedVolume() const { return clampedVolume_; }
  /// Cell-stages so far whose outgoing fluxes the draining time limited (split scheme only).
  int drainedCells() const { return drainedCells_; }

  /// Numerical flux through one face, as the update consumes it (see kernels/flow/riemann.cl).
  struct FaceFlux {
    double mass = 0, normalMomentum = 0, tangentialMomentum = 0, pressure = 0;
    double corrMinus = 0, corrPlus = 0;  ///< hydrostatic corrections (h^2 - h*^2) / 2 per side
  };

 private:
  struct State {
    std::vector<double> h, qx, qy;
  };
  /// h, eta, normal and tangential velocity of one cell seen along direction dir (0: x, 1: y).
  struct Prim {
    double h, eta, un, ut;
  };
  /// Reconstructed values at the minus (lo) and plus (hi) faces of one cell along one direction.
  struct Faces {
    double hLo, hHi, etaLo, etaHi, unLo, unHi, utLo, utHi;
  };

  double velocity(double h, double q) const;
  double limiter(double backward, double forward) const;
  Prim prim(const State& s, int i, int j, int dir) const;
  /// The face values the fluxes use: the MUSCL ones, advanced by the predictor under Hancock.
  Faces reconstruct(const State& s, int i, int j, int dir) const;
  Faces muscl(const State& s, int i, int j, int dir) const;
  /// The MUSCL-Hancock predictor of the faces f of cell (i, j) (Time Scheme=hancock).
  Faces predict(const State& s, const Faces& f, int i, int j, int dir) const;
  FaceFlux riemann(double hl, double ul, double vl, double hr, double ur, double vr, double g) const;
  /// The Hancock predictor's view of one face (kernels/flow/hancock.cl, hancock_face).
  struct PredictorFace {
    double mass, dropMinus, dropPlus;
  };
  PredictorFace predictorFace(double hl, double el, double ul, double vl, double gl, double hr, double er, double ur,
                              double vr, double gr) const;
  FaceFlux faceFlux(const State& s, int i, int j, int dir) const;
  /// out = base/2 + (s + dt L(s))/2 when base is given, else s + dt L(s); returns the outward
  /// mass flux summed over boundary faces [m^2/s].
  /// dirs: 1 (x faces), 2 (y faces) or 3 (both). In the split scheme the fluxes out of draining
  /// cells are limited as kernels/flow/stage.cl states (draining time).
  double rkStage(const State& s, const State* base, double dt, State& out, double& added, int dirs) const;
  void friction(double dt);
  void track();
  void computeDiagnostics(double outflowVolume);

  Grid grid_;
  flow::FlowSettings settings_;
  std::vector<unsigned char> mask_;
  std::vector<double> bed_, manning_, gn_, gp_, slope_;  // slope_: bed-slope CFL speed
  std::vector<double> bx_, by_;  // bed slope for Manning along the bed (zero with slope correction off)
  std::vector<double> h_, qx_, qy_, hMax_, vMax_, arrival_;
  std::vector<double> farLevel_;  // the water level outside an open edge: the initial surface b + h
  double time_ = 0;
  double clampedVolume_ = 0;
  int splitStep_ = 0;              // sweeps' order: x first on even steps (FlowSolver::step)
  double predictorRatio_ = 0;      // dt / (2 dx) of the current step (Hancock predictor)
  mutable int drainedCells_ = 0;   // cell-stages whose outflow the draining time limited
  flow::FlowDiagnostics diag_;
};

}  // namespace talus::test
