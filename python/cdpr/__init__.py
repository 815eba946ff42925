"""cdpr: analysis and design of cable-driven parallel robots, from Python.

The classes and functions are the Rust crates of the cdpr project compiled into this package
(no command line in between): numpy arrays in and out, batches in parallel with the GIL
released. See ``docs/python.md`` for a tutorial.
"""

from ._cdpr import (
    METHODS,
    KinematicsResult,
    Robot,
    TensionResult,
    thread_count,
)

__all__ = [
    "METHODS",
    "KinematicsResult",
    "Robot",
    "TensionResult",
    "thread_count",
]


def _rebuild_robot(motion, frame, platform, t_min, t_max, kwargs):
    """Unpickles a :class:`Robot` (see ``Robot.__reduce__``)."""
    return Robot.from_anchors(motion, frame, platform, t_min, t_max, **kwargs)
