"""The options of single tension methods (issue 26) reach ``workspace`` and ``trajectory`` as
they reach ``cdpr workspace`` and ``cdpr trajectory``: ``interior`` (puncture), ``alternating``
(dykstra), ``p`` (p-norm), ``alpha`` (optimally-safe). Each answer is the command line's for the
same flags, and an option given to another method is refused as the command line refuses it.
"""

import numpy as np
import pytest

import cdpr


def test_workspace_with_puncture_interior_is_the_cli_report(cli, robot_path):
    path = robot_path("ipanema-like-8")
    robot = cdpr.Robot.load(path)
    icf = robot.workspace(resolution=6, method="puncture")
    cf = robot.workspace(resolution=6, method="puncture", interior="cf")
    ref_cf = cli("workspace", path, grid=6, method="puncture", interior="cf")
    ref_icf = cli("workspace", path, grid=6, method="puncture")
    assert cf.feasible_points == ref_cf["feasible_points"]
    assert icf.feasible_points == ref_icf["feasible_points"]
    # The option is honoured: the cf interior point reaches fewer poses here.
    assert cf.feasible_points < icf.feasible_points


def test_trajectory_with_p_norm_exponent_is_the_cli_report(cli, robot_path):
    path = robot_path("ipanema-like-8")
    robot = cdpr.Robot.load(path)
    a, b = [-0.3, -0.2, 0.8, 0, 0, 0], [0.3, 0.2, 1.2, 0, 0, 0]
    p6 = robot.trajectory([a, b], samples=5, method="p-norm", p=6.0)
    p4 = robot.trajectory([a, b], samples=5, method="p-norm")
    ref = cli("trajectory", path, from_=a, to=b, samples=5, method="p-norm", p=6.0)
    for k, t in enumerate(ref["tensions"]):
        assert p6.feasible[k] == (t is not None)
        if t is not None:
            np.testing.assert_allclose(p6.tensions[k], t, rtol=1e-9, atol=1e-9)
    assert np.abs(np.asarray(p6.tensions) - np.asarray(p4.tensions)).max() > 1e-6


def test_an_option_of_another_method_is_refused(robot_path):
    robot = cdpr.Robot.load(robot_path("ipanema-like-8"))
    with pytest.raises(ValueError, match="p"):
        robot.workspace(resolution=4, method="l2", p=6.0)
    with pytest.raises(ValueError, match="alpha"):
        robot.trajectory([[0, 0, 1, 0, 0, 0], [0.1, 0, 1, 0, 0, 0]], samples=3, alpha=2.0)
