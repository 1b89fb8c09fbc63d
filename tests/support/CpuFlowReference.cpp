// CPU reference of one shallow-water step (see CpuFlowReference.hpp for the scheme in one page).
// Written from the equations in the kernel file headers, not from the kernel code paths: faces are
// computed once per face into arrays, then every cell takes its divergence.
#include "support/CpuFlowReference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/Constants.hpp"
#include "flow/SlopeGravity.hpp"

namespace talus::test {

using flow::Boundary;
using flow::Limiter;

namespace {

/// Speed of a side towards the face (towards = +1 for the minus side, -1 for the plus side) where it
/// arrives supercritically, else 0.
double approachSpeed(double h, double un, double towards, double g) {
  const double w = std::max(0.0, towards * un);
  return w * w > g * h ? w : 0.0;
}

/// A side's (thickness, normal velocity) at the face bed zs >= its own bed
/// (kernels/flow/bernoulli_face.cl): Audusse's (eta - zs, un) unless it arrives supercritically
/// with speed w; then the depth with the same discharge and total head h + w^2 / (2 g) - (zs - z)
/// on the supercritical branch (Bernoulli), solved here by bisection between the side's depth and
/// the critical depth (an independent root finder from the kernel's Newton iteration), or the
/// critical state 2/3 E where the rise chokes the flow.
std::pair<double, double> bernoulliState(double h, double eta, double un, double towards, double g, double zs) {
  const double w = approachSpeed(h, un, towards, g);
  if (!(w > 0.0) || !(h > 0.0)) return {std::max(0.0, eta - zs), un};
  // From h and the rise (exact where z* is the side's own face bed), and exactly 0 where z* is the
  // side's own head, as in the kernel.
  const double head = eta + w * w / (2.0 * g);
  const double es = zs == head ? 0.0 : h + w * w / (2.0 * g) - (zs - (eta - h));
  if (!(es > 0.0)) return {0.0, 0.0};
  const double q2 = h * h * un * un, hc = std::cbrt(q2 / g);
  if (es <= 1.5 * hc) return {2.0 * es / 3.0, std::copysign(std::min(std::fabs(un), std::sqrt(2.0 * g * es / 3.0)), un)};
  // f(x) = x + q^2 / (2 g x^2) - es: f(h) = zs - z >= 0 and f(hc) = 3/2 hc - es < 0, so the root on
  // h's branch lies between h and hc.
  double a = h, b = hc;
  for (int it = 0; it < 200 && std::fabs(a - b) > 1e-15 * std::max(a, b); ++it) {
    const double mid = 0.5 * (a + b);
    const double f = mid + q2 / (2.0 * g * mid * mid) - es;
    (f > 0.0 ? a : b) = mid;
  }
  const double x = 0.5 * (a + b);
  return {x, x > h ? h * un / x : un};  // the face never passes more than the side's discharge h u
}

/// Bed-jump term of a side re-measured from z* (riemann.cl, face_between): its momentum flux minus
/// that of its face state, without g; Audusse's (h^2 - h*^2) / 2 unless it arrives supercritically.
double bernoulliJump(double h, double un, std::pair<double, double> face, double towards, double g) {
  double c = 0.5 * (h * h - face.first * face.first);
  if (approachSpeed(h, un, towards, g) > 0.0) c += (h * un * un - face.first * face.second * face.second) / g;
  return c;
}


}  // namespace

CpuFlowReference::CpuFlowReference(const Grid& grid, const flow::FlowSettings& settings,
                                   const flow::FlowInput& in)
    : grid_(grid), settings_(settings), mask_(in.mask.begin(), in.mask.end()), bed_(in.bed), manning_(in.manning),
      h_(in.h), qx_(in.qx), qy_(in.qy) {
  const std::size_t n = grid.cells();
  if (mask_.size() != n || bed_.size() != n || manning_.size() != n || h_.size() != n)
    throw std::invalid_argument("CpuFlowReference: input sizes differ from the grid");
  if (qx_.empty()) qx_.assign(n, 0.0);
  if (qy_.empty()) qy_.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    if (!mask_[k]) h_[k] = 0.0, bed_[k] = 0.0;
  // The level of the water outside an open edge: the edge cell's initial surface.
  farLevel_.resize(n);
  for (std::size_t k = 0; k < n; ++k) farLevel_[k] = bed_[k] + h_[k];
  // The dry-cell rule applies to the input too: no momentum where h <= h_dry (or outside).
  for (std::size_t k = 0; k < n; ++k)
    if (h_[k] <= settings_.hDry) qx_[k] = 0.0, qy_[k] = 0.0;
  const flow::SlopeGravity sg = flow::computeSlopeGravity(grid, bed_, in.mask, settings);
  gn_ = sg.gn;
  slope_ = sg.slopeSpeed;
  gp_ = sg.gp;
  bx_ = settings.slopeCorrection ? sg.slopeX : std::vector<double>(n, 0.0);
  by_ = settings.slopeCorrection ? sg.slopeY : std::vector<double>(n, 0.0);
  hMax_ = h_;
  vMax_.assign(n, 0.0);
  arrival_.assign(n, -1.0);
  track();
  computeDiagnostics(0.0);
}

bool CpuFlowReference::inside(int i, int j) const {
  return i >= 0 && j >= 0 && i < grid_.nx && j < grid_.ny && mask_[grid_.index(i, j)] != 0;
}

// Kurganov & Petrova's (2007, eq. 2.21) desingularised velocity with eps = h_dry is exactly q / h
// above the dry threshold; below it the velocity is zero (flow_common.cl).
double CpuFlowReference::velocity(double h, double q) const { return h > settings_.hDry ? q / h : 0.0; }

// Slope from the backward difference a and the forward difference b; zero at extrema.
double CpuFlowReference::limiter(double a, double b) const {
  if (settings_.limiter == Limiter::None || a * b <= 0.0) return 0.0;
  switch (settings_.limiter) {
    case Limiter::Minmod: return std::fabs(a) < std::fabs(b) ? a : b;
    case Limiter::VanLeer: return 2.0 * a * b / (a + b);  // harmonic mean
    case Limiter::MC: {                                   // minmod(2a, 2b, (a + b) / 2)
      const double centred = 0.5 * (a + b);
      return std::copysign(std::min({std::fabs(2.0 * a), std::fabs(2.0 * b), std::fabs(centred)}), centred);
    }
    default: return 0.0;
  }
}

CpuFlowReference::Prim CpuFlowReference::prim(const State& s, int i, int j, int dir) const {
  const std::size_t k = grid_.index(i, j);
  const double u = velocity(s.h[k], s.qx[k]), v = velocity(s.h[k], s.qy[k]);
  return {s.h[k], s.h[k] + bed_[k], dir == 0 ? u : v, dir == 0 ? v : u};
}

CpuFlowReference::Faces CpuFlowReference::reconstruct(const State& s, int i, int j, int dir) const {
  const Faces f = muscl(s, i, j, dir);
  return settings_.scheme == flow::TimeScheme::Hancock ? predict(s, f, i, j, dir) : f;
}

CpuFlowReference::Faces CpuFlowReference::muscl(const State& s, int i, int j, int dir) const {
  const int di = dir == 0 ? 1 : 0, dj = 1 - di;
  const Prim c = prim(s, i, j, dir);
  // The surface with the limiter over a minmod bed (flow_common.cl, reconstruct_surface), the bed
  // slope moved from db towards 0 just enough that both face thicknesses h -+ (se - slope)/2 lie
  // within the room below (the thicknesses' range [hmin, hmax] of the cell and its neighbours, or the
  // thickness slope of surface and bed limited alike); where no such slope exists but the unflattened faces
  // are positive (|se - db| <= 2h), the bed keeps db and the thickness slope se - db is clipped to
  // that range; zero slopes next to outside cells, in dry cells and otherwise.
  double dh = 0, de = 0, dun = 0, dut = 0;
  const bool bothInside = inside(i - di, j - dj) && inside(i + di, j + dj);
  if (bothInside && c.h > 0.0) {
    const Prim m = prim(s, i - di, j - dj, dir), p = prim(s, i + di, j + dj, dir);
    const double a = (c.eta - c.h) - (m.eta - m.h), b = (p.eta - p.h) - (c.eta - c.h);
    const double db = a * b <= 0.0 ? 0.0 : (std::fabs(a) < std::fabs(b) ? a : b);
    double de_m = c.eta - m.eta, de_p = p.eta - c.eta;
    if (settings_.scheme == flow::TimeScheme::Hancock) {
      // An empty neighbour whose bed stands above the cell's surface plus the kinetic head of its
      // motion towards it is a wall: difference zero (flow_common.cl, HANCOCK: GRAVITY there).
      const double um = std::max(0.0, -c.un), up = std::max(0.0, c.un);
      if (m.h <= 0.0 && m.eta > c.eta + um * um / (2.0 * kGravity)) de_m = 0.0;
      if (p.h <= 0.0 && p.eta > c.eta + up * up / (2.0 * kGravity)) de_p = 0.0;
    }
    const double se = limiter(de_m, de_p);
    const double hmax = std::max({m.h, c.h, p.h}), hmin = std::min({m.h, c.h, p.h});
    // |thickness slope| <= room: within [hmin, hmax], or within the thickness slope of the surface
    // and the bed limited alike if that is larger; never beyond positivity (2h)
    const double room = std::min(2.0 * c.h, std::max(2.0 * std::min(hmax - c.h, c.h - hmin),
                                                      std::fabs(se - limiter(a, b))));
    // The bed slope nearest db in [min(0, db), max(0, db)] with |se - slope| <= room, if any.
    const double lo = std::max(se - room, std::min(0.0, db)), hi = std::min(se + room, std::max(0.0, db));
    const bool flattenable = lo <= hi;
    const double near = flattenable ? std::clamp(db, lo, hi) : db;
    bool sloped = true;
    if (flattenable) {
      dh = se - near;
      de = se;
    } else if (std::fabs(se - db) <= 2.0 * c.h) {  // positive faces, but outside [hmin, hmax]
      dh = std::clamp(se - db, -room, room);
      de = db + dh;
    } else {
      sloped = false;
    }
    if (sloped) {
      dun = limiter(c.un - m.un, p.un - c.un);
      dut = limiter(c.ut - m.ut, p.ut - c.ut);
    }
  }
  Faces f{c.h - 0.5 * dh,   c.h + 0.5 * dh,   c.eta - 0.5 * de, c.eta + 0.5 * de,
          c.un - 0.5 * dun, c.un + 0.5 * dun, c.ut - 0.5 * dut, c.ut + 0.5 * dut};
  // A face no thicker than the dry threshold is dry, at the same face bed (flow_common.cl, dry_faces).
  if (f.hLo <= settings_.hDry) f.etaLo -= f.hLo, f.hLo = 0.0;
  if (f.hHi <= settings_.hDry) f.etaHi -= f.hHi, f.hHi = 0.0;
  return f;
}

// What the hydrostatic face between a minus side (h, eta, un, g) and a plus side does to each side
// (kernels/flow/hancock.cl, hancock_face): its mass flux (the Riemann flux between the sides'
// states at the face bed z* = min(max(z_l, z_r), min(head_l, head_r)); a side above z* keeps its
// own), and how far each side's face bed lies above z* (the drop it is pushed down).
CpuFlowReference::PredictorFace CpuFlowReference::predictorFace(double hl, double el, double ul, double vl, double gl,
                                                                double hr, double er, double ur, double vr,
                                                                double gr) const {
  const double zl = el - hl, zr = er - hr;
  const double wl = approachSpeed(hl, ul, 1.0, gl), wr = approachSpeed(hr, ur, -1.0, gr);
  const double bedFace = std::min(std::max(zl, zr), std::min(el + wl * wl / (2.0 * gl), er + wr * wr / (2.0 * gr)));
  const auto sl = bedFace >= zl ? bernoulliState(hl, el, ul, 1.0, gl, bedFace) : std::make_pair(hl, ul);
  const auto sr = bedFace >= zr ? bernoulliState(hr, er, ur, -1.0, gr, bedFace) : std::make_pair(hr, ur);
  const double mass = riemann(sl.first, sl.second, vl, sr.first, sr.second, vr, std::max(gl, gr)).mass;
  return {mass, std::max(0.0, zl - bedFace), std::max(0.0, zr - bedFace)};
}

// MUSCL-Hancock predictor (van Leer 1984; Toro 2009, sec. 14.4), from the formulas of
// kernels/flow/hancock.cl: both faces advance by half a step, r = dt / (2 dx), u_bar = (u_lo + u_hi)/2,
// dh = r (q_lo - q_hi) with q each face's mass flux (predictorFace, from the neighbours' MUSCL
// faces; the face's own h u next to outside cells and at empty faces), cut to
// empty the thinner face at most, du = -r [u_bar (u_hi - u_lo) + g ((eta_hi - drop_hi) -
// (eta_lo - drop_lo))] with each face's drop,
// dv = -r u_bar (v_hi - v_lo); a face at or below h_dry is dry (no thickness, no velocity).
CpuFlowReference::Faces CpuFlowReference::predict(const State& s, const Faces& f, int i, int j, int dir) const {
  const int di = dir == 0 ? 1 : 0, dj = 1 - di;
  const double r = predictorRatio_, g = gp_[grid_.index(i, j)];
  double qLo = f.hLo * f.unLo, qHi = f.hHi * f.unHi, dropLo = 0.0, dropHi = 0.0;
  if (inside(i - di, j - dj) && f.hLo > 0.0) {
    const Faces m = muscl(s, i - di, j - dj, dir);
    const PredictorFace pf = predictorFace(m.hHi, m.etaHi, m.unHi, m.utHi, gp_[grid_.index(i - di, j - dj)], f.hLo,
                                           f.etaLo, f.unLo, f.utLo, g);
    qLo = pf.mass, dropLo = pf.dropPlus;
  }
  if (inside(i + di, j + dj) && f.hHi > 0.0) {
    const Faces p = muscl(s, i + di, j + dj, dir);
    const PredictorFace pf = predictorFace(f.hHi, f.etaHi, f.unHi, f.utHi, g, p.hLo, p.etaLo, p.unLo, p.utLo,
                                           gp_[grid_.index(i + di, j + dj)]);
    qHi = pf.mass, dropHi = pf.dropMinus;
  }
  const double dh = std::max(r * (qLo - qHi), -std::min(f.hLo, f.hHi));
  const double ubar = 0.5 * (f.unLo + f.unHi);
  const double du = -r * (ubar * (f.unHi - f.unLo) + g * ((f.etaHi - dropHi) - (f.etaLo - dropLo)));
  const double dv = -r * ubar * (f.utHi - f.utLo);
  Faces p{f.hLo + dh, f.hHi + dh, f.etaLo + dh, f.etaHi + dh, f.unLo + du, f.unHi + du, f.utLo + dv, f.utHi + dv};
  if (!(p.hLo > settings_.hDry)) p.unLo = 0.0, p.utLo = 0.0;
  if (!(p.hHi > settings_.hDry)) p.unHi = 0.0, p.utHi = 0.0;
  if (p.hLo <= settings_.hDry) p.etaLo -= p.hLo, p.hLo = 0.0;
  if (p.hHi <= settings_.hDry) p.etaHi -= p.hHi, p.hHi = 0.0;
  return p;
}

// HLL (Harten, Lax & van Leer 1983) / HLLC (Toro 2001, ch. 10) with Toro's two-rarefaction wave
// speed estimates and the dry-bed speeds. `pressure` is the HLL average of h^2/2 without g.
CpuFlowReference::FaceFlux CpuFlowReference::riemann(double hl, double ul, double vl, double hr, double ur,
                                                     double vr, double g) const {
  FaceFlux f;
  if (hl <= 0.0 && hr <= 0.0) return f;
  const double cl = std::sqrt(g * hl), cr = std::sqrt(g * hr);
  double sl, sr;
  if (hl <= 0.0) {
    sl = ur - 2.0 * cr, sr = ur + cr;
  } else if (hr <= 0.0) {
    sl = ul - cl, sr = ul + 2.0 * cl;
  } else {
    const double uStar = 0.5 * (ul + ur) + cl - cr;
    const double cStar = 0.5 * (cl + cr) + 0.25 * (ul - ur);
    sl = std::min(ul - cl, uStar - cStar);
    sr = std::max(ur + cr, uStar + cStar);
  }
  const double ql = hl * ul, qr = hr * ur;
  if (sl >= 0.0 || sr <= 0.0) {  // supersonic: upwind physical flux
    const bool left = sl >= 0.0;
    const double h = left ? hl : hr, q = left ? ql : qr, u = left ? ul : ur, v = left ? vl : vr;
    f.mass = q, f.normalMomentum = q * u, f.tangentialMomentum = q * v, f.pressure = 0.5 * h * h;
    return f;
  }
  const double w = 1.0 / (sr - sl);
  f.mass = (sr * ql - sl * qr + sl * sr * (hr - hl)) * w;
  f.normalMomentum = (sr * ql * ul - sl * qr * ur + sl * sr * (qr - ql)) * w;
  f.pressure = (sr * 0.5 * hl * hl - sl * 0.5 * hr * hr) * w;
  if (settings_.riemann == flow::RiemannSolver::HLLC) {
    // Contact speed s* (Toro eq. 10.71); v is carried passively on the upwind side of s*.
    const double den = hr * (ur - sr) - hl * (ul - sl);
    const double sStar = den != 0.0 ? (sl * hr * (ur - sr) - sr * hl * (ul - sl)) / den : 0.5 * (sl + sr);
    f.tangentialMomentum = f.mass * (sStar >= 0.0 ? vl : vr);
  } else {
    f.tangentialMomentum = (sr * ql * vl - sl * qr * vr + sl * sr * (hr * vr - hl * vl)) * w;
  }
  return f;
}

// Face (i,j) of direction dir lies between cell (i-1,j) and (i,j) (dir 0) or (i,j-1) and (i,j).
CpuFlowReference::FaceFlux CpuFlowReference::faceFlux(const State& s, int i, int j, int dir) const {
  const int li = dir == 0 ? i - 1 : i, lj = dir == 0 ? j : j - 1;
  const bool lIn = inside(li, lj), rIn = inside(i, j);
  FaceFlux f;
  if (!lIn && !rIn) return f;
  struct Side {
    double h, eta, un, ut, g;
  } L{}, R{};
  if (lIn) {
    const Faces c = reconstruct(s, li, lj, dir);
    L = {c.hHi, c.etaHi, c.unHi, c.utHi, gp_[grid_.index(li, lj)]};
  }
  if (rIn) {
    const Faces c = reconstruct(s, i, j, dir);
    R = {c.hLo, c.etaLo, c.unLo, c.utLo, gp_[grid_.index(i, j)]};
  }
  // Ghost cell: a copy of the inside face state, normal velocity mirrored at a wall. Open and level
  // boundaries let water out only: while the inside flow moves away from them, they are walls; while
  // it moves towards a level edge, the ghost meets the inside's outgoing Riemann invariant u + 2c (outward normal)
  // with the incoming one of water at rest at the inside cell's far level outside, -2 sqrt(g d)
  // with d the far level's height over the inside face bed (0 where the outside is dry), unless the
  // outflow is supercritical (then the copy stands); and if that ghost would let water in, the face
  // is a wall after all.
  auto kind = [&](int a, int b) {
    const bool offRaster = a < 0 || b < 0 || a >= grid_.nx || b >= grid_.ny;
    return offRaster ? settings_.edge : settings_.nodata;
  };
  bool wall = false;
  const Side inside = lIn ? L : R;
  if (!lIn) {
    wall = kind(li, lj) == Boundary::Wall || R.un > 0.0;
    L = R;
    if (wall) L.un = -R.un;
  }
  if (!rIn) {
    wall = kind(i, j) == Boundary::Wall || L.un < 0.0;
    R = L;
    if (wall) R.un = -L.un;
  }
  const Boundary outsideKind = !lIn ? kind(li, lj) : kind(i, j);
  const bool open = (!lIn || !rIn) && !wall && outsideKind == Boundary::Level;
  if (open) {
    const double outward = lIn ? 1.0 : -1.0;  // the outside lies on the plus side when L is inside
    const double un = outward * inside.un, c = std::sqrt(inside.g * inside.h);
    if (un < c) {
      const double bedAtFace = inside.eta - inside.h;
      const double far = farLevel_[lIn ? grid_.index(li, lj) : grid_.index(i, j)];
      const double plus = un + 2.0 * c, minus = -2.0 * std::sqrt(inside.g * std::max(0.0, far - bedAtFace));
      const double cGhost = std::max(0.0, (plus - minus) / 4.0);
      Side& ghost = lIn ? R : L;
      ghost.un = outward * (plus + minus) / 2.0;
      ghost.h = cGhost * cGhost / inside.g;
      ghost.eta = bedAtFace + ghost.h;
    }
  }
  // Chen & Noelle (2017, eq. 3.4-3.9): face bed = higher face bed, but not above the lower head
  // (surface plus the kinetic head of the approach to the face); a side below it is re-measured from
  // it (Audusse et al. 2004 at rest, Bernoulli when approaching), a side above it keeps its state and
  // takes the bed force of the drop, h (z* - z).
  auto solve = [&]() {
    const double zl = L.eta - L.h, zr = R.eta - R.h;
    const double wl = approachSpeed(L.h, L.un, 1.0, L.g), wr = approachSpeed(R.h, R.un, -1.0, R.g);
    const double headL = L.eta + wl * wl / (2.0 * L.g), headR = R.eta + wr * wr / (2.0 * R.g);
    const double bedFace = std::min(std::max(zl, zr), std::min(headL, headR));
    const auto sl = bedFace >= zl ? bernoulliState(L.h, L.eta, L.un, 1.0, L.g, bedFace) : std::make_pair(L.h, L.un);
    const auto sr = bedFace >= zr ? bernoulliState(R.h, R.eta, R.un, -1.0, R.g, bedFace) : std::make_pair(R.h, R.un);
    FaceFlux r = riemann(sl.first, sl.second, L.ut, sr.first, sr.second, R.ut, std::max(L.g, R.g));
    r.corrMinus = bedFace >= zl ? bernoulliJump(L.h, L.un, sl, 1.0, L.g) : L.h * (bedFace - zl);
    r.corrPlus = bedFace >= zr ? bernoulliJump(R.h, R.un, sr, -1.0, R.g) : R.h * (bedFace - zr);
    return r;
  };
  f = solve();
  const bool inflow = (!lIn && f.mass > 0.0) || (!rIn && f.mass < 0.0);
  if (open && inflow) {
    wall = true;
    Side& ghost = lIn ? R : L;
    ghost = inside;
    ghost.un = -inside.un;
    f = solve();
  }
  if (wall) f.mass = 0.0, f.tangentialMomentum = 0.0;
  return f;
}

double CpuFlowReference::rkStage(const State& s, const State* base, double dt, State& out, double& added,
                                 int dirs) const {
  const int nx = grid_.nx, ny = grid_.ny;
  std::vector<FaceFlux> fx(static_cast<std::size_t>(nx + 1) * ny), fy(static_cast<std::size_t>(nx) * (ny + 1));
  if (dirs & 1)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i) fx[j * (nx + 1) + i] = faceFlux(s, i, j, 0);
  if (dirs & 2)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) fy[j * nx + i] = faceFlux(s, i, j, 1);

  const double r = dt / grid_.dx;
  if (flow::sweeps(settings_.scheme)) {
    // Draining time (Bollermann et al. 2011), in the split sweeps at every Courant number (the
    // kernel's split build, DRAINING = SPLIT): a cell whose outgoing mass fluxes would take more than
    // it holds within the stage gives each of them the fraction theta = h / (r O) of the stage in
    // which it still has water; a face's mass and advective momentum fluxes take the factor of its
    // upwind cell, its pressure and bed corrections stay.
    std::vector<double> theta(grid_.cells(), 1.0);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!inside(i, j)) continue;
        const FaceFlux &W = fx[j * (nx + 1) + i], &E = fx[j * (nx + 1) + i + 1];
        const FaceFlux &S = fy[j * nx + i], &N = fy[(j + 1) * nx + i];
        const double outgoing = std::max(E.mass, 0.0) - std::min(W.mass, 0.0) + std::max(N.mass, 0.0) -
                                std::min(S.mass, 0.0);
        const double h = s.h[grid_.index(i, j)];
        if (r * outgoing > h) theta[grid_.index(i, j)] = h / (r * outgoing);
      }
    auto limit = [&](FaceFlux& f, int im, int jm, int ip, int jp) {
      const bool minusUp = f.mass > 0.0;
      const int iu = minusUp ? im : ip, ju = minusUp ? jm : jp;
      if (!inside(iu, ju)) return;
      const double t = theta[grid_.index(iu, ju)];
      f.mass *= t, f.normalMomentum *= t, f.tangentialMomentum *= t;
    };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i <= nx; ++i) limit(fx[j * (nx + 1) + i], i - 1, j, i, j);
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) limit(fy[j * nx + i], i, j - 1, i, j);
    drainedCells_ += static_cast<int>(std::count_if(theta.begin(), theta.end(), [](double t) { return t < 1.0; }));
  }
  double outward = 0.0;
  out = s;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!inside(i, j)) continue;
      const std::size_t k = grid_.index(i, j);
      const FaceFlux &W = fx[j * (nx + 1) + i], &E = fx[j * (nx + 1) + i + 1];
      const FaceFlux &S = fy[j * nx + i], &N = fy[(j + 1) * nx + i];
      const double g = gp_[k];
      // Flux divergence; a cell is the minus side of its E/N faces and the plus side of W/S.
      double dh = -r * (E.mass - W.mass + N.mass - S.mass);
      const double east = E.normalMomentum + g * (E.pressure + E.corrMinus);
      const double west = W.normalMomentum + g * (W.pressure + W.corrPlus);
      const double north = N.normalMomentum + g * (N.pressure + N.corrMinus);
      const double south = S.normalMomentum + g * (S.pressure + S.corrPlus);
      double dqx = -r * (east - west + N.tangentialMomentum - S.tangentialMomentum);
      double dqy = -r * (north - south + E.tangentialMomentum - W.tangentialMomentum);
      // Centred bed source g_p (h_lo + h_hi)/2 (b_hi - b_lo) of the cell's own reconstruction,
      // plus (g_p - g_n) h db/dx (nonzero only for the cos^4 depth pressure).
      if (s.h[k] > 0.0) {
        for (int dir = 0; dir < 2; ++dir) {
          if (!((dirs >> dir) & 1)) continue;
          const int di = dir == 0 ? 1 : 0, dj = 1 - di;
          const Faces c = reconstruct(s, i, j, dir);
          double src = g * 0.5 * (c.hLo + c.hHi) * ((c.etaHi - c.hHi) - (c.etaLo - c.hLo));
          if (g != gn_[k] && inside(i - di, j - dj) && inside(i + di, j + dj))
            src -= (g - gn_[k]) * s.h[k] * 0.5 *
                   (bed_[grid_.index(i + di, j + dj)] - bed_[grid_.index(i - di, j - dj)]);
          (dir == 0 ? dqx : dqy) -= r * src;
        }
      }
      double h = s.h[k] + dh, qx = s.qx[k] + dqx, qy = s.qy[k] + dqy;
      if (base) {
        h = 0.5 * base->h[k] + 0.5 * h;
        qx = 0.5 * base->qx[k] + 0.5 * qx;
        qy = 0.5 * base->qy[k] + 0.5 * qy;
      }
      if (h <= settings_.hDry) {
        if (h < 0.0) added -= h * grid_.dx * grid_.dx;  // volume the clamp creates (see header)
        h = std::max(h, 0.0), qx = 0.0, qy = 0.0;
      }
      out.h[k] = h, out.qx[k] = qx, out.qy[k] = qy;
      if (!inside(i - 1, j)) outward -= W.mass;
      if (!inside(i + 1, j)) outward += E.mass;
      if (!inside(i, j - 1)) outward -= S.mass;
      if (!inside(i, j + 1)) outward += N.mass;
    }
  return outward;
}

// q <- q / (1 + dt g n^2 |U| / h_n^(4/3)): the linearised implicit Manning step of friction.cl along
// the bed (manning.cl): |U| = sqrt(|u|^2 + (u.grad b)^2), h_n = h cos(theta), cos^2 = g_n / g.
void CpuFlowReference::friction(double dt) {
  for (std::size_t k = 0; k < grid_.cells(); ++k) {
    if (!mask_[k] || h_[k] <= settings_.hDry || manning_[k] <= 0.0) continue;
    const double u = velocity(h_[k], qx_[k]), v = velocity(h_[k], qy_[k]);
    const double n = manning_[k];
    const double w = u * bx_[k] + v * by_[k];
    const double hn = h_[k] * std::sqrt(gn_[k] / kGravity);
    const double factor = 1.0 + dt * kGravity * n * n * std::sqrt(u * u + v * v + w * w) / std::pow(hn, 4.0 / 3.0);
    qx_[k] /= factor;
    qy_[k] /= factor;
  }
}

void CpuFlowReference::track() {
  for (std::size_t k = 0; k < grid_.cells(); ++k) {
    if (!mask_[k]) continue;
    const double u = velocity(h_[k], qx_[k]), v = velocity(h_[k], qy_[k]);
    hMax_[k] = std::max(hMax_[k], h_[k]);
    vMax_[k] = std::max(vMax_[k], std::sqrt(u * u + v * v));
    if (arrival_[k] < 0.0 && h_[k] > settings_.arrivalH) arrival_[k] = time_;
  }
}

void CpuFlowReference::computeDiagnostics(double outflowVolume) {
  const double area = grid_.dx * grid_.dx;
  diag_ = flow::FlowDiagnostics{};
  diag_.outflow = outflowVolume;
  diag_.minH = std::numeric_limits<double>::max();
  for (std::size_t k = 0; k < grid_.cells(); ++k) {
    if (!mask_[k]) continue;
    const double h = h_[k], u = velocity(h, qx_[k]), v = velocity(h, qy_[k]);
    // The CFL speed: both directions' (unsplit) or one direction's (split sweeps) wave speed.
    const double c = std::sqrt(kGravity * h) + slope_[k];
    if (h > 0.0)
      diag_.maxSpeed = std::max(diag_.maxSpeed, flow::sweeps(settings_.scheme)
                                                    ? std::max(std::fabs(u), std::fabs(v)) + c
                                                    : std::fabs(u) + std::fabs(v) + 2.0 * c);
    diag_.volume += h * area;
    diag_.kinetic += 0.5 * h * (u * u + v * v) * area;
    diag_.minH = std::min(diag_.minH, h);
  }
}

double CpuFlowReference::stableDt() const {
  if (diag_.maxSpeed <= 0.0) return std::numeric_limits<double>::infinity();
  return settings_.cfl * grid_.dx / diag_.maxSpeed;
}

void CpuFlowReference::step(double dt) {
  // Unsplit: one SSP-RK2 over both directions. Split: one per direction, x first on even steps and
  // y first on odd ones. Hancock: the same sweeps, one predictor-corrector stage each.
  const bool split = flow::sweeps(settings_.scheme);
  const bool hancock = settings_.scheme == flow::TimeScheme::Hancock;
  predictorRatio_ = 0.5 * dt / grid_.dx;
  // Hancock: friction Strang-split around the sweeps (FlowSolver::step), dt/2 before and after.
  if (hancock) friction(0.5 * dt);
  const int sweeps[2] = {split ? ((splitStep_ % 2 == 0) ? 1 : 2) : 3, split ? ((splitStep_ % 2 == 0) ? 2 : 1) : 0};
  clampedVolume_ = 0.0;
  double outflow = 0.0;
  for (const int dirs : sweeps) {
    if (!dirs) continue;
    const State u0{h_, qx_, qy_};
    State u1, u2;
    double added1 = 0.0, added2 = 0.0;
    if (hancock) {
      outflow += dt * rkStage(u0, nullptr, dt, u1, added1, dirs) * grid_.dx;
      clampedVolume_ += added1;
      h_ = u1.h, qx_ = u1.qx, qy_ = u1.qy;
      continue;
    }
    const double out1 = rkStage(u0, nullptr, dt, u1, added1, dirs);
    const double out2 = rkStage(u1, &u0, dt, u2, added2, dirs);
    // A negative stage-1 value is clamped before the RK average, which then counts it half.
    clampedVolume_ += 0.5 * added1 + added2;
    h_ = u2.h, qx_ = u2.qx, qy_ = u2.qy;
    // The RK2 average of the two stages' outward mass fluxes, times the face length dx and dt.
    outflow += 0.5 * dt * (out1 + out2) * grid_.dx;
  }
  if (split) ++splitStep_;
  friction(hancock ? 0.5 * dt : dt);
  time_ += dt;
  track();
  computeDiagnostics(outflow);
}

}  // namespace talus::test
