"""cdpr: analysis and design of cable-driven parallel robots, from Python.

The classes below are the Rust crates of the cdpr project compiled into this package (no
command line in between): numpy arrays in and out, batches in parallel with the GIL released.
Bad input raises ``ValueError`` with the library's message. See ``docs/python.md``.

>>> import cdpr
>>> robot = cdpr.Robot.from_anchors("point2", [[1, 0], [-0.5, 0.8], [-0.5, -0.8]], t_min=1, t_max=50)
>>> robot.dof, robot.n_cables, robot.motion
(2, 3, 'point2')
"""

from . import sweep
from ._cdpr import (
    METHODS,
    CapacityResult,
    ForwardResult,
    IsotropicResult,
    KinematicsResult,
    Robot,
    StiffnessResult,
    SimulationResult,
    TensionResult,
    TimedTrajectoryResult,
    TrajectoryResult,
    WorkspaceResult,
    __version__,
    calibrate,
    thread_count,
)

__all__ = [
    "METHODS",
    "CapacityResult",
    "ForwardResult",
    "IsotropicResult",
    "KinematicsResult",
    "Robot",
    "StiffnessResult",
    "SimulationResult",
    "TensionResult",
    "TimedTrajectoryResult",
    "TrajectoryResult",
    "WorkspaceResult",
    "__version__",
    "calibrate",
    "sweep",
    "thread_count",
]

