"""The chain family's C solver (templates/c/chain.h.jinja, chain.c.jinja) against its Python solver
(templates/python/chain.py.jinja), both rendered from the same derivation of two test arms: a PUMA-type 6R
(spherical wrist: position of the wrist centre, then the orientation) and a UR5e-type 6R (three parallel axes).

The C interprets the same plan as the Python module, so the two must agree on everything: the same solutions in
the same order (to 1e-9 rad, rounding and the least-squares polish aside), the same flags and status codes, the
same residuals; FK, its flag and manipulability, and the Jacobian to 1e-12. The C compiles with the strict flag
set (tests/cbuild.py) and runs clean under ASan/UBSan on random, singular and hostile inputs.
"""

from __future__ import annotations

import ctypes
import math
import subprocess
from pathlib import Path

import numpy as np
import pytest
from cbuild import SANITIZE_FLAGS, compile_executable, compile_shared, compiler, load
from chain_specs import SKEW3, poe_spec
from seeding import case_rng

from derive import own_robot, pipeline, runtime_files
from derive.catalogue import load as load_spec
from derive.render import header_lines

SPECS = {
    "puma_t": """family = "chain"
name = "puma_t"
title = "PUMA-type test arm"
convention = "standard"
[[joint]]
name = "q1"
alpha = "pi/2"
d = 0.6718
[[joint]]
name = "q2"
a = 0.4318
[[joint]]
name = "q3"
a = 0.0203
alpha = "-pi/2"
d = 0.15005
[[joint]]
name = "q4"
alpha = "pi/2"
d = 0.4318
[[joint]]
name = "q5"
alpha = "-pi/2"
[[joint]]
name = "q6"
d = 0.05
""",
    "ur_t": """family = "chain"
name = "ur_t"
title = "UR5e-type test arm"
convention = "standard"
[[joint]]
name = "q1"
alpha = "pi/2"
d = 0.1625
[[joint]]
name = "q2"
a = -0.425
[[joint]]
name = "q3"
a = -0.3922
[[joint]]
name = "q4"
alpha = "pi/2"
d = 0.1333
[[joint]]
name = "q5"
alpha = "-pi/2"
d = 0.0997
[[joint]]
name = "q6"
d = 0.0996
""",
    # a general 3R arm (no two of its first axes meet or are parallel: the polynomial op) + a ZYZ wrist
    "skew3": poe_spec("skew3", "general 3R arm + spherical wrist", **SKEW3),
}
# a UR5e with its last two axes apart (a5 = 3 cm, in q5's row): joints 1 and 5 from subproblem 6
SPECS["ur_off"] = (SPECS["ur_t"].replace('name = "ur_t"', 'name = "ur_off"')
                   .replace('title = "UR5e-type test arm"', 'title = "UR5e with an offset wrist"')
                   .replace('d = 0.0997\n', 'd = 0.0997\na = 0.03\n'))
NAMES = tuple(SPECS)
WRIST = 4  # q5: the middle wrist joint of both arms (0: the wrist singularity)

WK_OK, WK_ERR_NULL, WK_ERR_NONFINITE, WK_ERR_DESIGN, WK_ERR_RANGE = 0, -1, -2, -3, -4
STATUS_OK, STATUS_UNREACHABLE, STATUS_INDETERMINATE = 0, 1, 3
FLAG_SINGULAR_INVERSE, FLAG_DOUBLE_ROOT, FLAG_INDETERMINATE, FLAG_PROJECTED = 1, 8, 16, 32
D = ctypes.POINTER(ctypes.c_double)


# ------------------------------------------------------------------------------------------------ rendering
@pytest.fixture(scope="module")
def rendered(tmp_path_factory):
    """name -> (Python module, folder of its C): both rendered from one derivation, as pipeline / own_robot do."""
    out = tmp_path_factory.mktemp("chain_c")
    (out / "python").mkdir()
    (out / "python" / "_wristkin_runtime.py").write_text(runtime_files.emit("python/_runtime.py", header_lines()))
    pipeline.emit_c_runtime(out / "c")
    mods = {}
    for name, text in SPECS.items():
        spec = out / f"{name}.toml"
        spec.write_text(text)
        mech = load_spec(spec)
        ks = mech.kernels(mech.derive())
        assert mech.TEMPLATES[1:] == ("c/chain.h.jinja", "c/chain.c.jinja")
        files = pipeline.emit_solvers(name, mech, ks, out / "python", out / "c")
        first = [f.read_bytes() for f in files]
        pipeline.emit_solvers(name, mech, ks, out / "python", out / "c")
        assert [f.read_bytes() for f in files] == first  # byte-stable
        mods[name] = own_robot.import_solver(out, name)
    return {name: (mods[name], out / "c") for name in NAMES}


class ChainC:
    """ctypes binding of one rendered chain solver (strict flags, -O2)."""

    def __init__(self, py, cdir: Path):
        name = py.NAME
        so = compile_shared([cdir / f"{name}.c", cdir / "wristkin_runtime.c"], [cdir], f"chain_{name}")
        self.lib = load(so)
        self.name, self.n, self.max_ik = name, py.N_JOINTS, py.MAX_IK

        def solutions(max_n, nv):
            class S(ctypes.Structure):
                _fields_ = [("count", ctypes.c_int), ("status", ctypes.c_int), ("valid", ctypes.c_int * max_n),
                            ("flags", ctypes.c_uint * max_n), ("values", (ctypes.c_double * nv) * max_n),
                            ("aux", (ctypes.c_double * 1) * max_n)]
            return S
        self.IK, self.FK = solutions(py.MAX_IK, py.N_JOINTS), solutions(1, 12)

        class Design(ctypes.Structure):
            _fields_ = [("params", ctypes.c_double * max(1, len(py.DESIGN_NAMES))), ("base", ctypes.c_double * 12),
                        ("tool", ctypes.c_double * 12)]
        self.Design = Design
        dp, ik, fk = ctypes.POINTER(Design), ctypes.POINTER(self.IK), ctypes.POINTER(self.FK)
        for verb, args in (("design_init", [D, dp]), ("design_set_frames", [dp, D, D]), ("ik", [D, dp, ik]),
                           ("ik_near", [D, dp, D, ik]), ("fk", [D, dp, fk]), ("fk_matrix", [D, dp, D]),
                           ("jacobian", [D, dp, D]), ("ik_batch", [ctypes.c_size_t, D, dp, ik]),
                           ("fk_batch", [ctypes.c_size_t, D, dp, fk]), ("select_ik", [ik, D, D, D])):
            self.fn(verb).argtypes = args

    def fn(self, verb):
        return getattr(self.lib, f"wk_{self.name}_{verb}")

    @staticmethod
    def ptr(a):
        return None if a is None else np.ascontiguousarray(a, dtype=float).ctypes.data_as(D)

    def design(self, base=None, tool=None):
        d = self.Design()
        rc = self.fn("design_init")(None, ctypes.byref(d))
        if rc == WK_OK and (base is not None or tool is not None):
            rows = [None if m is None else np.ascontiguousarray(np.asarray(m, float)[:3].ravel()) for m in (base, tool)]
            rc = self.fn("design_set_frames")(ctypes.byref(d), self.ptr(rows[0]), self.ptr(rows[1]))
        return rc, d

    def ik(self, pose, design=None, previous=None):
        p = np.ascontiguousarray(np.asarray(pose, float)[:3].ravel())
        out = self.IK()
        dp = None if design is None else ctypes.byref(design)
        if previous is None:
            rc = self.fn("ik")(self.ptr(p), dp, ctypes.byref(out))
        else:
            prev = np.ascontiguousarray(previous, dtype=float)
            rc = self.fn("ik_near")(self.ptr(p), dp, self.ptr(prev), ctypes.byref(out))
        return rc, out

    def fk(self, q, design=None):
        out = self.FK()
        rc = self.fn("fk")(self.ptr(np.asarray(q, float)), None if design is None else ctypes.byref(design),
                           ctypes.byref(out))
        return rc, out

    def fk_matrix(self, q, design=None):
        o = np.zeros(12)
        rc = self.fn("fk_matrix")(self.ptr(np.asarray(q, float)), None if design is None else ctypes.byref(design),
                                  o.ctypes.data_as(D))
        return rc, np.vstack([o.reshape(3, 4), [0.0, 0.0, 0.0, 1.0]])

    def jacobian(self, q, design=None):
        o = np.zeros(6 * self.n)
        rc = self.fn("jacobian")(self.ptr(np.asarray(q, float)), None if design is None else ctypes.byref(design),
                                 o.ctypes.data_as(D))
        return rc, o.reshape(6, self.n)


@pytest.fixture(scope="module")
def solvers(rendered):
    return {name: (py, ChainC(py, cdir)) for name, (py, cdir) in rendered.items()}


# ------------------------------------------------------------------------------------------------ helpers
def _gap(a, b, kinds) -> float:
    return max((abs(math.remainder(x - y, 2 * math.pi)) if k == "R" else abs(x - y))
               for x, y, k in zip(a, b, kinds, strict=True))


def _joints(rng, py):
    return np.array([rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in py.JOINT_KINDS])


def _frame(rng):
    """A random rigid transform (4x4)."""
    x, y, z, w = rng.normal(size=4)
    n = math.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / n, y / n, z / n, w / n
    m = np.eye(4)
    m[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    m[:3, 3] = rng.uniform(-0.3, 0.3, 3)
    return m


def _assert_same(py, s, c_result, what="", tol=1e-9):
    """The C result equals the Python Solutions: status, and row by row (same order) values (within `tol`, or
    `tol(k, residual of C's row k)`), flags, residuals."""
    rc, o = c_result
    worst = 0.0
    assert rc == WK_OK, what
    assert o.status == s.status, f"{what}: status {o.status} != {s.status}"
    assert o.count == s.count, f"{what}: count {o.count} != {s.count}"
    for k in range(py.MAX_IK):
        assert bool(o.valid[k]) == bool(s.valid[k]), what
        if not s.valid[k]:
            assert int(o.flags[k]) == 0 and all(math.isnan(v) for v in o.values[k]), what
            continue
        gap = _gap(s.values[k], list(o.values[k]), py.JOINT_KINDS)
        tol_k = tol(k, o.aux[k][0]) if callable(tol) else tol
        assert gap <= tol_k, f"{what}: solution {k} differs by {gap:.3g} (tolerance {tol_k:.3g})"
        worst = max(worst, gap)
        assert int(o.flags[k]) == int(s.flags[k]), f"{what}: flags of {k}: {o.flags[k]} != {s.flags[k]}"
        # the FK residuals: equal to 1e-10, except at a double root (flagged): there J is singular, no Gauss-Newton
        # step improves on the candidate's sqrt(eps) error, and each language's candidate carries its own stages'
        # rounding, amplified to that level (seed 581528: a PUMA-type arm with its shoulder at a tangent and its
        # wrist at the family, 7.9e-10 in C and 9.3e-10 in Python, with both polishing through the same kernels by
        # the same steps)
        tangent = bool(int(s.flags[k]) & FLAG_DOUBLE_ROOT)
        assert o.aux[k][0] <= 1e-9 and (tangent or abs(o.aux[k][0] - s.aux[k, 0]) <= 1e-10), what
    return worst


# ------------------------------------------------------------------------------------------------ FK, Jacobian
@pytest.mark.parametrize("name", NAMES)
def test_fk_and_jacobian_equal_python(solvers, name):
    py, c = solvers[name]
    rng = case_rng(9101)
    worst = 0.0
    for i in range(150):
        q = _joints(rng, py) * (1.0 if i % 5 else 7.0)  # unwrapped angles too
        if i % 3 == 0:  # run-time base and tool frames
            b, t = _frame(rng), _frame(rng)
            dpy = py.make_design(None, base=b, tool=t)
            rc, dc = c.design(b, t)
            assert rc == WK_OK
        else:
            dpy, dc = None, None
        rc, t_c = c.fk_matrix(q, dc)
        assert rc == WK_OK
        rc, j_c = c.jacobian(q, dc)
        assert rc == WK_OK
        f = py.fk(q, dpy)
        rc, fc = c.fk(q, dc)
        assert rc == WK_OK and fc.count == 1 and fc.status == STATUS_OK
        worst = max(worst, float(np.max(np.abs(t_c - py.fk_matrix(q, dpy)))),
                    float(np.max(np.abs(j_c - py.jacobian(q, dpy)))),
                    float(np.max(np.abs(np.array(fc.values[0][:]) - f.values[0]))))
        # manipulability m = sqrt(det J^T J) = prod sigma_i, from two eigen-solvers (Jacobi in C, LAPACK in numpy):
        # each eigenvalue moves by ~eps sigma_max^2, so m by eps sigma_max^2 m sum 1 / sigma_i^2 / 2 (first order);
        # near a singularity that exceeds 1e-12 (WRISTKIN_TEST_SEED=821165: m = 3e-7, differing by 1.2e-12)
        sv = np.linalg.svd(py.jacobian(q, dpy), compute_uv=False)
        m = float(f.aux[0, 0])
        allow = 1e-12 + 16 * np.finfo(float).eps * sv[0] ** 2 * m * float(np.sum(1.0 / np.maximum(sv, 1e-300) ** 2))
        assert abs(fc.aux[0][0] - m) <= allow, (i, fc.aux[0][0], m, allow)
        assert int(fc.flags[0]) == int(f.flags[0])
    assert worst <= 1e-12, worst


# ------------------------------------------------------------------------------------------------ IK
@pytest.mark.parametrize("name", NAMES)
def test_ik_equals_python_on_random_poses(solvers, name):
    """Seeded random configurations (a third with `previous`, a fifth with run-time frames): the same solution
    sets in the same order, flags, residuals and status. The sets agree to 1e-9, or where the arm is near a
    singularity to their conditioning: two sets that reproduce the pose to residuals r_c, r_py lie up to
    4 (r_c + r_py + rounding) / sigma_min of J apart along its near-null vector (seed 753076: a PUMA-type arm with
    sigma_min 1.5e-8, both languages' sets at 3e-16 of the pose, 1.3e-8 apart once both were polished to rounding)."""
    py, c = solvers[name]
    rng = case_rng(9102)
    rounding = 64 * np.finfo(float).eps * max(1.0, py.SCALE)
    worst, counts = 0.0, {}
    for i in range(300):
        q = _joints(rng, py)
        if i % 5 == 0:
            b, t = _frame(rng), _frame(rng)
            dpy = py.make_design(None, base=b, tool=t)
            rc, dc = c.design(b, t)
            assert rc == WK_OK
        else:
            dpy, dc = None, None
        pose = py.fk_matrix(q, dpy)
        prev = None if i % 3 else q + rng.normal(0.0, 0.05, py.N_JOINTS)
        s = py.ik(pose, dpy, prev)

        def tol(k, residual_c, s=s, dpy=dpy):
            sigma_min = np.linalg.svd(py.jacobian(s.values[k], dpy), compute_uv=False)[-1]
            return max(1e-9, 4 * (s.aux[k, 0] + residual_c + rounding) / max(sigma_min, 1e-300))
        worst = max(worst, _assert_same(py, s, c.ik(pose, dc, prev), f"{name} pose {i}", tol=tol))
        counts[s.count] = counts.get(s.count, 0) + 1
        assert any(_gap(v, q, py.JOINT_KINDS) < 1e-6 for v in s)  # the generating joints are among them
    assert counts.get(8, 0) > 150, counts  # most random poses of both arms have all eight sets


@pytest.mark.parametrize("name", NAMES)
def test_singular_wrist_is_one_flagged_family(solvers, name):
    """q5 = 0: the two wrist branches of the generating arm configuration merge into one family, returned once
    (flagged singular and indeterminate, status indeterminate) with its free angle at 0 (the UR type: the angle
    of the parallel group, so the generating arm's group sum is set to 0 here; at another sum the Python
    representative need not reach the wrist point), equal to Python's; with `previous`, equal to Python's."""
    py, c = solvers[name]
    rng = case_rng(9103)
    for i in range(30):
        q = _joints(rng, py)
        q[WRIST] = 0.0
        if name == "ur_t":
            q[3] = math.remainder(-q[1] - q[2], 2 * math.pi)
        pose = py.fk_matrix(q)
        s = py.ik(pose)
        _assert_same(py, s, c.ik(pose), f"{name} singular {i}")
        assert s.status == STATUS_INDETERMINATE
        family = [k for k in range(py.MAX_IK) if s.valid[k] and s.flags[k] & FLAG_INDETERMINATE]
        assert family and all(s.flags[k] & FLAG_SINGULAR_INVERSE for k in family)
        arms = {tuple(np.round(s.values[k][:4], 6)) for k in family}
        assert len(arms) == len(family)  # one member per arm configuration
        for k in family:
            assert abs(math.remainder(s.values[k][WRIST], 2 * math.pi)) < 1e-9
            assert np.max(np.abs(c.fk_matrix(s.values[k])[1] - pose)) <= 1e-9
        prev = q + rng.normal(0.0, 0.05, py.N_JOINTS)
        _assert_same(py, py.ik(pose, None, prev), c.ik(pose, None, prev), f"{name} singular {i} near")
        rc, fc = c.fk(q)
        assert rc == WK_OK and fc.flags[0] & FLAG_SINGULAR_INVERSE and py.fk(q).flags[0] & FLAG_SINGULAR_INVERSE


@pytest.mark.parametrize("name", ("puma_t", "ur_t", "ur_off"))
def test_near_the_wrist_singularity_c_equals_python(solvers, name):
    """|q5| from 1e-7 to 1e-5, near (not at) the family: two regular wrist sets (subproblem 2 reads g on the
    smaller circle, so |sin q5| is resolved to rounding; subproblem 6's roots for the offset wrist). C equals Python
    set for set (values, order, flags); never empty. Near the singularity q4 and q6 are each fixed only to about
    e / |sin q5| for a pose error e (their sum or difference is well conditioned): the two languages' roundings
    (e ~ 100 eps for the intermediate lengths) and, where a set was polished, the polish's stopping error
    (POLISH_TOL) may differ by that. Where the arm is near a singularity too (the PUMA folded onto its shoulder,
    q2 ~ 1e-4: sigma_min of J 2.6e-11 at |q5| = 1e-5), both sets reproduce the pose to rounding and still differ
    along J's near-null vector by up to their residuals / sigma_min (J dq = F(q_a) - F(q_b) to first order; x4 for
    the max-entry to 2-norm), which is that bound's other term.
    Every set reproduces the pose to rounding (64 eps x size), status ok, the offset wrist's too since subproblem 6
    reads its near pair on the parts normal to n and every set is polished to POLISH_TOL (it was exempt: merged or
    family sets within IK_VERIFY_TOL). Was: up to 1e-11 (|sin q5| from cos q5 in subproblem 2) and 1e-9 (a merged
    family representative below |sin q5| = 1.4e-6, status indeterminate), and C and Python 1.0e-5 apart at
    WRISTKIN_TEST_SEED=5074."""
    py, c = solvers[name]
    rng = case_rng(9107)
    rounding = 64 * np.finfo(float).eps * max(1.0, py.SCALE)
    for i in range(100):
        q = _joints(rng, py)
        q[WRIST] = (1.0 if i % 2 else -1.0) * (1e-7, 3e-7, 1e-6, 3e-6, 1e-5)[i % 5]
        pose = py.fk_matrix(q)
        s = py.ik(pose)
        assert s.count >= 1, (name, i, s.reason)
        assert s.status == STATUS_OK and np.max(s.aux[s.valid]) <= rounding, (name, i, s.reason, s.aux[s.valid])
        wrist = (100 * np.finfo(float).eps + py.POLISH_TOL) / abs(math.sin(q[WRIST]))

        def tol(k, residual_c, s=s, wrist=wrist):
            if not max(s.aux[k, 0], residual_c) <= rounding:
                return max(1e-9, wrist)
            sigma_min = np.linalg.svd(py.jacobian(s.values[k]), compute_uv=False)[-1]
            return max(1e-9, wrist, 4 * (s.aux[k, 0] + residual_c + rounding) / sigma_min)
        _assert_same(py, s, c.ik(pose), f"{name} near-singular {i}", tol=tol)


def test_an_offset_wrist_near_its_singularity_with_a_straight_elbow_is_reachable(solvers):
    """ur_off at |sin q5| = 3e-6 with the elbow 9.4e-5 rad from straight (case 13 of the test above at
    WRISTKIN_TEST_SEED=525886). Was: unreachable in C and numpy: subproblem 6's q4 carries eps / |sin q5| and the
    group angle read after it eps / |sin q5|^2, so the elbow's u landed 1.3e-7 beyond its tangent band (widened
    only by 1 / g). Now the stages after subproblem 6 widen their bands by 1 / g^2, and a root those bands merged
    that the stage's own band separates is run as those two first: a set within the conditioning of the generating
    joints is returned, C equal to Python."""
    py, c = solvers["ur_off"]
    q = np.array([-0.8258674979657927, -0.013617302541742315, 9.381435177457931e-05, -2.5568302335404667, 3e-06,
                  2.5443378636647154])
    pose = py.fk_matrix(q)
    s = py.ik(pose)
    assert s.count >= 1, s.reason
    # both singularities at once: sigma_min of J is ~3e-10 here, so a set reproducing the pose to its residual r
    # lies within ~r / sigma_min of the generating joints along J's near-null vector (x4 for the max-entry to
    # 2-norm), the pose determining them no better (a set 2.4e-14 off the pose is 9e-5 rad off in the elbow)
    sigma_min = np.linalg.svd(py.jacobian(q), compute_uv=False)[-1]
    rounding = 64 * np.finfo(float).eps * max(1.0, py.SCALE)
    gaps = [(_gap(s.values[k], q, py.JOINT_KINDS), s.aux[k, 0]) for k in np.flatnonzero(s.valid)]
    assert min(gap - 4 * (res + rounding) / sigma_min for gap, res in gaps) <= 1e-9, (gaps, sigma_min)

    def tol(k, residual_c):
        return max(1e-9, 4 * (s.aux[k, 0] + residual_c + rounding) / sigma_min)
    _assert_same(py, s, c.ik(pose), "ur_off straight elbow", tol=tol)


def test_an_offset_wrist_near_its_singularity_returns_the_generating_joints(solvers):
    """ur_off with |q5| from 1e-10 to 3e-6 (random arm): the generating joints are among the sets within the
    conditioning allowance 1e-6 + 1e-13 / |q5| (the bench's), in C and in Python, and no call searches. Was: on 150 of
    200 such poses of the bench's offset-wrist UR5e they were missing. Subproblem 6's two roots there differ by
    ~|q5|: the quartic resolves them only to sqrt(eps), its merged root verified within IK_VERIFY_TOL with q6 up to
    0.05 rad off, and the singularity's candidate (taken within 1e-6 rad) stood in as a family member found by a
    361-angle search (180x the median call). Now the pair comes from the second equation's parts normal to n, each
    root to ~eps, and a set within IK_VERIFY_TOL is polished to rounding."""
    py, c = solvers["ur_off"]
    rng = case_rng(9111)
    rounding = 64 * np.finfo(float).eps * max(1.0, py.SCALE)
    deltas = (1e-10, 1e-9, 1e-8, 1e-7, 3e-7, 1e-6, 3e-6)
    for i in range(70):
        q = _joints(rng, py)
        q[WRIST] = (1.0 if i % 2 else -1.0) * deltas[i % len(deltas)]
        pose = py.fk_matrix(q)
        # or the conditioning at q where the arm is nearer a singularity than |q5| says (seed 753076: sigma_min
        # 1.3e-14 at |q5| = 1e-10, a set 3.9e-3 rad off reproducing the pose to 3e-16, in C and Python alike)
        sigma_min = np.linalg.svd(py.jacobian(q), compute_uv=False)[-1]
        allowance = 1e-6 + 1e-13 / abs(q[WRIST])
        rc, o = c.ik(pose)
        assert rc == WK_OK
        sp = py.ik(pose)
        for what, sets in (("python", [(sp.values[k], sp.aux[k, 0]) for k in np.flatnonzero(sp.valid)]),
                           ("c", [(list(o.values[k]), o.aux[k][0]) for k in range(o.count) if o.valid[k]])):
            excess = [_gap(v, q, py.JOINT_KINDS) - max(allowance, 4 * (res + rounding) / sigma_min) for v, res in sets]
            assert excess and min(excess) <= 0.0, (what, i, q[WRIST], sigma_min, min(excess, default=None))


def test_an_offset_wrist_root_next_to_its_split_pair_is_returned_once(solvers):
    """ur_off at q5 = -1e-7 (case 24 of the test above at WRISTKIN_TEST_SEED=913424). Was: the quartic's root at
    q5 = 1.0e-6, 1.03e-6 from the singularity's candidate in q1 (the window that drops a regular root as the same
    configuration was 1e-6), was kept beside the same root from the split: its two sets were returned twice, which
    filled MAX_IK = 8 before the generating joints were reached. Now a regular root within 1e-9 of a split root is
    dropped too (both are refined to ~eps), in C and Python alike."""
    py, c = solvers["ur_off"]
    q = np.array([-2.3789922276922026, 2.1620076130335333, -1.743838247657747, 1.4023669220346884, -1e-7,
                  2.6211950306137624])
    pose = py.fk_matrix(q)
    sigma_min = np.linalg.svd(py.jacobian(q), compute_uv=False)[-1]
    rounding = 64 * np.finfo(float).eps * max(1.0, py.SCALE)
    rc, o = c.ik(pose)
    assert rc == WK_OK
    sp = py.ik(pose)
    for what, sets in (("python", [(sp.values[k], sp.aux[k, 0]) for k in np.flatnonzero(sp.valid)]),
                       ("c", [(list(o.values[k]), o.aux[k][0]) for k in range(o.count) if o.valid[k]])):
        assert min(_gap(v, q, py.JOINT_KINDS) - max(1e-6, 4 * (res + rounding) / sigma_min)
                   for v, res in sets) <= 0.0, what
        # the sets here are distinct configurations (the pair ~1.1e-6 apart in q5, its elbows far apart)
        gaps = [_gap(a, b, py.JOINT_KINDS) for i, (a, _) in enumerate(sets) for b, _ in sets[i + 1:]]
        assert min(gaps) > 1e-6, (what, len(sets))


@pytest.mark.parametrize("name", ("puma_t", "ur_t", "ur_off"))
def test_previous_changes_no_set_near_the_wrist_singularity(solvers, name):
    """|q5| from 1e-9 to 1e-6: ik(pose) and ik(pose, previous=q) return the same sets, flags and status, in Python and
    in C (ik_near), and C equals Python. Was (ur_off, subproblem 6): with previous the singularity's candidate was
    kept as a family (its member at previous's q6 verified within IK_VERIFY_TOL) where without it no grid angle
    verified and the split roots were returned: 8 regular sets, status ok, against 6 with an indeterminate
    family."""
    py, c = solvers[name]
    rng = case_rng(9108)
    for i in range(60):
        q = _joints(rng, py)
        q[WRIST] = (1.0 if i % 2 else -1.0) * (1e-9, 1e-7, 1e-6)[i % 3]
        pose = py.fk_matrix(q)
        a, b = py.ik(pose), py.ik(pose, None, q)
        assert a.status == b.status and a.count >= 1, (name, i, a.reason, b.reason)
        _assert_same(py, a, c.ik(pose), f"{name} near {i}", tol=1.0)  # the sets, flags, status; values below
        _assert_same(py, b, c.ik(pose, None, q), f"{name} near {i} previous", tol=1.0)
        regular = [[k for k in np.flatnonzero(s.valid) if not s.flags[k] & FLAG_INDETERMINATE] for s in (a, b)]
        family = [[k for k in np.flatnonzero(s.valid) if s.flags[k] & FLAG_INDETERMINATE] for s in (a, b)]
        assert len(regular[0]) == len(regular[1]) and bool(family[0]) == bool(family[1]), (name, i, a.reason,
                                                                                         b.reason)
        for ka, kb in zip(*regular, strict=True):  # a regular set stays, flags and all
            assert a.flags[ka] == b.flags[kb], (name, i, ka)
            assert _gap(a.values[ka], b.values[kb], py.JOINT_KINDS) < 1e-9, (name, i, ka)
        # A family's member is previous's to pick, and members differ in how many sets they carry: where a later
        # stage (the elbow of the offset wrist, whose family moves the wrist centre) is at its tangent for one member
        # its two branches are one double root there (seed 77: previous's member had the elbow straight, 1 set; the
        # grid's member 2). So the counts may differ only by such a merge, flagged.
        if len(family[0]) != len(family[1]):
            fewer = min((a, family[0]), (b, family[1]), key=lambda t: len(t[1]))
            assert all(fewer[0].flags[k] & FLAG_DOUBLE_ROOT for k in fewer[1]), (name, i, a.reason, b.reason)


def test_offset_wrist_singularity_equals_python(solvers):
    """The offset-wrist UR (subproblem 6) at its exact wrist singularity, q5 = 0 or pi at any group sum (the free
    angle is q6's, and only an interval of it reaches the pose): C equals Python set for set (values, order, flags)
    without `previous` (the FAMILY_ANGLES search) and with it (ik_near); never empty, the family flagged."""
    py, c = solvers["ur_off"]
    rng = case_rng(9106)
    for i in range(200):
        q = _joints(rng, py)
        q[WRIST] = 0.0 if i % 2 else math.pi
        pose = py.fk_matrix(q)
        s = py.ik(pose)
        _assert_same(py, s, c.ik(pose), f"ur_off singular {i}")
        assert s.count >= 1 and s.status == STATUS_INDETERMINATE, (i, s.reason)
        assert any(s.flags[k] & FLAG_INDETERMINATE for k in np.flatnonzero(s.valid))
        near = py.ik(pose, None, q)
        _assert_same(py, near, c.ik(pose, None, q), f"ur_off singular {i} near")
        assert min(_gap(v, q, py.JOINT_KINDS) for v in near) < 1e-7


@pytest.mark.parametrize("name", NAMES)
def test_unreachable_and_invalid_inputs(solvers, name):
    py, c = solvers[name]
    rng = case_rng(9104)
    q = _joints(rng, py)
    pose = py.fk_matrix(q)

    far = np.eye(4)
    far[:3, 3] = (3.0, -2.0, 1.0)  # beyond the arm's reach
    assert py.ik(far).status == STATUS_UNREACHABLE
    rc, o = c.ik(far)
    assert (rc, o.status, o.count) == (WK_OK, STATUS_UNREACHABLE, 0)
    assert not any(o.valid) and all(math.isnan(v) for row in o.values for v in row)

    for bad_value in (math.nan, math.inf):
        bad = pose.copy()
        bad[1, 3] = bad_value
        rc, o = c.ik(bad)
        assert (rc, o.status, o.count) == (WK_ERR_NONFINITE, WK_ERR_NONFINITE, 0)
        assert all(math.isnan(v) for row in o.values for v in row)
    rc, o = c.ik(pose, None, np.full(py.N_JOINTS, math.nan))
    assert (rc, o.count) == (WK_ERR_NONFINITE, 0)
    rc, _ = c.fk(np.full(py.N_JOINTS, math.inf))
    assert rc == WK_ERR_NONFINITE
    assert c.fk_matrix(np.full(py.N_JOINTS, math.nan))[0] == WK_ERR_NONFINITE

    skew = pose.copy()
    skew[:3, :3] *= 1.01  # not a rotation
    assert c.ik(skew)[0] == WK_ERR_RANGE
    huge = pose.copy()
    huge[0, 3] = 2e6  # beyond LENGTH_MAX
    assert c.ik(huge)[0] == WK_ERR_RANGE

    # a rotation a little off SO(3) is projected and flagged, as in Python
    near = pose.copy()
    near[:3, :3] += rng.normal(0.0, 1e-8, (3, 3))
    s = py.ik(near)
    _assert_same(py, s, c.ik(near), "projected")
    assert s.count and all(s.flags[k] & FLAG_PROJECTED for k in range(py.MAX_IK) if s.valid[k])

    # NULL pointers and bad designs
    out = c.IK()
    assert c.fn("ik")(None, None, ctypes.byref(out)) == WK_ERR_NULL and out.count == 0
    assert c.fn("ik")(c.ptr(pose[:3].ravel()), None, None) == WK_ERR_NULL
    assert c.fn("design_init")(None, None) == WK_ERR_NULL
    rc, d = c.design()
    assert rc == WK_OK
    frame = np.eye(4)[:3].ravel().copy()
    frame[5] = math.nan
    assert c.fn("design_set_frames")(ctypes.byref(d), c.ptr(frame), None) == WK_ERR_NONFINITE
    frame[5] = 1.5  # not a rotation
    assert c.fn("design_set_frames")(ctypes.byref(d), None, c.ptr(frame)) == WK_ERR_DESIGN
    assert list(d.base) == list(np.eye(4)[:3].ravel())  # unchanged on error


@pytest.mark.parametrize("name", NAMES)
def test_batch_and_select_equal_python(solvers, name):
    py, c = solvers[name]
    rng = case_rng(9105)
    qs = np.array([_joints(rng, py) for _ in range(20)])
    fks = (c.FK * len(qs))()
    assert c.fn("fk_batch")(len(qs), c.ptr(qs.ravel()), None, fks) == WK_OK
    poses = np.array([list(f.values[0]) for f in fks])
    for q, row in zip(qs, poses, strict=True):
        assert np.max(np.abs(row - py.fk_matrix(q)[:3].ravel())) <= 1e-12
    iks = (c.IK * len(qs))()
    assert c.fn("ik_batch")(len(qs), c.ptr(poses.ravel()), None, iks) == WK_OK
    for q, row, o in zip(qs, poses, iks, strict=True):
        pose = np.vstack([row.reshape(3, 4), [0.0, 0.0, 0.0, 1.0]])
        s = py.ik(pose)
        _assert_same(py, s, (WK_OK, o), "batch")
        prev = q + 0.01
        assert c.fn("select_ik")(ctypes.byref(o), c.ptr(prev), None, None) == py.select(s, prev)
        assert c.fn("select_ik")(ctypes.byref(o), None, None, None) == py.select(s)
        lo, hi = np.full(py.N_JOINTS, -2.0), np.full(py.N_JOINTS, 2.0)
        assert (c.fn("select_ik")(ctypes.byref(o), c.ptr(prev), c.ptr(lo), c.ptr(hi))
                == py.select(s, prev, lower=lo, upper=hi))


# ------------------------------------------------------------------------------------------------ sanitizers
CHAIN_SANITIZE = Path(__file__).resolve().parent / "c" / "chain_sanitize.c"  # random, singular, hostile inputs


def _sanitizer_available() -> bool:
    probe = subprocess.run([compiler(), "-fsanitize=address,undefined", "-x", "c", "-", "-o", "/dev/null"],
                           input="int main(void){return 0;}", capture_output=True, text=True)
    return probe.returncode == 0


@pytest.mark.c_only  # no numpy result enters: the repeated passes on other kernels skip it
@pytest.mark.skipif(not _sanitizer_available(), reason="compiler has no ASan/UBSan runtime")
@pytest.mark.parametrize("name", NAMES)
def test_clean_under_asan_ubsan(rendered, name):
    py, cdir = rendered[name]
    flags = [*SANITIZE_FLAGS, f"-DMECH={name}", f'-DMECH_H="{name}.h"', f"-DN={py.N_JOINTS}",
             f"-DMAX_IK={py.MAX_IK}"]
    exe = compile_executable([CHAIN_SANITIZE, cdir / f"{name}.c", cdir / "wristkin_runtime.c"], [cdir],
                             f"chain_{name}_sanitize", extra_flags=flags)
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300,
                         env={"ASAN_OPTIONS": "detect_leaks=1:abort_on_error=1",
                              "UBSAN_OPTIONS": "halt_on_error=1:print_stacktrace=1"})
    assert run.returncode == 0, (run.returncode, run.stderr[-4000:])
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr
