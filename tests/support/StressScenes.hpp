// Randomised shallow-water scenes for the numerical stress suite (tests/stress), and the checker
// that runs one scene and verifies the solver's invariants after every step.
//
// A scene is a pure function of one 64-bit seed (std::mt19937_64 seeded with it, and only integer
// arithmetic on its raw output for the draws, so the scene does not depend on the standard library's
// distribution algorithms): the family (seed mod kStressFamilies), grid, DEM, nodata mask, water,
// momentum, Manning map, every solver setting, the precision, the step count and the time-step
// fraction. `TALUS_STRESS_SEED=<seed>` therefore reproduces exactly one scene.
//
// What is generated (each family biases the probabilities, see StressScenes.cpp):
//  - grids from 1x1 and 1xN / Nx1 up to 96x96, dx log-uniform in [0.1, 20] m;
//  - fractal DEMs (a spectral sum of octaves with random directions and phases) scaled to a target
//    steepest gradient from 0.01 up to 12, plus cliffs (vertical steps of 1-10 cell sizes or of
//    5-50 m), pits (single cells and small disks), near-vertical ramps (gradient 3-12);
//  - water: lakes at rest (a level over the DEM), dam-break blocks, single-cell releases, releases
//    touching the raster edge, 1 mm films over large areas with large dry areas around them, noisy
//    depths with dry patches; depths log-uniform from 1 mm to 50 m; optional initial velocities up to
//    Froude 3;
//  - nodata holes (random-walk blobs, some grown from wet cells so they cut into water);
//  - Manning n of 0 everywhere, 0.5-1 everywhere, a per-cell random field in [0, 1], patches of 0
//    and 1, or typical values;
//  - every limiter, HLL/HLLC, wall/open raster edge and nodata faces, slope correction on/off,
//    cos2/cos4 depth pressure, skip-dry-tiles on/off, CFL in (0, 1], float and double.
//
// The checker (runStressScene) downloads the fields after every step and checks: all fields and
// diagnostics finite, h >= 0, nodata cells empty, no momentum on dry cells, the volume balance
// |V + cumulative outflow - V0| within a precision-dependent bound, non-negative outflow per step,
// the kinetic-energy bound E_kin(t) <= E_kin(0) + g (P(0) - P(t)) + W(t) + slack (P: volume times
// centroid height above the lowest bed cell; W: the work the slope-corrected gravities can add, zero
// with slope correction off), that the step's CFL number (dt * max((|u| + c) + (|v| + c)) / dx on
// the state the step started from) never exceeds the setting, that the solver's diagnostics agree
// with the fields, and at the end that the maxima maps are finite and bound the final depths.
// The bounds and their reasoning are documented at their definitions in StressScenes.cpp.
#pragma once
#include <cstdint>
#include <string>

#include "compute/Precision.hpp"
#include "core/Grid.hpp"
#include "flow/FlowSettings.hpp"
#include "flow/FlowSolver.hpp"

namespace talus::test {

/// Scene families; the family of a seed is seed % kStressFamilies.
enum class StressFamily {
  Fractal = 0,      ///< fractal DEM, mixed releases, everything random
  Cliffs = 1,       ///< cliffs, pits and near-vertical ramps, deep water
  ThinFilm = 2,     ///< 1 mm films over large areas next to large dry areas
  TinyGrid = 3,     ///< 1x1, 1xN, Nx1, 2xN grids
  EdgeRelease = 4,  ///< single-cell releases and releases touching the raster edge
  Nodata = 5,       ///< nodata holes, many of them cutting into the water
  Friction = 6,     ///< extreme Manning n (0, 0.5-1, random fields) and fast initial flows
  Chaos = 7,        ///< every feature at once with the widest ranges
  /// Two-phase (solids + fluid) scenes: NOT selected by seed % kStressFamilies (that mapping is kept
  /// for the eight single-phase families); a debris scene comes from makeDebrisScene(seed), its own
  /// pure function of the seed, with its own seed sequence debrisSeed().
  Debris = 8,
};
inline constexpr int kStressFamilies = 8;  ///< single-phase families (seed % 8); Debris is separate
const char* familyName(StressFamily f);

/// Everything needed to run one scene.
struct StressScene {
  uint64_t seed = 0;
  StressFamily family = StressFamily::Fractal;
  Grid grid;
  flow::FlowInput input;
  flow::FlowSettings settings;
  compute::Precision precision = compute::Precision::Double;
  int steps = 0;            ///< steps to run (fewer if the domain drains completely)
  double dtFraction = 1.0;  ///< each step uses dt = dtFraction * stableDt()
  std::string description;  ///< one line: seed, family, grid, settings and the scene's features
};

/// The scene of `seed` (a pure function of the seed).
StressScene makeStressScene(uint64_t seed);

/// The seed of scene `index` of a run with base seed `base`: a well-mixed 64-bit value whose
/// residue mod kStressFamilies is `family`.
uint64_t stressSeed(uint64_t base, uint64_t index, StressFamily family);

/// The two-phase scene of `seed` (a pure function of the seed, independent of makeStressScene's
/// family rule): the grid, DEM (fractal or cliffs family), nodata mask, edges, precision and Manning
/// map of a single-phase Fractal / Cliffs scene derived from the seed, its water split into solids
/// and fluid (solids only, fluid only, or mixtures with fluid-only and solid-only cells), and random
/// two-phase settings: drag off / linear / quadratic with the multiplier often at 1e-3 or 1e6,
/// virtual mass on/off, Savage-Hutter or constant K in [0.3, 3], phi and delta in [10, 45] degrees,
/// cohesion 0 .. 1e6 Pa, pore factor B in [0, 1], solid density, grain size.
StressScene makeDebrisScene(uint64_t seed);

/// The seed of debris scene `index` of a run with base seed `base`.
uint64_t debrisSeed(uint64_t base, uint64_t index);

/// Result of running one scene through the checker.
struct StressOutcome {
  bool ok = true;
  std::string failure;          ///< first violated invariant: what, step, cell, values (empty if ok)
  int steps = 0;                ///< steps taken
  double balanceRatio = 0;      ///< worst |V + outflow - V0| / tolerance over the steps (<= 1 passes)
  double balanceRelative = 0;   ///< worst |V + outflow - V0| / V0
  double energyRatio = 0;       ///< worst (E_kin - E_kin(0) - g dP) / slack (<= 1 passes)
  double energyGainFraction = 0;///< worst E_kin / (E_kin(0) + g max(dP, 0)) (informative; 0 if none)
  double cflUsed = 0;           ///< worst dt * speed / dx (the setting bounds it)
  double cflAfter = 0;          ///< worst dt * speed(after the step) / dx (informative)
  double cflFaceGravity = 0;    ///< worst CFL with c from the larger g_p of each face (informative)
  double wallSeconds = 0;
};

/// Runs `scene` on the shared test device of its precision and checks the invariants after every
/// step; stops at the first violation (reported in `failure`, with the step and cell).
/// Two-phase scenes (settings.twoPhase) get the two-phase checks (see runDebrisScene in
/// StressScenes.cpp): finite fields, h_s, h_f >= 0, per-phase volume balance, a generous kinetic
/// energy bound, CFL; for them energyRatio is E_kin / bound (<= 1 passes).
StressOutcome runStressScene(const StressScene& scene);

}  // namespace talus::test
