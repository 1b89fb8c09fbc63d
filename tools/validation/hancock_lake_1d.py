#!/usr/bin/env python3
"""A lake at rest with dry islands under a one-stage MUSCL-Hancock step, in 1D (issue 21).

Why this exists: `Time Scheme=hancock` (kernels/flow/hancock.cl; unmerged when this was written)
keeps roll-wave crests that the two-stage scheme damps, but a lake at rest over a rough bed with dry islands grows
round-off into motion under it (docs/numerics.md, "Roll waves"). This script is an independent 1D
re-implementation of the same discretisation, small enough to read in one sitting, used to test
candidate predictors on that lake:

- reconstruction of the surface eta and the thickness h with a limiter (minmod or MC), first order
  where a face would be negative or the cell is dry;
- the predictor of the patch (primitive variables: the cell's mass change applied to both faces,
  du = -r [u_bar (u_hi - u_lo) + g (eta_hi - eta_lo)], r = dt / (2 dx));
- hydrostatic reconstruction at the faces (Audusse et al. 2004 with Chen & Noelle's cap,
  b* = min(max(b_L, b_R), min(eta_L, eta_R)), h* = min(h, eta - b*)), HLL flux, Audusse's
  correction and the centred bed source, so a lake at rest is an exact steady state;
- walls at both ends.

The candidate ("passing" predictor): the predictor's in-cell mass flux through each face is the part
of the face column that the corrector's Riemann problem will pass, h* u, instead of h u. A face whose
column lies partly below the neighbour's bed (a dry island's rise) is partly a wall: no mass leaves
through the blocked part, so the predictor must not drain the face there while the water presses
against it.

Run: python3 tools/validation/hancock_lake_1d.py [--seeds 10] [--steps 5000] [--cfl 0.9] [--sheet]
Prints, per limiter and candidate, the largest speed in cells deeper than 1 mm after the run, for each
random bed (64 cells of 1 m, bed uniform in [0, 1] m, lake surface 0.6 m, velocity noise 1e-12 m/s in
the wet cells); with --sheet, whether a candidate holds a sheet back on a rough slope (sheet(): its
centroid and front at 12 s at 5, 2.5 and 1.25 m cells over the same 5 m roughness blocks). Needs
numpy. About 1.5 min each.
"""
import argparse

import numpy as np

G = 9.81
H_DRY = 1e-10


def minmod(a, b):
    return np.where(a * b > 0, np.sign(a) * np.minimum(abs(a), abs(b)), 0.0)


def mc(a, b):
    return np.where(a * b > 0, np.sign(a) * np.minimum(np.minimum(2 * abs(a), 2 * abs(b)), 0.5 * abs(a + b)), 0.0)


def face_states(elo, ehi, hlo, hhi):
    """b*, and h* of the left (hi face of cell k) and right (lo face of cell k+1) sides of every face."""
    bl, br = ehi[:-1] - hhi[:-1], elo[1:] - hlo[1:]
    bs = np.minimum(np.maximum(bl, br), np.minimum(ehi[:-1], elo[1:]))
    hl = np.minimum(hhi[:-1], np.maximum(ehi[:-1] - bs, 0.0))
    hr = np.minimum(hlo[1:], np.maximum(elo[1:] - bs, 0.0))
    return hl, hr


def hll(hl, ul, hr, ur):
    cl, cr = np.sqrt(G * hl), np.sqrt(G * hr)
    sl, sr = np.minimum(ul - cl, ur - cr), np.maximum(ul + cl, ur + cr)
    ql, qr = hl * ul, hr * ur
    fl = np.array([ql, ql * ul + G * hl**2 / 2])
    fr = np.array([qr, qr * ur + G * hr**2 / 2])
    den = np.where(sr - sl > 0, sr - sl, 1.0)
    f = np.where(sl >= 0, fl, np.where(sr <= 0, fr, (sr * fl - sl * fr + sl * sr * (np.array([hr, qr]) - np.array([hl, ql]))) / den))
    return np.where((hl <= H_DRY) & (hr <= H_DRY), 0.0, f)


def advance(b, h, u, dx, cfl, limiter, passing, islands_are_walls, steps=None, t_end=None, outflow_slope=None):
    """Advances (h, u) over the bed b by `steps` steps or to `t_end`; walls at both ends, or with
    outflow_slope a wall upstream and an open end downstream whose ghost bed continues that slope."""
    n = len(b)
    t, k = 0.0, 0
    while (steps is not None and k < steps) or (t_end is not None and t < t_end):
        k += 1
        H = np.concatenate([[h[0]] * 2, h, [h[-1]] * 2])
        B = np.concatenate([[b[0]] * 2, b, [b[-1]] * 2])
        U = np.concatenate([[-u[0]] * 2, u, [-u[-1]] * 2])
        if outflow_slope is not None:
            U[-2:] = u[-1]
            B[-2:] = b[-1] - outflow_slope * dx * np.array([1.0, 2.0])
        E = H + B
        hc, ec, uc = H[1:-1], E[1:-1], U[1:-1]
        dl, dr = E[1:-1] - E[:-2], E[2:] - E[1:-1]
        if islands_are_walls:
            # A dry neighbour whose bed stands above this cell's surface is a wall, not a sample of
            # the surface: the difference to it is no surface gradient (a reflecting wall's ghost
            # would have this cell's own surface, difference 0).
            dl = np.where((H[:-2] <= H_DRY) & (B[:-2] > ec), 0.0, dl)
            dr = np.where((H[2:] <= H_DRY) & (B[2:] > ec), 0.0, dr)
        dE = limiter(dl, dr)
        dH = limiter(H[1:-1] - H[:-2], H[2:] - H[1:-1])
        dU = limiter(U[1:-1] - U[:-2], U[2:] - U[1:-1])
        hlo, hhi, elo, ehi = hc - dH / 2, hc + dH / 2, ec - dE / 2, ec + dE / 2
        first = (hlo < 0) | (hhi < 0) | (hc <= H_DRY)
        hlo, hhi = np.where(first, hc, hlo), np.where(first, hc, hhi)
        elo, ehi = np.where(first, ec, elo), np.where(first, ec, ehi)
        ulo = np.where(first | (hlo <= H_DRY), np.where(hlo > H_DRY, uc, 0.0), uc - dU / 2)
        uhi = np.where(first | (hhi <= H_DRY), np.where(hhi > H_DRY, uc, 0.0), uc + dU / 2)
        speed = np.abs(uc) + np.sqrt(G * hc)
        dt = cfl * dx / max(speed.max(), 1e-12)
        if t_end is not None:
            dt = min(dt, t_end - t)
        t += dt
        r = dt / (2 * dx)
        # Predictor.
        if passing:
            hl, hr = face_states(elo, ehi, hlo, hhi)
            q_lo = np.concatenate([[hlo[0] * ulo[0]], hr * ulo[1:]])
            q_hi = np.concatenate([hl * uhi[:-1], [hhi[-1] * uhi[-1]]])
        else:
            q_lo, q_hi = hlo * ulo, hhi * uhi
        dh = r * (q_lo - q_hi)
        dh = np.where(np.minimum(hlo, hhi) + dh < 0, -np.minimum(hlo, hhi), dh)
        du = -r * (0.5 * (ulo + uhi) * (uhi - ulo) + G * (ehi - elo))
        hlo, hhi, elo, ehi = hlo + dh, hhi + dh, elo + dh, ehi + dh
        ulo, uhi = np.where(hlo > H_DRY, ulo + du, 0.0), np.where(hhi > H_DRY, uhi + du, 0.0)
        # Corrector: fluxes between extended cells k and k + 1, sources of the real cells.
        hl, hr = face_states(elo, ehi, hlo, hhi)
        f = hll(hl, uhi[:-1], hr, ulo[1:])
        i = slice(1, n + 1)
        h_lo, h_hi = hlo[i], hhi[i]
        hs_lo, hs_hi = hr[0:n], hl[1:n + 1]
        b_lo, b_hi = elo[i] - h_lo, ehi[i] - h_hi
        src = -G * (h_lo + h_hi) / 2 * (b_hi - b_lo) - G * (h_hi**2 - hs_hi**2) / 2 + G * (h_lo**2 - hs_lo**2) / 2
        q = h * u - dt / dx * (f[1, 1:n + 1] - f[1, 0:n]) + dt / dx * src
        h = np.maximum(h - dt / dx * (f[0, 1:n + 1] - f[0, 0:n]), 0.0)
        u = np.where(h > H_DRY, q / np.maximum(h, 1e-300), 0.0)
    return h, u


def lake(seed, steps, cfl, limiter, passing, islands_are_walls, n=64, eta0=0.6):
    """The lake: largest speed in cells deeper than 1 mm after `steps` steps."""
    rng = np.random.default_rng(seed)
    b = rng.uniform(0.0, 1.0, n)
    h = np.maximum(eta0 - b, 0.0)
    u = np.zeros(n)
    u[h > 0] = 1e-12 * rng.standard_normal((h > 0).sum())
    h, u = advance(b, h, u, 1.0, cfl, limiter, passing, islands_are_walls, steps=steps)
    return np.abs(u[h > 1e-3]).max()


def sheet(seed, dx, cfl, limiter, passing, islands_are_walls, length=1000.0, t_end=12.0):
    """A frictionless sheet on a rough slope: bed -0.25 x plus a roughness uniform in [0, 1] m on
    blocks of 5 m (the same blocks at every dx), 2 m of water over the first 50 m, a wall upstream,
    open downstream; returns the water's centroid and its front (last cell deeper than 1 cm) at
    t_end."""
    n = int(round(length / dx))
    x = (np.arange(n) + 0.5) * dx
    rng = np.random.default_rng(seed)
    b = -0.25 * x + np.repeat(rng.uniform(0.0, 1.0, int(length / 5.0)), int(round(5.0 / dx)))
    h = np.where(x < 50.0, 2.0, 0.0)
    h, u = advance(b, h, np.zeros(n), dx, cfl, limiter, passing, islands_are_walls, t_end=t_end, outflow_slope=0.25)
    return (h * x).sum() / h.sum(), x[h > 1e-2].max()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--cfl", type=float, default=0.9)
    ap.add_argument("--sheet", action="store_true", help="the rough-slope sheet instead of the lake")
    a = ap.parse_args()
    variants = [(lname, lim, walls, passing) for lname, lim in (("minmod", minmod), ("MC", mc))
                for walls in (False, True) for passing in (False, True)]
    def label(lname, walls, passing):
        surf = "islands are walls" if walls else "every neighbour"
        pred = "h* u (passing)" if passing else "h u (the patch)"
        return f"{lname:6s} surface slope from {surf:17s} predictor mass flux {pred:16s}"
    if a.sheet:
        seeds = range(1, min(a.seeds, 3) + 1)
        print(f"sheet at 12 s, CFL {a.cfl}: centroid / front [m] for beds {list(seeds)}")
        for dx in (5.0, 2.5, 1.25):
            for lname, lim, walls, passing in variants:
                if dx < 5.0 and not walls:
                    continue
                res = [sheet(s, dx, a.cfl, lim, passing, walls) for s in seeds]
                print(f"dx {dx:4.2f} {label(lname, walls, passing)}: " + " ".join(f"{c:6.1f} / {f:4.0f}" for c, f in res))
        return
    print(f"largest speed [m/s] in cells deeper than 1 mm after {a.steps} steps at CFL {a.cfl}, beds 1..{a.seeds}")
    for lname, lim, walls, passing in variants:
        res = [lake(s, a.steps, a.cfl, lim, passing, walls) for s in range(1, a.seeds + 1)]
        print(f"{label(lname, walls, passing)}: " + " ".join(f"{x:.0e}" for x in res))


if __name__ == "__main__":
    main()
