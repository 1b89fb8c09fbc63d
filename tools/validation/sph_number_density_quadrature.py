#!/usr/bin/env python3
"""The quadrature error of the particles' number density S = sum_j W(|x_i - x_j|, h) on an unbounded
layout of the R2 sequence (the seeding's), as the spacing dp grows against a fixed h.

S dp^2 would be 1 for an exact quadrature of the kernel's integral (the cubic spline of
kernels/particles/sph.cl, normalised to 1 in 2D). The particles' areas A_i = a_i / S_i
(kernels/particles/particle_density.cl) inherit its error: the anchor a_i takes away its value at the
seeding (h/dp = 2 at 4 particles per cell), not its change as the layer spreads. Quoted in
tests/verification/test_particle_thickness.cpp and docs/particles.md.

Prints, per spreading factor (dp / dp_seeded): h/dp, the mean and standard deviation of S dp^2 over
200 particles far from the sample's edges, and the same of tr(M)/2 with M the kernel-gradient moment
sum_j dp^2 (x_j - x_i) (x) grad_i W_ij (1 for an exact quadrature).
Usage: /usr/bin/python3 tools/validation/sph_number_density_quadrature.py  (numpy; about 10 s)
"""
import numpy as np

SIGMA = 10.0 / (7.0 * np.pi)  # 2D cubic spline (Monaghan & Lattanzio 1985)


def w(r, h):
    q = r / h
    f = np.where(q < 1, 1 - 1.5 * q**2 + 0.75 * q**3, np.where(q < 2, 0.25 * (2 - q) ** 3, 0.0))
    return SIGMA / h**2 * f


def dw(r, h):
    q = r / h
    f = np.where(q < 1, -3 * q + 2.25 * q**2, np.where(q < 2, -0.75 * (2 - q) ** 2, 0.0))
    return SIGMA / h**3 * f


def main():
    g = 1.32471795724474602596  # the plastic number: R2 in 2D
    n = np.arange(40000)
    side = 100.0
    pts = np.stack([(0.5 + n / g) % 1, (0.5 + n / g**2) % 1], axis=1) * side
    area = side**2 / len(n)  # dp^2
    dp = np.sqrt(area)
    h0 = 2 * dp  # 4 particles per cell, h = dx
    centre = np.array([side / 2, side / 2])
    sample = np.argsort(np.sum((pts - centre) ** 2, axis=1))[:200]
    print("spread  h/dp   S dp^2 mean    sd   | tr(M)/2 mean    sd")
    for spread in [1.0, 1.2, 1.5, 2.0, 2.5, 3.0]:
        h = h0 / spread  # the layout scaled by `spread` against a fixed h
        s_vals, m_vals = [], []
        for i in sample:
            d = pts - pts[i]
            r = np.sqrt(np.sum(d**2, axis=1))
            s_vals.append(w(r, h).sum() * area)
            m = r > 0
            f = dw(r[m], h) / r[m]  # grad_i W_ij = f (x_i - x_j)
            m_vals.append(-np.sum(f * np.sum(d[m] ** 2, axis=1)) * area / 2)
        print(f"{spread:5.2f} {h / dp:5.2f}   {np.mean(s_vals):.4f}  {np.std(s_vals):.4f}  |  "
              f"{np.mean(m_vals):.4f}  {np.std(m_vals):.4f}")


if __name__ == "__main__":
    main()
