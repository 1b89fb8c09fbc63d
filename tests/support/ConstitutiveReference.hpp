// A plain C++ (double) reference of the particle constitutive update of
// kernels/particles/constitutive.cl, written independently of it for the kernel tests.
//
// Same model (see the kernel's header for the equations: paper P.12-P.26, P.40-P.41, P.79-P.82,
// P.89-P.94; Bui et al. 2008), different arithmetic route:
// - stresses, strain rates and spins are full 3 x 3 tensors (sigma_xz = sigma_yz = 0, sigma_zz the
//   prescribed overburden); invariants come from the deviator matrix, I1 = tr sigma,
//   J2 = 1/2 s:s;
// - the Jaumann rotation is the matrix product Q sigma Q^T with Q = exp(w dt), built from the
//   angle w_xy dt;
// - plane stress: the elastic increment is dt (2G dev(eps') + K tr(eps') I) of the 3D tensor whose
//   vertical entry eps'_zz is solved for numerically so that the vertical stress does not change
//   (not the kernel's closed form lambda*), of which the in-plane components are kept;
// - the plastic multiplier is f* / (df/dsigma : D_ps : dg/dsigma), D_ps that same plane-stress
//   response, with the double contraction evaluated numerically from the tensors (not the
//   kernel's closed form h);
// - the remapping finds the in-plane tension and compression limits and the scale factor of the
//   deviator by bisection on the yield function itself (no closed forms), so it checks the
//   kernel's algebra rather than repeating it.
// Tension positive, SI units, angles in radians.
#pragma once

namespace talus::test {

/// One particle's material: E [Pa], nu [-], phi and psi [rad], current cohesion c [Pa].
struct ConstitutiveMaterial {
  double E = 0, nu = 0, phi = 0, c = 0, psi = 0;
};

/// In-plane stress (tension positive) [Pa].
struct ConstitutiveStress {
  double xx = 0, yy = 0, xy = 0;
};

/// Result of one reference step.
struct ConstitutiveStep {
  ConstitutiveStress stress;  // the new in-plane stress [Pa]
  double dlambda = 0;         // plastic multiplier of the step (0 when elastic)
  double epsVRate = 0;        // volumetric strain rate [1/s]
  bool yielded = false;       // the trial state lay outside the surface
  double trialYield = 0;      // f of the elastic trial state [Pa]
};

/// The yield function f = alpha_phi I1 + sqrt(J2) - k_c of the 3D state (s, szz).
double referenceYield(const ConstitutiveStress& s, double szz, const ConstitutiveMaterial& m);

/// One step of the stress update over dt with velocity gradient L[a][b] = dv_a/dx_b.
ConstitutiveStep referenceStressUpdate(const ConstitutiveStress& s, const double L[2][2], double szz,
                                       const ConstitutiveMaterial& m, double dt);

/// Cohesion after one step (P.26), and the intact-bond fraction c/c0 (1 for c0 <= 0).
double referenceCohesion(double c, double c0, double epsVRate, double epsC, double dt, bool yielding);
double referenceBondFraction(double c, double c0);

}  // namespace talus::test
