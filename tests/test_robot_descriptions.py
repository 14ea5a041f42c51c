"""Test robots in three description formats (tests/robots/<robot>/: URDF, DH TOML, POE TOML) and the independent
numeric reference that reads them (tests/reference/chain.py).

The three files of one robot describe the same kinematics (joint zeros, joint signs, base and flange frames),
so their base -> tool0 transforms agree to 1e-12 for every joint vector. kr6_calibrated is the kr6 with axis 3
tilted by 2e-7 rad and axis 5 offset by 3e-8 m (URDF and POE only).
"""

from __future__ import annotations

import math
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from reference import chain
from seeding import case_rng

ROBOTS_DIR = Path(__file__).resolve().parent / "robots"
ROBOTS = ("kr6", "irb120", "tx2_60", "ur5e", "lrmate", "youbot", "iiwa14", "kr6_calibrated", "scara")
NO_DH = {"kr6_calibrated"}
JOINTS = {"youbot": 5, "iiwa14": 7, "scara": 4}   # 6 otherwise
TYPES = {"scara": ("revolute", "revolute", "prismatic", "revolute")}  # all revolute otherwise
# flange position at the zero pose, base_link frame: from the data-sheet lengths, independent of the files
HOME_FLANGE = {
    "kr6": (0.025 + 0.455 + 0.42 + 0.08, 0.0, 0.4 + 0.035),
    "irb120": (0.1, -0.2 + 0.302 + 0.072, 0.05 + 0.29 + 0.27 + 0.07),     # mounted at (0.1, -0.2, 0.05), +90 deg
    "tx2_60": (0.0, 0.02, 0.375 + 0.29 + 0.31 + 0.07),
    "ur5e": (0.425 + 0.3922, 0.1333 + 0.0996, 0.1625 - 0.0997),
    "lrmate": (0.05 + 0.335 + 0.08, 0.0, 0.33 + 0.33 + 0.035),
    "youbot": (0.143 + 0.033, 0.0, 0.046 + 0.147 + 0.155 + 0.135 + 0.2175),
    "iiwa14": (0.0, 0.0, 0.36 + 0.42 + 0.4 + 0.126),
    "scara": (0.325 + 0.275, 0.0, 0.2 - 0.17),
}
# real IK solution counts by geometry (chain.offset_wrist_solution_count / chain.ur_solution_count)
SOLUTION_COUNT = {
    "kr6": lambda T: chain.offset_wrist_solution_count(T, d1=0.4, a1=0.025, a2=0.455, a3=0.035, d4=0.42, d6=0.08),
    "ur5e": lambda T: chain.ur_solution_count(T, d1=0.1625, a2=-0.425, a3=-0.3922, d4=0.1333, d5=0.0997,
                                              d6=0.0996),
}


def _types(robot: str) -> tuple[str, ...]:
    return TYPES.get(robot, ("revolute",) * JOINTS.get(robot, 6))


def robot_files(robot: str) -> dict[str, Path]:
    d = ROBOTS_DIR / robot
    files = {"urdf": d / f"{robot}.urdf", "poe": d / f"{robot}_poe.toml"}
    if robot not in NO_DH:
        files["dh"] = d / f"{robot}_dh.toml"
    return files


def descriptions(robot: str) -> dict[str, chain.Chain]:
    files = robot_files(robot)
    out = {"urdf": chain.urdf_fk(files["urdf"], "base_link", "tool0"), "poe": chain.poe_fk(files["poe"])}
    if "dh" in files:
        out["dh"] = chain.dh_fk(files["dh"])
    return out


def _toml(path: Path) -> dict:
    with open(path, "rb") as f:
        return tomllib.load(f)


# ----------------------------------------------------------------------------------------------------------
# the files
# ----------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("robot", ROBOTS)
def test_files_present(robot):
    present = sorted(p.name for p in (ROBOTS_DIR / robot).iterdir())
    assert present == sorted(p.name for p in robot_files(robot).values())


@pytest.mark.parametrize("robot", ROBOTS)
def test_toml_metadata(robot):
    for kind, path in robot_files(robot).items():
        if kind == "urdf":
            continue
        data = _toml(path)
        assert data["family"] == "chain"
        assert data["name"] == f"{robot}_{kind}"
        for key in ("title", "source"):
            assert isinstance(data[key], str) and data[key].strip() and "\n" not in data[key], (path, key)
        assert data["convention"] in (("standard", "modified") if kind == "dh" else ("poe",))
        for joint, jtype in zip(data["joint"], _types(robot), strict=True):
            assert joint["type"] == jtype
            assert chain.number(joint["lower"]) < chain.number(joint["upper"]), (path, joint["name"])
            if kind == "poe":
                assert abs(np.linalg.norm([chain.number(v) for v in joint["axis"]]) - 1.0) < 1e-15
        assert ("home" in data) == (kind == "poe")


def test_both_dh_conventions_are_used():
    conventions = {r: _toml(robot_files(r)["dh"])["convention"] for r in ROBOTS if r not in NO_DH}
    assert sorted(r for r, c in conventions.items() if c == "modified") == ["kr6", "lrmate", "tx2_60"]
    assert sorted(r for r, c in conventions.items() if c == "standard") == ["iiwa14", "irb120", "scara", "ur5e",
                                                                             "youbot"]


@pytest.mark.parametrize("robot", ROBOTS)
def test_urdf_structure(robot):
    """base_link -> tool0 path: every link declared, tool0 hangs off a fixed joint, one more fixed joint on the
    path (folded by any reader), every moving joint revolute with limits lower < upper."""
    root = ET.parse(robot_files(robot)["urdf"]).getroot()
    assert root.get("name") == robot
    links = {link.get("name") for link in root.findall("link")}
    assert {"base_link", "tool0"} <= links
    by_child = {}
    for joint in root.findall("joint"):
        assert {joint.find("parent").get("link"), joint.find("child").get("link")} <= links
        by_child[joint.find("child").get("link")] = joint
    path, link = [], "tool0"
    while link != "base_link":
        path.append(by_child[link])
        link = by_child[link].find("parent").get("link")
    path.reverse()
    kinds = [j.get("type") for j in path]
    assert kinds[-1] == "fixed"
    assert kinds.count("fixed") >= 2
    assert [k for k in kinds if k != "fixed"] == list(_types(robot))
    for joint in path:
        if joint.get("type") in ("revolute", "prismatic"):
            limit = joint.find("limit")
            assert float(limit.get("lower")) < float(limit.get("upper")), joint.get("name")


@pytest.mark.parametrize("robot", ROBOTS)
def test_joint_names_and_limits_agree(robot):
    chains = descriptions(robot)
    urdf = chains["urdf"]
    assert urdf.n == JOINTS.get(robot, 6)
    for kind, c in chains.items():
        assert c.names == urdf.names, kind
        assert c.types == _types(robot), kind
        np.testing.assert_array_equal(c.lower, urdf.lower, err_msg=kind)
        np.testing.assert_array_equal(c.upper, urdf.upper, err_msg=kind)


def test_joint_counts():
    assert descriptions("youbot")["urdf"].n == 5
    assert descriptions("iiwa14")["urdf"].n == 7
    for robot in ("kr6", "irb120", "tx2_60", "ur5e", "lrmate", "kr6_calibrated"):
        assert all(c.n == 6 for c in descriptions(robot).values()), robot


@pytest.mark.parametrize("robot", ROBOTS)
def test_same_fk_in_every_format(robot):
    """URDF, DH and POE: the same base -> tool0 transform at q = 0, at 50 random joint vectors within the limits
    and at 10 outside them (atol 1e-12)."""
    chains = descriptions(robot)
    urdf = chains["urdf"]
    rng = case_rng(301 + ROBOTS.index(robot))
    qs = [np.zeros(urdf.n)] + [chain.random_joints(urdf.limits, rng) for _ in range(50)]
    qs += [rng.uniform(-2 * np.pi, 2 * np.pi, urdf.n) for _ in range(10)]
    for q in qs:
        T = urdf(q)
        np.testing.assert_allclose(T[3], [0, 0, 0, 1], atol=0)
        np.testing.assert_allclose(T[:3, :3].T @ T[:3, :3], np.eye(3), atol=1e-14)
        for kind, c in chains.items():
            np.testing.assert_allclose(c(q), T, rtol=0, atol=1e-12, err_msg=f"{robot} {kind} at q = {q!r}")


@pytest.mark.parametrize("robot", sorted(HOME_FLANGE))
def test_home_flange_matches_data_sheet_lengths(robot):
    for kind, c in descriptions(robot).items():
        np.testing.assert_allclose(c(np.zeros(c.n))[:3, 3], HOME_FLANGE[robot], atol=1e-12, err_msg=kind)


# ----------------------------------------------------------------------------------------------------------
# the reference itself
# ----------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("robot", ROBOTS)
def test_jacobian_matches_finite_differences(robot):
    """The joint axes the IK uses (axes_points) are those of the FK: analytic Jacobian = finite differences."""
    rng = case_rng(311 + ROBOTS.index(robot))
    for kind, c in descriptions(robot).items():
        for _ in range(3):
            q = chain.random_joints(c.limits, rng)
            J = c.jacobian(q)
            np.testing.assert_allclose(J, chain.finite_difference_jacobian(c, q), rtol=0, atol=1e-7,
                                       err_msg=f"{robot} {kind}")


def test_helpers():
    T = chain.xyz_rpy((0.1, 0.2, 0.3), (0.3, -1.2, 2.5))
    for angle in (1e-13, 1e-8, 0.5, np.pi - 1e-7, np.pi):
        S = T @ chain.rot_x(angle)
        assert chain.pose_error(T, S) == pytest.approx(angle, rel=1e-6, abs=1e-14)
        assert np.linalg.norm(chain.log_rot(S[:3, :3] @ T[:3, :3].T)) == pytest.approx(angle, rel=1e-9, abs=1e-14)
    assert chain.pose_error(T, T @ chain.trans(3e-11, 0, 0)) == pytest.approx(3e-11, rel=1e-3)
    w = chain.wrap_angle([np.pi, -np.pi, 3 * np.pi, 0.5 - 4 * np.pi])
    np.testing.assert_allclose(w, [np.pi, np.pi, np.pi, 0.5], atol=1e-12)
    assert chain.number("-3*pi/4 + 0.5") == pytest.approx(-3 * np.pi / 4 + 0.5)
    assert chain.number(2) == 2.0
    for bad in ("__import__('os')", "pi**2", "sin(pi)", True):
        with pytest.raises(ValueError):
            chain.number(bad)
    rng = case_rng(321)
    limits = [(-1.0, 2.0), (-math.inf, math.inf)]
    for _ in range(20):
        q = chain.random_joints(limits, rng)
        assert -1.0 <= q[0] <= 2.0 and -np.pi <= q[1] <= np.pi


def test_readers_refuse_bad_input(tmp_path):
    urdf = robot_files("kr6")["urdf"]
    with pytest.raises(ValueError):
        chain.urdf_fk(urdf, "tool0", "base_link")       # base must be an ancestor of tip
    with pytest.raises(ValueError):
        chain.urdf_fk(urdf, "base_link", "no_such_link")
    text = robot_files("kr6")["dh"].read_text()
    bad = tmp_path / "bad_dh.toml"
    bad.write_text(text.replace('alpha = "pi/2"', 'alpha = "pi/two"'))
    with pytest.raises(ValueError):
        chain.dh_fk(bad)
    bad.write_text(text.replace('convention = "modified"', 'convention = "sideways"'))
    with pytest.raises(ValueError):
        chain.dh_fk(bad)
    poe = robot_files("kr6")["poe"].read_text()
    bad.write_text(poe.replace("axis = [0.0, 1.0, 0.0]", "axis = [0.0, 2.0, 0.0]"))
    with pytest.raises(ValueError):
        chain.poe_fk(bad)


def test_urdf_sub_path():
    """urdf_fk between inner links: the joints between them only, fixed joints folded."""
    full = chain.urdf_fk(robot_files("kr6")["urdf"], "base_link", "tool0")
    wrist = chain.urdf_fk(robot_files("kr6")["urdf"], "link_3", "flange")
    assert wrist.names == ("a4", "a5", "a6")
    q = case_rng(322).uniform(-3, 3, 6)
    arm = chain.urdf_fk(robot_files("kr6")["urdf"], "base_link", "link_3")
    T = arm(q[:3]) @ wrist(q[3:]) @ chain.xyz_rpy((0, 0, 0), (0, np.pi / 2, 0))
    np.testing.assert_allclose(T, full(q), atol=1e-14)


# ----------------------------------------------------------------------------------------------------------
# multistart IK
# ----------------------------------------------------------------------------------------------------------

def _poses_with_count(robot, count, k, stream):
    c = descriptions(robot)["dh"]
    rng = case_rng(stream)
    out = []
    while len(out) < k:
        q = rng.uniform(-np.pi, np.pi, c.n)
        if SOLUTION_COUNT[robot](c(q)) == count:
            out.append(q)
    return c, out


def _check_solutions(c, T, sols, q_true=None):
    for s in sols:
        assert chain.pose_error(c(s), T) < 1e-10
        assert np.all(s > -np.pi) and np.all(s <= np.pi)
    for i in range(len(sols)):
        for j in range(i):
            assert np.max(np.abs(chain.wrap_angle(sols[i] - sols[j]))) > 1e-6
    if q_true is not None:
        assert min(np.max(np.abs(chain.wrap_angle(s - q_true))) for s in sols) < 1e-8


@pytest.mark.slow
@pytest.mark.parametrize("robot", ["kr6", "ur5e"])
def test_ik_all_finds_all_8(robot):
    """Random poses with 8 real solutions (by geometry): ik_all finds all 8, each reproducing the pose."""
    c, qs = _poses_with_count(robot, 8, 5, 331 + ["kr6", "ur5e"].index(robot))
    for q in qs:
        T = c(q)
        sols = chain.ik_all(c, c.n, T)
        assert len(sols) == 8, (robot, q)
        _check_solutions(c, T, sols, q)


@pytest.mark.slow
def test_ik_all_does_not_invent_solutions():
    """kr6 poses whose shoulder-back configuration cannot reach the wrist centre have 4 solutions; ur5e poses
    with fewer than 8 likewise: ik_all finds exactly those."""
    c, (q,) = _poses_with_count("kr6", 4, 1, 333)
    sols = chain.ik_all(c, c.n, c(q))
    assert len(sols) == 4
    _check_solutions(c, c(q), sols, q)
    c, (q,) = _poses_with_count("ur5e", 4, 1, 334)
    sols = chain.ik_all(c, c.n, c(q))
    assert len(sols) == 4
    _check_solutions(c, c(q), sols, q)


def test_ik_all_with_limits_and_early_stop():
    c = descriptions("kr6")["urdf"]
    rng = case_rng(335)
    q = chain.random_joints(c.limits, rng)
    T = c(q)
    limited = chain.ik_all(c, c.n, T, limits=c.limits, starts=60)
    assert limited
    for s in limited:
        assert np.all(s >= c.lower - 1e-9) and np.all(s <= c.upper + 1e-9)
        assert chain.pose_error(c(s), T) < 1e-10
    early = chain.ik_all(c, c.n, T, starts=60, max_solutions=2)
    assert len(early) == 2


def test_ik_all_five_joints_youbot():
    """5R: the 6 pose equations solved in the least-squares sense; a pose from FK is reached exactly."""
    for kind, c in descriptions("youbot").items():
        q = chain.random_joints(c.limits, case_rng(336))
        T = c(q)
        sols = chain.ik_all(c, c.n, T, starts=40)
        assert 1 <= len(sols) <= 4, kind
        _check_solutions(c, T, sols, q)
        # a pose off the 5-dimensional set of reachable poses has no exact solution
        assert chain.ik_all(c, c.n, T @ chain.rot_x(0.3), starts=10) == []


def test_ik_all_seven_joints_iiwa_with_a_fixed_joint():
    c = descriptions("iiwa14")["poe"]
    q = chain.random_joints(c.limits, case_rng(337))
    T = c(q)
    with pytest.raises(ValueError):
        chain.ik_all(c, c.n, T)
    sols = chain.ik_all(c, c.n, T, fixed={2: q[2]}, starts=60)
    assert 1 <= len(sols) <= 8
    _check_solutions(c, T, sols, q)
    assert all(s[2] == pytest.approx(chain.wrap_angle(q[2]), abs=1e-15) for s in sols)


def test_ik_all_on_a_plain_callable():
    """Without .jacobian (any q -> 4 x 4 callable), ik_all uses finite differences."""
    c = descriptions("ur5e")["poe"]
    q = chain.random_joints(c.limits, case_rng(338))
    T = c(q)
    sols = chain.ik_all(lambda x: c(x), 6, T, starts=30)
    assert sols
    _check_solutions(c, T, sols, None)


# ----------------------------------------------------------------------------------------------------------
# the calibrated kr6
# ----------------------------------------------------------------------------------------------------------

def _angle(u, v):
    return math.atan2(np.linalg.norm(chain.cross(u, v)), float(np.dot(u, v)))


def _line_distance(p1, u1, p2, u2):
    n = chain.cross(u1, u2)
    return abs(float(np.dot(p2 - p1, n))) / np.linalg.norm(n)


def test_calibrated_kr6_deviates(record_property):
    """Axes 2 and 3 are 2e-7 rad from parallel, axis 5 misses axes 4 and 6 by 3e-8 m (the plain kr6: parallel and
    intersecting up to rounding, < 1e-15); URDF and POE agree on this and on the FK, which differs from the kr6's."""
    plain = descriptions("kr6")
    calibrated = descriptions("kr6_calibrated")
    angles = {}
    for kind, c in calibrated.items():
        _, axes, points = c.axes_points(np.zeros(6))
        angle = _angle(axes[1], axes[2])
        angles[kind] = angle
        assert angle == pytest.approx(2e-7, rel=1e-6), f"{kind}: axes 2 and 3 at {angle!r} rad"
        assert _line_distance(points[3], axes[3], points[4], axes[4]) == pytest.approx(3e-8, rel=1e-5), kind
        assert _line_distance(points[5], axes[5], points[4], axes[4]) == pytest.approx(3e-8, rel=1e-5), kind
        assert _angle(axes[3], axes[5]) == 0.0
        assert np.linalg.norm(chain.cross(points[5] - points[3], axes[3])) < 1e-15   # axes 4 and 6 coaxial
    record_property("kr6_calibrated axis 2-3 angle (rad)", angles["urdf"])
    for kind, c in plain.items():
        _, axes, points = c.axes_points(np.zeros(6))
        assert _angle(axes[1], axes[2]) < 1e-15, kind                                   # parallel up to rounding
        assert _line_distance(points[3], axes[3], points[4], axes[4]) < 1e-15, kind     # intersecting
    rng = case_rng(341)
    for _ in range(50):
        q = chain.random_joints(plain["urdf"].limits, rng)
        T = calibrated["urdf"](q)
        np.testing.assert_allclose(calibrated["poe"](q), T, rtol=0, atol=1e-12)
        assert 1e-9 < chain.pose_error(T, plain["urdf"](q)) < 1e-6
