"""Inverse kinematics against `cdpr kinematics --json`, shapes, dtypes and bad input."""

import numpy as np
import pytest

import cdpr
from conftest import random_poses

ROBOTS = ["tdpm-4", "krut-3", "ipanema-like-8", "tdpm-3"]


@pytest.mark.parametrize("name", ROBOTS)
def test_matches_cli(cli, robot_path, name):
    robot = cdpr.Robot.load(robot_path(name))
    poses = random_poses(robot, 4, seed=1)
    batch = robot.inverse_kinematics(poses)
    dim = robot.frame.shape[1]
    for k, q in enumerate(poses):
        ref = cli("kinematics", robot_path(name), pose=q)
        np.testing.assert_allclose(batch.lengths[k], ref["lengths"], rtol=1e-14)
        np.testing.assert_allclose(batch.unit_vectors[k][:, :dim], ref["unit_vectors"], atol=1e-14)
        np.testing.assert_allclose(batch.wrench_matrix[k], ref["wrench_matrix"], atol=1e-13)
        np.testing.assert_allclose(
            batch.attachment_points[k][:, :dim], ref["attachment_points"], atol=1e-14
        )


def test_shapes_and_dtypes(robot_path):
    robot = cdpr.Robot.load(robot_path("ipanema-like-8"))
    assert (robot.dof, robot.n_cables, robot.motion) == (6, 8, "spatial")
    poses = random_poses(robot, 300)
    k = robot.inverse_kinematics(poses)
    assert k.lengths.shape == (300, 8) and k.lengths.dtype == np.float64
    assert k.unit_vectors.shape == (300, 8, 3)
    assert k.wrench_matrix.shape == (300, 6, 8)
    np.testing.assert_allclose(np.linalg.norm(k.unit_vectors, axis=2), 1.0, atol=1e-14)
    one = robot.inverse_kinematics(poses[7])
    assert one.lengths.shape == (8,) and one.wrench_matrix.shape == (6, 8)
    np.testing.assert_array_equal(one.wrench_matrix, k.wrench_matrix[7])
    # Lists, integer arrays and non-contiguous views are accepted and give the same numbers.
    np.testing.assert_array_equal(
        robot.inverse_kinematics(poses[7].tolist()).lengths, one.lengths
    )
    view = np.asfortranarray(poses)[::3]
    np.testing.assert_array_equal(robot.inverse_kinematics(view).lengths, k.lengths[::3])


def test_planar_unit_vectors_have_zero_z(robot_path):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    k = robot.inverse_kinematics(np.zeros((3, 3)))
    assert np.all(k.unit_vectors[..., 2] == 0.0)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_pose_is_value_error(robot_path, bad):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    poses = np.zeros((100, 3))
    poses[42, 1] = bad
    with pytest.raises(ValueError, match=r"poses: element \[42, 1\]"):
        robot.inverse_kinematics(poses)
    with pytest.raises(ValueError, match="finite"):
        robot.tensions(poses)


def test_wrong_shape_is_value_error(robot_path):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    with pytest.raises(ValueError, match=r"expected shape \(N, 3\) or \(3,\)"):
        robot.inverse_kinematics(np.zeros((5, 2)))
    with pytest.raises(ValueError, match="not an array of numbers"):
        robot.inverse_kinematics([["a", "b", "c"]])


def test_degenerate_cable_names_the_pose():
    robot = cdpr.Robot.from_anchors("point2", [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0]], t_min=1, t_max=10)
    poses = np.array([[0.0, 0.0], [1.0, 0.0]])
    with pytest.raises(ValueError, match=r"poses\[1\].*cable"):
        robot.inverse_kinematics(poses)


@pytest.mark.parametrize("count", [1, 1000])
def test_misaligned_arrays_are_read(robot_path, count):
    # As pickle protocol 5 (Dask) can hand them over: float64 data at an odd address.
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    poses = np.random.default_rng(0).uniform(-0.3, 0.3, (count, 3))
    raw = np.zeros(poses.nbytes + 1, dtype=np.uint8)
    odd = np.frombuffer(raw.data, dtype=np.float64, count=poses.size, offset=1).reshape(poses.shape)
    odd[...] = poses
    assert not odd.flags.aligned
    np.testing.assert_array_equal(robot.inverse_kinematics(odd).lengths, robot.inverse_kinematics(poses).lengths)


@pytest.mark.parametrize("count", [5, 3000])
def test_out_reuses_the_arrays_of_an_earlier_result(robot_path, count):
    robot = cdpr.Robot.load(robot_path("ipanema-like-8"))
    first, second = random_poses(robot, count, seed=2), random_poses(robot, count, seed=3)
    out = robot.inverse_kinematics(first)
    lengths = out.lengths
    res = robot.inverse_kinematics(second, out=out)
    assert res is out and res.lengths is lengths  # written in place, no new arrays
    fresh = robot.inverse_kinematics(second)
    for name in ("lengths", "unit_vectors", "wrench_matrix", "attachment_points"):
        np.testing.assert_array_equal(getattr(res, name), getattr(fresh, name))
    # A result of another batch size (or a single pose for a batch) is refused.
    with pytest.raises(ValueError, match=r"out.lengths: expected shape \(4, 8\)"):
        robot.inverse_kinematics(second[:4], out=out)
    with pytest.raises(ValueError, match="expected shape"):
        robot.inverse_kinematics(second[0], out=out)
