// The particle (hybrid MPM/SPH) solver of structured solids on the device (spec §5): particles seeded
// from the initial rasters, each sub-step
//   neighbour grid (sort, tables, reorder) -> areal density and thickness -> velocity gradient and
//   stress (Jaumann, Drucker-Prager, cohesion degradation) -> internal forces (stress, artificial
//   viscosity and stress) -> terrain forces, friction, symplectic update, removal at the domain edge,
// with the sub-step dt_p = CFL h / (c + |v|max) from the elastic wave speed (multi-rate: step(dt)
// takes as many sub-steps as dt needs).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "compute/Reducer.hpp"
#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"
#include "particles/NeighbourGrid.hpp"
#include "particles/ParticleGridTransfer.hpp"
#include "particles/ParticleSeeding.hpp"
#include "particles/ParticleSettings.hpp"

namespace talus::particles {

/// Terrain the particles move on (row-major on `grid`).
struct ParticleTerrain {
  std::vector<uint8_t> mask;  ///< 1 inside the domain
  std::vector<double> bed;    ///< b [m]
  bool slopeCorrection = true;  ///< g_n = g cos^2(theta) (spec §1)
  bool curvature = false;       ///< the bed's curvature in g_n (flow::FlowSettings::curvature)
};

/// Per-particle material (one value per seeded particle, or one value for all when of size 1).
struct ParticleMaterial {
  std::vector<double> density;   ///< rho_c [kg/m^3]
  std::vector<double> phi;       ///< internal friction angle [rad]
  std::vector<double> delta;     ///< bed friction angle [rad]
  std::vector<double> cohesion;  ///< initial cohesion c0 [Pa]
  std::vector<double> structured;  ///< initial f_sc (empty: 1)
  std::vector<double> confined;    ///< initial f_fc (empty: 1)
  std::vector<double> fluidVolume; ///< confined fluid volume V_f0 [m^3] inside the particle's volume (empty: 0)
};

/// Host copy of the particle state (live particles only, in the solver's current order).
struct ParticleState {
  std::vector<double> x, y, vx, vy, mass, sxx, syy, sxy, cohesion, cohesion0, plastic, H;
  std::vector<double> density;          ///< rho_c [kg/m^3]
  std::vector<double> Nxx, Nyy, Nxy;    ///< depth-integrated total in-plane stress of the last sub-step [Pa m]
  std::vector<double> structured0, confined0;  ///< initial f_sc, f_fc
  std::size_t size() const { return x.size(); }
};

/// The particles seen on the terrain grid (P2G with cubic B-splines, spec §6), row-major.
struct ParticleGridFields {
  std::vector<double> thickness;         ///< confined-phase thickness H_c [m]
  std::vector<double> cohesionFraction;  ///< sum w m c / sum w m c0 (-1 where no particle with c0 > 0 reaches)
  std::vector<double> releasedFluid;     ///< fluid released by broken bonds since the start, as thickness [m]
};

struct ParticleDiagnostics {
  std::size_t count = 0;       ///< live particles
  double mass = 0;             ///< [kg]
  double outflowMass = 0;      ///< mass removed at the domain edge in the last step [kg]
  double kinetic = 0;          ///< on the bed, m (|v|^2 + (v . grad b)^2) / 2 [J]
  double maxSpeed = 0;         ///< [m/s]
  double confinedFluid = 0;    ///< fluid volume held by the particles [m^3]
  double pendingRelease = 0;   ///< fluid released from broken bonds, not yet moved to the grid [m^3]
  /// Energy the artificial viscosity dissipated since the start (>= 0) [J] (particle_forces.cl).
  double viscousDissipation = 0;
  /// Work the artificial stress did on the particles since the start (either sign) [J].
  double artificialStressWork = 0;
  /// Energy the basal friction and the wall contacts took since the start (>= 0) [J]
  /// (particle_integrate.cl).
  double frictionWork = 0;
  /// Potential energy released since the start, sum m g (b(start) - b(now)) along the particles' paths
  /// on the bed surface, for the particles still in the domain at each sub-step [J].
  double potentialReleased = 0;
  int subSteps = 0;            ///< sub-steps of the last step
};

class ParticleSolver {
 public:
  ParticleSolver(compute::Context& ctx, const Grid& grid, const ParticleTerrain& terrain, const ParticleSettings& settings);

  /// Uploads particles (positions, masses, volumes from the seeding) with their material, at rest
  /// and stress free (the lateral push is the Bell-Rankine term).
  void setParticles(const SeededParticles& seeded, const ParticleMaterial& material);
  /// Sets the particle velocities (host order of setParticles / state()).
  void setVelocities(const std::vector<double>& vx, const std::vector<double>& vy);

  /// Largest stable sub-step for the current state [s].
  double stableSubStep();
  /// Advances by dt in ceil(dt / stableSubStep()) equal sub-steps (re-evaluated each sub-step).
  void step(double dt);
  /// Evaluates the fields a step derives from the state (thickness, areal density, depth-integrated
  /// stress, divergence) for the current state without advancing it, so that a layer written
  /// before the first step (t = start) holds defined values. Re-sorts the particles.
  void computeDerivedFields();

  const ParticleDiagnostics& diagnostics() const { return diag_; }
  ParticleState state() const;
  /// The evolving particle state (every per-particle field of the live particles, raw bytes of the
  /// run's precision, in the current order) and the time, for checkpoints. restoreState() after
  /// setParticles() of the same scene continues bitwise as if the run had not stopped.
  std::vector<char> saveState() const;
  void restoreState(const std::vector<char>& bytes);
  /// Transfers the particles to the terrain grid (re-sorts them first; results are unchanged by it).
  ParticleGridFields gridFields();
  /// False after restoring a checkpoint written before the peak maps were kept (they restart at 0).
  bool maxMapsRestored() const { return maxMapsRestored_; }
  /// Raises the peak maps of the particle phase by the P2G of the current positions (call after each
  /// grid step; kernels/particles/particle_maxima.cl). Kept in checkpoints.
  void trackMaxima();
  /// Peak confined-phase thickness [m] and speed [m/s] per cell since the start.
  std::vector<double> thicknessMax() const { return hMax_.download(); }
  std::vector<double> speedMax() const { return vMax_.download(); }
  /// Moves the fluid released since the last call onto the grid's free fluid: adds its volume to
  /// `h` (thickness, m) and its momentum (the particles' velocity) to `qx`, `qy` (m^2/s), by P2G with
  /// the cubic B-spline weights (exact in total). Returns the volume moved [m^3] (0: nothing launched).
  double releaseToGrid(compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy);
  /// Couples the particles to the grid's free fluid with the drag closure and parameters of
  /// `fluid` (drag law, multiplier, exponents, viscosity, virtual mass, fluid density) and grain
  /// size `grain` [m]; until called, exchangeWithFluid() does nothing.
  void setFluidCoupling(const flow::DebrisSettings& fluid, double grain);
  /// One exchange with the free fluid over dt (kernels/particles/particle_exchange.cl): drag relaxes
  /// the relative velocity of the confined phase and the fluid per cell, conserving momentum (the
  /// fluid's discharge qx, qy is updated, the particles get the confined phase's change by G2P), and
  /// the fluid depth at every particle is stored for the buoyancy-reduced friction of the next
  /// sub-steps. h, qx, qy: the flow solver's fields.
  void exchangeWithFluid(const compute::RealBuffer& h, compute::RealBuffer& qx, compute::RealBuffer& qy, double dt);
  /// The particles as part of the grid's bed (kernels/particles/particle_bed.cl): writes (H_c, u_c,
  /// v_c) per cell into `bed` (3 x cells) from the P2G of the last exchangeWithFluid() (zeros without
  /// particles). The particles must not move between that exchange and applyBedImpulse().
  void writeGridBed(compute::RealBuffer& bed);
  /// Gives the particles the impulse `impulse` (2 x cells, momentum per area [kg m^-1 s^-1]) that the
  /// grid phases exerted on that bed, by G2P with the P2G weights (momentum-conserving).
  void applyBedImpulse(const compute::RealBuffer& impulse);
  /// Whether the P2G of the last exchange still describes the particles (they have not moved since).
  bool gridTransferValid() const { return gridValid_; }
  /// Recomputes that P2G from the current positions (after restoreState(), for a bitwise resume).
  void refreshGridTransfer();
  std::size_t count() const { return count_; }
  /// g_n [m/s^2] at (x, y) on the particles' bed surface, as the kernels take it
  /// (particle_common.cl, bed_normal_gravity of bed_gradient).
  double normalGravityAt(double x, double y) const;
  double smoothingLength() const { return h_; }
  /// Mean particle spacing of the seeding [m].
  double meanSpacing() const { return spacing_; }
  double time() const { return time_; }

 private:
  void subStep(double dt);
  /// The first half of a sub-step: neighbour sort, thickness and stress over ds (0: evaluation only).
  /// False when no particle is left.
  bool sortAndEvaluateStress(double ds);
  void writeParams();
  void reorderAll();
  void allocateNeighbourLists();
  void updateDiagnostics();
  static const std::vector<compute::RealBuffer ParticleSolver::*>& stateFields();

  compute::Context& ctx_;
  Grid grid_;
  ParticleSettings settings_;
  double h_ = 0, time_ = 0, waveSpeed_ = 0;
  double spacing_ = 1;  ///< mean particle spacing dp [m] (seeded cells' area / particles)
  std::size_t count_ = 0, capacity_ = 0;
  ParticleDiagnostics diag_;
  std::unique_ptr<NeighbourGrid> neighbours_;
  std::unique_ptr<ParticleGridTransfer> transfer_;
  compute::RealBuffer releasedMap_, scratchX_, scratchY_;  ///< cumulative released fluid per cell [m]
  compute::Reducer reducer_;
  compute::RawBuffer params_;
  compute::Buffer<uint8_t> mask_;
  compute::RealBuffer bed_, limitedSlope_;
  compute::RealBuffer bedPatch_;  ///< the bed surface's bilinear patches (particle_common.cl, bed_gradient)
  std::vector<double> patchHost_;  ///< the same on the host (normalGravityAt)
  bool slopeCorrection_ = true;
  // Particle fields (reordered together at every neighbour build).
  compute::RealBuffer x_, y_, vx_, vy_, m_, rho_, phi_, delta_, coh_, coh0_, sxx_, syy_, sxy_, plastic_, A_, V_, fsc0_, ffc0_;
  compute::RealBuffer Vf_, Vf0_, released_, fluidDepth_;
  compute::RealBuffer liftOff_;  ///< speed at which a particle moves away from the bed [m/s] (curvature term)
  /// a_i = A_i S_i, the particle's share of its neighbours' number density (particle_density.cl); 0 until the
  /// first stress pass sets it from the seeded area
  compute::RealBuffer areaShare_;
  // Fluid coupling (setFluidCoupling).
  bool coupled_ = false;
  double grain_ = 0.01;
  compute::RawBuffer debrisParams_;
  compute::Kernel drag_, gridBed_, bedVelocity_, cellVelocity_;
  bool gridValid_ = false;  ///< cellH_, cellM_, cellPx_, cellPy_ hold the P2G of the current positions
  compute::RealBuffer cellH_, cellM_, cellPx_, cellPy_, cellDu_, cellDv_;
  compute::RealBuffer cellU_, cellV_;  ///< the cells' confined-phase velocity after the exchange (PIC share only)
  // Per sub-step scratch (not reordered).
  compute::RealBuffer rhoA_, H_, Nxx_, Nyy_, Nxy_, gradCorrection_, numberDensity_, ax_, ay_, speed_;
  /// Rows of count_ entries per sub-step: outflow mass, then the artificial viscosity's and the artificial
  /// stress's acceleration (x, y) from particle_forces, which particle_integrate turns into their work.
  compute::RealBuffer tally_;
  compute::RealBuffer artStress_;  ///< R of each particle (artificial_stress.cl), rows of the capacity
  /// Each particle's neighbours within the support, listed by particle_stress for particle_forces
  /// (nbCap_ entries per particle; a particle with more walks the neighbour grid itself).
  compute::Buffer<cl_uint> nbList_, nbCount_;
  compute::RealBuffer nbGrad_;  ///< the listed pairs' kernel-gradient factors (sph.cl, sph_grad_factor)
  unsigned nbCap_ = 0;
  bool maxMapsRestored_ = true;
  compute::RealBuffer hMax_, vMax_;  ///< peak maps of the particle phase (trackMaxima)
  compute::RealBuffer trackH_, trackM_, trackPx_, trackPy_;  ///< trackMaxima's P2G
  compute::Kernel maxima_;
  compute::Kernel stress_, forces_, integrate_, speedKernel_;
};

}  // namespace talus::particles
