"""Shared fixtures: the repository's robot files and the `cdpr` command for cross-checks.

Every function of the package is compared with the command line's JSON on the same inputs.
The command is found as $CDPR_CLI, else target/{debug,release}/cdpr of the repository (built by
`cargo test --workspace` in CI), else built here with `cargo build -p cdpr`.
"""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
ROBOTS = REPO / "examples" / "robots"


def _find_cli():
    env = os.environ.get("CDPR_CLI")
    if env:
        return pathlib.Path(env)
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    for profile in ("debug", "release"):
        exe = target / profile / "cdpr"
        if exe.exists():
            return exe
    subprocess.run(["cargo", "build", "-p", "cdpr", "--bin", "cdpr"], cwd=REPO, check=True)
    return target / "debug" / "cdpr"


@pytest.fixture(scope="session")
def cli():
    """`cli("tension", robot_path, "--pose", q, ...)` → the parsed JSON of the command."""
    exe = _find_cli()

    def run(command, robot, **options):
        args = [str(exe), command, str(robot), "--json"]
        for key, value in options.items():
            flag = "--" + key.rstrip("_").replace("_", "-")
            if value is True:
                args.append(flag)
            elif isinstance(value, (list, tuple, np.ndarray)):
                args.append(flag + "=" + ",".join(repr(float(v)) for v in value))
            else:
                args.append(f"{flag}={value}")
        out = subprocess.run(args, capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        return json.loads(out.stdout)

    run.exe = exe  # the executable itself, for timing it
    return run


@pytest.fixture
def robot_path():
    return lambda name: ROBOTS / f"{name}.toml"


def random_poses(robot, count, seed=0):
    """Poses spread over the central part of the frame's bounding box (angles within ±0.1)."""
    rng = np.random.default_rng(seed)
    lo, hi = robot.frame.min(axis=0), robot.frame.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo) / 2
    dim = len(lo)
    pos = centre + 0.6 * half * rng.uniform(-1, 1, (count, dim))
    angles = robot.dof - dim
    if angles:
        return np.hstack([pos, rng.uniform(-0.1, 0.1, (count, angles))])
    return pos
