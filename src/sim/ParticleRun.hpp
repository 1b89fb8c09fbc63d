// The particles of a hybrid-mode run inside the simulation loop (spec §7): the particle solver,
// stepped inside each grid step (multi-rate sub-steps), its health check, mass bookkeeping and
// diagnostics columns, and its view for the desktop application (ParticleView).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "compute/Context.hpp"
#include "core/Raster.hpp"
#include "flow/FlowSolver.hpp"
#include "particles/ParticleSolver.hpp"
#include "sim/ParticleScene.hpp"
#include "sim/ParticleView.hpp"

namespace talus::sim {

class ParticleRun : public ParticleView {
 public:
  /// Seeds the particles and couples them to the grid `flow` (which must outlive this run): the
  /// fluid exchange, and with FlowSettings::particleBed the particles as part of the grid's bed,
  /// set up for the first grid step.
  ParticleRun(compute::Context& ctx, const Raster& dem, const ParticleScene& scene, flow::FlowSolver& flow);

  /// The largest grid step the loop should take so that progress and outputs stay fine-grained:
  /// 200 particle sub-steps (infinite without particles).
  double maxStep();
  /// After a grid step of dt: gives the particles the impulse of the grid's bed forces of that step,
  /// advances them by dt, moves the fluid their broken bonds released onto the grid's free fluid,
  /// exchanges drag with it and sets the particle bed of the next grid step. Returns an empty
  /// string, or what went wrong (non-finite speeds) with the time.
  std::string step(double dt, double time);
  /// Fluid volume moved to the grid by the last step [m^3] (a source of the grid's volume balance).
  double releasedLastStep() const { return releasedLast_; }
  /// Fluid volume moved to the grid since the start [m^3].
  double releasedTotal() const { return releasedTotal_; }

  double initialMass() const { return initialMass_; }
  double mass() const { return solver_->diagnostics().mass; }
  double cumulativeOutflow() const { return outflow_; }
  /// (mass + outflow + rho_f released water - initial) / initial.
  double balanceError() const;
  /// Columns for diagnostics.csv: particles, mass [kg], outflow of the step [kg], kinetic energy on the
  /// bed [J], and since the start the energy the artificial viscosity dissipated, the work of the
  /// artificial stress, the energy friction and walls took and the potential energy released [J].
  static const char* csvHeader() {
    return "particles,particle_mass_kg,particle_outflow_kg,particle_kinetic_J,particle_viscous_dissipation_J,"
           "particle_art_stress_work_J,particle_friction_work_J,particle_potential_released_J";
  }
  std::string csvRow() const;
  /// Writes the particles as a GeoPackage point layer (docs/outputs.md, "Particle layers").
  void writeLayer(const std::string& path) const;
  /// The particles on the grid: confined thickness and cohesion fraction (for the final maps).
  particles::ParticleGridFields gridFields() { return solver_->gridFields(); }
  particles::ParticleSolver& solver() { return *solver_; }
  /// Particle state and bookkeeping for checkpoints (restoreState after construction from the same scene).
  std::vector<char> saveState() const;
  void restoreState(const std::vector<char>& bytes);
  /// Exchange with the grid and the particle bed of the next grid step (see step()).
  void coupleToGrid(double dt);

  // ParticleView
  std::size_t count() const override;
  std::vector<ParticleAttributeInfo> attributes() const override;
  std::vector<float> positions() const override;
  std::vector<float> attribute(const std::string& name) const override;

 private:
  const Raster& dem_;
  flow::FlowSolver& flow_;
  std::unique_ptr<particles::ParticleSolver> solver_;
  double initialMass_ = 0, outflow_ = 0, releasedLast_ = 0, releasedTotal_ = 0, fluidDensity_ = 1000;
  bool fluidAtParticles_ = false;  ///< the particles hold a non-zero fluid depth from the last exchange
  // Host copy for viewers, refreshed lazily once per step.
  mutable particles::ParticleState cache_;
  mutable bool cacheValid_ = false;
  const particles::ParticleState& state() const;
};

}  // namespace talus::sim
