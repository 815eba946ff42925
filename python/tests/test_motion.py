"""Robots in motion through the requests of cdpr-api (issue 28): timed trajectories with inverse
dynamics and motors, forward dynamics and the mass matrix.

``Robot.trajectory(…, time_law=…)`` and ``Robot.simulate(…)`` build the request the command line
builds, so their answers are the command's JSON bit for bit (``==``); the mass matrix is checked
against M = [[m I, −m[c]×], [m[c]×, R I_G Rᵀ − m[c]×[c]×]] written out here, and against the
command's inertial wrench M ẍ at rest.
"""

import numpy as np
import pytest

import cdpr
from conftest import ROBOTS

A, B = [-0.3, 0.0, 0.8, 0.0, 0.0, 0.0], [0.3, 0.2, 1.2, 0.0, 0.0, 0.1]
WINCH = (
    "axial_stiffness = 60000.0\nwinch = { drum_radius = 0.05, gear_ratio = 10.0, "
    "motor_inertia = 2e-4, max_torque = 100.0, max_speed = 300.0 }"
)


@pytest.fixture
def winches(tmp_path):
    """The 8-cable robot with a winch on every cable and an offset centre of mass."""
    text = (ROBOTS / "ipanema-like-8.toml").read_text()
    text = text.replace("axial_stiffness = 60000.0", WINCH)
    text = text.replace("centre_of_mass = [0.0, 0.0, 0.0]", "centre_of_mass = [0.02, -0.01, 0.03]")
    path = tmp_path / "winches.toml"
    path.write_text(text)
    return path, cdpr.Robot.load(path)


def rows(a):
    """A result's array as the JSON's rows, None where a row is NaN (an infeasible sample)."""
    return [None if np.isnan(r).any() else r.tolist() for r in a]


def test_a_timed_trajectory_is_the_cli_report(cli, winches):
    path, robot = winches
    res = robot.trajectory([A, B], time_law="quintic", duration=1.0, dt=0.05, dynamics=True)
    ref = cli("trajectory", path, from_=A, to=B, time_law="quintic", duration=1.0, dt=0.05,
              dynamics=True)
    assert isinstance(res, cdpr.TimedTrajectoryResult)
    assert res.t.tolist() == ref["t"]
    for key in ["poses", "velocity", "acceleration", "cable_lengths", "cable_speeds",
                "cable_accelerations", "inertial_wrench", "motor_speeds"]:
        assert getattr(res, key).tolist() == ref[key], key
    for key in ["tensions", "motor_torques", "motor_powers"]:
        assert rows(getattr(res, key)) == ref[key], key
    assert res.reason == ref["reasons"] and res.feasible_count == ref["feasible_count"] == 21
    assert res.motors_within_limits is ref["motors_within_limits"] is True
    assert res.motor_limit_violations == ref["motor_limit_violations"] == []
    assert (res.duration, res.dt, res.time_law, res.method, res.dynamics) == (
        ref["duration"], ref["dt"], "quintic", "l2", True)
    assert res.waypoint_times == ref["waypoint_times"]
    # Quasi-static and without winches: no inertial wrench, no motors.
    plain = cdpr.Robot.load(ROBOTS / "ipanema-like-8.toml")
    q = plain.trajectory([A, B], time_law="cubic", duration=1.0, dt=0.25)
    assert q.inertial_wrench is None and q.motor_torques is None and q.t.tolist() == [
        0.0, 0.25, 0.5, 0.75, 1.0]


def test_waypoint_times_and_an_untimed_path_are_the_cli_reports(cli, winches, tmp_path):
    path, robot = winches
    c = [0.3, -0.2, 1.0, 0.0, 0.0, 0.0]
    file = tmp_path / "w.toml"
    file.write_text("".join(
        f"[[waypoints]]\npose = {list(p)}\ntime = {t}\n" for p, t in [(A, 0.0), (B, 0.6), (c, 1.5)]))
    res = robot.trajectory([A, B, c], times=[0.0, 0.6, 1.5], time_law="parabolic-blend", dt=0.1)
    ref = cli("trajectory", path, waypoints=file, time_law="parabolic-blend", dt=0.1)
    assert res.t.tolist() == ref["t"] and res.waypoint_times == [0.0, 0.6, 1.5]
    assert res.velocity.tolist() == ref["velocity"] and rows(res.tensions) == ref["tensions"]
    untimed = robot.trajectory([A, B], samples=9, method="linf")
    ref = cli("trajectory", path, from_=A, to=B, samples=9, method="linf")
    assert isinstance(untimed, cdpr.TrajectoryResult)
    assert untimed.s.tolist() == ref["s"] and rows(untimed.tensions) == ref["tensions"]
    assert untimed.max_jump.tolist() == ref["max_jump"]


def test_bad_timing_is_a_value_error(winches):
    _, robot = winches
    with pytest.raises(ValueError, match="time law"):
        robot.trajectory([A, B], time_law="septic", duration=1.0)
    with pytest.raises(ValueError, match="--dt needs --time-law"):
        robot.trajectory([A, B], dt=0.1)
    with pytest.raises(ValueError, match="times: 2 numbers for 3 waypoints"):
        robot.trajectory([A, B, A], times=[0.0, 1.0], time_law="cubic")
    with pytest.raises(ValueError, match="duration"):
        robot.trajectory([A, B], time_law="cubic", duration=-1.0)


def test_a_simulation_is_the_cli_report(cli, winches):
    path, robot = winches
    res = robot.simulate(A, 0.1, 0.02, tensions=[20.0] * 8, velocity=[0.1, 0, 0, 0, 0, 0.2])
    ref = cli("simulate", path, from_=A, tensions=[20.0] * 8, duration=0.1, dt=0.02,
              velocity=[0.1, 0, 0, 0, 0, 0.2])
    for key in ["t", "poses", "velocities", "accelerations", "tensions"]:
        assert getattr(res, key).tolist() == ref[key], key
    assert (res.steps, res.rejected_steps, res.integrator) == (ref["steps"], 0, "rk4")
    # Inverse then forward dynamics: driven by a timed trajectory's tensions (interpolated
    # linearly between samples), the platform follows the planned poses, the gap shrinking as
    # dt² (second order: the interpolation error of the tensions).
    gaps = []
    for dt in [0.01, 0.001]:
        traj = robot.trajectory([A, B], time_law="quintic", duration=1.0, dt=dt, dynamics=True)
        sim = robot.simulate(A, 1.0, dt, tension_profile=(traj.t, traj.tensions))
        np.testing.assert_allclose(sim.t, traj.t, rtol=0, atol=1e-12)
        gaps.append(np.abs(sim.poses - traj.poses).max())
    assert gaps[1] < 1e-5 and gaps[0] / gaps[1] > 50, gaps
    fast = robot.simulate(A, 0.1, 0.02, tensions=[20.0] * 8, integrator="rk45", tolerance=1e-8)
    assert fast.integrator == "rk45" and fast.steps > 0
    with pytest.raises(ValueError, match="give one drive"):
        robot.simulate(A, 0.1, 0.02, tensions=[20.0] * 8, unstrained_lengths=[2.0] * 8)
    with pytest.raises(ValueError, match="integrator"):
        robot.simulate(A, 0.1, 0.02, tensions=[20.0] * 8, integrator="euler")


def cross(c):
    return np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])


def test_the_mass_matrix_is_the_newton_euler_one(cli, winches):
    path, robot = winches
    m, cbar = 5.0, np.array([0.02, -0.01, 0.03])
    inertia = np.diag([0.0208333, 0.0208333, 0.0333333])
    theta = 0.4
    rz = np.array([[np.cos(theta), -np.sin(theta), 0], [np.sin(theta), np.cos(theta), 0], [0, 0, 1]])
    poses = np.array([[0.1, 0.0, 1.0, 0.0, 0.0, 0.0], [0.0, 0.2, 1.1, 0.0, 0.0, theta]])
    got = robot.mass_matrix(poses)
    assert got.shape == (2, 6, 6)
    for k, rot in enumerate([np.eye(3), rz]):
        c = rot @ cbar
        ip = rot @ inertia @ rot.T - m * cross(c) @ cross(c)
        want = np.block([[m * np.eye(3), -m * cross(c)], [m * cross(c), ip]])
        np.testing.assert_allclose(got[k], want, rtol=1e-13, atol=1e-15)
    np.testing.assert_array_equal(robot.mass_matrix(poses[1]), got[1])
    # At rest (t = 0 of a cubic law) b = 0: the command's inertial wrench is M ẍ.
    ref = cli("trajectory", path, from_=A, to=B, time_law="cubic", duration=1.0, dt=0.5,
              dynamics=True)
    w = robot.mass_matrix(A) @ np.array(ref["acceleration"][0])
    np.testing.assert_allclose(w, ref["inertial_wrench"][0], rtol=1e-12, atol=1e-12)
    point = cdpr.Robot.load(ROBOTS / "tdpm-4.toml")
    with pytest.raises(ValueError, match="mass"):
        point.mass_matrix([0.0, 0.0, 0.0])


CASPR = ROBOTS.parents[1] / "crates" / "cdpr-io" / "tests" / "data" / "caspr"


def test_a_caspr_trajectory_is_the_cli_report(cli):
    """``caspr_trajectory=``: CASPR's IPAnema 2 ``traj_z_up`` (a quintic lift from z = 0.5 to 2 m in
    1 s, time_step 0.01 s) with its inverse dynamics, equal to ``cdpr trajectory --trajectory``."""
    d = CASPR / "spatial_manipulators" / "IPAnema_2"
    robot_file, traj = d / "IPAnema_2_cables.xml", d / "IPAnema_2_trajectories.xml"
    robot = cdpr.Robot.load(robot_file)
    res = robot.trajectory(caspr_trajectory=str(traj), trajectory_id="traj_z_up", dynamics=True)
    ref = cli("trajectory", robot_file, trajectory=traj, trajectory_id="traj_z_up", dynamics=True)
    assert isinstance(res, cdpr.TimedTrajectoryResult)
    assert res.t.tolist() == ref["t"] and len(ref["t"]) == 101
    for key in ["poses", "velocity", "acceleration", "cable_lengths", "inertial_wrench"]:
        assert getattr(res, key).tolist() == ref[key], key
    assert rows(res.tensions) == ref["tensions"]
    assert res.poses[0].tolist() == [0.0, 0.0, 0.5, 0.0, 0.0, 0.0]
    assert res.poses[-1].tolist() == [0.0, 0.0, 2.0, 0.0, 0.0, 0.0]
    # Bad combinations are ValueErrors naming what to give.
    with pytest.raises(ValueError, match="not both"):
        robot.trajectory([[0, 0, 1, 0, 0, 0], [0, 0, 1.5, 0, 0, 0]], caspr_trajectory=str(traj))
    with pytest.raises(ValueError, match="trajectory_id needs caspr_trajectory"):
        robot.trajectory([[0, 0, 1, 0, 0, 0], [0, 0, 1.5, 0, 0, 0]], trajectory_id="traj_z_up")
    with pytest.raises(ValueError, match="traj_9"):
        robot.trajectory(caspr_trajectory=str(traj), trajectory_id="traj_9")
