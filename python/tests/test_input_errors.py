"""Bad input from Python is a ``ValueError`` with the library's words (issue 25): negative
counts (not the ``OverflowError`` of an unsigned conversion), negative tension bounds (a cable
can only pull), and the package's version."""

import re

import pytest

import cdpr


def _point2(**bounds):
    return cdpr.Robot.from_anchors("point2", [[1, 0], [-0.5, 0.8], [-0.5, -0.8]], **bounds)


def test_version_is_the_crate_version():
    assert isinstance(cdpr.__version__, str)
    assert re.fullmatch(r"\d+\.\d+\.\d+.*", cdpr.__version__), cdpr.__version__


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda r: r.workspace(resolution=-3), "resolution = -3"),
        (lambda r: r.trajectory([[0.0, 0.0], [0.1, 0.1]], samples=-5), "samples = -5"),
        (lambda r: r.forward_kinematics([1.0, 1.0, 1.0], max_iterations=-1), "max_iterations = -1"),
    ],
)
def test_negative_counts_are_value_errors(call, name):
    robot = _point2(t_min=1, t_max=50)
    with pytest.raises(ValueError, match=re.escape(name) + ".*integer ≥ 0"):
        call(robot)


@pytest.mark.parametrize(
    "bounds, message",
    [
        ({"t_min": -5, "t_max": -1}, r"t_min\[0\] = -5 N is negative"),
        ({"t_min": [1, -2, 1], "t_max": 50}, r"t_min\[1\] = -2 N is negative"),
        ({"t_max": -1}, r"t_max\[0\] = -1 N is negative"),
        ({"t_min": 5, "t_max": 1}, "t_min"),
    ],
)
def test_negative_or_inverted_tension_bounds_are_value_errors(bounds, message):
    with pytest.raises(ValueError, match=message):
        _point2(**bounds)


def test_zero_lower_bound_is_accepted():
    robot = _point2(t_min=0, t_max=50)
    assert list(robot.t_min) == [0.0, 0.0, 0.0]
