"""Issue 27 in Python: `cdpr.calibrate` (against `cdpr calibrate --json`, noise-free recovery,
identifiability) and the forward-kinematics statuses of measured lengths."""

import numpy as np
import pytest

import cdpr


def _as_built(robot_path):
    nominal = cdpr.Robot.load(robot_path("spidercam-like-4"))
    shifts = np.array(
        [[0.03, -0.02, 0.01], [-0.01, 0.04, -0.02], [0.02, 0.01, 0.03], [-0.03, -0.01, 0.0]]
    )
    truth = cdpr.Robot.from_anchors("point3", nominal.frame + shifts, t_min=100, t_max=10000)
    return nominal, truth


def _poses(k):
    t = np.arange(k, dtype=float)
    return np.stack(
        [35 * np.sin(0.7 * t), 25 * np.cos(1.3 * t + 0.4), 12 + 8 * np.sin(0.5 * t)], axis=1
    )


def test_known_poses_recover_anchors_and_offsets(robot_path):
    nominal, truth = _as_built(robot_path)
    poses = _poses(12)
    offsets = np.array([0.1, -0.05, 0.02, 0.0])
    readings = truth.inverse_kinematics(poses).lengths - offsets
    out = cdpr.calibrate(nominal, readings, known_poses=poses)
    assert out["identifiable"]
    np.testing.assert_allclose(out["frame"], truth.frame, atol=1e-9)
    np.testing.assert_allclose(out["offsets"], offsets, atol=1e-9)
    assert out["poses"] is None
    assert out["sigma"]["gains"] is None


def test_self_calibration_matches_the_cli(cli, robot_path, tmp_path):
    nominal, truth = _as_built(robot_path)
    readings = truth.inverse_kinematics(_poses(30)).lengths
    out = cdpr.calibrate(nominal, readings, unknowns="frame")
    assert out["identifiable"] and out["gauge_count"] == 6
    csv = tmp_path / "s.csv"
    np.savetxt(csv, readings, delimiter=",", header="l1,l2,l3,l4", comments="", fmt="%.17g")
    ref = cli("calibrate", robot_path("spidercam-like-4"), samples=csv, unknowns="frame")
    np.testing.assert_allclose(out["frame"], ref["frame"], atol=1e-9)
    d = lambda f: np.linalg.norm(np.asarray(f)[:, None] - np.asarray(f)[None], axis=2)
    np.testing.assert_allclose(d(out["frame"]), d(truth.frame), atol=1e-9)


def test_a_six_cable_spatial_robot_is_not_identifiable(robot_path):
    crane = cdpr.Robot.load(robot_path("caspr-nist-robocrane"))
    poses = np.zeros((20, 6))
    poses[:, 2] = 1.5 + 0.01 * np.arange(20)
    readings = crane.inverse_kinematics(poses).lengths
    out = cdpr.calibrate(crane, readings, unknowns="frame")
    assert not out["identifiable"]
    assert out["samples_needed"] is None


def test_bad_input_raises_value_error(robot_path):
    nominal, _ = _as_built(robot_path)
    with pytest.raises(ValueError, match="one reading per cable"):
        cdpr.calibrate(nominal, np.ones((5, 3)))
    with pytest.raises(ValueError, match="unknown parameter group"):
        cdpr.calibrate(nominal, np.ones((5, 4)), unknowns="anchors")


def test_forward_statuses_of_measured_lengths(robot_path):
    robot = cdpr.Robot.load(robot_path("spidercam-like-4"))
    exact = robot.inverse_kinematics([0.0, 0.0, 10.0]).lengths
    fk = robot.forward_kinematics(exact)
    assert fk.status == "solved"
    np.testing.assert_allclose(fk.pose, [0, 0, 10], atol=1e-9)
    rounded = np.round(robot.inverse_kinematics([3.0, -7.0, 10.0]).lengths, 4)
    fk = robot.forward_kinematics(rounded)
    assert fk.status == "fitted"
    assert fk.residual_rms < 1e-4 and fk.pose_std.shape == (3,)
    assert robot.forward_kinematics(exact, [0, 0, 45]).status == "above the anchors"
