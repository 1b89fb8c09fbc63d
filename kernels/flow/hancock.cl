// The predictor of the MUSCL-Hancock scheme (Time Scheme=hancock; van Leer 1984, SIAM J. Sci. Stat.
// Comput. 5, 1; Toro 2009, Riemann Solvers and Numerical Methods for Fluid Dynamics, sec. 14.4): both
// face states of a cell advance by half a step, so that the fluxes of the single corrector stage are
// centred in time (second order in space and time with one flux evaluation per sweep, against the
// two of SSP-RK2). Near Courant number 1 it is much less dissipative than SSP-RK2 with the same
// reconstruction: on a steep slope, roll waves keep their crests at 20 cells per wavelength
// (tests/verification/test_roll_waves.cpp, docs/numerics.md "Roll waves").
//
// In primitive variables along the sweep (Toro 2009, eq. 14.40, the quasi-linear form), with
// r = dt / (2 dx), u_bar = (u_lo + u_hi) / 2 the cell's normal velocity and v the tangential one:
//   dh = r (q_lo - q_hi)                (q: the corrector's mass flux of each face, hancock_face),
//   du = -r [u_bar (u_hi - u_lo) + g (eta_hi - eta_lo)]    (advection, pressure and bed slope; each
//                                                            face surface less its drop, hancock_face),
//   dv = -r u_bar (v_hi - v_lo).
// The pressure and the bed slope enter as one surface difference: a lake at rest (flat face
// surfaces, no velocity) is left exactly as it is, so the scheme stays well-balanced bit for bit;
// and no face velocity is a momentum divided by a thin face's thickness. Where dh would empty the
// thinner face it is cut to leave that face at zero (positivity of the predicted states; the
// corrector is positive by the split sweeps' draining time, stage.cl); a face left at or below
// h_dry has no velocity. A first-order cell (equal face values) still changes: its thickness by
// its faces' mass fluxes, its velocity by their drops.
// Friction is not in the predictor: the step is Strang-split, friction over dt/2 before and after
// it (FlowSolver::step). With friction in the predictor as well, a sheet on a rough slope was
// slowed twice (its 5 m map 0.39 from the 1.25 m one, 0.31 without) and the linear roll waves
// travelled 2 % slow.
#ifndef TALUS_FLOW_HANCOCK_CL
#define TALUS_FLOW_HANCOCK_CL
#include "flow/riemann.cl"

/// What the corrector's hydrostatic face between the minus side m and the plus side p does to each
/// side, as the predictor needs it (from the unpredicted face values; hydrostatic_face, riemann.cl):
/// - q: the mass flux through the face (per unit width, from m to p): the corrector's own flux,
///   the hydrostatic reconstruction's Riemann flux, evaluated with the unpredicted states. The
///   predictor's thickness change is thus a first-order Godunov half-step, which sees the face as
///   the corrector will: no mass leaves through the part of a face below the neighbour's bed, and
///   the lake at rest stays exact. Two other forms were measured (docs/numerics.md):
///   the faces' own h u (Toro's predictor) thinned a face that water presses against a rise, so its
///   hydrostatic push (h^2 - h*^2)/2 fell while the momentum into it grew: a lake among dry islands
///   over a rough bed grew round-off into 0.2 m/s (tools/validation/hancock_lake_1d.py); each
///   side's h* u at z* held that lake but held sheets back at every rise of a rough slope (5 m map
///   0.49 from the 1.25 m one, against 0.28 for the SSP-RK2 sweeps; this form 0.28).
/// - drop: how far the side's face bed lies above z* (0 where it does not): the corrector pushes the
///   side towards the lower neighbour with Chen & Noelle's h (z* - z) (riemann.cl, face_between),
///   the force of a surface lowered by the drop. The predictor takes it as such (e_face - drop in
///   its surface difference). Without it a cell whose own reconstruction is flat (first order: a
///   film thinner than the bed's change of slope) got no acceleration in the predictor, so the
///   corrector moved no mass while its bed force accelerated the water: a 1 mm film on a fractal
///   slope gained 4.8 times the energy it released in its first step (stress seed
///   14493454552802392858 with the MUSCL-Hancock sweeps).
typedef struct {
  real mass, drop_m, drop_p;
} PredictorFace;

INLINE PredictorFace hancock_face(Side m, Side p) {
  const HydrostaticFace f = hydrostatic_face(m, p);
  PredictorFace o;
  o.mass = f.r.fh;
  o.drop_m = fmax((real)0, f.zm - f.bs);
  o.drop_p = fmax((real)0, f.zp - f.bs);
  return o;
}

/// The predictor's change of both face thicknesses from the mass fluxes q_lo, q_hi of the cell's two
/// faces (see above), cut where it would empty the thinner face.
INLINE real hancock_thickness_change(CellFaces f, real q_lo, real q_hi, real r) {
  const real dh = r * (q_lo - q_hi);
  const real thinner = fmin(f.h_lo, f.h_hi);
  return thinner + dh < (real)0 ? -thinner : dh;
}

/// The predicted faces from the MUSCL faces f, the thickness change dh and the two faces' drops.
INLINE CellFaces hancock_predict(CellFaces f, real dh, real drop_lo, real drop_hi, real g, real r, real h_dry) {
  const real ubar = (real)0.5 * (f.un_lo + f.un_hi);
  const real du = -r * (ubar * (f.un_hi - f.un_lo) + g * ((f.e_hi - drop_hi) - (f.e_lo - drop_lo)));
  const real dv = -r * ubar * (f.ut_hi - f.ut_lo);
  CellFaces o;
  o.h_lo = f.h_lo + dh;
  o.h_hi = f.h_hi + dh;
  o.e_lo = f.e_lo + dh;
  o.e_hi = f.e_hi + dh;
  const int wet_lo = o.h_lo > h_dry, wet_hi = o.h_hi > h_dry;
  o.un_lo = wet_lo ? f.un_lo + du : (real)0;
  o.un_hi = wet_hi ? f.un_hi + du : (real)0;
  o.ut_lo = wet_lo ? f.ut_lo + dv : (real)0;
  o.ut_hi = wet_hi ? f.ut_hi + dv : (real)0;
  return o;
}

#endif
