"""cdpr.sweep on a Dask LocalCluster, with the concurrent.futures fallback, and the doctests."""

import concurrent.futures
import doctest
import pathlib

import pytest

import cdpr
from cdpr.sweep import feasible_volume, random_layouts, rank, sweep

REPO = pathlib.Path(__file__).resolve().parents[2]


def test_local_sweep_ranks_layouts():
    layouts = random_layouts(6, seed=11)
    volumes = sweep(feasible_volume, layouts, max_workers=2)
    assert volumes == [feasible_volume(f) for f in layouts]
    assert all(v >= 0.0 for v in volumes) and max(volumes) > 0.0
    ranked = rank(layouts, volumes)
    assert [v for v, _, _ in ranked] == sorted(volumes, reverse=True)
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        assert sweep(feasible_volume, layouts, executor=pool, chunk_size=4) == volumes


def test_dask_local_cluster_sweep():
    distributed = pytest.importorskip("dask.distributed")
    layouts = random_layouts(8, seed=12)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
        dashboard_address=None,
    ) as cluster, distributed.Client(cluster) as client:
        volumes = sweep(feasible_volume, layouts, client=client, chunk_size=3)
        # Robots cross process boundaries too (they pickle through their arrays).
        robot = cdpr.Robot.load(REPO / "examples" / "robots" / "tdpm-4.toml")
        n = client.submit(lambda r: r.n_cables, robot).result()
    assert n == 4
    assert volumes == [feasible_volume(f) for f in layouts]


def test_sweep_rejects_both_engines():
    with pytest.raises(ValueError, match="not both"):
        sweep(abs, [1], client=object(), executor=object())


def test_module_doctests():
    for module in (cdpr, cdpr.sweep):
        result = doctest.testmod(module)
        assert result.failed == 0 and result.attempted > 0, module


def test_docs_tutorial_runs(monkeypatch):
    """Every example of docs/python.md, executed from the repository root."""
    monkeypatch.chdir(REPO)
    result = doctest.testfile(
        str(REPO / "docs" / "python.md"), module_relative=False,
        optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
    )
    assert result.failed == 0 and result.attempted > 20
