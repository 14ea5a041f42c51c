"""The arm angle as a 7R S-R-S arm's redundancy parameter (`wristkin derive --redundancy arm-angle`, issue 23):
the iiwa14's URDF derived as a user would, its solvers (C extension and numpy) checked against an independent
reference: the URDF's own transforms (tests/reference/chain.py) give each joint's world axis and point, the arm
angle is read from them geometrically, and a multistart Levenberg-Marquardt on the pose and the arm angle (seven
equations in seven joints) counts the solutions."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest
from reference import chain as ref
from scipy.optimize import least_squares
from seeding import case_rng

from derive import own_robot
from derive.kinematics.planner import NoClosedForm
from derive.model import NoDecomposition

ROBOTS = Path(__file__).parent / "robots"
IIWA = ROBOTS / "iiwa14" / "iiwa14.urdf"
_CACHE: dict = {}


def solver():
    """(C-backed module, numpy module, folder) of the iiwa14 at its arm angle (its derived arm_angle stage)."""
    if "iiwa" not in _CACHE:
        out = Path(tempfile.mkdtemp(prefix="wk_arm_angle_"))
        own_robot.derive(IIWA, out, name="iiwa_psi", redundancy="arm-angle", progress=lambda _: None)
        _CACHE["iiwa"] = (own_robot.import_solver(out, "iiwa_psi"),
                          own_robot.import_solver(out, "iiwa_psi", backend="numpy"), out)
    return _CACHE["iiwa"]


def _common_point(points, axes):
    """The least-squares common point of lines (point, unit axis)."""
    m = sum(np.eye(3) - np.outer(a, a) for a in axes)
    v = sum((np.eye(3) - np.outer(a, a)) @ p for p, a in zip(points, axes, strict=True))
    return np.linalg.solve(m, v)


def reference_angle(chain, q) -> float:
    """The arm angle from the reference's world axes and points at q: shoulder and wrist centres where their axes
    meet, the elbow point on its axis nearest the shoulder, the angle about the shoulder-wrist line from the first
    axis's part normal to it."""
    _, axes, points = chain.axes_points(q)
    s = _common_point(points[:3], axes[:3])
    w = _common_point(points[4:], axes[4:])
    e = points[3] + np.dot(axes[3], s - points[3]) * axes[3]
    u = (w - s) / np.linalg.norm(w - s)
    n1 = axes[0] - np.dot(axes[0], u) * u
    n1 /= np.linalg.norm(n1)
    side = (e - s) - np.dot(e - s, u) * u
    return math.atan2(float(np.dot(side, np.cross(u, n1))), float(np.dot(side, n1)))


def _gap(a, b) -> float:
    return float(np.max(np.abs(ref.wrap_angle(np.asarray(a) - np.asarray(b)))))


def multistart(chain, T, psi, seed, starts=60):
    """Every distinct solution of FK(q) = T with arm angle psi that LM finds from `starts` random starts."""
    rng = np.random.default_rng(seed)

    def residual(q):
        t = chain(q)
        return np.r_[t[:3, 3] - T[:3, 3], ref.log_rot(t[:3, :3] @ T[:3, :3].T),
                     math.remainder(reference_angle(chain, q) - psi, 2 * math.pi)]
    found = []
    for _ in range(starts):
        r = least_squares(residual, rng.uniform(-math.pi, math.pi, 7), method="lm", xtol=1e-15, ftol=1e-15,
                          gtol=1e-15, max_nfev=400)
        if np.max(np.abs(residual(r.x))) < 1e-10:
            q = ref.wrap_angle(r.x)
            if all(_gap(q, f) > 1e-6 for f in found):
                found.append(q)
    return found


def test_an_srs_arm_is_solved_at_its_arm_angle():
    """Random poses of the iiwa14 at the arm angle of the joints that made them: the generating joints among the
    sets, every set reaching the pose on the URDF's own transforms at that arm angle (read geometrically), and the
    sets equal to the multistart reference's (none missing, none spurious), in C and on numpy (one test: the
    reference's solutions, ~10 s of LM, serve both)."""
    chain = ref.load(IIWA)
    mods = [solver()[:2]]
    for m, _ in mods:
        if os.environ.get("WRISTKIN_BACKEND") != "numpy":  # make test-portable runs the numpy fallback
            assert m.BACKEND == "c"
        assert m.DESIGN_NAMES == ("arm_angle",) and m.MAX_IK == 8 and "arm angle" in m.DECOMPOSITION
    rng = case_rng(2300)
    for k in range(6):
        q = rng.uniform(-math.pi, math.pi, 7)
        T = chain(q)
        psi = reference_angle(chain, q)
        found = multistart(chain, T, psi, seed=k) if k < 2 else None
        for mod in (m for pair in mods for m in pair):
            assert abs(math.remainder(mod.arm_angle(q) - psi, 2 * math.pi)) < 1e-12
            s = mod.ik(T, [psi])
            assert s.status == mod.STATUS_OK, s.reason
            sets = s.values[s.valid]
            assert min(_gap(v, q) for v in sets) < 1e-9
            for v in sets:
                assert np.max(np.abs(chain(v) - T)) < 1e-9
                assert abs(math.remainder(reference_angle(chain, v) - psi, 2 * math.pi)) < 1e-9
            assert len(sets) == 8 and all(_gap(v, w) > 1e-6 for i, v in enumerate(sets) for w in sets[:i])
            if found is not None:  # none missing (none spurious: each set checked on the reference above)
                for f in found:
                    assert min(_gap(f, v) for v in sets) < 1e-6


def test_any_arm_angle_gives_eight_sets_with_the_elbow_there():
    """One pose, the arm angle swept over the circle: every set reaches the pose at that arm angle, 8 of them."""
    m, py, _ = solver()
    chain = ref.load(IIWA)
    q = case_rng(2301).uniform(-2.0, 2.0, 7)
    T = chain(q)
    for psi in np.linspace(-math.pi, math.pi, 13):
        for mod in (m, py):
            s = mod.ik(T, [psi])
            assert s.count == 8, (psi, s.reason)
            for v in s.values[s.valid]:
                assert np.max(np.abs(chain(v) - T)) < 1e-9
                assert abs(math.remainder(reference_angle(chain, v) - psi, 2 * math.pi)) < 1e-9


def test_the_arm_angle_singularities_are_flagged():
    """The wrist centre on the first axis (the reference plane undefined): valid sets, status indeterminate. The arm
    stretched (the elbow on the shoulder-wrist line: every arm angle is that configuration): the sets flagged
    singular."""
    m, py, _ = solver()
    chain = ref.load(IIWA)
    for mod in (m, py):
        q = np.array([0.3, 0.2, 0.4, 1.2, 0.0, -1.2, 0.5])  # a regular configuration next to them
        q_on = np.array([0.3, 0.0, 0.0, 0.0, 0.0, 0.7, 0.5])  # straight up: the wrist centre on the first axis
        s = mod.ik(chain(q_on), [0.4])
        assert s.count >= 1 and s.status == mod.STATUS_INDETERMINATE, s.reason
        for v in s.values[s.valid]:
            assert np.max(np.abs(chain(v) - chain(q_on))) < 1e-9
        stretched = np.array([0.3, 0.9, 0.2, 0.0, 0.4, 0.7, 0.5])
        s = mod.ik(chain(stretched), [mod.arm_angle(stretched)])
        assert s.count >= 1 and all(f & mod.FLAG_SINGULAR_INVERSE for f in s.flags[s.valid]), s.reason
        assert min(_gap(v, stretched) for v in s.values[s.valid]) < 1e-6
        s = mod.ik(chain(q), [mod.arm_angle(q)])
        assert min(_gap(v, q) for v in s.values[s.valid]) < 1e-9


def test_the_c_verb_reads_the_arm_angle_as_python_does(tmp_path):
    """wk_NAME_arm_angle (the C header's verb) equals the module's arm_angle and the reference's."""
    m, _, out = solver()
    chain = ref.load(IIWA)
    rng = case_rng(2302)
    qs = rng.uniform(-math.pi, math.pi, (20, 7))
    src = tmp_path / "main.c"
    src.write_text('#include <stdio.h>\n#include "iiwa_psi.h"\nint main(void) {\n  double q[7], psi;\n'
                   '  while (scanf("%lf %lf %lf %lf %lf %lf %lf", q, q + 1, q + 2, q + 3, q + 4, q + 5, q + 6)'
                   ' == 7) {\n'
                   '    if (wk_iiwa_psi_arm_angle(q, NULL, &psi) != 0) return 1;\n    printf("%.17g\\n", psi);\n  }\n'
                   '  return wk_iiwa_psi_arm_angle(NULL, NULL, &psi) == 0;\n}\n')
    exe = tmp_path / "psi"
    c_dir = out / "c"
    r = subprocess.run(["gcc", "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-o", str(exe), str(src),
                        *map(str, sorted(c_dir.glob("*.c"))), f"-I{c_dir}", "-lm"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([str(exe)], input="\n".join(" ".join(repr(float(v)) for v in q) for q in qs),
                       capture_output=True, text=True)
    assert r.returncode == 0
    for q, line in zip(qs, r.stdout.split(), strict=True):
        assert abs(math.remainder(float(line) - reference_angle(chain, q), 2 * math.pi)) < 1e-12
        assert abs(math.remainder(float(line) - m.arm_angle(q), 2 * math.pi)) < 1e-12


def test_arms_that_are_no_s_r_s_are_refused_with_the_reason(tmp_path):
    """The Panda (its wrist axes meet in no point) and a 6-joint arm are refused, naming what is missing; --free
    with it too."""
    with pytest.raises((NoClosedForm, NoDecomposition), match="joint5, joint6, joint7 meet in no point"):
        own_robot.load(ROBOTS / "panda" / "panda_dh.toml", redundancy="arm-angle")
    from derive.spec import SpecError

    with pytest.raises(SpecError, match="7-joint revolute arm"):
        own_robot.load(ROBOTS / "ur5e" / "ur5e.urdf", base="base_link", tip="tool0", redundancy="arm-angle")
    with pytest.raises(SpecError, match="not both"):
        own_robot.load(IIWA, free="a3", redundancy="arm-angle")


def test_the_module_command_takes_the_arm_angle(tmp_path):
    m, _, out = solver()
    chain = ref.load(IIWA)
    q = case_rng(2303).uniform(-2.0, 2.0, 7)
    psi = m.arm_angle(q)
    T = chain(q)
    r = subprocess.run([sys.executable, str(out / "python" / "iiwa_psi.py"), "ik", "--pose",
                        *map(repr, T[:3].ravel().tolist()), "--arm-angle", repr(psi), "--json"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    import json

    sets = [s["values"] for s in json.loads(r.stdout)["solutions"]]
    assert len(sets) == 8 and min(_gap(v, q) for v in sets) < 1e-9


def test_the_arm_angle_solver_is_clean_under_asan_ubsan():
    """The sanitizer driver of a one-parameter own-robot solver (tests/c/own_robot_sanitize.c: random, special and
    hostile inputs, every returned set reproducing the pose) on the arm-angle solver, at arm angle 0.4."""
    from cbuild import SANITIZE_FLAGS, compile_executable, sanitizer_available

    if not sanitizer_available():
        pytest.skip("compiler has no ASan/UBSan runtime")
    m, _, out = solver()
    cdir = out / "c"
    flags = [*SANITIZE_FLAGS, "-DMECH=iiwa_psi", '-DMECH_H="iiwa_psi.h"', f"-DN={m.N_JOINTS}", f"-DMAX_IK={m.MAX_IK}"]
    driver = Path(__file__).parent / "c" / "own_robot_sanitize.c"
    exe = compile_executable([driver, cdir / "iiwa_psi.c", cdir / "wristkin_runtime.c"], [cdir],
                             "chain_iiwa_psi_sanitize", extra_flags=flags)
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300,
                         env={"ASAN_OPTIONS": "detect_leaks=1:abort_on_error=1",
                              "UBSAN_OPTIONS": "halt_on_error=1:print_stacktrace=1"})
    assert run.returncode == 0, (run.returncode, run.stderr[-4000:])
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr


def test_near_its_singularities_the_generating_joints_are_returned():
    """The elbow nearly stretched (q4 = +-delta: the distance reads it only to sqrt(eps), and the merged root stood
    for one side of the line, the shoulder and wrist a half turn off the other side's joints: 5 of 10 poses missed
    at delta <= 1e-8), the wrist (q6) and the shoulder (q2 lines up a1 and a3) near their families: the generating
    joints within the conditioning allowance 1e-6 + 1e-13 / delta (a pose rounded to eps moves the joints along
    the near-null direction by ~eps / sigma_min), down to 1e-10 (at 1e-12 the families' bands stand in, as for
    every robot: README, Known defects), in C and on numpy."""
    m, py, _ = solver()
    chain = ref.load(IIWA)
    rng = case_rng(2304)
    for joint in (3, 5, 1):
        for delta in (1e-10, 1e-8, 1e-6, 1e-4):
            for k in range(4):
                q = rng.uniform(-math.pi, math.pi, 7)
                q[joint] = delta * (1 if k % 2 else -1)
                T = chain(q)
                psi = reference_angle(chain, q)
                for mod in (m, py):
                    s = mod.ik(T, [psi])
                    assert min(_gap(v, q) for v in s.values[s.valid]) <= 1e-6 + 1e-13 / delta, (joint, delta, k)


def test_the_sets_are_named_by_their_branches():
    """BRANCHES names the elbow's and the shoulder's choice (their joints' signs) and the wrist's; the 8 sets of a
    regular pose carry the 8 combinations, and select(branch=...) picks the one asked for."""
    m, _, _ = solver()
    assert m.BRANCHES == {"elbow": ["positive", "negative"], "shoulder": ["positive", "negative"],
                          "wrist": ["noflip", "flip"]}
    q = case_rng(2305).uniform(-2.0, 2.0, 7)
    s = m.ik(m.fk_matrix(q), [m.arm_angle(q)])
    names = {tuple(sorted(m.branch_of(v).items())) for v in s.values[s.valid]}
    assert len(names) == 8
    wide = (np.full(7, -10.0), np.full(7, 10.0))  # no joint limits: every set may be picked
    for v in s.values[s.valid]:
        want = m.branch_of(v)
        k = m.select(s, lower=wide[0], upper=wide[1], branch=want)
        assert np.array_equal(s.values[k], v)
        assert (v[3] >= 0) == (want["elbow"] == "positive") and (v[1] >= 0) == (want["shoulder"] == "positive")


def test_description_files_as_shipped(tmp_path):
    """pybullet's iiwa (kuka_iiwa/model.urdf as shipped: its axes 5e-13 off an exact S-R-S arm, from rounded
    angles) is solved at its arm angle on its ideal table (the end frame's difference bounded in the audit); the
    ROS-Industrial kuka_lbr_iiwa xacro, whose joint a2 and a3 stand 0.44 mm off axis a1, is refused naming the
    shoulder (the arm angle would be read 1e-3 rad off: hold a joint instead)."""
    import pybullet_data
    import rtbdata

    urdf = Path(pybullet_data.getDataPath()) / "kuka_iiwa" / "model.urdf"
    own_robot.derive(urdf, tmp_path, name="pb_iiwa", redundancy="arm-angle", progress=lambda _: None)
    m = own_robot.import_solver(tmp_path, "pb_iiwa")
    py = own_robot.import_solver(tmp_path, "pb_iiwa", backend="numpy")
    # the stages take 5e-13 as the numbers' rounding (the ideal table, the end frame's difference bounded in the
    # audit's description step): not a calibrated robot
    assert not m.CALIBRATED
    rng = case_rng(2306)
    for _ in range(10):
        q = rng.uniform(-math.pi, math.pi, 7)
        T = m.fk_matrix(q)
        for mod in (m, py):
            s = mod.ik(T, [mod.arm_angle(q)])
            assert s.count == 8 and min(_gap(v, q) for v in s.values[s.valid]) < 1e-9
    kuka = Path(rtbdata.__file__).parent / "xacro" / "kuka_description" / "kuka_lbr_iiwa"
    with pytest.raises((NoClosedForm, NoDecomposition), match="joint_a1, joint_a2, joint_a3 meet in no point"):
        own_robot.load(kuka / "urdf" / "lbr_iiwa_14_r820.xacro", tip="tool0", redundancy="arm-angle",
                       packages={"kuka_lbr_iiwa_support": str(kuka)})


def test_the_elbow_held_of_a_description_file_as_shipped(tmp_path):
    """pybullet's iiwa as shipped (axes 5e-13 off an exact S-R-S arm) with its elbow lbr_iiwa_joint_4 held (a
    self-motion, kinematics/planner.held_elbow_plan): its FK's poses are within the held elbow's reach band (1e-9 of
    its size) and solved, previous's generating joints among the sets, C equal to numpy; the arm angle's module
    verb reads the member's angle (tests/test_derived_robot.py tests the iiwa14 fixture at length)."""
    import pybullet_data

    urdf = Path(pybullet_data.getDataPath()) / "kuka_iiwa" / "model.urdf"
    own_robot.derive(urdf, tmp_path, name="pb_held", free="lbr_iiwa_joint_4", progress=lambda _: None)
    m = own_robot.import_solver(tmp_path, "pb_held")
    py = own_robot.import_solver(tmp_path, "pb_held", backend="numpy")
    rng = case_rng(2307)
    for _ in range(10):
        q = rng.uniform(-math.pi, math.pi, 7)
        T = m.fk_matrix(q, [q[3]])
        for mod in (m, py):
            s = mod.ik(T, [q[3]], previous=q)
            assert s.status == mod.STATUS_INDETERMINATE and min(_gap(v, q) for v in s.values[s.valid]) < 1e-9
            assert abs(math.remainder(mod.arm_angle(s.values[s.valid][0], [q[3]]) - mod.arm_angle(q, [q[3]]),
                                      2 * math.pi)) < 1e-9
