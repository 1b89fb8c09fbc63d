// Options of the particle (hybrid MPM/SPH) mode, spec §5, with their run-file defaults.
#pragma once

namespace talus::particles {

enum class ParticleEarthPressure { SavageHutter = 0, Constant = 1 };

struct ParticleSettings {
  double youngModulus = 1e7;     ///< E [Pa]
  double poisson = 0.3;          ///< nu [-]
  double soundSpeed = 0;         ///< c_sound [m/s] for the time step and artificial viscosity; 0: elastic c_p
  double smoothingFactor = 1.0;  ///< h = smoothingFactor * dx (paper: h = dx)
  double cfl = 0.2;              ///< dt_p = cfl h / (c + |v|max)
  /// Monaghan artificial viscosity (P.83-P.84), at Bui et al.'s (2008) values for soils; the paper's
  /// scenes set its alpha_Pi = beta_Pi = 1.
  double alphaPi = 0.1, betaPi = 0.0;
  /// Gray-Monaghan artificial stress epsilon_0 (P.85), off: the kernel-corrected forces need no remedy
  /// for the tensile instability, and the term's work is an energy source (docs/particles.md; Gray et
  /// al. 2001 use 0.3 with n = 4, which the paper's scenes set).
  double epsArt = 0.0;
  double nArt = 4;               ///< its exponent n
  double dilatancy = 0;          ///< psi [rad]
  double epsCrit = 0.1;          ///< critical strain of the cohesion degradation (P.26)
  double poreB = 1.0;            ///< basal pore-pressure factor B (P.39)
  double fluidDensity = 1000.0;  ///< rho_f of the confined fluid released from broken bonds [kg/m^3]
  ParticleEarthPressure earthPressure = ParticleEarthPressure::Constant;
  double kConst = 1.0;
  /// Whether the raster edge and the faces to nodata cells hold the particles as walls (else a
  /// particle crossing them leaves the domain and is counted as outflow); the grid's `Boundary
  /// Type` and `Nodata Boundary Type`, with their defaults.
  bool edgeWalls = false;
  /// PIC share a of the velocity the particles take from the exchange with the grid's fluid (spec
  /// §6): v_p <- (1 - a) (v_p + du(x_p)) + a (u_c + du)(x_p), u_c the cell's confined-phase velocity
  /// (P2G); 0 is FLIP (each particle keeps its own velocity plus the exchange's change), 1 PIC.
  double picFraction = 0.0;
  bool nodataWalls = true;
  /// Entries of each particle's neighbour list (particle_stress lists, particle_forces reads; a
  /// particle with more neighbours walks the neighbour grid in particle_forces, with the same sums).
  /// 0: 1.5 times the neighbours at the seeding's spacing (ParticleSolver::allocateNeighbourLists).
  unsigned neighbourListEntries = 0;

  double shearModulus() const { return youngModulus / (2 * (1 + poisson)); }
  /// The in-plane bulk modulus of plane stress, lambda* + G = E / (2 (1 - nu)) [Pa]
  /// (kernels/particles/constitutive.cl, step 3).
  double planeBulkModulus() const { return youngModulus / (2 * (1 - poisson)); }
  /// The modulus of the fastest in-plane elastic wave of the plane-stress law the particles use
  /// (kernels/particles/constitutive.cl, step 3): lambda* + 2G = E / (1 - nu^2) [Pa].
  double inPlaneWaveModulus() const { return youngModulus / (1 - poisson * poisson); }
};

}  // namespace talus::particles
