"""``cable_model=`` (issue 29): elastic and sagging cables through the requests of the command line.

``inverse_kinematics``, ``tensions``, ``forward_kinematics`` and ``trajectory`` with
``cable_model="elastic"`` or ``"catenary"`` build the request ``cdpr … --cable-model`` builds,
so their answers are its JSON bit for bit; the physics is checked on top (the elastic straight
cable's L0 = l/(1 + t/EA); the forward kinematics returns the pose whose tensions gave the
lengths).
"""

import numpy as np
import pytest

import cdpr

POSE = [0.2, -0.1, 1.0, 0.02, 0.0, 0.05]


@pytest.fixture
def heavy(robot_path, tmp_path):
    """ipanema-like-8 with 20 g/m cables (E·S = 60 kN from the file), no pulleys."""
    text = robot_path("ipanema-like-8").read_text()
    path = tmp_path / "heavy.toml"
    path.write_text(
        text.replace("axial_stiffness = 60000.0", "axial_stiffness = 60000.0\nlinear_density = 0.02")
    )
    return path, cdpr.Robot.load(path)


def test_kinematics_with_sagging_cables_is_the_cli_report(cli, heavy):
    path, robot = heavy
    t = [100.0, 90.0, 150.0, 100.0, 110.0, 130.0, 95.0, 140.0]
    res = robot.inverse_kinematics(POSE, cable_model="catenary", tensions=t)
    ref = cli("kinematics", path, pose=POSE, cable_model="catenary", tensions=t)
    for key in ("unstrained_lengths", "chord_lengths", "frame_end_tensions", "max_sag"):
        assert getattr(res, key).tolist() == ref[key], key
    assert res.wrench_matrix.tolist() == ref["wrench_matrix"]
    assert res.platform_end_tensions.tolist() == t
    assert (res.max_sag > 0).all()
    # Along a heavy elastic cable (T_A − T_B) + (T_A² − T_B²)/(2EA) = w (z_A − z_B) exactly.
    ta, tb = res.frame_end_tensions, res.platform_end_tensions
    w = 0.02 * np.linalg.norm(robot.gravity)
    rise = robot.frame[:, 2] - robot.inverse_kinematics(POSE).attachment_points[:, 2]
    np.testing.assert_allclose((ta - tb) + (ta**2 - tb**2) / (2 * 6e4), w * rise, rtol=1e-9, atol=1e-11)
    # Weightless elastic cables: L0 = l/(1 + t/EA) on the straight chord.
    el = robot.inverse_kinematics(POSE, cable_model="elastic", tensions=t)
    chords = robot.inverse_kinematics(POSE).lengths
    np.testing.assert_allclose(el.unstrained_lengths, chords / (1 + np.array(t) / 6e4), rtol=1e-13)


def test_statics_and_forward_kinematics_round_trip(cli, heavy):
    path, robot = heavy
    res = robot.tensions(POSE, method="l2", cable_model="catenary")
    ref = cli("tension", path, pose=POSE, method="l2", cable_model="catenary")
    assert res.feasible and ref["feasible"]
    assert res.tensions.tolist() == ref["tensions"]
    assert res.unstrained_lengths.tolist() == ref["unstrained_lengths"]
    assert res.residual == ref["residual"]
    # Those unstrained lengths hold the platform at the pose with those tensions.
    fk = robot.forward_kinematics(res.unstrained_lengths, POSE, cable_model="catenary")
    assert fk.status == "equilibrium"
    np.testing.assert_allclose(fk.pose, POSE, atol=1e-8)
    np.testing.assert_allclose(fk.tensions, res.tensions, rtol=1e-6)
    fk_ref = cli(
        "forward", path, unstrained_lengths=res.unstrained_lengths, guess=POSE, cable_model="catenary"
    )
    assert fk.pose == fk_ref["pose"] and fk.tensions.tolist() == fk_ref["tensions"]


def test_trajectory_compensation_is_the_cli_report(cli, heavy):
    path, robot = heavy
    a, b = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0], [0.3, 0.2, 1.2, 0.0, 0.0, 0.0]
    res = robot.trajectory([a, b], samples=3, cable_model="elastic")
    ref = cli("trajectory", path, from_=a, to=b, samples=3, cable_model="elastic")
    assert res.cable_model == "elastic"
    assert res.unstrained_lengths.tolist() == ref["unstrained_lengths"]
    assert res.platform_end_tensions.tolist() == ref["platform_end_tensions"]
    assert res.drum_angles is None  # no winches in the file
    plain = robot.trajectory([a, b], samples=3)
    assert plain.cable_model is None and plain.unstrained_lengths is None


def test_bad_cable_model_arguments_are_value_errors(heavy, robot_path):
    _, robot = heavy
    with pytest.raises(ValueError, match="cable_model"):
        robot.inverse_kinematics(POSE, cable_model="rope", tensions=[1.0] * 8)
    with pytest.raises(ValueError, match="tensions"):
        robot.inverse_kinematics(POSE, cable_model="catenary")
    with pytest.raises(ValueError, match="tensions"):
        robot.inverse_kinematics(POSE, tensions=[1.0] * 8)
    with pytest.raises(ValueError, match="sotda"):
        robot.tensions(POSE, method="sotda", cable_model="elastic")
    plain = cdpr.Robot.load(robot_path("tdpm-4"))
    with pytest.raises(ValueError, match="axial_stiffness"):
        plain.tensions([0.0, 0.0, 0.0], cable_model="elastic")
