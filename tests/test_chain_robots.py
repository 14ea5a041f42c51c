"""Bring your own robot: classic arms written in three formats (tests/robots/: URDF, DH table, POE spec) go
through `wristkin derive` and the emitted solvers are checked against the independent numeric reference
(tests/reference/chain.py: its own URDF / DH / POE readers and a multistart Levenberg-Marquardt IK).
tests/robots/ur5e_offset (a DH table only, a test arm): the UR5e with its last two axes 3 cm apart, which the
planner solves by subproblem 6; the same checks, plus its exact wrist singularity.

Tolerances: FK and Jacobian agree to 1e-12 x the robot's size (two products of the same rigid motions in a
different order: rounding only); IK sets reproduce the pose to 1e-9 (IK_VERIFY_TOL, the solver's own
acceptance) and equal the reference's to 1e-6 rad (the reference deduplicates at 1e-6 and converges to 1e-10 in
the pose, so its joints are good to ~1e-10 / sigma_min; poses are drawn away from singularities by requiring
sigma_min / sigma_max > 1e-3).
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import derived_cache
import numpy as np
import pytest
from chain_specs import SKEW3, poe_spec
from reference import chain as ref
from seeding import case_rng

from derive import own_robot

ROBOTS = Path(__file__).parent / "robots"
FREE = {"iiwa14": "a3"}  # the redundant arm's joint held as a run-time parameter
SIX = ("kr6", "irb120", "tx2_60", "ur5e", "lrmate")
ALL = SIX + ("youbot", "iiwa14")
FORMATS = ("urdf", "dh", "poe")
_CACHE: dict = {}
EPS = float(np.finfo(float).eps)


def _file(robot: str, fmt: str) -> Path:
    return ROBOTS / robot / (f"{robot}.urdf" if fmt == "urdf" else f"{robot}_{fmt}.toml")


def solver(robot: str, fmt: str = "urdf", **options):
    """The solver `wristkin derive` writes for the robot's description (derived once per process)."""
    key = (robot, fmt, tuple(sorted(options.items())))
    if key not in _CACHE:
        import tempfile

        out = Path(tempfile.mkdtemp(prefix=f"wk_{robot}_{fmt}_"))
        name = f"{robot}_{fmt}_solver"
        # the URDF solvers run the C (the folder's extension), the DH and POE ones numpy: both paths are tested
        derived_cache.derive(_file(robot, fmt), out, name=name, free=FREE.get(robot), native=fmt == "urdf",
                             **options)
        _CACHE[key] = (own_robot.import_solver(out, name), out)
    return _CACHE[key][0]


def reference(robot: str, fmt: str = "urdf"):
    return ref.load(_file(robot, fmt))


def _design(m, q):
    """The held joint's value where the module has one (a derived module's design is its DH lengths: default)."""
    return [q[m._FREE]] if m._FREE >= 0 else None


def _gap(a, b, kinds) -> float:
    return max((abs(math.remainder(x - y, 2 * math.pi)) if k == "R" else abs(x - y)) for x, y, k in
               zip(a, b, kinds, strict=False))


def _regular_joints(m, rng, margin=1e-3):
    """Random joints (uniform in (-pi, pi]) whose Jacobian has sigma_min / sigma_max > margin."""
    while True:
        q = rng.uniform(-math.pi, math.pi, m.N_JOINTS)
        s = np.linalg.svd(m.jacobian(q, _design(m, q)), compute_uv=False)
        if s[-1] / s[0] > margin:
            return q


def _size(m) -> float:
    return max(1.0, float(m.SCALE))


# ------------------------------------------------------------------------------------------------ forward
@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("robot", ALL)
def test_fk_and_jacobian_equal_the_reference(robot, fmt):
    m, r = solver(robot, fmt), reference(robot, fmt)
    rng = case_rng(11)
    for _ in range(20):
        q = rng.uniform(-math.pi, math.pi, m.N_JOINTS)
        d = _design(m, q)
        np.testing.assert_allclose(m.fk_matrix(q, d), r(q), atol=1e-12 * _size(m))
        np.testing.assert_allclose(m.jacobian(q, d), r.jacobian(q), atol=1e-12 * _size(m))


# ------------------------------------------------------------------------------------------------ inverse
@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("robot", ALL)
def test_ik_contains_the_generating_joints_and_every_set_reproduces_the_pose(robot, fmt):
    m = solver(robot, fmt)
    rng = case_rng(12)
    for _ in range(40):
        q = rng.uniform(-math.pi, math.pi, m.N_JOINTS)
        d = _design(m, q)
        T = m.fk_matrix(q, d)
        sol = m.ik(T, d)
        assert sol.status in (m.STATUS_OK, m.STATUS_INDETERMINATE), sol.reason
        assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-7
        for v in sol:
            assert np.max(np.abs(m.fk_matrix(v, d) - T)) <= m.IK_VERIFY_TOL


@pytest.mark.parametrize("robot", ALL)
def test_ik_sets_equal_the_multistart_reference(robot):
    """None missed, none spurious: the closed form's sets equal every solution the numeric reference finds."""
    m, r = solver(robot), reference(robot)
    rng = case_rng(13)
    for k in range(3):
        q = _regular_joints(m, rng)
        d = _design(m, q)
        T = m.fk_matrix(q, d)
        fixed = {m._FREE: q[m._FREE]} if m._FREE >= 0 else None
        found = ref.ik_all(r, m.N_JOINTS, T, fixed=fixed, seed=k)
        ours = list(m.ik(T, d))
        assert len(ours) == len(found), (robot, len(ours), len(found))
        for v in found:
            assert min(_gap(v, w, m.JOINT_KINDS) for w in ours) < 1e-6


@pytest.mark.parametrize("robot", SIX + ("youbot",))
def test_three_formats_give_the_same_solution_sets(robot):
    ms = [solver(robot, f) for f in FORMATS]
    rng = case_rng(14)
    for _ in range(10):
        q = rng.uniform(-math.pi, math.pi, ms[0].N_JOINTS)
        T = ms[0].fk_matrix(q)
        sets = [sorted(tuple(np.round(v, 7)) for v in m.ik(T)) for m in ms]
        assert len(sets[0]) == len(sets[1]) == len(sets[2])
        for a in sets[0]:
            for other in sets[1:]:
                assert min(_gap(a, b, ms[0].JOINT_KINDS) for b in other) < 1e-7


@pytest.mark.parametrize("robot", ALL)
def test_the_folder_extension_and_numpy_give_the_same_answers(robot):
    m = solver(robot)
    if os.environ.get("WRISTKIN_BACKEND") != "numpy":
        assert m.BACKEND == "c" and "ik" in m.NATIVE_VERBS
    py = own_robot.import_solver(_CACHE[(robot, "urdf", ())][1], f"{robot}_urdf_solver", backend="numpy")
    assert py.BACKEND == "numpy"
    base = np.eye(4)
    base[:3, 3] = (0.2, -0.1, 0.5)
    tool = np.eye(4)
    tool[:3, :3] = [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]
    rng = case_rng(21)
    for frames in ({}, {"base": base, "tool": tool}):
        for _ in range(15):
            q = rng.uniform(-math.pi, math.pi, m.N_JOINTS)
            params = [q[m._FREE]] if m._FREE >= 0 or m._ARM_ANGLE else None
            dc, dp = m.make_design(params, **frames), py.make_design(params, **frames)
            T = py.fk_matrix(q, dp)
            np.testing.assert_allclose(m.fk_matrix(q, dc), T, atol=1e-13)
            np.testing.assert_allclose(m.jacobian(q, dc), py.jacobian(q, dp), atol=1e-12)
            a, b = m.ik(T, dc), py.ik(T, dp)
            assert a.count == b.count and a.status == b.status
            np.testing.assert_allclose(a.values[a.valid], b.values[b.valid], atol=1e-9)
            np.testing.assert_array_equal(a.flags, b.flags)
        batch = m.ik_batch(np.array([py.fk_matrix(x, dp) for x in rng.uniform(-3, 3, (5, m.N_JOINTS))]), dc)
        assert batch.values.shape == (5, m.MAX_IK, m.N_JOINTS)


def test_a_user_s_own_c_file_in_the_folder_leaves_the_extension_built(tmp_path):
    """The extension compiles the C files wristkin wrote, not every file in OUT/c: a user's test harness with its own
    main beside them made the build fail, and the solvers fell back to numpy with an empty reason."""
    if os.environ.get("WRISTKIN_BACKEND") == "numpy":
        pytest.skip("the numpy backend is forced")
    derived_cache.derive(ROBOTS / "kr6" / "kr6.urdf", tmp_path, name="kr6_mine")
    # a timing harness as users write one: built on its own with -D_POSIX_C_SOURCE, which the extension's flags lack
    (tmp_path / "c" / "my_harness.c").write_text('#include <time.h>\n#include "kr6_mine.h"\n'
                                                 "int main(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, "
                                                 "&t); return 0; }\n")
    said = []
    own_robot.derive(ROBOTS / "kr6" / "kr6.urdf", tmp_path, name="kr6_mine", progress=said.append)
    assert not any("no C extension" in line for line in said), said
    m = own_robot.import_solver(tmp_path, "kr6_mine")
    assert m.BACKEND == "c"
    assert (tmp_path / "c" / "my_harness.c").is_file()  # the user's file stays


def test_the_decomposition_is_read_from_the_axes():
    assert "spherical wrist" in solver("kr6").DECOMPOSITION
    assert "three parallel axes" in solver("ur5e").DECOMPOSITION
    assert solver("kr6").MAX_IK == solver("ur5e").MAX_IK == 8
    assert solver("youbot").MAX_IK == 4
    assert "5 of the 6 pose components" in solver("youbot").CONTROLS


# ------------------------------------------------------------------------------------------------ partial / redundant
def test_a_five_joint_arm_reports_poses_outside_what_it_controls():
    m = solver("youbot")
    rng = case_rng(15)
    q = rng.uniform(-1.0, 1.0, 5)
    T = m.fk_matrix(q)
    tilted = T.copy()
    c, s = math.cos(0.3), math.sin(0.3)
    tilted[:3, :3] = T[:3, :3] @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])  # a roll the arm cannot make
    out = m.ik(tilted)
    assert out.count == 0 and out.status == m.STATUS_UNREACHABLE
    assert "controls" in out.reason


def test_a_redundant_arm_takes_its_free_joint_per_call():
    m = solver("iiwa14")
    assert m.DESIGN_NAMES == ("a3",)
    rng = case_rng(16)
    q = rng.uniform(-2.0, 2.0, 7)
    T = m.fk_matrix(q, [q[2]])
    for v in (q[2], q[2] + 0.4):
        sol = m.ik(T, [v])
        assert all(abs(s[2] - math.remainder(v, 2 * math.pi)) < 1e-12 for s in sol)
        for s in sol:
            assert np.max(np.abs(m.fk_matrix(s, [v]) - T)) <= m.IK_VERIFY_TOL
    assert min(_gap(s, q, m.JOINT_KINDS) for s in m.ik(T, [q[2]])) < 1e-7


# ------------------------------------------------------------------------------------------------ near-special geometry
def test_a_calibrated_arm_is_solved_on_ideal_axes_and_polished_on_the_true_ones():
    m = solver("kr6_calibrated")
    assert 0.0 < m.GEOMETRY_DEVIATION <= m.GEOMETRY_TOL
    r = reference("kr6_calibrated")
    rng = case_rng(17)
    for _ in range(20):
        q = _regular_joints(m, rng)
        T = r(q)
        sol = m.ik(T)
        assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-7
        for v in sol:
            assert ref.pose_error(r(v), T) < 1e-10


def test_an_srs_arm_s_held_elbow_is_planned_as_a_self_motion_and_never_picked():
    """The iiwa14 with its elbow a4 held: the spherical shoulder turns the arm about the shoulder-wrist line and the
    spherical wrist undoes it, so every reachable pose has infinitely many solutions. It is planned as the held
    elbow (the shoulder at previous's arm angle, then the wrist: the derived stages solve it,
    tests/test_derived_robot.py), listed last among the choices and never picked without --free (its poses are only
    those at the elbow's reach)."""
    from derive.families.chain import workable_free_joints

    held = own_robot.description(_file("iiwa14", "urdf"), free="a4")
    assert held.held_elbow and [op["op"] for op in held.plan()[0].ops] == ["begin", "held_elbow", "orient"]
    mech = own_robot.description(_file("iiwa14", "urdf"))
    choices = workable_free_joints(mech.NAME, mech.title, mech.desc)
    assert choices[-1] == "a4" and {"a1", "a3", "a5", "a7"} <= set(choices)
    assert mech.desc.free != 3 and not mech.held_elbow


def test_a_tolerance_below_the_deviation_leaves_the_general_6r():
    """Below the calibrated arm's deviation no decomposition holds (the planner's refusal names the axes); the 6R
    is then solved by elimination on its true axes, with nothing idealised."""
    from derive.kinematics.planner import NoClosedForm, find_plan

    mech = own_robot.description(_file("kr6_calibrated", "urdf"), geometry_tol=1e-9)
    with pytest.raises(NoClosedForm, match="a2/a3"):
        find_plan(mech.solver_chain(mech.chain), 1e-9)
    plan, ideal = mech.plan()
    assert [op["op"] for op in plan.ops] == ["general6r"] and "general 6R" in plan.strategy
    # nothing idealised: the chain as read, up to the rounding of re-normalising its points (feet on the axes)
    np.testing.assert_allclose(ideal.axes, mech.chain.axes, rtol=0, atol=1e-15)
    np.testing.assert_allclose(ideal.points, mech.chain.points, rtol=0, atol=1e-15)


# ------------------------------------------------------------------------------------------------ singular and tangent
def test_the_wrist_singularity_gives_one_flagged_set_per_family():
    m = solver("kr6")
    q = np.array([0.3, -1.2, 0.8, 0.5, 0.0, -0.4])
    T = m.fk_matrix(q)
    sol = m.ik(T, previous=q)
    # the arm configuration of q has its wrist at the singularity: the one-parameter family once, flagged, its
    # member nearest `previous` (q itself); the other arm configurations have regular wrists (two sets each)
    k = int(np.argmin([_gap(v, q, m.JOINT_KINDS) if ok else 9.0 for v, ok in zip(sol.values, sol.valid, strict=True)]))
    assert _gap(sol.values[k], q, m.JOINT_KINDS) < 1e-7
    assert sol.flags[k] & m.FLAG_INDETERMINATE and sol.status == m.STATUS_INDETERMINATE
    same_arm = [v for v in sol if _gap(v[:3], q[:3], "RRR") < 1e-7]
    assert len(same_arm) == 1
    assert sol.count % 2 == 1
    for v in sol:
        assert np.max(np.abs(m.fk_matrix(v) - T)) <= m.IK_VERIFY_TOL


def test_the_stretched_elbow_is_one_double_root():
    m = solver("ur5e")
    q = np.array([0.4, -0.7, 0.0, 0.9, 1.1, -0.2])  # elbow straight: the elbow subproblem is tangent
    T = m.fk_matrix(q)
    sol = m.ik(T)
    assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-6  # sqrt(eps) at a double root
    assert any(sol.flags[k] & m.FLAG_DOUBLE_ROOT for k in np.flatnonzero(sol.valid))
    for v in sol:
        assert np.max(np.abs(m.fk_matrix(v) - T)) <= m.IK_VERIFY_TOL


# ------------------------------------------------------------------------------------------------ as users describe it
def test_poses_as_matrix_xyz_rpy_and_xyz_quaternion():
    m = solver("kr6")
    q = np.array([0.2, -0.9, 0.4, 0.3, 0.7, -0.1])
    T = m.fk_matrix(q)
    r = T[:3, :3]
    yaw, pitch, roll = math.atan2(r[1, 0], r[0, 0]), -math.asin(r[2, 0]), math.atan2(r[2, 1], r[2, 2])
    w = 0.5 * math.sqrt(1 + np.trace(r))
    quat = [(r[2, 1] - r[1, 2]) / (4 * w), (r[0, 2] - r[2, 0]) / (4 * w), (r[1, 0] - r[0, 1]) / (4 * w), w]
    a = np.array(list(m.ik(T)))
    for pose in ([*T[:3, 3], roll, pitch, yaw], [*T[:3, 3], *quat], T[:3], T.ravel()):
        np.testing.assert_allclose(np.array(list(m.ik(pose))), a, atol=1e-9)


def test_base_and_tool_change_at_run_time():
    m = solver("ur5e")
    base = np.eye(4)
    base[:3, :3] = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]])
    base[:3, 3] = (0.1, -0.2, 0.8)
    tool = np.eye(4)
    tool[:3, 3] = (0.0, 0.0, 0.15)
    d = m.make_design(base=base, tool=tool)
    q = np.array([0.3, -1.1, 1.2, -0.4, 0.9, 0.2])
    T = m.fk_matrix(q, d)
    np.testing.assert_allclose(T, base @ m.fk_matrix(q) @ tool, atol=1e-14)
    sol = m.ik(T, d)
    assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-7
    jac_fd = ref.finite_difference_jacobian(lambda x: m.fk_matrix(x, d), q)
    np.testing.assert_allclose(m.jacobian(q, d), jac_fd, atol=1e-6)


def test_branches_are_named_and_selectable():
    m = solver("kr6")
    assert set(m.BRANCHES) == {"shoulder", "elbow", "wrist"}
    rng = case_rng(18)
    while True:
        q = rng.uniform(-math.pi, math.pi, 6)
        sol = m.ik(m.fk_matrix(q))
        if sol.count == 8:
            break
    labels = [tuple(sorted(m.branch_of(v).items())) for v in sol]
    assert len(set(labels)) == 8  # each set is one combination of the named branches
    wide = ([-10.0] * 6, [10.0] * 6)  # every set is within these: the branch alone decides
    for want in ({"elbow": "up", "wrist": "flip"}, {"shoulder": "back", "elbow": "down"}):
        k = m.select(sol, None, *wide, branch=want)
        assert k >= 0 and all(m.branch_of(sol.values[k])[b] == lab for b, lab in want.items())
    with pytest.raises(m.InvalidInput, match="unknown branch"):
        m.select(sol, branch={"knee": "up"})


def test_limits_from_the_description_filter_the_selection():
    m = solver("kr6")
    assert np.isfinite(m.LOWER).all() and np.isfinite(m.UPPER).all()
    q = np.array([0.2, -0.9, 0.4, 0.3, 0.7, -0.1])
    sol = m.ik(m.fk_matrix(q))
    k = m.select(sol, previous=q)
    assert np.all(sol.values[k] >= m.LOWER) and np.all(sol.values[k] <= m.UPPER)


def test_bad_input_is_a_typed_error():
    m = solver("kr6")
    for pose in (np.full((4, 4), np.nan), np.zeros(5), np.diag([2.0, 1.0, 1.0, 1.0]), "pose"):
        with pytest.raises(m.InvalidInput):
            m.ik(pose)
    with pytest.raises(m.InvalidInput):
        m.fk_matrix([0.0] * 5)
    with pytest.raises(m.InvalidDesign):
        m.make_design(base=np.zeros((3, 3)))
    far = np.eye(4)
    far[:3, 3] = (10.0, 0.0, 0.0)
    out = m.ik(far)
    assert out.count == 0 and out.status == m.STATUS_UNREACHABLE and "reachable" in out.reason


# ------------------------------------------------------------------------------------------------ the command
def test_the_command_writes_importable_solvers_and_an_audit(tmp_path):
    """The command derives the robot's stages: importable, linted Python, C, CasADi and an audit naming the
    decomposition and its first stage."""
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parent.parent)}
    cmd = [sys.executable, "-m", "derive.cli", "derive", str(_file("ur5e", "urdf")), "--out", str(tmp_path),
           "--name", "my_ur"]
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
    assert done.returncode == 0, done.stderr
    assert "wrote" in done.stdout
    for rel in ("python/my_ur.py", "python/_wristkin_runtime.py", "c/my_ur.h", "c/my_ur.c", "casadi/my_ur.casadi",
                "audit/my_ur.md"):
        assert (tmp_path / rel).is_file(), rel
    lint = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--config",
                           str(Path(__file__).parent.parent / "pyproject.toml"), str(tmp_path / "python")],
                          capture_output=True, text=True, check=False)
    assert lint.returncode == 0, lint.stdout  # generated code passes ruff (the project's settings)
    report = (tmp_path / "audit" / "my_ur.md").read_text()
    assert "three parallel axes" in report
    assert "IK stage 1: angle shoulder_pan_joint" in report
    probe = ("import sys; sys.path.insert(0, sys.argv[1]); import my_ur; import numpy as np; "
             "print(my_ur.ik(my_ur.fk_matrix([0.1, -1, 1, 0.2, 0.3, 0.4])).count)")
    run = subprocess.run([sys.executable, "-S", "-c", probe, str(tmp_path / "python")], capture_output=True,
                         text=True, check=False, env={"PYTHONPATH": str(Path(np.__file__).parent.parent)})
    assert run.returncode == 0 and int(run.stdout) >= 1, run.stderr


def _skew_spec(tmp_path, kinds="RRRRRR"):
    spec = tmp_path / "skew.toml"
    spec.write_text('family = "chain"\nname = "skew"\ntitle = "six skew axes"\nconvention = "poe"\n' + "".join(
        f'[[joint]]\nname = "j{i}"\ntype = "{"revolute" if k == "R" else "prismatic"}"\naxis = [{math.cos(i)}, '
        f'{math.sin(i)}, {0.3 * i}]\npoint = [{0.1 * i}, {0.2 * i * i}, {0.05 * i}]\n' for i, k in enumerate(kinds))
        + "[home]\nposition = [0.5, 0.1, 0.2]\n")
    return spec


def _derive_command(spec, out):
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parent.parent)}
    return subprocess.run([sys.executable, "-m", "derive.cli", "derive", str(spec), "--out", str(out)],
                          capture_output=True, text=True, env=env, check=False)


def test_the_command_solves_six_skew_axes_by_elimination(tmp_path):
    """No decomposition fits six skew axes: the general 6R (tests/test_general6r*.py check its sets)."""
    done = _derive_command(_skew_spec(tmp_path), tmp_path / "o")
    assert done.returncode == 0, done.stderr
    m = own_robot.import_solver(tmp_path / "o", "skew", backend="numpy")
    assert "general 6R by elimination" in m.DECOMPOSITION and m.MAX_IK == 16


def test_the_command_refuses_a_chain_without_a_closed_form(tmp_path):
    """Skew axes with a slide among them: neither a decomposition nor the 6R elimination applies; the refusal
    names the axes."""
    done = _derive_command(_skew_spec(tmp_path, "RRRPRR"), tmp_path / "o")
    assert done.returncode == 1
    assert "no closed-form decomposition" in done.stderr and "j0/j1" in done.stderr
    assert "Traceback" not in done.stderr


def test_the_module_solves_from_the_command_line():
    m = solver("kr6")
    path = _CACHE[("kr6", "urdf", ())][1] / "python" / "kr6_urdf_solver.py"
    q = [0.2, -0.9, 0.4, 0.3, 0.7, -0.1]
    T = m.fk_matrix(q)
    r = T[:3, :3]
    rpy = [math.atan2(r[2, 1], r[2, 2]), -math.asin(r[2, 0]), math.atan2(r[1, 0], r[0, 0])]
    import json

    run = subprocess.run([sys.executable, str(path), "ik", "--pose", *map(str, [*T[:3, 3], *rpy]), "--json"],
                         capture_output=True, text=True, check=True)
    out = json.loads(run.stdout)
    assert out["status"] == "ok" and len(out["solutions"]) == m.ik(T).count
    assert min(_gap(s["values"], q, m.JOINT_KINDS) for s in out["solutions"]) < 1e-7
    assert set(out["solutions"][0]["branches"]) == set(m.BRANCHES)
    bad = subprocess.run([sys.executable, str(path), "ik", "--pose", "1", "2"], capture_output=True, text=True)
    assert bad.returncode == 2 and "error" in bad.stderr


SMALL = {
    # name: (DH rows (type, a, alpha, d, theta), expected decomposition words, max sets)
    "roll": ([("revolute", 0.0, "0", 0.05, 0.0)], "one axis at the end", 1),
    "wrist3": ([("revolute", 0.0, "-pi/2", 0.0, 0.0), ("revolute", 0.0, "pi/2", 0.0, 0.0),
                ("revolute", 0.0, "0", 0.1, 0.0)], "spherical wrist", 2),
    "scara": ([("revolute", 0.4, "0", 0.3, 0.0), ("revolute", 0.3, "pi", 0.0, 0.0),
               ("prismatic", 0.0, "0", 0.0, 0.0), ("revolute", 0.0, "0", 0.1, 0.0)], "one axis at the end", 2),
    "cylindrical": ([("revolute", 0.0, "0", 0.5, 0.0), ("prismatic", 0.0, "-pi/2", 0.2, 0.0),
                     ("prismatic", 0.0, "0", 0.3, 0.0), ("revolute", 0.0, "-pi/2", 0.0, 0.0),
                     ("revolute", 0.0, "pi/2", 0.0, 0.0), ("revolute", 0.0, "0", 0.1, 0.0)], "spherical wrist", 4),
}


def _dh_spec(name, rows) -> str:
    text = f'family = "chain"\nname = "{name}"\ntitle = "{name}"\nconvention = "standard"\n'
    for i, (kind, a, alpha, d, theta) in enumerate(rows):
        text += (f'[[joint]]\nname = "j{i + 1}"\ntype = "{kind}"\na = {a}\nalpha = "{alpha}"\nd = {d}\n'
                 f'theta = {theta}\n')
    return text


def test_a_scara_with_equal_links_folded_keeps_both_elbows(tmp_path):
    """A SCARA with a1 = a2 folded to pi -+ 1e-6 ... 1e-12: the flange lies |w| = a delta from axis 1, known to eps of
    itself, so the pose fixes both elbows and the first joint (to 1e-6 + 1e-13 / delta). Its elbow is a planar
    distance op: 1 - u^2 is read from the factors (|w|^2 - (a1 - a2)^2)((a1 + a2)^2 - |w|^2), not next to a1 a2. Was:
    24 of 40 poses missing the generating joints (the elbows merged, the first joint a family, some unreachable),
    in C and numpy alike."""
    rows = [("revolute", 0.3, "0", 0.4, 0.0), ("revolute", 0.3, "pi", 0.0, 0.0),
            ("prismatic", 0.0, "0", 0.0, 0.0), ("revolute", 0.0, "0", 0.1, 0.0)]
    spec = tmp_path / "scara_eq.toml"
    spec.write_text(_dh_spec("scara_eq", rows))
    derived_cache.derive(spec, tmp_path / "out")
    r = ref.load(spec)
    for backend in ("numpy", None):
        m = own_robot.import_solver(tmp_path / "out", "scara_eq", backend)
        rng = case_rng(20)
        for i in range(24):
            delta = (1e-6, 1e-8, 1e-10, 1e-12)[i % 4] * (1.0 if i % 8 < 4 else -1.0)
            q = np.array([rng.uniform(-3.0, 3.0), math.pi + delta, rng.uniform(-0.3, 0.3), rng.uniform(-3.0, 3.0)])
            sol = m.ik(r(q))
            gaps = [_gap(v, q, m.JOINT_KINDS) for v in sol]
            assert gaps and min(gaps) <= 1e-6 + 1e-13 / abs(delta), (backend, i, delta, sol.reason, gaps)


@pytest.mark.parametrize("name", sorted(SMALL))
def test_chains_with_fewer_joints_and_slides(name, tmp_path):
    rows, words, max_sets = SMALL[name]
    spec = tmp_path / f"{name}.toml"
    spec.write_text(_dh_spec(name, rows))
    derived_cache.derive(spec, tmp_path / "out")
    m, r = own_robot.import_solver(tmp_path / "out", name), ref.load(spec)
    assert words in m.DECOMPOSITION and m.MAX_IK == max_sets
    rng = case_rng(19)
    for k in range(12):
        q = np.array([rng.uniform(-math.pi, math.pi) if t == "R" else rng.uniform(-0.4, 0.4) for t in m.JOINT_KINDS])
        T = r(q)
        np.testing.assert_allclose(m.fk_matrix(q), T, atol=1e-12)
        sol = m.ik(T)
        assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-7
        if k < 3:
            found = ref.ik_all(r, m.N_JOINTS, T, seed=k)
            assert len(found) == sol.count
    if len(rows) < 6:  # a pose off the chain's image: unreachable, saying what the chain controls
        off = r(np.zeros(len(rows)))
        off[:3, :3] = off[:3, :3] @ np.array([[1, 0, 0], [0, 0.8, -0.6], [0, 0.6, 0.8]])
        off[:3, 3] += (0.01, 0.02, 0.03)
        out = m.ik(off)
        assert out.count == 0 and "controls" in out.reason


def test_a_wrist_at_the_base_is_solved_from_the_tool(tmp_path):
    """The KR6 read backwards (its spherical wrist at the base): the planner reverses the chain."""
    from derive.kinematics.poe import reverse

    kr6 = own_robot.description(_file("kr6", "poe")).chain
    back = reverse(kr6)
    r = back.home[:3, :3]
    rpy = [math.atan2(r[2, 1], r[2, 2]), -math.asin(r[2, 0]), math.atan2(r[1, 0], r[0, 0])]
    spec = tmp_path / "backwards.toml"
    spec.write_text(poe_spec("backwards", "KR6 reversed", back.axes, back.points, back.home[:3, 3], rpy,
                             back.joint_names))
    derived_cache.derive(spec, tmp_path / "out")
    m, ref_chain = own_robot.import_solver(tmp_path / "out", "backwards"), ref.load(spec)
    assert m.DECOMPOSITION.startswith("from the tool") and m.MAX_IK == 8
    rng = case_rng(20)
    for k in range(10):
        q = rng.uniform(-math.pi, math.pi, 6)
        T = ref_chain(q)
        sol = m.ik(T)
        assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-7
        if k < 2:
            # 200 starts: the default 20 found 6 of the 8 at Haswell seed 242070 (a multistart may miss one)
            assert len(ref.ik_all(ref_chain, 6, T, seed=k, starts=200)) == sol.count


def test_a_general_3r_arm_is_solved_by_its_polynomial(tmp_path):
    """No two of the first three axes meet or are parallel: no invariant separates them, so their joints come
    from every real root of a degree-8 polynomial (subproblem 5 in effect): the derived spatial3 stage (its twists
    off the 5-degree grid stay numbers); the sets equal the reference's."""
    spec = tmp_path / "skew3.toml"
    spec.write_text(poe_spec("skew3", "general 3R arm + wrist", **SKEW3))
    derived_cache.derive(spec, tmp_path / "out", native=False)
    m = own_robot.import_solver(tmp_path / "out", "skew3")
    assert m.MAX_IK == 8
    assert "return _spatial3_stage(_k_stage1," in (tmp_path / "out" / "python" / "skew3.py").read_text()
    r = ref.load(spec)
    rng = case_rng(22)
    for k in range(20):
        q = rng.uniform(-math.pi, math.pi, 6)
        T = r(q)
        sol = m.ik(T)
        assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) < 1e-7
        for v in sol:
            assert np.max(np.abs(m.fk_matrix(v) - T)) <= m.IK_VERIFY_TOL
        if k < 4:
            found = ref.ik_all(r, 6, T, seed=k)
            assert len(found) == sol.count
            for v in found:
                assert min(_gap(v, w, m.JOINT_KINDS) for w in sol) < 1e-6


def test_a_ur_wrist_singularity_is_never_empty():
    """q5 = 0 or pi on a UR: axes 2, 3, 4 and 6 are parallel, a one-parameter family whose free angle also moves
    the wrist point, so only an interval of it reaches the pose. Without `previous` a member is still returned
    (the search over FAMILY_ANGLES stops at the first verified one); with it, the generating configuration."""
    m = solver("ur5e")
    rng = case_rng(23)
    for i in range(60):
        q = rng.uniform(-math.pi, math.pi, 6)
        q[4] = 0.0 if i % 2 else math.pi
        T = m.fk_matrix(q)
        sol = m.ik(T)
        assert sol.count >= 1 and sol.status == m.STATUS_INDETERMINATE, (i, sol.reason)
        for v in sol:
            assert np.max(np.abs(m.fk_matrix(v) - T)) <= m.IK_VERIFY_TOL
        assert min(_gap(v, q, m.JOINT_KINDS) for v in m.ik(T, previous=q)) < 1e-7


# the URDF solver runs the C (the folder's extension), DH numpy; the offset wrist's (subproblem 6) has DH only, and
# its C is compared with its numpy near the singularity in test_derived_robot
@pytest.mark.parametrize(("robot", "fmt"), (("ur5e", "urdf"), ("ur5e", "dh"), ("ur5e_offset", "dh")))
def test_a_ur_near_its_wrist_singularity_is_never_empty(robot, fmt):
    """|q5| from 1e-7 to 1e-5: near, not at, the family. Within the double-root tolerance (|sin q5| <= 1e-6) the
    two wrist roots merge into one common vector on the group's axis, a family whose members need not reproduce a
    pose that is not singular (12 of 200 poses at |q5| = 1e-6 came back empty); the two roots are then taken
    instead, sets with every angle defined. The offset wrist's quartic merges its two nearby roots the same way
    (or resolves them only to sqrt(eps)): its roots are refined by Newton on subproblem 6's two equations, and a
    merged one that verifies nothing is split along them (9 of 200 poses at |q5| = 1e-6 had come back empty).
    Every returned set reproduces the pose through the independent reference's FK (the solver's acceptance
    IK_VERIFY_TOL, plus 1e-12 for the two FKs' rounding); the offset wrist's by its sp6 stage."""
    m, r = solver(robot, fmt), reference(robot, fmt)
    rng = case_rng(24)
    for i in range(100):
        q = rng.uniform(-math.pi, math.pi, 6)
        q[4] = (1.0 if i % 2 else -1.0) * (1e-7, 3e-7, 1e-6, 3e-6, 1e-5)[i % 5]
        T = r(q)
        sol = m.ik(T)
        assert sol.count >= 1, (i, q[4], sol.reason)
        for v in sol:
            assert np.max(np.abs(r(v) - T)) <= m.IK_VERIFY_TOL + 1e-12, (i, q[4])


# ------------------------------------------------------------------------------------------ offset wrist (subproblem 6)
OFFSET = "ur5e_offset"  # the UR5e with a5 = 3 cm (tests/robots/ur5e_offset, DH only): axes 5 and 6 apart


def _joint_tol(m, q) -> float:
    """How far from q a set may be that reproduces q's pose to IK_VERIFY_TOL (the solver's acceptance), from the
    conditioning at q: to first order |dq| <= |dT| / sigma_min(J(q)), |dT| (a twist) at most sqrt(6) times the
    largest entry error of [R | p]; a factor 10 for the second-order term (the poses are regular or the bound is
    loose anyway). The solvers are far better (rounding), but nothing less follows from the acceptance."""
    s = np.linalg.svd(m.jacobian(q), compute_uv=False)
    return 10.0 * math.sqrt(6.0) * m.IK_VERIFY_TOL / max(float(s[-1]), 1e-300)


def test_offset_wrist_is_subproblem_6_and_fk_equals_the_reference():
    m, r = solver(OFFSET, "dh"), reference(OFFSET, "dh")
    assert "offset wrist" in m.DECOMPOSITION and "subproblem 6" in m.DECOMPOSITION
    assert m.MAX_IK == 8  # a quartic in q1, two elbows each
    # the serial family's module, its first stage subproblem 6's
    assert m._STAGES[0][0].__name__ == "_solve_stage1"
    rng = case_rng(24)
    for _ in range(20):
        q = rng.uniform(-math.pi, math.pi, 6)
        # two products of the same rigid motions in a different order: rounding only
        np.testing.assert_allclose(m.fk_matrix(q), r(q), atol=1e-12 * _size(m))
        np.testing.assert_allclose(m.jacobian(q), r.jacobian(q), atol=1e-12 * _size(m))


def test_offset_wrist_ik_contains_the_generating_joints_and_every_set_reproduces_the_pose():
    m, r = solver(OFFSET, "dh"), reference(OFFSET, "dh")
    rng = case_rng(25)
    counts = {}
    for _ in range(60):
        q = rng.uniform(-math.pi, math.pi, 6)
        T = r(q)  # the reference's FK: the pose does not come from the solver
        sol = m.ik(T)
        assert sol.status == m.STATUS_OK, sol.reason
        assert min(_gap(v, q, m.JOINT_KINDS) for v in sol) <= _joint_tol(m, q)
        for v in sol:
            assert np.max(np.abs(r(v) - T)) <= m.IK_VERIFY_TOL + 1e-12 * _size(m)  # + the FK's rounding
        counts[sol.count] = counts.get(sol.count, 0) + 1
    assert counts.get(8, 0) >= 20, counts  # most random poses have all eight sets


def test_offset_wrist_sets_equal_the_multistart_reference():
    """None missed, none spurious: on regular poses (sigma_min / sigma_max > 1e-3) the sets equal every solution
    the numeric reference finds, to 1e-6 rad (the reference's dedup; it converges to 1e-10 in the pose, so its
    joints are good to ~1e-10 / sigma_min <= 1e-7 here)."""
    m, r = solver(OFFSET, "dh"), reference(OFFSET, "dh")
    rng = case_rng(26)
    for k in range(4):
        q = _regular_joints(m, rng)
        T = r(q)
        found = ref.ik_all(r, 6, T, seed=k)
        ours = list(m.ik(T))
        assert len(ours) == len(found), (len(ours), len(found))
        for v in found:
            assert min(_gap(v, w, m.JOINT_KINDS) for w in ours) < 1e-6


def test_offset_wrist_singularity_gives_the_generating_family():
    """q5 = 0 or pi exactly: axis 6 parallel to axes 2, 3, 4, a one-parameter family (q6 against the group's
    sum) whose free angle also moves the wrist point. Without `previous` the family is still returned (flagged
    singular and indeterminate), with q1 and q5 of the generating configuration; with `previous` = the generating
    configuration, that configuration; with `previous` moved along the family, the member at its q6."""
    m, r = solver(OFFSET, "dh"), reference(OFFSET, "dh")
    rng = case_rng(27)
    for i in range(60):
        q = rng.uniform(-math.pi, math.pi, 6)
        # the elbow at least 0.3 rad from straight / folded: the 2R reach then has a margin of ~9 mm, so a 1e-3 rad
        # step of q6 (which moves the wrist point by < 1 mm) stays inside the family's interval
        q[2] = math.copysign(rng.uniform(0.3, math.pi - 0.3), q[2])
        q[4] = 0.0 if i % 2 else math.pi
        T = r(q)
        sol = m.ik(T)
        assert sol.count >= 1 and sol.status == m.STATUS_INDETERMINATE, (i, sol.reason)
        family = [k for k in np.flatnonzero(sol.valid) if sol.flags[k] & m.FLAG_INDETERMINATE]
        assert family and all(sol.flags[k] & m.FLAG_SINGULAR_INVERSE for k in family)
        for v in sol:
            assert np.max(np.abs(r(v) - T)) <= m.IK_VERIFY_TOL + 1e-12 * _size(m)
        # q1 from subproblem 4 and q5 where axis 6 lines up with n: rounding, or sqrt(eps) ~ 1e-8 at a tangent
        assert min(_gap(sol.values[k][[0, 4]], q[[0, 4]], "RR") for k in family) < 1e-7
        # with `previous`: q6 taken from it, the rest from closed forms at that angle (the planar pair conditioned
        # by the elbow's margin above), so again rounding, not the singular Jacobian's conditioning
        # (a set index's row: the module keeps each set at its branch word)
        near = m.ik(T, previous=q)
        k = min(np.flatnonzero(near.valid), key=lambda i: _gap(near.values[i], q, m.JOINT_KINDS))
        assert _gap(near.values[k], q, m.JOINT_KINDS) < 1e-7 and near.flags[k] & m.FLAG_INDETERMINATE
        prev = q.copy()
        prev[5] += 1e-3
        moved = m.ik(T, previous=prev)
        k = min(np.flatnonzero(moved.valid), key=lambda i: _gap(moved.values[i], prev, m.JOINT_KINDS))
        assert abs(math.remainder(moved.values[k][5] - prev[5], 2 * math.pi)) < 1e-12
        assert _gap(moved.values[k], q, m.JOINT_KINDS) < 2e-2  # the same member of the family, 1e-3 along it
        assert np.max(np.abs(r(moved.values[k]) - T)) <= m.IK_VERIFY_TOL + 1e-12 * _size(m)


def test_near_the_shoulder_singularity_the_irb120_ik_keeps_the_generating_set():
    """Found by a near-singular sweep: joints 1e-8 rad from where sigma_min of J vanishes. Both backends must return a
    set within the conditioning (1e-6 rad) of the generating joints. Was a known defect (the C path reported these
    poses unreachable): subproblem 2 read g^2 as a difference of squared norms, which lost the digits of g near the
    family; read on the smaller circle it keeps them."""
    m = solver("irb120")
    py = own_robot.import_solver(_CACHE[("irb120", "urdf", ())][1], "irb120_urdf_solver", backend="numpy")
    for q in ([1.1914814065032804, 0.7102794555645185, -2.657260800597763, -0.07257564666280425, -1.8043360707549974,
               -2.307837226526689],
              [2.921478497285915, 3.111420688612141, -1.2865811162338414, 2.1802550639811065, -2.3595853210018447,
               1.467692152915598]):
        q = np.array(q)
        T = py.fk_matrix(q)
        for mod in (m, py):
            s = mod.ik(T)
            assert s.count >= 1 and min(_gap(v, q, mod.JOINT_KINDS) for v in s.values[s.valid]) < 1e-6


# ------------------------------------------------------------------------------------------------ Franka Panda
@pytest.mark.parametrize("free", ("joint4", "joint7"))  # the free joints the planner accepts on the Panda
def test_panda_sets_meet_their_reported_residual_on_the_modules_own_fk(free, tmp_path):
    """Franka Panda (modified DH, tests/robots/panda) with a free joint, joint2 = +-1e-7 (axes 1 and 3 nearly
    line up): every valid set's residual is the module's own fk_matrix residual and at most IK_VERIFY_TOL, in C
    (the folder's extension) and on numpy. Was: fk_matrix missed the pose by up to 1.6e-9 while the set reported
    9.8e-10 (measured on the held, reversed solver chain, not on base . chain . tool). The derived stages check a set
    on the FK from its joints' cos and sin as the stages gave them, fk_matrix takes them from the values: the two
    differ by the FK's own rounding (fk_rounding: 16 eps of the pose's size), which the bound allows."""
    derived_cache.derive(_file("panda", "dh"), tmp_path, name="panda_t", free=free, native=True)
    m = own_robot.import_solver(tmp_path, "panda_t")
    assert m.DESIGN_NAMES == (free,)
    rng = case_rng(31)
    checked = 0
    for i in range(150):
        q = rng.uniform(-math.pi, math.pi, 7)
        q[1] = 1e-7 if i % 2 else -1e-7
        d = m.make_design([q[m._FREE]])
        T = m.fk_matrix(q, d)
        for s in (m.ik(T, d), m._ik_numpy(T, d, None)):
            assert s.count >= 1, (i, s.reason)
            for k in np.flatnonzero(s.valid):
                e = float(np.max(np.abs(m.fk_matrix(s.values[k], d) - T)))
                rounding = m._runtime.fk_rounding(float(np.max(np.abs(T[:3, 3]))))
                assert e <= m.IK_VERIFY_TOL and e <= s.aux[k, 0] * (1 + 1e-12) + rounding, (i, k, e, s.aux[k, 0])
                checked += 1
    assert checked >= 300


def test_panda_with_joint2_held_is_solved_away_from_its_self_motion(tmp_path):
    """Franka Panda with joint2 held: at joint2 = 0 or pi joints 1 and 3 line up (a self-motion: every pose has
    infinitely many solutions). Was: planned at the held value 0 only, so refused for every value ("no closed-form
    decomposition", joint1/joint3 collinear). Now planned at the sampled values away from those (the general 6R),
    the generating joints found at other values, and ik at joint2 within GEOMETRY_TOL of 0 or pi refused with
    InvalidDesign in C (WK_ERR_DESIGN, worded by the numpy path) and on numpy (it said "unreachable")."""
    derived_cache.derive(_file("panda", "dh"), tmp_path, name="panda_j2", free="joint2")
    m = own_robot.import_solver(tmp_path, "panda_j2")
    py = own_robot.import_solver(tmp_path, "panda_j2", backend="numpy")
    if os.environ.get("WRISTKIN_BACKEND") != "numpy":  # make test-portable runs the numpy fallback
        assert m.BACKEND == "c"
    assert tuple(v for v, _ in m._DEGENERATE_HELD) == (0.0, math.pi)
    rng = case_rng(35)
    for i in range(12):
        q = rng.uniform(-math.pi, math.pi, 7)
        if i < 4:
            q[1] = (0.0, math.pi, 5e-7, -math.pi + 5e-7)[i]
            for mod in (m, py):
                with pytest.raises(mod.InvalidDesign, match="self-motion"):
                    mod.ik(mod.fk_matrix(q, [q[1]]), [q[1]])
            continue
        T = m.fk_matrix(q, [q[1]])
        for mod in (m, py):
            s = mod.ik(T, [q[1]])
            assert min(_gap(v, q, mod.JOINT_KINDS) for v in s.values[s.valid]) < 1e-6, (i, s.reason)



def test_panda_with_joint6_held_is_solved_where_its_joints_5_and_7_meet(tmp_path):
    """Franka Panda with joint6 held: joints 1-3 meet (a spherical shoulder) and joints 5 and 7 meet wherever joint6
    is held away from 0 and pi. Was refused: planned at the held value 0 only, where 5 and 7 are parallel, no
    decomposition fit, and the general 6R's reading (a spherical shoulder makes it degenerate) missed solutions,
    which its audit caught (a traceback from `wristkin derive`). Now planned at the sampled held values: the tool
    side's meeting point placed by joints 7, 5, 4 and the shoulder's orientation; at joint6 within GEOMETRY_TOL of
    0 or pi (the meeting point at infinity) ik refuses the held value with InvalidDesign, naming the axes. None of the
    multistart reference's sets missing, none spurious (each distinct and reaching the pose on the description's own
    products), C and numpy, also 1e-4 from the refused values (the meeting point 880 m away)."""
    derived_cache.derive(_file("panda", "dh"), tmp_path, name="panda_j6", free="joint6")
    m = own_robot.import_solver(tmp_path, "panda_j6")
    py = own_robot.import_solver(tmp_path, "panda_j6", backend="numpy")
    if os.environ.get("WRISTKIN_BACKEND") != "numpy":  # make test-portable runs the numpy fallback
        assert m.BACKEND == "c"
    assert "spherical wrist" in m.DECOMPOSITION and "general 6R" not in m.DECOMPOSITION
    assert tuple(v for v, _ in m._DEGENERATE_HELD) == (0.0, math.pi)
    r = reference("panda", "dh")
    rng = case_rng(36)
    held = (0.0, math.pi, 4e-7, 1e-4, math.pi - 1e-4, 0.7, 2.0, -0.017)
    for i, h in enumerate(held):
        q = rng.uniform(-math.pi, math.pi, 7)
        q[5] = h
        T = m.fk_matrix(q, [h])
        if i < 3:
            for mod in (m, py):
                with pytest.raises(mod.InvalidDesign, match="joint7 and joint5 turn parallel"):
                    mod.ik(T, [h])
            continue
        found = ref.ik_all(r, 7, T, fixed={5: h}, seed=i)
        for mod in (m, py):
            s = mod.ik(T, [h])
            sets = s.values[s.valid]
            assert min(_gap(v, q, mod.JOINT_KINDS) for v in sets) < 1e-6, (h, s.reason)
            for v in found:  # none missing (the multistart may miss some itself: seed 11 under Haswell found 6 of 8)
                assert min(_gap(v, w, mod.JOINT_KINDS) for w in sets) < 1e-6, h
            for k, v in enumerate(sets):  # none spurious: each reaches the pose on the description's own products
                assert np.max(np.abs(r(v) - T)) <= mod.IK_VERIFY_TOL
                assert all(_gap(v, w, mod.JOINT_KINDS) > 1e-6 for w in sets[:k])

# ------------------------------------------------------------------------------------------------ near-singular wrists
def _backends(robot, fmt):
    """(C or numpy module of the format, its numpy path as a function of (T, previous))."""
    m = solver(robot, fmt)
    return m, (lambda T, prev=None: m.ik(T, None, prev)), (lambda T, prev=None: m._ik_numpy(T, m._design(None), prev))


@pytest.mark.parametrize("fmt", FORMATS)
def test_previous_only_picks_among_the_sets_of_a_near_singular_wrist(fmt):
    """UR5e at q5 = 1e-7 with the elbow stretched (q3 = 0): `previous` must not change the sets or the status. Was:
    ik(T) status indeterminate with 4 sets (a family representative at angle 0, the elbow split 0.03 rad off), and
    ik(T, previous=q) status ok with 2 or 3 sets: |sin q5| below 1.4e-6 was merged into a family whose free angle
    moved the wrist point. Now |sin q5| is resolved (two regular sets where they reach) and the elbow stage reads
    its u with the wrist's noise (STAGE_NOISE): both calls give the same sets, the generating one among them."""
    q = [2.2894391843723243, -1.3904920366683693, 0.0, -2.781826279995679, 1e-07, -1.915369214935412]
    m, *paths = _backends("ur5e", fmt)
    T = m.fk_matrix(q)
    for ik in paths:
        a, b = ik(T), ik(T, q)
        assert a.status == b.status == m.STATUS_OK, (a.reason, b.reason)
        assert a.count == b.count >= 3
        np.testing.assert_array_equal(a.values[a.valid], b.values[b.valid])
        np.testing.assert_array_equal(a.flags, b.flags)
        assert min(_gap(v, q, m.JOINT_KINDS) for v in a) < 1e-6
        assert np.max(a.aux[a.valid]) <= m.IK_VERIFY_TOL


@pytest.mark.parametrize("fmt", FORMATS)
def test_a_folded_elbow_behind_a_near_singular_wrist_is_one_root_in_c_and_numpy(fmt):
    """UR5e at q3 = pi (folded elbow, a double root) and q5 = 1e-5: the elbow's u carries the wrist's noise (~eps /
    |sin q5|, 2e-12 here), so a band of DOUBLE_ROOT_TOL split it or not by rounding: numpy returned 8 sets and C 7
    (the URDF solver 8 on both, the DH and POE ones 7). Now 7 everywhere, the folded elbow once (flagged), on the
    pose to rounding and within the conditioning of the generating joints: the double root resolves the elbow's
    noise eps / |sin q5| to its square root (4.7e-6 rad here; the derived stages' set is 8.4e-6 off with the pose
    reproduced to 1e-16), so 10 sqrt(eps / |sin q5|)."""
    q = [-2.247701436774141, 1.6129556685313249, math.pi, -2.6956545549834385, 1e-05, 2.861457331635221]
    m, *paths = _backends("ur5e", fmt)
    T = m.fk_matrix(q)
    for ik in paths:
        s = ik(T)
        assert s.count == 7 and s.status == m.STATUS_OK, (s.count, s.reason)
        folded = [k for k in np.flatnonzero(s.valid) if s.flags[k] & m.FLAG_DOUBLE_ROOT]
        assert len(folded) == 1
        assert _gap(s.values[folded[0]], q, m.JOINT_KINDS) < 10 * math.sqrt(EPS / 1e-5)
        assert np.max(np.abs(m.fk_matrix(s.values[folded[0]]) - T)) <= 1e-12  # DOUBLE_ROOT_POLISH_TOL: polished
