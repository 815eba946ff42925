"""Tension distribution against `cdpr tension --json`."""

import numpy as np
import pytest

import cdpr
from conftest import random_poses

CASES = [
    ("tdpm-4", "l2", [5.0, -10.0, 1.0]),
    ("tdpm-4", "closed-form", [5.0, -10.0, 1.0]),
    ("tdpm-4", "l1", None),
    ("krut-4", "linf", [10.0, -20.0]),
    ("ipanema-like-8", "l2", None),
    ("ipanema-like-8", "improved-closed-form", [0, 0, -20.0, 0, 0, 0]),
]


@pytest.mark.parametrize("name,method,wrench", CASES)
def test_matches_cli(cli, robot_path, name, method, wrench):
    robot = cdpr.Robot.load(robot_path(name))
    poses = random_poses(robot, 6, seed=2)
    res = robot.tensions(poses, wrench, method=method)
    assert res.method == method
    for k, q in enumerate(poses):
        opts = {"pose": q, "method": method}
        if wrench is not None:
            opts["wrench"] = wrench
        ref = cli("tension", robot_path(name), **opts)
        assert res.feasible[k] == ref["feasible"]
        assert res.reason[k] == ref["reason"]
        np.testing.assert_allclose(res.external_wrench[k], ref["external_wrench"], atol=1e-12)
        if ref["feasible"]:
            np.testing.assert_allclose(res.tensions[k], ref["tensions"], rtol=1e-9, atol=1e-9)
            assert res.residual[k] == pytest.approx(ref["residual"], abs=1e-9)
        else:
            assert np.all(np.isnan(res.tensions[k])) and np.isnan(res.residual[k])


def test_both_outcomes_occur_and_certificates_hold(robot_path):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    poses = random_poses(robot, 2000, seed=3) * [1.5, 1.5, 3.0]
    res = robot.tensions(poses, [0.0, -10.0, 0.0])
    assert 0 < res.feasible.sum() < len(poses)
    assert res.feasible.dtype == np.bool_ and res.tensions.shape == (2000, 4)
    w = robot.inverse_kinematics(poses).wrench_matrix
    t = res.tensions[res.feasible]
    eq = np.einsum("kij,kj->ki", w[res.feasible], t) + res.external_wrench[res.feasible]
    assert np.abs(eq).max() < 1e-8
    assert np.all(t >= robot.t_min - 1e-9) and np.all(t <= robot.t_max + 1e-9)
    assert all((r is None) == f for r, f in zip(res.reason, res.feasible))


def test_single_pose_gives_scalars(robot_path):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    res = robot.tensions([0.1, -0.2, 0.0], [5, -10, 1], method="closed-form")
    assert res.feasible is True and isinstance(res.residual, float) and res.reason is None
    assert res.tensions.shape == (4,)
    np.testing.assert_allclose(res.tensions, [17.038099, 8.086583, 16.851392, 5.0], atol=1e-6)


def test_per_pose_wrenches(robot_path):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    poses = np.zeros((3, 3))
    wrenches = np.array([[0, -10.0, 0], [0, -20.0, 0], [0, -30.0, 0]])
    res = robot.tensions(poses, wrenches)
    for k in range(3):
        np.testing.assert_array_equal(res.tensions[k], robot.tensions(poses[k], wrenches[k]).tensions)
    with pytest.raises(ValueError, match="wrenches"):
        robot.tensions(poses, np.zeros((2, 3)))
    with pytest.raises(ValueError, match="wrenches"):
        robot.tensions(poses, [0, np.nan, 0])


def test_bad_method_and_sotda_without_stiffness(robot_path):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    with pytest.raises(ValueError, match="known: exact, pinv"):
        robot.tensions([0, 0, 0], method="l3")
    with pytest.raises(ValueError, match="axial_stiffness"):
        robot.tensions([0, 0, 0], method="sotda")
    assert "l2" in cdpr.METHODS


def test_gravity_from_the_robot_file_is_added():
    kw = dict(t_min=1.0, t_max=1000.0)
    frame = [[1.0, 1.0], [-1.0, 1.0], [0.0, -1.0]]
    light = cdpr.Robot.from_anchors("point2", frame, **kw)
    heavy = cdpr.Robot.from_anchors("point2", frame, mass=2.0, **kw)
    np.testing.assert_allclose(heavy.tensions([0, 0]).external_wrench, [0, -2 * 9.80665])
    np.testing.assert_allclose(
        heavy.tensions([0, 0]).tensions, light.tensions([0, 0], [0, -2 * 9.80665]).tensions
    )
