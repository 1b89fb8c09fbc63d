// Numerical flux through one cell face for the shallow-water equations in horizontal coordinates
// with vertical thickness h (spec §4 with h_s = 0):
//   h_t + div(h u) = 0,
//   (h u)_t + div(h u u) + g_p h grad h = -g_n h grad b.
// From the MUSCL face values of the two cells beside the face: ghost states at boundaries, the
// hydrostatic reconstruction of Audusse et al. (2004, SIAM J. Sci. Comput. 25, eq. 2.7-2.9) with the
// subcell face bed of Chen & Noelle (2017) for well-balancing and positivity (moving water climbs a
// rise with its head: flow/bernoulli_face.cl), and an HLL (Harten, Lax & van Leer 1983) or HLLC (Toro 2001,
// "Shock-capturing methods for free-surface shallow flows", ch. 10) flux.
//
// The hydrostatic pressure part of the normal-momentum flux is returned without its factor g, so
// each cell multiplies it by its own slope-corrected g_p (spec §1); this keeps a lake at rest exact
// where g_p varies from cell to cell.
#ifndef TALUS_FLOW_RIEMANN_CL
#define TALUS_FLOW_RIEMANN_CL
#include "flow/bernoulli_face.cl"
#include "flow/flow_common.cl"

typedef struct {
  real fh, fqn, fqt, p;
} FaceFlux;

/// Wave-speed estimates of Toro (2001) for a shallow-water-type system with sound speeds cl, cr:
/// two-rarefaction estimates where both sides are wet, the dry-bed speeds u -+ 2c otherwise.
INLINE real2 wave_speeds(real hl, real ul, real cl, real hr, real ur, real cr) {
  if (hl <= (real)0) return (real2)(ur - (real)2 * cr, ur + cr);
  if (hr <= (real)0) return (real2)(ul - cl, ul + (real)2 * cl);
  const real us = (real)0.5 * (ul + ur) + cl - cr;
  const real cs = (real)0.5 * (cl + cr) + (real)0.25 * (ul - ur);
  return (real2)(fmin(ul - cl, us - cs), fmax(ur + cr, us + cs));
}

/// HLL flux (Harten, Lax & van Leer 1983) of mass, normal momentum and pressure between the left
/// state (hl, ul, vl, pressure pl) and the right state (hr, ur, vr, pr), with wave speeds s = (sl, sr);
/// the tangential momentum is upwinded across the contact wave (HLLC, Toro 2001) or HLL-averaged.
INLINE FaceFlux hll_core(real hl, real ul, real vl, real pl, real hr, real ur, real vr, real pr, real2 s) {
  FaceFlux f;
  const real sl = s.x, sr = s.y;
  const real ql = hl * ul, qr = hr * ur;
  if (sl >= (real)0) {
    f.fh = ql;
    f.fqn = ql * ul;
    f.fqt = ql * vl;
    f.p = pl;
    return f;
  }
  if (sr <= (real)0) {
    f.fh = qr;
    f.fqn = qr * ur;
    f.fqt = qr * vr;
    f.p = pr;
    return f;
  }
  const real inv = (real)1 / (sr - sl);
  f.fh = (sr * ql - sl * qr + sl * sr * (hr - hl)) * inv;
  f.fqn = (sr * ql * ul - sl * qr * ur + sl * sr * (qr - ql)) * inv;
  f.p = (sr * pl - sl * pr) * inv;
#if RIEMANN == 1
  // HLLC: the tangential velocity is a passive scalar carried across the contact wave s*.
  const real denom = hr * (ur - sr) - hl * (ul - sl);
  const real ss = fabs(denom) > (real)0 ? (sl * hr * (ur - sr) - sr * hl * (ul - sl)) / denom : (real)0.5 * (sl + sr);
  f.fqt = f.fh * (ss >= (real)0 ? vl : vr);
#else
  f.fqt = (sr * ql * vl - sl * qr * vr + sl * sr * (hr * vr - hl * vl)) * inv;
#endif
  return f;
}

/// Shallow-water HLL/HLLC flux between (hl, ul, vl) and (hr, ur, vr), u normal, v tangential; g sets
/// the wave speeds; the pressure part is h^2/2 (the cell multiplies it by its own g_p).
INLINE FaceFlux riemann_flux(real hl, real ul, real vl, real hr, real ur, real vr, real g) {
  if (hl <= (real)0 && hr <= (real)0) {
    FaceFlux f = {0, 0, 0, 0};
    return f;
  }
  const real2 s = wave_speeds(hl, ul, sqrt(g * hl), hr, ur, sqrt(g * hr));
  return hll_core(hl, ul, vl, (real)0.5 * hl * hl, hr, ur, vr, (real)0.5 * hr * hr, s);
}

/// Face value of one side: thickness, free surface, normal and tangential velocity, and g_p of its cell.
typedef struct {
  real h, e, un, ut, g;
} Side;

/// Everything a cell needs from one of its faces.
typedef struct {
  real fh;      // mass flux (per unit width, along +dir)
  real fqn;     // normal momentum flux without the pressure part
  real fqt;     // tangential momentum flux
  real p;       // HLL pressure flux P (the cell adds g_p * P)
  real corr_m;  // bed-jump term of the minus-side cell (face_between, bernoulli_jump_term at a rise)
  real corr_p;  // same for the plus-side cell
} Face;

/// The ghost of a level edge from characteristics (subcritical outflow needs one condition from
/// outside; the zero-gradient ghost of an open edge gives none, and a lake against such an edge is
/// only neutrally at rest: over a rough bed it starts to drain by itself, docs/numerics.md). The
/// outside is water at rest at level `far` over the inside face's bed: the ghost carries the inside's outgoing Riemann
/// invariant u_n + 2c and the outside's incoming one, -2 sqrt(g (far - z)) (0 for a dry outside, a
/// free overfall), so u_g = (R+ + R-)/2, c_g = (R+ - R-)/4 (Toro 2001, "Shock-capturing methods for
/// free-surface shallow flows", sec. 4.4 and 12.3). Supercritical outflow (u_n >= c) needs no
/// condition from outside: the ghost is the inside state. `s` is +1 when the outside is on the plus
/// side, -1 when on the minus side. A lake at rest at the outside's level gets its own state back.
INLINE void open_ghost(const Side* in, Side* gh, real s, real far) {
  *gh = *in;
  const real c = sqrt(in->g * in->h), un = s * in->un;  // un > 0: towards the outside
  if (un >= c) return;
  const real z = in->e - in->h;
  const real rout = un + (real)2 * c, rin = -(real)2 * sqrt(in->g * fmax((real)0, far - z));
  const real ug = (real)0.5 * (rout + rin), cg = fmax((real)0, (real)0.25 * (rout - rin));
  gh->un = s * ug;
  gh->h = cg * cg / in->g;
  gh->e = z + gh->h;
}

/// The flux between two face states by the hydrostatic reconstruction with a subcell face bed (Chen
/// & Noelle 2017, SIAM J. Numer. Anal. 55, eq. 3.4-3.9): the face bed is the higher of the two face
/// beds, but never above the lower of the two heads, z* = min(max(z_m, z_p), min(H_m, H_p)), where
/// a side's head H is its free surface plus the kinetic head of its approach to the face (the free
/// surface for water at rest or moving away; flow/bernoulli_face.cl). A side whose face bed lies
/// below z* meets a rise and is re-measured from z*: at rest Audusse's h* = e - z*, approaching with
/// its discharge and head kept (bernoulli_state). A side above z* (its neighbour's head is lower
/// than its own bed: a thin sheet on a steep coarse slope, water at a cliff edge) keeps its state.
typedef struct {
  real zm, zp, bs;  // face beds and z*
  real2 sm, sp;     // (thickness, normal velocity) of each side at the face
  real wm, wp;      // each side's supercritical approach speed (0 at rest, subcritical, moving away)
  FaceFlux r;
} HydrostaticFace;

INLINE HydrostaticFace hydrostatic_face(Side m, Side p) {
  HydrostaticFace f;
  f.zm = m.e - m.h;
  f.zp = p.e - p.h;
  const Approach am = side_approach(m.h, m.e, m.un, (real)1, m.g);
  const Approach ap = side_approach(p.h, p.e, p.un, (real)-1, p.g);
  f.wm = am.w;
  f.wp = ap.w;
  f.bs = fmin(fmax(f.zm, f.zp), fmin(am.head, ap.head));
  f.sm = f.bs >= f.zm ? bernoulli_state(m.h, m.e, m.un, am, m.g, f.bs) : (real2)(m.h, m.un);
  f.sp = f.bs >= f.zp ? bernoulli_state(p.h, p.e, p.un, ap, p.g, f.bs) : (real2)(p.h, p.un);
  f.r = riemann_flux(f.sm.x, f.sm.y, m.ut, f.sp.x, f.sp.y, p.ut, fmax(m.g, p.g));
  return f;
}

/// Replaces an outside side by the ghost of the inside one (see face_between); returns 1 when the
/// face acts as a wall. Shared by the fluid and the solid fluxes.
INLINE int ghost_sides(int m_in, Side* m, int p_in, Side* p, int kind) {
  int wall = 0;
  if (!m_in) {
    wall = kind == BOUNDARY_WALL || p->un > (real)0;
    *m = *p;
    m->un = wall ? -p->un : p->un;
  } else if (!p_in) {
    wall = kind == BOUNDARY_WALL || m->un < (real)0;
    *p = *m;
    p->un = wall ? -m->un : m->un;
  }
  return wall;
}

/// The face between side m (minus) and side p (plus). An outside side (m_in or p_in zero) becomes
/// the ghost of the inside one: a wall mirrors it with the normal velocity reversed; open and level
/// boundaries (kinds BOUNDARY_OPEN, BOUNDARY_LEVEL) are outflow only: while the inside flow moves
/// away from them, or while a level edge's ghost would push water in, they act as walls, so no water
/// ever enters through them. While the flow moves towards them, the ghost of an open edge is the
/// inside state (zero gradient: the outside continues the inside), that of a level edge the
/// characteristic ghost of open_ghost against still water at level `far` outside (the inside cell's
/// initial surface; for the two-phase fluid, over the solids). Walls pass no mass and no tangential
/// momentum.
INLINE Face face_between(int m_in, Side m, int p_in, Side p, int kind, real far) {
  Face f = {0, 0, 0, 0, 0, 0};
  if (!m_in && !p_in) return f;
  int wall = ghost_sides(m_in, &m, p_in, &p, kind);
  const int characteristic = (!m_in || !p_in) && !wall && kind == BOUNDARY_LEVEL;
  if (characteristic) {
    if (!m_in) open_ghost(&p, &m, (real)-1, far);
    else open_ghost(&m, &p, (real)1, far);
  }
  HydrostaticFace hf = hydrostatic_face(m, p);
  // Outflow only: where the outside's level would push water in (the inside has fallen below it),
  // the level face is a wall (the inside state mirrored), as while the inside flows away from it.
  if (characteristic && ((!m_in && hf.r.fh > (real)0) || (!p_in && hf.r.fh < (real)0))) {
    wall = 1;
    if (!m_in) {
      m = p;
      m.un = -p.un;
    } else {
      p = m;
      p.un = -m.un;
    }
    hf = hydrostatic_face(m, p);
  }
  const FaceFlux r = hf.r;
  const real zm = hf.zm, zp = hf.zp, bs = hf.bs;
  f.fh = wall ? (real)0 : r.fh;
  f.fqn = r.fqn;
  f.fqt = wall ? (real)0 : r.fqt;
  f.p = r.p;
  // The source of the bed jump between a side's face bed and z*: at a rise the difference of the
  // side's own momentum flux and that of its state at z* (bernoulli_jump_term; at rest Audusse's
  // (h^2 - h*^2)/2, bitwise); at a drop (the side keeps its state) Chen & Noelle's h (z* - z) < 0,
  // the bed force of the fall to the neighbour's head, which drives a sheet on a staircase by its
  // true slope. Without it (Audusse's z* = max(z_m, z_p)) the face only passes a dam-break flux and
  // water on slopes steeper than depth over cell size is held back by the grid.
  f.corr_m = bs >= zm ? bernoulli_jump_term(m.h, m.un, hf.sm, hf.wm, m.g) : m.h * (bs - zm);
  f.corr_p = bs >= zp ? bernoulli_jump_term(p.h, p.un, hf.sp, hf.wp, p.g) : p.h * (bs - zp);
  return f;
}

#endif
