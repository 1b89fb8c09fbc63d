// Exact reference solutions of the shallow-water equations (Ritter, Stoker, Thacker) and the error
// norms the verification suite uses to compare them with the finite-volume solver.
//
// Equations (flat-bed 1D form shown; the 2D form adds the y flux and -g h b_y):
//   h_t + (hu)_x = 0,   (hu)_t + (hu^2 + g h^2 / 2)_x = -g h b_x.
#pragma once
#include <functional>
#include <vector>

namespace talus::analytic {

/// Depth [m] and depth-averaged velocity [m/s] at one point of a 1D solution.
struct State1D {
  double h;
  double u;
};

/// Ritter (1892) dam break onto a dry bed: depth hL for x < x0 at t = 0, dry for x >= x0, flat
/// frictionless bed. With c0 = sqrt(g hL) and xi = (x - x0) / t the solution is hL, u = 0 for
/// xi <= -c0; h = (2 c0 - xi)^2 / (9 g), u = 2 (xi + c0) / 3 for -c0 < xi < 2 c0; dry beyond.
/// t <= 0 returns the initial state. Throws std::invalid_argument unless hL > 0 and g > 0.
State1D ritter(double x, double t, double x0, double hL, double g);

/// Intermediate (star) state and shock speed of the Stoker problem.
struct StokerStar {
  double hm;          ///< depth between the rarefaction and the shock [m]
  double um;          ///< velocity there [m/s]
  double shockSpeed;  ///< speed of the bore running into the still water hR [m/s]
};

/// Solves the Stoker matching condition for hL > hR >= 0 (see Analytic.cpp for the equation) by
/// bracketed Newton iteration on c_m = sqrt(g h_m), to about 1e-15 relative. hR = 0 gives the dry
/// limit hm = 0, um = shockSpeed = 2 sqrt(g hL). Throws std::invalid_argument unless
/// hL > hR >= 0 and g > 0.
StokerStar stokerStar(double hL, double hR, double g);

/// Stoker (1957) wet dam break: hL left of x0, hR right (0 <= hR <= hL), both at rest, flat
/// frictionless bed: a left rarefaction into the star state, then a right-moving shock. hR = 0
/// reduces to ritter(); hR = hL is still water. t <= 0 returns the initial state.
State1D stoker(double x, double t, double x0, double hL, double hR, double g);

/// Depth and velocity at one point of a 2D solution.
struct State2D {
  double h;
  double u;
  double v;
};

/// Thacker (1981) planar oscillation in a paraboloid, in the form of Delestre et al. (2013),
/// SWASHES, "planar surface in a paraboloid". Bed b = -h0 (1 - r^2 / a^2), r measured from
/// (xc, yc). With X = x - xc, Y = y - yc and omega = sqrt(2 g h0) / a:
///   surface  b + h = (eta h0 / a^2) (2 X cos wt + 2 Y sin wt - eta)   (where wet),
///   depth    h = max(0, h0 (1 - ((X - eta cos wt)^2 + (Y - eta sin wt)^2) / a^2)),
///   velocity u = -eta omega sin wt,  v = eta omega cos wt   (uniform over the wet disk).
/// The wet region is a disk of radius a whose centre circles (xc, yc) at radius eta; the volume
/// is pi a^2 h0 / 2 at all times. The SWASHES test uses a = 1, h0 = 0.1, eta = 0.5, g = 9.81
/// and the domain [0, 4]^2 with xc = yc = 2.
struct ThackerPlanar {
  double a = 1.0;     ///< radius of the paraboloid at the rest level b = 0 [m]
  double h0 = 0.1;    ///< depth of the paraboloid's vertex below b = 0 [m]
  double eta = 0.5;   ///< radius of the circle the wet disk's centre runs on [m]
  double g = 9.81;    ///< gravity [m/s^2]
  double xc = 2.0;    ///< x of the paraboloid's vertex [m]
  double yc = 2.0;    ///< y of the paraboloid's vertex [m]

  /// Angular frequency sqrt(2 g h0) / a [1/s].
  double omega() const;
  /// Period 2 pi / omega [s].
  double period() const;
  /// Bed elevation b(x, y) [m].
  double bed(double x, double y) const;
  /// Water surface b + h [m]; equal to the bed where dry.
  double surface(double x, double y, double t) const;
  /// Depth h(x, y, t) >= 0 [m].
  double h(double x, double y, double t) const;
  /// x velocity in the wet region (uniform in space) [m/s].
  double u(double t) const;
  /// y velocity in the wet region (uniform in space) [m/s].
  double v(double t) const;
  /// Full state at (x, y, t); the velocity is zero where the point is dry.
  State2D state(double x, double y, double t) const;
  /// Initial state state(x, y, 0): a tilted planar lake with u = 0, v = eta omega where wet.
  State2D initial(double x, double y) const { return state(x, y, 0.0); }
  /// Volume of water, pi a^2 h0 / 2 [m^3].
  double volume() const;
};

/// Sum of |f_i - g_i| * cellArea. Throws std::invalid_argument if the sizes differ.
double l1(const std::vector<double>& f, const std::vector<double>& g, double cellArea);

/// l1(f, g, cellArea) divided by sum |g_i| * cellArea. Returns 0 when both are zero and +infinity
/// when only the reference g is zero. Throws std::invalid_argument if the sizes differ.
double relativeL1(const std::vector<double>& f, const std::vector<double>& g, double cellArea);

/// Observed order of accuracy log(eCoarse / eFine) / log(ratio) from the errors on two grids whose
/// cell sizes differ by the factor ratio. Throws std::invalid_argument unless both errors are > 0
/// and ratio > 1.
double observedOrder(double eCoarse, double eFine, double ratio);

/// Average of f over [xc - dx/2, xc + dx/2] by composite Gauss-Legendre quadrature (5 points on
/// each of 4 equal sub-intervals; exact for polynomials of degree <= 9). Use it to turn a point
/// solution into finite-volume cell averages, which matters at fronts and shocks.
double cellAverage1D(const std::function<double(double)>& f, double xc, double dx);

/// Thickness behind a rise dz of steady frictionless flow (thickness h, speed u) whose pressure is
/// pg h^2 / 2 and which climbs against the bed's gravity g: the supercritical root of
/// q^2 / (2 x^2) + pg x = u^2 / 2 + pg h - g dz (Bernoulli; water: pg = g; a granular layer with
/// earth-pressure coefficient K: pg = K g), by bisection between h and the critical thickness
/// (q^2 / pg)^(1/3). Throws std::invalid_argument if the flow is not supercritical or chokes.
double supercriticalThicknessBehindRise(double h, double u, double dz, double pg, double g);

}  // namespace talus::analytic
