#!/usr/bin/env python3
"""Vectorised numpy reference for `cdpr dextrous` with the l1 method at redundancy 1.

The same computation as

    cdpr dextrous benches/numpy/tdpm-4-table6.10-run1.toml --orientations -0.2:0.2:21 \
        --grid 400 --box -1,1,-1,1 --wrench 5,-10,1 --method l1 --json

(the thesis chapter on planar tendon-driven manipulators, Table 6.10 run 1, load L3 of
Table 6.3): a (400+1)^2 grid over [-1, 1]^2, 21 orientations in [-0.2, 0.2] rad; a point belongs
to the dextrous workspace when, at every orientation, every cable is at least 0.1 long and the
constrained minimum-l1 tensions (Algorithm 6.1: t = M + N t_B on the feasible interval of t_B,
the end with the smaller sum) exist within [5, 100] N. All points of one orientation are solved
at once with numpy array operations (no Python loop over points).

Prints the dextrous area (grid points x cell area, as cdpr) and the time of the computation;
`time python3 benches/numpy/dextrous_l1.py` gives the whole-process figure of issue 13.
"""

import math
import sys
import time

import numpy as np

T_MIN, T_MAX, L_MIN = 5.0, 100.0, 0.1
LOAD = np.array([5.0, -10.0, 1.0])  # w_e of load L3: f_x, f_y (N), tau (N m)
BETAS = [0.7572, 2.922, 3.097, 5.449]


def robot():
    """Frame anchors on the square [-1, 1]^2 at the angles BETAS, platform of Table 6.1."""
    frame = []
    for b in BETAS:
        c, s = math.cos(b), math.sin(b)
        rho = 1.0 / max(abs(c), abs(s))
        frame.append([rho * c, rho * s])
    s = 0.1 / math.sqrt(2.0)
    platform = [[s, s], [-s, s], [-0.1, -0.1], [0.1, -0.1]]
    return np.array(frame), np.array(platform)


def feasible(x, y, phi, frame, platform):
    """Boolean array: the criteria at every (x, y) for orientation phi."""
    c, s = math.cos(phi), math.sin(phi)
    a = platform @ np.array([[c, s], [-s, c]])  # R a_i (rows)
    # Cable vectors l_i = c_i - (p + R a_i): shape (points, 4, 2).
    lx = frame[None, :, 0] - x[:, None] - a[None, :, 0]
    ly = frame[None, :, 1] - y[:, None] - a[None, :, 1]
    length = np.hypot(lx, ly)
    ok = np.all(length >= L_MIN, axis=1)
    length = np.where(length > 0, length, 1.0)
    ux, uy = lx / length, ly / length
    mz = a[None, :, 0] * uy - a[None, :, 1] * ux  # (R a_i) x u_i
    w = np.stack([ux, uy, mz], axis=1)  # (points, 3, 4): W
    # Null vector d_j = (-1)^j det(W without column j) (signed maximal minors).
    cols = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]
    d = np.stack(
        [(-1) ** j * np.linalg.det(w[:, :, cols[j]]) for j in range(4)], axis=1
    )
    f = np.argmax(np.abs(d), axis=1)  # the free cable t_B
    dn = d / np.take_along_axis(d, f[:, None], axis=1)  # N, with N_f = 1
    # Particular solution M with M_f = 0: the other three cables solve W_A t_A = -w_ext.
    idx = np.array(cols)[f]  # (points, 3)
    wa = np.take_along_axis(w, idx[:, None, :], axis=2)
    rows_norm = np.prod(np.linalg.norm(w, axis=2), axis=1)
    regular = np.abs(np.take_along_axis(d, f[:, None], axis=1)[:, 0]) > 1e-10 * rows_norm
    wa = np.where(regular[:, None, None], wa, np.eye(3)[None])
    ta = np.linalg.solve(wa, np.broadcast_to(-LOAD, (len(x), 3))[:, :, None])[:, :, 0]
    m = np.zeros((len(x), 4))
    np.put_along_axis(m, idx, ta, axis=1)
    # Feasible interval of t_B (eq. 6.18), then the end with the smaller sum (Alg. 6.1).
    with np.errstate(divide="ignore", invalid="ignore"):
        lo_i = (T_MIN - m) / dn
        hi_i = (T_MAX - m) / dn
    lo_i, hi_i = np.minimum(lo_i, hi_i), np.maximum(lo_i, hi_i)
    zero = np.abs(dn) <= 1e-14
    lo_i = np.where(zero, -np.inf, lo_i)
    hi_i = np.where(zero, np.inf, hi_i)
    const_ok = np.all(~zero | ((m >= T_MIN - 1e-10) & (m <= T_MAX + 1e-10)), axis=1)
    lo, hi = lo_i.max(axis=1), hi_i.min(axis=1)
    slope = dn.sum(axis=1)
    tb = np.where(slope < 0, hi, lo)
    tensions = m + dn * tb[:, None]  # the l1 tensions (computed, as cdpr does)
    del tensions
    return ok & regular & const_ok & (lo <= hi + 1e-10 * np.maximum(1.0, np.abs(hi)))


def main():
    grid = int(sys.argv[1]) if len(sys.argv) > 1 else 400
    slices = int(sys.argv[2]) if len(sys.argv) > 2 else 21
    frame, platform = robot()
    start = time.perf_counter()
    g = np.linspace(-1.0, 1.0, grid + 1)
    x, y = (v.ravel() for v in np.meshgrid(g, g, indexing="ij"))
    inside = np.ones(len(x), dtype=bool)
    for phi in np.linspace(-0.2, 0.2, slices):
        inside &= feasible(x, y, phi, frame, platform)
    cell = (2.0 / grid) ** 2
    seconds = time.perf_counter() - start
    print(
        f"dextrous area {inside.sum() * cell:.6f} m^2 ({inside.sum()} of {len(x)} points, "
        f"{slices} orientations); numpy {seconds:.3f} s"
    )


if __name__ == "__main__":
    main()
