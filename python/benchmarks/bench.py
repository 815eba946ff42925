"""Speed of the cdpr Python package (issue 18), measured side by side in one run.

    python python/benchmarks/bench.py                      # everything, the full sizes
    python python/benchmarks/bench.py --scipy-poses 2000   # a shorter scipy loop
    RAYON_NUM_THREADS=1 python python/benchmarks/bench.py  # batches on one thread

1. Inverse kinematics + wrench matrix of 10⁶ poses of the 8-cable spatial robot
   (examples/robots/ipanema-like-8.toml), one batch call, alternating with the plain Rust loop
   doing the same work on one thread (`cdpr._cdpr._ik_reference_loop`: no numpy, no Python
   inside; the same loop as the criterion bench
   `cargo bench -p cdpr-benches --bench kinematics -- kinematics_batch`). Twice: into fresh
   memory (new arrays; the Rust loop allocates its buffers inside its clock) and into reused
   memory (`out=` the previous result; the Rust loop's buffers written before its clock, as
   criterion's are).
2. Per-call overhead of a single-pose call: the time of `robot.inverse_kinematics(q)` for one
   pose minus the Rust loop's time per pose (measured in the same run), with a trivial native
   call and np.empty(3) printed for scale on a loaded machine.
3. Constrained minimum-2-norm tensions (method "l2", thesis eq. (6.17)) of 10⁵ poses:
   `robot.tensions(poses)` against the same problem min ‖t‖² s.t. W t + w = 0,
   t_min ≤ t ≤ t_max solved pose by pose with scipy's SLSQP (scipy.optimize.minimize), given W
   and w precomputed (so the scipy side is not charged for kinematics). Both answers are compared.

Timings are medians of repeated runs (time.perf_counter, and process CPU time for [1]);
per-call figures are the fastest of repeated runs (the least disturbed on a busy machine).
"""

import argparse
import os
import pathlib
import statistics
import time

import numpy as np

import cdpr
from cdpr._cdpr import _ik_reference_buffers, _ik_reference_loop

REPO = pathlib.Path(__file__).resolve().parents[2]
ROBOT = REPO / "examples" / "robots" / "ipanema-like-8.toml"


def poses_8(robot, count, seed=0):
    """Poses over the central part of the frame (|x| ≤ 1, |y| ≤ 0.75, z ∈ [0.5, 1.5], ±0.1 rad)."""
    rng = np.random.default_rng(seed)
    return np.column_stack(
        [
            rng.uniform(-1.0, 1.0, count),
            rng.uniform(-0.75, 0.75, count),
            rng.uniform(0.5, 1.5, count),
            rng.uniform(-0.1, 0.1, (count, 3)),
        ]
    )


def median_time(f, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def per_call(f, calls=20000, repeat=7):
    """Fastest of `repeat` runs of the mean time of one call (s): the least disturbed by other
    processes on a busy machine."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(calls):
            f()
        times.append(time.perf_counter() - t0)
    return min(times) / calls


def scipy_l2(w, w_ext, t_min, t_max):
    from scipy.optimize import minimize

    n = w.shape[1]
    t0 = np.clip(np.linalg.lstsq(w, -w_ext, rcond=None)[0], t_min, t_max)
    s = float(np.max(np.abs(t_max[np.isfinite(t_max)]), initial=1.0))  # scaled to O(1)
    res = minimize(
        lambda t: (t @ t) / s**2,
        t0,
        jac=lambda t: 2 * t / s**2,
        method="SLSQP",
        bounds=list(zip(t_min, t_max)),
        constraints=[{"type": "eq", "fun": lambda t: (w @ t + w_ext) / s, "jac": lambda t: w / s}],
        options={"ftol": 1e-14, "maxiter": 500},
    )
    ok = res.success and np.abs(w @ res.x + w_ext).max() < 1e-6
    return res.x if ok else np.full(n, np.nan)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--ik-poses", type=int, default=1_000_000)
    ap.add_argument("--tension-poses", type=int, default=100_000)
    ap.add_argument("--scipy-poses", type=int, default=None, help="default: all tension poses")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    robot = cdpr.Robot.load(ROBOT)
    print(f"cdpr package, {cdpr.thread_count()} rayon thread(s) "
          f"(RAYON_NUM_THREADS={os.environ.get('RAYON_NUM_THREADS', 'unset')}); robot {robot}")

    # 1. IK + W of a large batch, alternating with the plain Rust loop (same process), twice:
    # (a) into fresh memory: the package's new arrays against the Rust loop allocating its
    #     buffers inside its clock; each result is kept alive until the clock stops (the Rust
    #     loop frees its buffers after its clock too);
    # (b) into reused memory: `out=` the previous result against the Rust loop with buffers it
    #     wrote before (`_ik_reference_buffers`; criterion's `kinematics_batch` reuses them too).
    # Writing 104 floats per pose (832 MB for 10⁶ poses) into fresh pages makes the kernel
    # zero them on first touch: that cost, not the kinematics, dominates (a).
    q = poses_8(robot, args.ik_poses)
    reused = robot.inverse_kinematics(q)
    buffers = _ik_reference_buffers(robot, len(q))
    for label, reuse in (("fresh output memory", False), ("reused output (out=)", True)):
        ours, rust, ours_cpu, rust_cpu = [], [], [], []
        for _ in range(args.repeat):
            c0, t0 = time.process_time(), time.perf_counter()
            res = robot.inverse_kinematics(q, out=reused) if reuse else robot.inverse_kinematics(q)
            ours.append(time.perf_counter() - t0)
            ours_cpu.append(time.process_time() - c0)
            del res
            c0 = time.process_time()
            rust.append(_ik_reference_loop(robot, q, buffers if reuse else None))
            rust_cpu.append(time.process_time() - c0)
        t_ik, t_rust = statistics.median(ours), statistics.median(rust)
        c_ik, c_rust = statistics.median(ours_cpu), statistics.median(rust_cpu)
        print(f"[1] inverse_kinematics, {args.ik_poses} poses (IK + W, 8 cables), {label}: "
              f"median wall {t_ik * 1e3:.1f} ms = {t_ik / args.ik_poses * 1e9:.0f} ns/pose; the "
              f"Rust loop on one thread {t_rust * 1e3:.1f} ms = "
              f"{t_rust / args.ik_poses * 1e9:.0f} ns/pose; package / Rust = {t_ik / t_rust:.2f} "
              f"(wall), {c_ik / c_rust:.2f} (CPU time: {c_ik * 1e3:.0f} ms vs "
              f"{c_rust * 1e3:.0f} ms)")
    del reused, buffers

    # 2. Per-call overhead of one pose: the call minus the Rust loop's time per pose, the loop
    # writing into buffers it has already touched (a single pose's 832 bytes of output come
    # from numpy's small-block cache, not from fresh pages).
    one = q[0].copy()
    small = q[:100_000]
    warm = _ik_reference_buffers(robot, len(small))
    per_pose = min(_ik_reference_loop(robot, small, warm) for _ in range(args.repeat)) / len(small)
    t_call = per_call(lambda: robot.inverse_kinematics(one))
    t_dof = per_call(lambda: robot.dof)
    t_np = per_call(lambda: np.empty(3))
    print(f"[2] inverse_kinematics(one pose): {t_call * 1e9:.0f} ns per call; the Rust loop "
          f"{per_pose * 1e9:.0f} ns per pose; overhead {(t_call - per_pose) * 1e9:.0f} ns "
          f"(for scale, in this run: the property robot.dof {t_dof * 1e9:.0f} ns, "
          f"np.empty(3) {t_np * 1e9:.0f} ns)")
    t_tcall = per_call(lambda: robot.tensions(one), calls=5000)
    saved = os.environ.get("RAYON_NUM_THREADS")
    tb = q[:20_000]
    t_tbatch = median_time(lambda: robot.tensions(tb), args.repeat) / len(tb)
    print(f"    tensions(one pose): {t_tcall * 1e9:.0f} ns per call; in a batch "
          f"{t_tbatch * 1e9:.0f} ns/pose on {cdpr.thread_count()} thread(s) (RAYON_NUM_THREADS="
          f"{saved or 'unset'})")

    # 3. l2 tensions against scipy.
    m = args.tension_poses
    qt = poses_8(robot, m, seed=1)
    t_ours = median_time(lambda: robot.tensions(qt, method="l2"), args.repeat)
    ours = robot.tensions(qt, method="l2")
    ms = args.scipy_poses or m
    kin = robot.inverse_kinematics(qt[:ms])
    w_ext = ours.external_wrench[:ms]
    t_min, t_max = robot.t_min, robot.t_max
    t0 = time.perf_counter()
    ref = np.array([scipy_l2(kin.wrench_matrix[k], w_ext[k], t_min, t_max) for k in range(ms)])
    t_scipy = time.perf_counter() - t0
    agree_feasible = np.mean(np.isfinite(ref[:, 0]) == ours.feasible[:ms])
    both = np.isfinite(ref[:, 0]) & ours.feasible[:ms]
    diff = np.abs(ref[both] - ours.tensions[:ms][both]).max() if both.any() else float("nan")
    per_ours, per_scipy = t_ours / m, t_scipy / ms
    print(f"[3] l2 tensions, {m} poses: cdpr {t_ours * 1e3:.1f} ms ({per_ours * 1e6:.2f} µs/pose, "
          f"{ours.feasible.mean():.1%} feasible); scipy SLSQP loop over {ms} poses "
          f"{t_scipy:.1f} s ({per_scipy * 1e6:.0f} µs/pose); ratio {per_scipy / per_ours:.0f}× "
          f"per pose; verdicts agree on {agree_feasible:.2%}, max |Δt| {diff:.2e} N")


if __name__ == "__main__":
    main()
