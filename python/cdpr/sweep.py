"""Design sweeps: map a function over design candidates, on one machine or a Dask cluster.

A design study (dimensional synthesis over many candidate geometries, a tolerance study) is a
function ``evaluate(candidate) -> result`` mapped over candidates. :func:`sweep` runs that map
with an existing engine instead of a scheduler of its own:

* ``client=``: a ``dask.distributed.Client`` (the documented path): ``client.map`` submits one
  task per candidate (or per chunk of ``chunk_size`` candidates) to the cluster's workers and
  the results are gathered in order. The client decides where: a ``LocalCluster`` on this
  machine, or a real cluster (``Client("tcp://scheduler:8786")``) whose workers have ``cdpr``
  installed.
* ``executor=``: any ``concurrent.futures.Executor`` (``ThreadPoolExecutor``,
  ``ProcessPoolExecutor``).
* neither: a local ``ThreadPoolExecutor``. Threads are enough when ``evaluate`` spends its time
  in cdpr's batch methods, which release the GIL (and are parallel themselves).

Process pools may use any start method: the package builds its thread pool anew in a forked
child. ``evaluate`` and the candidates are pickled for process pools and Dask: define ``evaluate`` at
module level (or let Dask's cloudpickle carry a closure) and pass arrays or :class:`cdpr.Robot`
objects (which pickle through their arrays).

The example of the docs, ``random_layouts`` + ``feasible_volume``: random 8-cable frame
layouts ranked by the volume of their wrench-feasible workspace.
"""

from __future__ import annotations

import concurrent.futures
import math
from typing import Any, Callable, Iterable, List, Optional, Sequence, TypeVar

import numpy as np

from ._cdpr import Robot

C = TypeVar("C")
R = TypeVar("R")

__all__ = ["sweep", "rank", "random_layouts", "feasible_volume", "IPANEMA_LIKE_PLATFORM"]


def _apply_chunk(function: Callable[[C], R], chunk: Sequence[C]) -> List[R]:
    return [function(c) for c in chunk]


def sweep(
    function: Callable[[C], R],
    candidates: Iterable[C],
    *,
    client: Any = None,
    executor: Optional[concurrent.futures.Executor] = None,
    max_workers: Optional[int] = None,
    chunk_size: int = 1,
) -> List[R]:
    """``[function(c) for c in candidates]``, evaluated in parallel; results in candidate order.

    ``client``: a ``dask.distributed.Client``; ``executor``: a ``concurrent.futures`` executor;
    neither: a ``ThreadPoolExecutor(max_workers)``. ``chunk_size`` candidates go to one task
    (fewer, larger tasks when one evaluation is short). An exception raised by ``function``
    is raised here.

    >>> sweep(abs, [-3, 1, -2])
    [3, 1, 2]
    """
    if client is not None and executor is not None:
        raise ValueError("give client= or executor=, not both")
    if chunk_size < 1:
        raise ValueError(f"chunk_size must be ≥ 1, got {chunk_size}")
    items = list(candidates)
    chunks = [items[i : i + chunk_size] for i in range(0, len(items), chunk_size)]
    if client is not None:
        futures = client.map(_apply_chunk, [function] * len(chunks), chunks, pure=False)
        parts = client.gather(futures)
    elif executor is not None:
        parts = list(executor.map(_apply_chunk, [function] * len(chunks), chunks))
    else:
        with concurrent.futures.ThreadPoolExecutor(max_workers) as pool:
            parts = list(pool.map(_apply_chunk, [function] * len(chunks), chunks))
    return [r for part in parts for r in part]


def rank(candidates: Sequence[C], scores: Sequence[float], *, descending: bool = True):
    """``(score, index, candidate)`` triples sorted by score (best first; NaN last).

    >>> [i for _, i, _ in rank(["a", "b", "c"], [0.5, 2.0, float("nan")])]
    [1, 0, 2]
    """
    def key(k):
        s = scores[k]
        if s is None or (isinstance(s, float) and math.isnan(s)):
            return (1, 0.0)
        return (0, -s if descending else s)

    order = sorted(range(len(candidates)), key=key)
    return [(scores[k], k, candidates[k]) for k in order]


#: The platform attachments of ``examples/robots/ipanema-like-8.toml`` (m): a 0.2 × 0.2 × 0.1 m
#: cuboid, the upper cables at its lower corners and vice versa (crossed as on IPAnema robots).
IPANEMA_LIKE_PLATFORM = np.array(
    [
        [sx * 0.1, sy * 0.1, pz]
        for pz in (-0.05, 0.05)
        for sx, sy in ((1, 1), (-1, 1), (-1, -1), (1, -1))
    ]
)


def random_layouts(count: int, seed: int = 0, size=(4.0, 3.0, 2.0), jitter: float = 0.3):
    """``count`` random 8-cable frame layouts, arrays (8, 3) (m).

    Each is the ipanema-like frame (a box of ``size`` centred on the floor's middle, four upper
    and four lower anchors at its corners) with every anchor moved by up to ``jitter`` × the box
    size along each axis, uniformly and independently: the candidates of a layout study.
    """
    rng = np.random.default_rng(seed)
    sx, sy, sz = size
    corners = np.array(
        [
            [cx * sx / 2, cy * sy / 2, z]
            for z in (sz, 0.0)
            for cx, cy in ((1, 1), (-1, 1), (-1, -1), (1, -1))
        ]
    )
    scale = np.array(size) * jitter
    return [corners + rng.uniform(-1, 1, (8, 3)) * scale for _ in range(count)]


def feasible_volume(
    frame,
    platform=IPANEMA_LIKE_PLATFORM,
    *,
    t_min: float = 10.0,
    t_max: float = 1000.0,
    mass: float = 5.0,
    resolution: int = 8,
    box=(-1.0, 1.0, -0.75, 0.75, 0.3, 1.7),
) -> float:
    """The volume (m³) of the wrench-feasible constant-orientation workspace of one layout.

    The positions of a grid of ``resolution`` intervals per side over ``box`` (xmin, xmax,
    ymin, ymax, zmin, zmax) where tensions in [t_min, t_max] (N) hold the platform of ``mass``
    (kg) under gravity (criterion ``tension``, method l2), times the cell volume. The grid is
    evaluated in parallel with the GIL released.
    """
    robot = Robot.from_anchors(
        "spatial", frame, platform, t_min, t_max, mass=mass, name="layout"
    )
    return robot.workspace(resolution=resolution, box=list(box), criteria="tension").volume
