"""The GIL is released during batches, batches agree with single poses, robots pickle."""

import pickle
import threading
import time

import numpy as np

import cdpr
from conftest import random_poses


def test_batches_release_the_gil(robot_path):
    robot = cdpr.Robot.load(robot_path("ipanema-like-8"))
    poses = random_poses(robot, 2000, seed=7)
    # Grow the batch until one call lasts long enough to watch (≥ 0.3 s).
    while True:
        t0 = time.perf_counter()
        robot.tensions(poses)
        if time.perf_counter() - t0 > 0.3:
            break
        poses = np.vstack([poses, poses])
    window = {}

    def work():
        window["start"] = time.perf_counter()
        robot.tensions(poses)
        window["end"] = time.perf_counter()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    start, end = window["start"], window["end"]
    middle = [t for t in ticks if start + 0.25 * (end - start) < t < start + 0.75 * (end - start)]
    # With the GIL held for the whole call, this thread could not run at all in its middle.
    assert len(middle) > 100, (len(middle), end - start)


def test_batch_equals_pose_by_pose(robot_path):
    robot = cdpr.Robot.load(robot_path("ipanema-like-8"))
    poses = random_poses(robot, 700, seed=8)  # several rayon blocks
    batch = robot.tensions(poses)
    for k in range(0, 700, 97):
        one = robot.tensions(poses[k])
        assert one.feasible == batch.feasible[k] and one.reason == batch.reason[k]
        np.testing.assert_array_equal(one.tensions, batch.tensions[k])
    kin = robot.inverse_kinematics(poses)
    np.testing.assert_array_equal(kin.wrench_matrix[555], robot.inverse_kinematics(poses[555]).wrench_matrix)


def test_an_error_in_a_parallel_batch_names_the_first_bad_pose():
    robot = cdpr.Robot.from_anchors("point2", [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0]], t_min=1, t_max=10)
    poses = np.zeros((5000, 2)) + [0.1, 0.1]
    poses[[1234, 4000]] = [1.0, 0.0]  # on an anchor: a zero-length cable
    try:
        robot.inverse_kinematics(poses)
    except ValueError as e:
        assert str(e).startswith("poses[1234]:"), str(e)
    else:
        raise AssertionError("no error")


def test_robots_pickle(robot_path):
    robot = cdpr.Robot.load(robot_path("ipanema-like-8"))
    back = pickle.loads(pickle.dumps(robot))
    assert repr(back) == repr(robot)
    for attr in ("frame", "platform", "t_min", "t_max", "gravity", "centre_of_mass", "axial_stiffness"):
        np.testing.assert_array_equal(getattr(back, attr), getattr(robot, attr))
    assert back.mass == robot.mass and back.min_cable_length == robot.min_cable_length
    q = random_poses(robot, 50)
    np.testing.assert_array_equal(back.tensions(q).tensions, robot.tensions(q).tensions)


def test_from_anchors_validates(robot_path):
    import pytest

    with pytest.raises(ValueError, match="unknown motion|motion"):
        cdpr.Robot.from_anchors("hexapod", [[0, 0]])
    with pytest.raises(ValueError, match=r"frame: expected shape \(n, 2\)"):
        cdpr.Robot.from_anchors("point2", [[0, 0, 0]])
    with pytest.raises(ValueError, match="platform attachment"):
        cdpr.Robot.from_anchors("planar", [[0, 0], [1, 1], [2, 0]])
    with pytest.raises(ValueError, match="finite"):
        cdpr.Robot.from_anchors("point2", [[0, np.nan], [1, 1]])
    with pytest.raises(ValueError, match=r"t_max: expected a number or an array of shape \(3,\)"):
        cdpr.Robot.from_anchors("point2", [[1, 0], [0, 1], [-1, -1]], t_max=[1, 2])
    with pytest.raises(ValueError):
        cdpr.Robot.from_anchors("point2", [[1, 0], [0, 1], [-1, -1]], t_min=5, t_max=1)
    r = cdpr.Robot.from_anchors("point2", [[1, 0], [0, 1], [-1, -1]], t_min=[1, 2, 3], t_max=9.0)
    np.testing.assert_array_equal(r.t_min, [1, 2, 3])
    np.testing.assert_array_equal(r.gravity, [0, -9.80665])
    # The same robot as its file gives the same numbers.
    path = robot_path("tdpm-4")
    f = cdpr.Robot.load(path)
    a = cdpr.Robot.from_anchors("planar", f.frame, f.platform, f.t_min, f.t_max, mass=f.mass,
                                min_cable_length=f.min_cable_length)
    q = [[0.1, -0.2, 0.05], [0.3, 0.1, -0.1]]
    np.testing.assert_array_equal(a.tensions(q, [0, -10, 0]).tensions, f.tensions(q, [0, -10, 0]).tensions)


def test_load_errors_are_value_errors(tmp_path):
    import pytest

    bad = tmp_path / "bad.toml"
    bad.write_text('motion = "planar"\n[tension]\nmin = 5.0\nmax = 1.0\n')
    with pytest.raises(ValueError, match="bad.toml:"):
        cdpr.Robot.load(bad)
    with pytest.raises(ValueError, match="cannot read"):
        cdpr.Robot.load(tmp_path / "missing.toml")
