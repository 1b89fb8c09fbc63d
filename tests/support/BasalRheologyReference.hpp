// Independent host reference of the solids' basal laws (kernels/flow/basal_rheology.cl), written
// from the physical form of each law rather than from the kernels' closed forms: the implicit step
// q + ds T(q) = q* is solved by bisection on q (Coulomb, Voellmy, mu(I)) or on the bed shear
// (Herschel-Bulkley, whose depth-averaged speed is integrated numerically over the velocity
// profile of a plug above a sheared layer instead of taken from its closed form).
#pragma once
#include <array>

#include "flow/Rheology.hpp"

namespace talus::test {

/// One column as the kernels see it (per unit horizontal area; basal_rheology.cl, BasalColumn).
struct BasalColumnRef {
  double hSt = 1, h = 1;       ///< stage thickness (Coulomb weight) and thickness of q [m]
  double nG = 9.81, gN = 9.81; ///< (1 - B gamma) g_n and g_n [m/s^2]
  double cosT = 1, stretch = 1;  ///< cos(theta) and |U| / |u|
  double rho = 2000;           ///< solid density [kg/m^3]
  double tanDelta = 0.5;       ///< Coulomb
};

/// Along-bed depth-averaged speed of a Herschel-Bulkley layer of bed-normal thickness H under bed
/// shear tau (0 at or below the yield stress), by Simpson quadrature of the velocity profile.
double herschelBulkleySpeed(double tau, double tauY, double K, double n, double H);

/// q / q* after the implicit basal step of law `law` with kernel parameters `rheo`
/// (flow::RheologyLaw::params).
double basalFactorRef(flow::Rheology law, const std::array<double, 4>& rheo, const BasalColumnRef& c, double qStar,
                      double ds);

}  // namespace talus::test
