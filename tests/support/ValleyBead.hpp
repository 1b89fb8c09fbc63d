// A smooth valley profile and the exact motion of a bead on it: the reference of the solids'
// curved-terrain tests (kernels/flow/solid_bed.cl, point 1: gravity with the bed's curvature).
//
// Valley. A straight slope of alpha_1 turns into a counter-slope of alpha_2 (0 for a flat floor):
// b'(x) runs linearly from -tan(alpha_1) to +tan(alpha_2) over a transition of width W (constant
// curvature b'' = (tan alpha_1 + tan alpha_2) / W there). b = 0 at the floor, where b' = 0.
//
// Bead. A point on z = b(x) in horizontal coordinates, Coulomb friction mu, obeys
//   x'' = -lambda (b' + mu sign(x')),   lambda = (g + b'' x'^2) / (1 + b'^2) >= 0,
// lambda the normal reaction per unit mass over sqrt(1 + b'^2): the bed carries the weight and the
// centripetal acceleration of the bend (friction grows in concave bends). Without friction it
// conserves (x'^2 (1 + b'^2)) / 2 + g b.
#pragma once

namespace talus::test {

struct Valley {
  double s1, s2;  ///< tan(alpha_1), tan(alpha_2)
  double w;       ///< transition width [m]
  double xa;      ///< start of the transition [m]
  double xf;      ///< the floor, b'(xf) = 0 [m]

  /// Slopes in degrees; the transition starts at xa = z0 / tan(alpha_1) + margin, so a release
  /// z0 above the floor lies on the straight slope with `margin` metres of bed above it.
  Valley(double alpha1Deg, double alpha2Deg, double width, double z0, double margin);

  double slope(double x) const;      ///< b'(x)
  double curvature(double x) const;  ///< b''(x)
  double bed(double x) const;        ///< b(x), 0 at the floor
};

/// Where a bead released at rest at x0 first turns (or stops; x0 where friction holds it): integrated
/// by RK4 with step dt [s] until its velocity changes sign. Throws std::runtime_error if it has not turned within
/// 10^7 steps.
double beadTurningPoint(const Valley& v, double x0, double mu, double dt = 1e-4);

}  // namespace talus::test
