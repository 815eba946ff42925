"""Capacity margin, isotropic force, stiffness, workspace and trajectory against the CLI."""

import pathlib
import pickle

import numpy as np
import pytest

import cdpr
from conftest import random_poses


@pytest.mark.parametrize(
    "name,wrench,shape",
    [
        ("krut-3", [0.0, -100.0], {}),
        ("krut-4", [10.0, -50.0], {"wrench_ball": 20.0}),
        ("tdpm-4", [0.0, -10.0, 0.0], {"wrench_box": [5.0, 5.0, 0.5]}),
    ],
)
def test_capacity_margin_matches_cli(cli, robot_path, name, wrench, shape):
    robot = cdpr.Robot.load(robot_path(name))
    poses = random_poses(robot, 4, seed=4)
    res = robot.capacity_margin(poses, wrench, **shape)
    for k, q in enumerate(poses):
        ref = cli("capacity", robot_path(name), pose=q, wrench=wrench, **shape)
        assert res.feasible[k] == ref["feasible"]
        assert res.capacity_margin[k] == pytest.approx(ref["capacity_margin"], rel=1e-12, abs=1e-9)
        assert res.limiting_facet[k] == ref["limiting_facet"]["index"]
    assert res.limiting_facet.dtype == np.int64 and res.feasible.dtype == np.bool_


@pytest.mark.parametrize("name", ["krut-3", "tdpm-4", "ipanema-like-8"])
def test_isotropic_force_matches_cli(cli, robot_path, name):
    robot = cdpr.Robot.load(robot_path(name))
    poses = random_poses(robot, 3, seed=5)
    res = robot.isotropic_force(poses)
    for k, q in enumerate(poses):
        ref = cli("isotropic", robot_path(name), pose=q)
        assert res.isotropic_force[k] == pytest.approx(ref["isotropic_force"], rel=1e-12, abs=1e-9)
        assert res.wrench_radius[k] == pytest.approx(ref["wrench_radius"], rel=1e-12, abs=1e-9)
        assert res.definition == ref["definition"]


def test_isotropic_force_under_load_matches_cli(cli, robot_path):
    path = robot_path("tdpm-4")
    robot = cdpr.Robot.load(path)
    poses = random_poses(robot, 3, seed=9)
    res = robot.isotropic_force(poses, [0.0, -10.0, 0.5])
    for k, q in enumerate(poses):
        ref = cli("isotropic", path, pose=q, wrench=[0.0, -10.0, 0.5])
        assert res.isotropic_force[k] == pytest.approx(ref["isotropic_force"], rel=1e-12, abs=1e-9)
        assert res.wrench_radius[k] == pytest.approx(ref["wrench_radius"], rel=1e-12, abs=1e-9)
    # The load enters: the same poses without it give other values.
    assert not np.allclose(robot.isotropic_force(poses).isotropic_force, res.isotropic_force)


def test_isotropic_force_of_krut_robot_is_the_published_value(robot_path):
    # Krut, Company & Pierrot 2004, §IV-B: 225·√3 N at the centre of the 3-motor robot (the
    # file gives the anchors to 1e-6 mm, hence the tolerance).
    robot = cdpr.Robot.load(robot_path("krut-3"))
    assert robot.isotropic_force([0.0, 0.0]).isotropic_force == pytest.approx(225 * 3**0.5, rel=1e-9)


def test_isotropic_force_gives_the_faces_of_a_hand_derived_square():
    # A point between four cables along ±x and ±y, 0 ≤ t ≤ 10 N: W t = (t1 − t2, t3 − t4), so
    # the available force set is the square [−10, 10]² N, four edges with normals ±e_x, ±e_y
    # and offsets 10 N, counter-clockwise seen from outside (the normal on the right of each
    # edge's direction in the plane).
    frame = [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]]
    robot = cdpr.Robot.from_anchors("point2", frame, t_min=0.0, t_max=10.0)
    res = robot.isotropic_force([0.0, 0.0])
    assert res.isotropic_force == pytest.approx(10.0, abs=1e-12)
    corners = {tuple(v) for v in np.round(res.vertices, 12)}
    assert corners == {(10.0, 10.0), (10.0, -10.0), (-10.0, 10.0), (-10.0, -10.0)}
    assert len(res.faces) == 4 and res.normals.shape == (4, 2) and res.offsets.shape == (4,)
    assert {tuple(n) for n in np.round(res.normals, 12)} == {(1, 0), (-1, 0), (0, 1), (0, -1)}
    np.testing.assert_allclose(res.offsets, 10.0, atol=1e-12)
    for face, n in zip(res.faces, res.normals):
        a, b = res.vertices[face[0]], res.vertices[face[1]]
        np.testing.assert_allclose([n @ a, n @ b], 10.0, atol=1e-12)
        edge = b - a
        assert edge[0] * n[1] - edge[1] * n[0] < 0  # counter-clockwise: n points right of the edge
    # Batches give the index only.
    batch = robot.isotropic_force([[0.0, 0.0], [0.1, 0.0]])
    assert batch.faces is None and batch.vertices is None


@pytest.mark.parametrize("name,pose", [("krut-4", [0.1, -0.2]), ("spidercam-like-4", [5.0, 3.0, 20.0])])
def test_isotropic_force_faces_match_cli(cli, robot_path, name, pose):
    robot = cdpr.Robot.load(robot_path(name))
    res = robot.isotropic_force(pose)
    ref = cli("isotropic", robot_path(name), pose=pose)
    np.testing.assert_array_equal(res.vertices, np.array(ref["vertices"]))
    assert [f.tolist() for f in res.faces] == ref["faces"]
    np.testing.assert_array_equal(res.normals, np.array(ref["normals"]))
    np.testing.assert_array_equal(res.offsets, np.array(ref["offsets"]))
    for face, n, d in zip(res.faces, res.normals, res.offsets):
        np.testing.assert_allclose(res.vertices[face] @ n, d, rtol=1e-9, atol=1e-9)
        assert np.all(res.vertices @ n <= d + 1e-9 * max(1.0, abs(d)))
        if res.vertices.shape[1] == 3:  # counter-clockwise seen from outside
            p0, p1, p2 = res.vertices[face[:3]]
            assert np.cross(p1 - p0, p2 - p0) @ n > 0


def test_stiffness_matches_cli(cli, robot_path):
    path = robot_path("ipanema-like-8")
    robot = cdpr.Robot.load(path)
    poses = random_poses(robot, 3, seed=6)
    t = robot.tensions(poses).tensions
    res = robot.stiffness(poses, t)
    assert res.stiffness.shape == (3, 6, 6)
    for k, q in enumerate(poses):
        ref = cli("stiffness", path, pose=q, tensions=t[k])
        np.testing.assert_allclose(res.stiffness[k], ref["stiffness"], rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(res.passive[k], ref["passive"], rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(res.active[k], ref["active"], rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(res.stiffness, res.passive + res.active, rtol=1e-12, atol=1e-9)
    with pytest.raises(ValueError, match="no axial stiffness"):
        cdpr.Robot.load(robot_path("tdpm-4")).stiffness([0, 0, 0], [10.0] * 4)


@pytest.mark.parametrize(
    "name,options",
    [
        ("tdpm-4", {"wrench": [0.0, -10.0, 0.0], "resolution": 20}),
        ("tdpm-4", {"criteria": "tension,wrench-closure", "orientation": 0.1, "resolution": 15}),
        ("krut-4", {"criteria": ["capacity:5"], "wrench_box": [10.0, 10.0], "resolution": 12}),
        ("ipanema-like-8", {"resolution": 6}),
    ],
)
def test_workspace_grid_matches_cli(cli, robot_path, name, options):
    robot = cdpr.Robot.load(robot_path(name))
    res = robot.workspace(**options)
    dim = robot.frame.shape[1]
    flags = {"grid": options["resolution"]}
    if "wrench" in options:
        flags["wrench"] = options["wrench"]
    if "criteria" in options:
        c = options["criteria"]
        flags["criteria"] = c if isinstance(c, str) else ",".join(c)
    if "orientation" in options:
        flags["orientation"] = [options["orientation"]]
    if "wrench_box" in options:
        flags["wrench_box"] = options["wrench_box"]
    ref = cli("workspace", robot_path(name), **flags)
    assert res.feasible_points == ref["feasible_points"]
    assert res.total_points == ref["total_points"]
    assert res.area == pytest.approx(ref["area"], rel=1e-12)
    assert res.area_cells == pytest.approx(ref["area_cells"], rel=1e-12)
    assert res.area_points == pytest.approx(ref["area_points"], rel=1e-12)
    assert res.volume_convention == ref["volume_convention"] == "cells"
    assert res.cell_area == pytest.approx(ref["cell_area"], rel=1e-12)
    if dim == 3:
        assert res.volume == res.area
    assert res.criteria == ref["criteria"] and res.method == ref["tension_method"]
    np.testing.assert_allclose(res.external_wrench, ref["external_wrench"], atol=1e-12)
    assert res.feasible.shape == (options["resolution"] + 1,) * dim
    assert res.feasible.dtype == np.bool_ and res.feasible.sum() == res.feasible_points
    assert res.points.shape == (res.feasible_points, dim)
    # Every feasible grid point passes the tension criterion when evaluated pose by pose.
    if "criteria" not in options and dim == 2:
        iy, ix = np.nonzero(res.feasible)
        pts = np.column_stack([res.x[ix], res.y[iy], np.zeros(len(ix))])
        assert robot.tensions(pts, options.get("wrench")).feasible.all()


def test_workspace_chord_matches_cli(cli, robot_path):
    path = robot_path("tdpm-4")
    res = cdpr.Robot.load(path).workspace(boundary="chord", wrench=[0.0, -10.0, 0.0])
    ref = cli("workspace", path, boundary="chord", wrench=[0.0, -10.0, 0.0])
    assert res.area == pytest.approx(ref["area"], rel=1e-12)
    assert len(res.boundaries) == len(ref["boundaries"])
    for b, r in zip(res.boundaries, ref["boundaries"]):
        np.testing.assert_allclose(b, r, atol=1e-12)


def test_workspace_bad_input(robot_path):
    robot = cdpr.Robot.load(robot_path("tdpm-4"))
    with pytest.raises(ValueError, match="unknown criterion `tensoin`"):
        robot.workspace(criteria="tensoin")
    with pytest.raises(ValueError, match="box needs 4"):
        robot.workspace(box=[0, 1])
    with pytest.raises(ValueError, match="orientation"):
        robot.workspace(orientation=float("nan"))
    with pytest.raises(ValueError, match="chord"):
        cdpr.Robot.load(robot_path("ipanema-like-8")).workspace(boundary="chord")


def test_trajectory_matches_cli(cli, robot_path):
    path = robot_path("ipanema-like-8")
    robot = cdpr.Robot.load(path)
    a, b = [-0.8, -0.5, 0.6, 0, 0, 0], [0.8, 0.5, 1.4, 0.1, 0, -0.1]
    res = robot.trajectory([a, b], samples=21, wrenches=[0, 0, -50.0, 0, 0, 0])
    ref = cli("trajectory", path, from_=a, to=b, samples=21, wrench=[0, 0, -50.0, 0, 0, 0])
    np.testing.assert_allclose(res.s, ref["s"], atol=1e-15)
    np.testing.assert_allclose(res.poses, ref["poses"], atol=1e-12)
    for k, t in enumerate(ref["tensions"]):
        assert res.feasible[k] == (t is not None) and res.reason[k] == ref["reasons"][k]
        if t is not None:
            np.testing.assert_allclose(res.tensions[k], t, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(res.max_jump, ref["max_jump"], rtol=1e-9, atol=1e-9)
    assert res.discontinuities == ref["discontinuities"]
    assert res.feasible_count == ref["feasible_count"]
    with pytest.raises(ValueError, match="at least two poses"):
        robot.trajectory([a])


@pytest.mark.parametrize("name", ["tdpm-4", "ipanema-like-8"])
def test_forward_kinematics_matches_cli_and_inverts_ik(cli, robot_path, name):
    path = robot_path(name)
    robot = cdpr.Robot.load(path)
    truth = random_poses(robot, 5, seed=10)
    lengths = robot.inverse_kinematics(truth).lengths
    guess = truth + 0.05  # one guess per row, near the truth (a local solver)
    res = robot.forward_kinematics(lengths, guess)
    assert res.pose.shape == truth.shape and res.residual.shape == (5,)
    np.testing.assert_allclose(res.pose, truth, atol=1e-7)
    assert list(res.status) == ["solved"] * 5 and np.all(res.residual <= 1e-9)
    np.testing.assert_allclose(robot.inverse_kinematics(res.pose).lengths, lengths, atol=1e-9)
    for k in range(2):
        ref = cli("forward", path, lengths=lengths[k], guess=guess[k])
        np.testing.assert_allclose(res.pose[k], ref["pose"], atol=1e-12)
        assert res.status[k] == ref["status"] and res.iterations[k] == ref["iterations"]
        assert res.residual[k] == pytest.approx(ref["residual"], abs=1e-15)
        assert res.min_singular_value[k] == pytest.approx(ref["min_singular_value"], rel=1e-9)
    # Without a guess: the multi-start of `cdpr forward`, every distinct solution.
    one = robot.forward_kinematics(lengths[0])
    ref = cli("forward", path, lengths=lengths[0])
    assert one.status == ref["status"] and isinstance(one.residual, float)
    np.testing.assert_allclose(one.pose, ref["pose"], atol=1e-9)
    assert one.solutions.shape == (len(ref["solutions"]), robot.dof)
    with pytest.raises(ValueError, match=r"lengths: expected shape"):
        robot.forward_kinematics(lengths[:, :2])
    with pytest.raises(ValueError, match="finite"):
        robot.forward_kinematics(np.full(robot.n_cables, np.nan))


def test_workspace_mesh_is_closed_and_measures_the_grid(robot_path):
    robot = cdpr.Robot.load(robot_path("ipanema-like-8"))
    res = robot.workspace(resolution=8, boundary="mesh", criteria="tension")
    grid = robot.workspace(resolution=8, criteria="tension")
    assert res.feasible_points == grid.feasible_points
    v, f = res.vertices, res.faces
    assert v.shape[1] == 3 and f.shape[1] == 3 and f.dtype == np.int64 and f.max() < len(v)
    # Closed and consistently oriented: every directed edge appears once, its reverse once.
    edges = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    directed = {tuple(e) for e in edges}
    assert len(directed) == len(edges) and all((b, a) in directed for a, b in directed)
    # Divergence theorem recomputed here: the same volume, close to the grid's.
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    assert np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6 == pytest.approx(res.volume, rel=1e-9)
    assert res.volume == pytest.approx(grid.volume, rel=0.25)
    with pytest.raises(ValueError, match="space|spatial|point3"):
        cdpr.Robot.load(robot_path("tdpm-4")).workspace(boundary="mesh")


def test_workspace_mesh_matches_cli(cli, robot_path):
    path = robot_path("ipanema-like-8")
    res = cdpr.Robot.load(path).workspace(resolution=6, boundary="mesh", criteria="tension")
    ref = cli("workspace", path, grid=6, boundary="mesh", criteria="tension")
    assert res.volume == pytest.approx(ref["volume"], rel=1e-12)
    assert res.area == pytest.approx(ref["area"], rel=1e-12)
    assert res.surface_area == pytest.approx(ref["surface_area"], rel=1e-12)
    np.testing.assert_allclose(res.vertices, ref["vertices"], atol=1e-12)
    np.testing.assert_array_equal(res.faces, ref["triangles"])


DATA = pathlib.Path(__file__).resolve().parents[2] / "crates" / "cdpr-io" / "tests" / "data"


@pytest.mark.parametrize(
    "model",
    ["wirecenter/IPAnema.wcrfx", "caspr/spatial_manipulators/CAROCA/CAROCA_cables.xml"],
)
def test_every_robot_file_format_loads_and_matches_cli(cli, model):
    path = DATA / model
    robot = cdpr.Robot.load(path)
    q = np.zeros(robot.dof)
    q[:3] = robot.frame.mean(axis=0)
    kin = robot.inverse_kinematics(q)
    ref = cli("kinematics", path, pose=q)
    np.testing.assert_allclose(kin.lengths, ref["lengths"], rtol=1e-12)
    np.testing.assert_allclose(kin.wrench_matrix, ref["wrench_matrix"], atol=1e-12)
    back = pickle.loads(pickle.dumps(robot))
    np.testing.assert_array_equal(back.inverse_kinematics(q).lengths, kin.lengths)


def test_fewer_cables_than_dof_kinematics_works_analyses_refuse(cli):
    # 2DIPAnema2 declares 3R3T (spatial, 6 DOF) for 4 cables: IK as the CLI, wrench analyses a
    # ValueError naming n and DOF.
    path = DATA / "wirecenter" / "2DIPAnema2.wcrfx"
    robot = cdpr.Robot.load(path)
    assert (robot.dof, robot.n_cables) == (6, 4)
    q = np.array([0.01, -0.02, 0.0, 0.0, 0.0, 0.1])
    kin = robot.inverse_kinematics(q)
    ref = cli("kinematics", path, pose=q)
    np.testing.assert_allclose(kin.lengths, ref["lengths"], rtol=1e-12)
    assert kin.wrench_matrix.shape == (6, 4)
    message = "n = 4 cables for DOF = 6"
    with pytest.raises(ValueError, match=message):
        robot.tensions(q)
    with pytest.raises(ValueError, match=message):
        robot.capacity_margin(q, np.zeros(6), wrench_ball=1.0)
    with pytest.raises(ValueError, match=message):
        robot.isotropic_force(q)


def test_passive_springs_are_part_of_the_external_wrench(cli):
    # CASPR's Passive_springs_planar: 4 cables and 4 passive springs (K = 5 N/m, l0 = 1 m); the
    # springs' force at each pose enters w_ext as in `cdpr tension`.
    path = DATA / "caspr/planar_manipulators/Passive_springs_planar/Passive_springs_planar_cables.xml"
    robot = cdpr.Robot.load(path)
    poses = np.array([[0.2, -0.1, 0.3], [-0.3, 0.4, -0.2]])
    res = robot.tensions(poses)
    for k, q in enumerate(poses):
        ref = cli("tension", path, pose=q)
        np.testing.assert_allclose(res.external_wrench[k], ref["external_wrench"], atol=1e-12)
        np.testing.assert_allclose(res.tensions[k], ref["tensions"], atol=1e-9)
        springs = cli("kinematics", path, pose=q)["passive_springs"]
        weight = np.array([0.0, -3.0 * 9.81, 0.0])
        np.testing.assert_allclose(res.external_wrench[k], weight + springs["wrench"], atol=1e-12)
    with pytest.raises(ValueError, match="4 passive spring"):
        robot.workspace(resolution=4)


@pytest.mark.parametrize("criteria", ["volume", "isotropic", "length:x", "det"])
def test_criteria_errors_are_the_cli_s(robot_path, criteria):
    # One parser (cdpr_workspace::parse_criteria) behind `--criteria` and `criteria=`.
    import subprocess

    from conftest import _find_cli

    robot = cdpr.Robot.load(robot_path("krut-4"))
    with pytest.raises(ValueError) as err:
        robot.workspace(resolution=4, criteria=[criteria])
    out = subprocess.run(
        [str(_find_cli()), "workspace", str(robot_path("krut-4")), "--grid", "4",
         "--criteria", criteria],
        capture_output=True, text=True,
    )
    assert out.returncode == 2
    message = str(err.value)
    assert message.startswith("criteria: ")
    assert message[len("criteria: "):] in out.stderr
