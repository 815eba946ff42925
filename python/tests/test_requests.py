"""One pose through the requests of cdpr-api (issue 25).

Given one pose (or one set of cable lengths), the methods build the request the command line
builds and run it, so their answers are the command's JSON bit for bit (``==``, not approx);
the batch loops give the same answers to rounding.
"""

import numpy as np
import pytest

import cdpr
from conftest import random_poses

PATH = "ipanema-like-8"
WRENCH = [0.0, 5.0, -20.0, 0.5, 0.0, 0.1]


@pytest.fixture
def spatial(robot_path):
    path = robot_path(PATH)
    robot = cdpr.Robot.load(path)
    return path, robot, random_poses(robot, 2, seed=25)


def test_kinematics_of_one_pose_is_the_cli_report(cli, spatial):
    path, robot, poses = spatial
    res = robot.inverse_kinematics(poses[0])
    ref = cli("kinematics", path, pose=poses[0])
    assert res.lengths.tolist() == ref["lengths"]
    assert res.unit_vectors.tolist() == ref["unit_vectors"]
    assert res.wrench_matrix.tolist() == ref["wrench_matrix"]
    assert res.attachment_points.tolist() == ref["attachment_points"]
    batch = robot.inverse_kinematics(poses)
    np.testing.assert_allclose(batch.wrench_matrix[0], res.wrench_matrix, rtol=1e-12, atol=1e-12)


def test_tensions_of_one_pose_are_the_cli_report(cli, spatial):
    path, robot, poses = spatial
    res = robot.tensions(poses[0], WRENCH)
    ref = cli("tension", path, pose=poses[0], wrench=WRENCH)
    assert ref["feasible"] and res.feasible is True and res.reason is None
    assert res.tensions.tolist() == ref["tensions"]
    assert res.residual == ref["residual"]
    assert res.external_wrench.tolist() == ref["external_wrench"]
    assert res.method == ref["method"] == "l2"
    batch = robot.tensions(poses, WRENCH)
    np.testing.assert_allclose(batch.tensions[0], res.tensions, rtol=1e-9, atol=1e-9)
    # An infeasible answer keeps its shape: NaN tensions and residual, and the reason.
    heavy = robot.tensions(poses[0], [0.0, 0.0, -1e9, 0.0, 0.0, 0.0])
    assert heavy.feasible is False and isinstance(heavy.reason, str)
    assert np.isnan(heavy.tensions).all() and np.isnan(heavy.residual)


def test_capacity_and_isotropic_force_of_one_pose_are_the_cli_reports(cli, spatial):
    path, robot, poses = spatial
    res = robot.capacity_margin(poses[0], WRENCH, wrench_ball=2.0)
    ref = cli("capacity", path, pose=poses[0], wrench=WRENCH, wrench_ball=2.0)
    assert res.capacity_margin == ref["capacity_margin"]
    assert res.feasible is ref["feasible"]
    assert res.limiting_facet == ref["limiting_facet"]["index"]
    iso = robot.isotropic_force(poses[0], WRENCH)
    ref = cli("isotropic", path, pose=poses[0], wrench=WRENCH)
    assert iso.isotropic_force == ref["isotropic_force"]
    assert iso.wrench_radius == ref["wrench_radius"]
    assert iso.definition == ref["definition"]
    batch = robot.isotropic_force(poses, WRENCH)
    assert batch.isotropic_force[0] == pytest.approx(iso.isotropic_force, rel=1e-12, abs=1e-9)


def test_stiffness_of_one_pose_is_the_cli_report(cli, spatial):
    path, robot, poses = spatial
    t = robot.tensions(poses[0]).tensions
    res = robot.stiffness(poses[0], t)
    ref = cli("stiffness", path, pose=poses[0], tensions=t)
    assert res.stiffness.tolist() == ref["stiffness"]
    assert res.passive.tolist() == ref["passive"]
    assert res.active.tolist() == ref["active"]
    # A per-cable E·S overrides the robot's; a scalar one is the command's --axial-stiffness.
    es = np.full(robot.n_cables, 2.0e4)
    ref = cli("stiffness", path, pose=poses[0], tensions=t, axial_stiffness=2.0e4)
    assert robot.stiffness(poses[0], t, es).passive.tolist() == ref["passive"]
    with pytest.raises(ValueError, match="tensions"):
        robot.stiffness(poses[0], -t)


def test_forward_kinematics_of_one_set_of_lengths_is_the_cli_report(cli, robot_path):
    path = robot_path("tdpm-4")
    robot = cdpr.Robot.load(path)
    q = random_poses(robot, 1, seed=26)[0]
    lengths = robot.inverse_kinematics(q).lengths
    res = robot.forward_kinematics(lengths)
    ref = cli("forward", path, lengths=lengths)
    assert res.pose.tolist() == ref["pose"]
    assert res.residual == ref["residual"] and res.status == ref["status"]
    assert res.iterations == ref["iterations"] and res.converged is ref["converged"]
    assert res.pose_std.tolist() == ref["pose_std"]
    assert res.solutions.tolist() == [s["pose"] for s in ref["solutions"]]
    guessed = robot.forward_kinematics(lengths, q)
    assert guessed.pose.tolist() == cli("forward", path, lengths=lengths, guess=q)["pose"]
    assert guessed.solutions is None
    # Another iteration limit than the request's runs the batch loop, with the same answer.
    other = robot.forward_kinematics(lengths, q, max_iterations=200)
    np.testing.assert_allclose(other.pose, guessed.pose, rtol=1e-9, atol=1e-9)
