// Exact reference solutions for the granular (Savage-Hutter) and two-phase grid model, used by the
// verification tests of the depth-averaged two-phase solver (spec sections 1, 4 and 10):
//  - the Mangeney, Heinrich & Roche (2000) dam break of a granular mass on an inclined plane with
//    Coulomb friction, written in the model's horizontal coordinates;
//  - a rigid block sliding on a uniform plane (slope-corrected gravity g_n = g cos^2(theta));
//  - the repose slope of a Savage-Hutter pile and the Savage-Hutter (1989) earth-pressure
//    coefficients;
//  - the relaxation of two uniform phases coupled by linear or quadratic drag (with virtual mass).
//
// Conventions (spec section 1): horizontal x, positive down the slope; thickness H measured
// vertically; g = talus::kGravity = 9.81 m/s^2. The bed of a uniform plane is b = -x tan(theta).
#pragma once

#include "core/Constants.hpp"
#include "support/Analytic.hpp"

namespace talus::analytic {

/// Mangeney, Heinrich & Roche (2000) dam break, in horizontal coordinates. It is the exact
/// solution of the constant-coefficient system
///   h_t + (h u)_x = 0,   (h u)_t + (h u^2 + c0^2 h^2 / (2 H0))_x = m h,
/// i.e. pressure coefficient kp = c0^2 / H0 and constant acceleration m, from h = H0 for x < x0,
/// h = 0 for x >= x0, u = 0. With xi = x - x0 - m t^2 / 2 (a frame accelerating with m):
///   xi <= -c0 t:            h = H0,                                u = m t      (reservoir)
///   -c0 t < xi < 2 c0 t:    h = H0 (2 c0 - xi / t)^2 / (9 c0^2),   u = 2 (c0 + xi / t) / 3 + m t
///   xi >= 2 c0 t:           h = 0,                                 u = 0        (dry)
/// (Mangeney et al. 2000, eqs. 20-22: a Ritter rarefaction carried by the accelerating frame.)
///
/// On a plane of slope theta with bed friction delta and earth-pressure coefficient K the model
/// reduces to this system with c0 = sqrt(K g_p H0) and m = g_n (tan(theta) - tan(delta)); see
/// mangeneyFromSlope(). As a Coulomb-friction solution it is physical only for m >= 0 (then
/// u >= 0 everywhere, so friction points upslope everywhere, as assumed).
///
/// Validity: the reservoir is semi-infinite. If the mass only occupies x >= xUpper (a free upper
/// end, or a wall at xUpper), the upper end sends a disturbance into the reservoir whose head
/// travels with the characteristic speed u + c0 = m t + c0, i.e. it is at
/// xUpper + c0 t + m t^2 / 2 (validFrom()). The solution stays exact downslope of that point, and
/// everywhere in the mass while the disturbance has not reached the fan, t < validUntil(xUpper)
/// = (x0 - xUpper) / (2 c0). Mass is therefore NOT conserved on a finite window: the reservoir
/// keeps flowing in through the upper end. Tests should use a long reservoir (or compare only
/// downslope of validFrom()).
struct MangeneyDamBreak {
  double H0 = 1.0;  ///< reservoir thickness [m], > 0
  double c0 = 1.0;  ///< wave speed sqrt(kp H0) [m/s], > 0
  double m = 0.0;   ///< constant acceleration, positive down the slope [m/s^2]
  double x0 = 0.0;  ///< initial position of the front (dam) [m]

  /// Thickness h(x, t) >= 0 [m]; t <= 0 gives the initial state.
  double h(double x, double t) const;
  /// Velocity u(x, t) [m/s]; 0 where dry and for t <= 0.
  double u(double x, double t) const;
  /// h and u together.
  State1D state(double x, double t) const;
  /// Wet/dry front x0 + 2 c0 t + m t^2 / 2 [m].
  double front(double t) const;
  /// Head of the rarefaction (upslope edge of the fan, where the reservoir starts to thin):
  /// x0 - c0 t + m t^2 / 2 [m].
  double rear(double t) const;
  /// Pressure coefficient kp = c0^2 / H0 [m/s^2] (K g_p in the granular model).
  double kp() const { return c0 * c0 / H0; }
  /// Exact integral of h over [a, b] at time t [m^2] (closed form; b < a gives the negative).
  /// Divide by the cell width to get finite-volume cell averages.
  double integralH(double a, double b, double t) const;
  /// Upslope limit of the region where the solution is exact when the mass starts at xUpper:
  /// xUpper + c0 t + m t^2 / 2 [m].
  double validFrom(double xUpper, double t) const;
  /// Time until which the whole solution is exact for a mass starting at xUpper < x0:
  /// (x0 - xUpper) / (2 c0) [s].
  double validUntil(double xUpper) const;
};

/// Builds the Mangeney dam break for a granular mass of thickness H0 on a uniform plane of slope
/// thetaRad with bed friction deltaRad and constant earth-pressure coefficient K (spec section 1):
/// c0 = sqrt(K g_p H0), with g_p = g cos^2(theta) (cos4 = false, the default pressure coefficient)
/// or g cos^4(theta) (cos4 = true); m = g_n (tan(theta) - tan(delta)) with g_n = g cos^2(theta).
/// Throws std::invalid_argument unless H0 > 0, K > 0, 0 <= theta < pi/2, 0 <= delta < pi/2 and
/// tan(theta) >= tan(delta) (otherwise friction would hold the reservoir and the constant-m
/// solution does not apply).
MangeneyDamBreak mangeneyFromSlope(double H0, double thetaRad, double deltaRad, double K, bool cos4,
                                   double x0);

/// Horizontal acceleration of a rigid mass on a uniform plane of slope thetaRad with Coulomb bed
/// friction deltaRad, in the model's horizontal coordinates [m/s^2]:
///   g cos^2(theta) (tan(theta) - tan(delta)) = cos(theta) g (sin(theta) - cos(theta) tan(delta))
/// when tan(theta) > tan(delta) (the along-slope acceleration projected on the horizontal), 0
/// otherwise (a block at rest stays at rest). Positive down the slope. Throws
/// std::invalid_argument unless 0 <= theta, delta < pi/2.
double slidingAcceleration(double thetaRad, double deltaRad);

/// Horizontal position x0 + a t^2 / 2 of a block released at rest at x0 at t = 0, with
/// a = slidingAcceleration(thetaRad, deltaRad) [m]. t <= 0 gives x0.
double slidingPosition(double x0, double thetaRad, double deltaRad, double t);

/// Horizontal velocity a t of the same block [m/s]. t <= 0 gives 0.
double slidingVelocity(double thetaRad, double deltaRad, double t);

/// Steepest free-surface slope |dH/dx| at which a Savage-Hutter pile on flat ground stays at rest:
/// the depth-averaged momentum balance at rest is K g H |dH/dx| <= g H tan(delta), so the limit is
/// tan(delta) / K. Throws std::invalid_argument unless K > 0 and 0 <= delta < pi/2.
double reposeSlope(double deltaRad, double K);

/// Savage & Hutter (1989) earth-pressure coefficient
///   K = 2 / cos^2(phi) (1 -+ sqrt(1 - cos^2(phi) / cos^2(delta))) - 1
/// (minus: active, passive = false; plus: passive). The sqrt argument is clipped at 0 when
/// delta > phi (the coefficient is then 2 / cos^2(phi) - 1 for both). Always K_act <= K_pas and
/// K_pas >= 1; at delta = 0 they are the Rankine values (1 -+ sin phi) / (1 +- sin phi).
/// Throws std::invalid_argument unless 0 <= phi, delta < pi/2.
double earthPressure(double phiRad, double deltaRad, bool passive);

/// Velocities of the two phases of a uniform two-phase layer.
struct PhaseVelocities {
  double us;  ///< solid velocity [m/s]
  double uf;  ///< fluid velocity [m/s]
};

/// Exact relaxation of uniform phases with (areal) masses ms, mf > 0 and initial velocities us0,
/// uf0, coupled by a linear drag F = k (uf - us) per area acting on the solids (-F on the fluid)
/// and a virtual-mass force mvm d(uf - us)/dt (solids gain it, the fluid loses it):
///   ms dus/dt = k w + mvm dw/dt,   mf duf/dt = -k w - mvm dw/dt,   w = uf - us.
/// Total momentum ms us + mf uf is constant and w(t) = w0 exp(-r t) with
/// r = linearDragRate(ms, mf, k, mvm). t <= 0 returns the initial state.
/// Throws std::invalid_argument unless ms, mf > 0 and k, mvm >= 0.
PhaseVelocities linearDragRelaxation(double ms, double mf, double us0, double uf0, double k,
                                     double t, double mvm = 0.0);

/// Decay rate k beta / (1 + mvm beta) of the relative velocity under linear drag, with
/// beta = 1/ms + 1/mf [1/s].
double linearDragRate(double ms, double mf, double k, double mvm = 0.0);

/// Same as linearDragRelaxation for the quadratic drag F = k |w| w (1D):
///   w(t) = w0 / (1 + k' |w0| t),  k' = k beta / (1 + mvm beta),  beta = 1/ms + 1/mf.
/// Total momentum is constant. t <= 0 returns the initial state.
/// Throws std::invalid_argument unless ms, mf > 0 and k, mvm >= 0.
PhaseVelocities quadraticDragRelaxation(double ms, double mf, double us0, double uf0, double k,
                                        double t, double mvm = 0.0);

}  // namespace talus::analytic
