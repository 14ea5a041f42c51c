"""The user-robot solver's hand-written runtime sources (runtime/c/chain, runtime/python/chain) tested as they are:
each kernel on random instances whose answer is known by construction (numpy here, never the generated code),
and every source compiled strictly as a file of its own."""

from __future__ import annotations

import ctypes
import hashlib
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from cbuild import RUNTIME_C, compile_shared, compiler, load
from seeding import case_rng

from derive import own_robot, pipeline, runtime_files
from derive.catalogue import load as load_spec
from derive.render import environment

ROOT = Path(__file__).resolve().parent.parent
CHAIN_C = ROOT / "runtime" / "c" / "chain"
D = ctypes.POINTER(ctypes.c_double)
IP = ctypes.POINTER(ctypes.c_int)
U = ctypes.POINTER(ctypes.c_uint)
FLAG_SINGULAR_INVERSE, FLAG_DOUBLE_ROOT, FLAG_INDETERMINATE = 1, 8, 16


def _rot(k, t):
    k = np.asarray(k, float)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(t) * kx + (1 - math.cos(t)) * kx @ kx


def _unit(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def _p(a):
    return np.ascontiguousarray(a, dtype=float).ctypes.data_as(D)


def _angle_gap(a, b):
    return abs(math.remainder(a - b, 2 * math.pi))


@pytest.fixture(scope="module")
def lib():
    harness = ROOT / "tests" / "c" / "chain_runtime_harness.c"
    # the harness includes the sources: their bytes name the build (compile_shared hashes only what it is given)
    shared = [ROOT / "runtime" / "c" / n
              for n in ("poly_real_roots.c", "wk_poly_ops.c", "wk_geom3.c", "wk_spatial3.c", "wk_sp6.c")]
    h = hashlib.sha256(b"".join(p.read_bytes() for p in [*sorted(CHAIN_C.iterdir()), *shared])).hexdigest()[:16]
    so = compile_shared([harness, RUNTIME_C], [ROOT / "runtime" / "c"], "chain_runtime",
                        extra_flags=[f"-DWKT_SOURCES={h}"])
    L = load(so)
    L.wkt_trig.argtypes = [ctypes.c_double] * 3 + [D, U]
    L.wkt_root_amplification.argtypes = [ctypes.c_int, D, U, ctypes.c_double]
    L.wkt_root_amplification.restype = ctypes.c_double
    L.wkt_sp1.argtypes = [D, D, D, D]
    L.wkt_sp2.argtypes = [D, D, D, D, ctypes.c_int, D, IP, D, U]
    L.wkt_sp3.argtypes = [D, D, D, ctypes.c_double, D, U]
    L.wkt_sp4.argtypes = [D, D, D, ctypes.c_double, D, U]
    L.wkt_sp6.argtypes = [D, D, D, D, D, ctypes.c_double, D, D, D, D, U]
    L.wkt_sp6_split.argtypes = [D, D, D, D, D, ctypes.c_double, D, D, ctypes.c_double, ctypes.c_double, D, D]
    L.wkt_lstsq.argtypes = [D, ctypes.c_int, ctypes.c_int, D, D]
    L.wkt_solve_square.argtypes = [D, ctypes.c_int, D, D]
    L.wkt_lu_solve_many.argtypes = [D, ctypes.c_int, D, ctypes.c_int, D]
    L.wkt_spectrum.argtypes = [D, ctypes.c_int, D]
    L.wkt_spectrum.restype = ctypes.c_double
    L.wkt_conditioning.argtypes = [D, ctypes.c_int, D]
    for verb in ("wkt_fk", "wkt_jacobian"):
        getattr(L, verb).argtypes = [ctypes.c_int, IP, D, D, D, D, D]
    L.wkt_polish.argtypes = [ctypes.c_int, IP, D, D, D, D, D]
    L.wkt_polish.restype = ctypes.c_double
    L.wkt_held_reversed_fk.argtypes = [ctypes.c_int, IP, D, D, D, ctypes.c_double, D, D]
    L.wkt_spatial3.argtypes = [D, D, D, D, D, D, D, U]
    L.wkt_perpendicular.argtypes = [D, D]
    L.wkt_orient_rest.argtypes = [D, D, ctypes.c_double, ctypes.c_double, D]
    L.wkt_transpose.argtypes = [D, D]
    L.wkt_meet_point.argtypes = [D, D, ctypes.c_int, ctypes.c_int, ctypes.c_int, D]
    return L


def test_the_harness_constants_are_the_derived_tolerances():
    """The harness compiles the kernels with a generated solver's constants: the pipeline's, not other ones."""
    from derive.tolerances import TOLERANCES

    text = (ROOT / "tests" / "c" / "chain_runtime_harness.c").read_text()
    for macro, key in (("CK_TANGENT_TOL", "stage_tangent"), ("CK_DOUBLE_ROOT_TOL", "double_root"),
                       ("CK_IK_VERIFY_TOL", "ik_verify"), ("CK_SINGULAR_EPS", "singular")):
        assert f"#define {macro} {TOLERANCES[key]}\n" in text, macro


# ------------------------------------------------------------------------------------------------ subproblems
def test_trig_roots_satisfy_the_equation_and_a_tangent_is_one_double_root(lib):
    rng = case_rng(2201)
    t, f = np.zeros(2), (ctypes.c_uint * 2)()
    for _ in range(200):
        a, b = rng.normal(size=2)
        t0 = rng.uniform(-math.pi, math.pi)
        c = a * math.cos(t0) + b * math.sin(t0)
        n = lib.wkt_trig(a, b, c, _p(t), f)
        assert 1 <= n <= 2 and min(_angle_gap(x, t0) for x in t[:n]) < 1e-9
        assert all(abs(a * math.cos(x) + b * math.sin(x) - c) < 1e-12 for x in t[:n])
    # |c| = hypot(a, b): the tangent, one root flagged double
    n = lib.wkt_trig(3.0, 4.0, 5.0, _p(t), f)
    assert n == 1 and f[0] & FLAG_DOUBLE_ROOT and abs(t[0] - math.atan2(4.0, 3.0)) < 1e-7
    assert lib.wkt_trig(3.0, 4.0, 5.1, _p(t), f) == 0  # beyond the tangent: no root


def test_sp1_finds_the_rotation_angle_and_refuses_a_point_on_the_axis(lib):
    rng = case_rng(2202)
    t = np.zeros(1)
    for _ in range(200):
        k, p, t0 = _unit(rng), rng.normal(size=3), rng.uniform(-math.pi, math.pi)
        assert lib.wkt_sp1(_p(k), _p(p), _p(_rot(k, t0) @ p), _p(t)) == 1
        assert _angle_gap(t[0], t0) < 1e-9
    k = _unit(rng)
    assert lib.wkt_sp1(_p(k), _p(0.7 * k), _p(0.7 * k), _p(t)) == 0


def test_sp2_returns_both_angle_pairs_of_two_rotations_meeting(lib):
    """rot(k1, t1) p1 = rot(k2, t2) p2: the generating pair among the (at most two) returned."""
    rng = case_rng(2203)
    t1, t2, has1, f = np.zeros(2), np.zeros(2), (ctypes.c_int * 2)(), (ctypes.c_uint * 2)()
    for _ in range(200):
        k1, k2, p1 = _unit(rng), _unit(rng), rng.normal(size=3)
        a, b = rng.uniform(-math.pi, math.pi, 2)
        p2 = _rot(k2, b).T @ (_rot(k1, a) @ p1)
        n = lib.wkt_sp2(_p(p1), _p(k1), _p(p2), _p(k2), 0, _p(t1), has1, _p(t2), f)
        assert 1 <= n <= 2
        for i in range(n):
            assert np.allclose(_rot(k1, t1[i]) @ p1, _rot(k2, t2[i]) @ p2, atol=1e-9)
        assert min(_angle_gap(t1[i], a) + _angle_gap(t2[i], b) for i in range(n)) < 1e-7


def test_root_amplification_is_the_roots_sensitivity(lib, py):
    """A trig stage's roots phi +- w move by du / |sin w| for a change du of u = cos w (finite differences of acos
    agree to 1e-3 relative); a double root within the band counts 1 / sqrt(DOUBLE_ROOT_TOL); the stages before
    multiply it (the errors compound). C and Python (chain_subproblems._root_amplification) agree."""
    f = (ctypes.c_uint * 2)(0, 0)
    for w in (1.0, 0.1, 1e-2, 1e-3):
        t = np.array([0.3 + w, 0.3 - w])
        du = 1e-4 * w * w  # its second-order term ~1e-4 relative, its rounding eps / du <= 2e-6
        sens = abs(math.acos(math.cos(w) - du) - w) / du
        amp = lib.wkt_root_amplification(2, _p(t), f, 1.0)
        assert math.isclose(amp, max(1.0, sens), rel_tol=1e-3), (w, amp, sens)
        assert amp == py.sub._root_amplification([(t[0], 0), (t[1], 0)], 1.0)
        assert math.isclose(lib.wkt_root_amplification(2, _p(t), f, 1e9), 1e9 * amp, rel_tol=4e-16)
        assert lib.wkt_root_amplification(2, _p(t), f, 1e9) == py.sub._root_amplification([(t[0], 0), (t[1], 0)], 1e9)
    double = (ctypes.c_uint * 2)(FLAG_DOUBLE_ROOT, 0)
    assert math.isclose(lib.wkt_root_amplification(1, _p(np.zeros(2)), double, 1.0), 1e6)  # the harness: 1e-12
    # the stand-in robot's band (closed-form stages): 32 eps
    assert math.isclose(py.sub._root_amplification([(0.0, FLAG_DOUBLE_ROOT)], 1.0), 1 / math.sqrt(32 * 2.0**-52))


def test_sp3_and_sp4_roots_keep_the_distance_and_the_height(lib):
    rng = case_rng(2204)
    t, f = np.zeros(2), (ctypes.c_uint * 2)()
    for _ in range(200):
        k, h, p1, p2 = _unit(rng), _unit(rng), rng.normal(size=3), rng.normal(size=3)
        t0 = rng.uniform(-math.pi, math.pi)
        d = float(np.linalg.norm(_rot(k, t0) @ p1 - p2))
        n = lib.wkt_sp3(_p(k), _p(p1), _p(p2), d, _p(t), f)
        assert 1 <= n <= 2 and min(_angle_gap(x, t0) for x in t[:n]) < _allowance(f, n)
        assert all(abs(np.linalg.norm(_rot(k, x) @ p1 - p2) - d) < 1e-9 for x in t[:n]) or f[0] & FLAG_DOUBLE_ROOT
        e = float(h @ _rot(k, t0) @ p1)
        n = lib.wkt_sp4(_p(h), _p(k), _p(p1), e, _p(t), f)
        assert 1 <= n <= 2 and min(_angle_gap(x, t0) for x in t[:n]) < _allowance(f, n)
        assert all(abs(h @ _rot(k, x) @ p1 - e) < 1e-9 for x in t[:n]) or f[0] & FLAG_DOUBLE_ROOT


def _allowance(f, n):
    """How far the generating angle may be from a returned root: two separate roots are conditioned 1 / |sin w|
    <= 1 / sqrt(DOUBLE_ROOT_TOL) = 1e6 outside the band, so eps-level inputs move them by < 1e-9 (1e-7 allowed);
    within the double-root band (1 - u^2 <= DOUBLE_ROOT_TOL, one root at the tangent) by the band's half-width
    asin(sqrt(1e-12))."""
    return math.asin(math.sqrt(1e-12)) * 1.001 + 1e-9 if n == 1 and f[0] & FLAG_DOUBLE_ROOT else 1e-7


def test_sp6_returns_the_generating_pair(lib):
    """Two invariants of a three-joint group (the UR with an offset wrist's subproblem): n . (R0^T y - p0) = d0 and
    n^T R4 R5 h5 = (R0^T g) . n; built from known (q0, q4, q5)."""
    rng = case_rng(2205)
    q0s, q4s, f = np.zeros(17), np.zeros(17), (ctypes.c_uint * 17)()  # CK_SP6_MAX
    for _ in range(60):
        n_, h0, h4, h5 = _unit(rng), _unit(rng), _unit(rng), _unit(rng)
        p0, p4 = rng.normal(size=3), rng.normal(size=3)
        a, b = rng.uniform(-math.pi, math.pi, 2)
        # n . rot(h0, -q0) p0 - n . rot(h4, q4) p4 = d0 and n . rot(h0, -q0) g = n . rot(h4, q4) h5 (ck_sp6's
        # equations, its coefficients from ck_trig_coef)
        d0 = float(n_ @ _rot(h0, -a) @ p0 - n_ @ _rot(h4, b) @ p4)
        g = _rot(h0, a) @ _rot(h4, b) @ h5
        nr = lib.wkt_sp6(_p(n_), _p(h0), _p(p0), _p(h4), _p(p4), d0, _p(g), _p(h5), _p(q0s), _p(q4s), f)
        assert 0 <= nr <= 9
        assert min(_angle_gap(q0s[i], a) + _angle_gap(q4s[i], b) for i in range(nr)) < 1e-6


# ------------------------------------------------------------------------------------------------ dense numerics
def test_lstsq_and_spectrum_agree_with_numpy(lib):
    rng = case_rng(2206)
    for m, n in ((3, 3), (6, 6), (6, 7), (6, 4)):
        for _ in range(20):
            a, b = rng.normal(size=(m, n)), rng.normal(size=m)
            x = np.zeros(n)
            lib.wkt_lstsq(_p(a), m, n, _p(b), _p(x))
            assert np.allclose(x, np.linalg.lstsq(a, b, rcond=None)[0], atol=1e-10)
    # the polish's square solve: lstsq's answer to rounding times the conditioning; a (near) rank-deficient J is
    # refused (pivot below 1e-8 of the largest entry), for the SVD to decide
    for _ in range(40):
        a, b = rng.normal(size=(6, 6)), rng.normal(size=6)
        x = np.zeros(6)
        assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 1
        ref = np.linalg.lstsq(a, b, rcond=None)[0]
        assert np.max(np.abs(x - ref)) <= 1e-13 * np.linalg.cond(a) * max(1.0, np.max(np.abs(ref)))
    a[:, 5] = a[:, 4] * (1.0 + 1e-12)
    assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 0
    for n in (6, 7, 5):
        j = rng.normal(size=(6, n))
        ratio = np.zeros(1)
        man = lib.wkt_spectrum(_p(j), n, _p(ratio))
        s = np.linalg.svd(j, compute_uv=False)
        assert math.isclose(ratio[0], s[-1] / s[0], rel_tol=1e-10) and math.isclose(man, np.prod(s), rel_tol=1e-10)
    j = rng.normal(size=(6, 6))
    j[:, 5] = j[:, 4]  # rank 5: flagged singular by both readings
    man = np.zeros(1)
    assert lib.wkt_conditioning(_p(j), 6, _p(man)) == 3
    assert lib.wkt_conditioning(_p(rng.normal(size=(6, 6))), 6, _p(man)) == 0
    # the singular flag and the manipulability by the runtime's bounds (|det J| / ||J||_F^6 first for a square J,
    # then the Gram matrix's Cholesky factors, else the SVD): the SVD's verdict wherever the ratio is not within 2x
    # of SINGULAR_EPS (1e-6), the product of the singular values to 1e-9 (where the Gram matrix's Cholesky
    # factors read it, to its conditioning: eps (sigma_max / sigma_min)^2 relative)
    for ratio in np.geomspace(1e-10, 1.0, 41):
        u, _ = np.linalg.qr(rng.normal(size=(6, 6)))
        v, _ = np.linalg.qr(rng.normal(size=(6, 6)))
        s = np.sort(np.concatenate([[1.0, ratio], rng.uniform(ratio, 1.0, 4)]))[::-1] * rng.uniform(0.1, 3.0)
        j = u @ np.diag(s) @ v.T
        flag = lib.wkt_conditioning(_p(j), 6, _p(man))
        if not 0.5e-6 <= ratio <= 2e-6:
            assert (flag != 0) == (ratio <= 1e-6), ratio
        assert math.isclose(man[0], np.prod(s), rel_tol=1e-9 + 64 * np.finfo(float).eps / ratio**2), ratio


def test_the_conditioning_bound_decides_all_but_a_narrow_band_around_eps():
    """wk_conditioning_bound (the shared runtime) proves sigma_min / sigma_max above or below eps, or leaves it to the
    caller's SVD. Its verdicts are the SVD's wherever it gives one; since the bracket on lambda_max (power steps, then
    U I - G positive definite) it leaves undecided only ratios within ~3-30 % of eps = 1e-6 (was: a factor ~7, and the
    SVD took 2/3 of a near-singular call's time), whatever the spread of the other singular values."""
    so = compile_shared([RUNTIME_C], [ROOT / "runtime" / "c"], "wk_runtime_bound")
    lib = load(so)
    lib.wk_conditioning_bound.argtypes = [D, ctypes.c_int, ctypes.c_double, D]
    lib.wk_conditioning_bound.restype = ctypes.c_int
    rng = case_rng(2216)
    man = np.zeros(1)
    undecided = 0
    # the geometric sweep, then ratios within 10 % of eps, where a proven verdict must still be the SVD's (the margins
    # against the rounding of G's Cholesky factor)
    for ratio in np.concatenate([np.geomspace(1e-8, 1e-4, 161), [1e-6 * 0.87, 1e-6 * 1.13],
                                 np.linspace(0.9e-6, 1.1e-6, 81)]):
        for spread in (1.0, 0.3, 1e-2):
            u, _ = np.linalg.qr(rng.normal(size=(6, 6)))
            v, _ = np.linalg.qr(rng.normal(size=(6, 6)))
            s = np.sort(np.concatenate([[1.0, ratio], rng.uniform(max(ratio, spread), 1.0, 4)]))[::-1]
            j = u @ np.diag(s * rng.uniform(0.1, 3.0)) @ v.T
            got = lib.wk_conditioning_bound(_p(j), 6, 1e-6, _p(man))
            sv = np.linalg.svd(j, compute_uv=False)
            true = sv[-1] / sv[0]
            if got:
                assert (got < 0) == (true <= 1e-6), (ratio, spread, got)
            elif not 0.9e-6 <= ratio <= 1.1e-6:
                undecided += 1
                assert 0.97e-6 <= true <= 1.28e-6, (ratio, spread)
    assert undecided <= 16


def test_three_axes_read_a_rotation_as_the_orientation_op_and_the_arm_angle_do(lib, py):
    """ck_orient_rest / _orient_rest (the orientation op's reading of three units; the arm angle's core has its
    own, tested through test_arm_angle): from subproblem 2's (t1, t2) of R(u0, a0) R(u1, a1) R(u2, a2) = rd, the three
    angles rebuild rd (an independent product of axis-angle rotations), C equal to Python."""
    rng = case_rng(2216)
    out = np.zeros(3)
    for _ in range(50):
        u = np.array([_unit(rng) for _ in range(3)])
        a = rng.uniform(-math.pi, math.pi, 3)
        rd = _rot(u[0], a[0]) @ _rot(u[1], a[1]) @ _rot(u[2], a[2])
        for t1, t2, _f in py.sub._sp2(tuple(rd @ u[2]), tuple(u[0]), tuple(u[2]), tuple(u[1]), 1.0):
            angles = py.sub._orient_rest([tuple(v) for v in u], tuple(map(tuple, rd)), t1, t2)
            lib.wkt_orient_rest(_p(np.ascontiguousarray(u)), _p(np.ascontiguousarray(rd)), t1, t2, _p(out))
            assert np.allclose(out, angles, atol=1e-14)
            got = _rot(u[0], angles[0]) @ _rot(u[1], angles[1]) @ _rot(u[2], angles[2])
            assert np.max(np.abs(got - rd)) < 1e-12


def test_perpendicular_transpose_and_points(lib):
    rng = case_rng(2207)
    o = np.zeros(3)
    for _ in range(50):
        k = _unit(rng)
        lib.wkt_perpendicular(_p(k), _p(o))
        assert abs(o @ k) < 1e-14 and abs(np.linalg.norm(o) - 1) < 1e-14
    r = rng.normal(size=(3, 3))
    rt = np.zeros(9)
    lib.wkt_transpose(_p(r), _p(rt))
    assert np.array_equal(rt.reshape(3, 3), r.T)
    # axes 0 and 1 meet at c (CK_MEET = 1), a point on axis 2 (CK_ON = 2), the normal of axes 0 and 1 (CK_CROSS = 5)
    c = rng.normal(size=3)
    axes = np.array([_unit(rng), _unit(rng), _unit(rng)])
    points = np.array([c + 0.3 * axes[0], c - 0.2 * axes[1], rng.normal(size=3)])
    lib.wkt_meet_point(_p(axes), _p(points), 1, 0, 1, _p(o))
    assert np.allclose(o, c, atol=1e-12)
    lib.wkt_meet_point(_p(axes), _p(points), 2, 2, 0, _p(o))
    assert np.array_equal(o, points[2])
    lib.wkt_meet_point(_p(axes), _p(points), 5, 0, 1, _p(o))
    n = np.cross(axes[0], axes[1])
    assert np.allclose(o, n / np.linalg.norm(n), atol=1e-15)


# ------------------------------------------------------------------------------------------------ chains
def _chain(rng, n):
    kinds = np.array([1 if i == 1 else 0 for i in range(n)], dtype=np.int32)  # joint 1 a slide
    axes, points = np.array([_unit(rng) for _ in range(n)]), rng.normal(size=(n, 3))
    home = np.eye(4)
    home[:3, :3] = _rot(_unit(rng), 0.7)
    home[:3, 3] = rng.normal(size=3)
    return kinds, axes, points, home


def _poe(kinds, axes, points, home, q):
    t = np.eye(4)
    for kind, h, p, v in zip(kinds, axes, points, q, strict=True):
        e = np.eye(4)
        if kind:
            e[:3, 3] = h * v
        else:
            e[:3, :3] = _rot(h, v)
            e[:3, 3] = p - e[:3, :3] @ p
        t = t @ e
    return t @ home


def _args(kinds, axes, points, home):
    return (len(kinds), kinds.ctypes.data_as(IP), _p(axes), _p(points), _p(home[:3]))


def test_fk_jacobian_polish_and_chain_variants_against_a_numpy_product_of_exponentials(lib):
    rng = case_rng(2208)
    for _ in range(20):
        kinds, axes, points, home = _chain(rng, 6)
        args = _args(kinds, axes, points, home)
        q = rng.uniform(-math.pi, math.pi, 6)
        pose, jac = np.zeros(12), np.zeros(36)
        lib.wkt_fk(*args, _p(q), _p(pose))
        assert np.allclose(pose.reshape(3, 4), _poe(kinds, axes, points, home, q)[:3], atol=1e-13)
        lib.wkt_jacobian(*args, _p(q), _p(jac))
        h, num = 1e-6, np.zeros((6, 6))
        t0 = _poe(kinds, axes, points, home, q)
        for i in range(6):
            dq = np.zeros(6)
            dq[i] = h
            tp, tm = _poe(kinds, axes, points, home, q + dq), _poe(kinds, axes, points, home, q - dq)
            w = (tp[:3, :3] - tm[:3, :3]) / (2 * h) @ t0[:3, :3].T
            num[:, i] = np.concatenate([(tp[:3, 3] - tm[:3, 3]) / (2 * h), [w[2, 1], w[0, 2], w[1, 0]]])
        # the chain's Jacobian is at its last joint's frame origin... compare the angular rows, and the linear
        # ones through FK's own central differences at the end frame's origin (as tests/test_chain_robots.py)
        assert np.allclose(jac.reshape(6, 6)[3:], num[3:], atol=1e-7)
        # polish: from 1e-4 off the solution back onto the pose
        target = np.ascontiguousarray(t0[:3].ravel())
        q1 = q + rng.normal(scale=1e-4, size=6)
        err = lib.wkt_polish(*args, _p(q1), _p(target))
        assert err < 1e-12 and np.allclose(_poe(kinds, axes, points, home, q1), t0, atol=1e-12)
        # joint 2 (CK_FREE of the harness) held, read from the tool: the inverse of the full chain's end frame
        held = rng.uniform(-math.pi, math.pi)
        rest = np.delete(q, 2)
        lib.wkt_held_reversed_fk(*args, held, _p(rest[::-1].copy()), _p(pose))
        full = _poe(kinds, axes, points, home, np.insert(rest, 2, held))
        assert np.allclose(np.vstack([pose.reshape(3, 4), [0, 0, 0, 1]]), np.linalg.inv(full), atol=1e-12)


def test_spatial3_returns_the_generating_joints_among_its_roots(lib):
    rng = case_rng(2209)
    qa, qb, qc, f = np.zeros(12), np.zeros(12), np.zeros(12), (ctypes.c_uint * 12)()  # WK_S3_MAX
    for _ in range(40):
        axes, points = np.array([_unit(rng) for _ in range(3)]), rng.normal(size=(3, 3))
        q = rng.uniform(-math.pi, math.pi, 3)
        x = rng.normal(size=3)
        y = _poe(np.zeros(3, np.int32), axes, points, np.eye(4), q)[:3] @ np.append(x, 1.0)
        nr = lib.wkt_spatial3(_p(axes), _p(points), _p(x), _p(y), _p(qa), _p(qb), _p(qc), f)
        assert 1 <= nr <= 12
        for i in range(nr):
            t = _poe(np.zeros(3, np.int32), axes, points, np.eye(4), [qa[i], qb[i], qc[i]])
            assert np.allclose(t[:3] @ np.append(x, 1.0), y, atol=1e-7)
        assert min(sum(_angle_gap(u, v) for u, v in zip((qa[i], qb[i], qc[i]), q, strict=True))
                   for i in range(nr)) < 1e-6


# ------------------------------------------------------------------------------------------------ as files
def test_every_source_compiles_strictly_where_a_robot_includes_it(tmp_path, monkeypatch):
    """The robots' C with each runtime source #included by its path instead of inlined: every file (the interpreter
    and the entry points too) compiled as it is, with the switches of a subproblem-6 robot and a polynomial one."""
    sys.path.insert(0, str(ROOT / "tests"))
    from test_chain_c import SPECS

    monkeypatch.setitem(environment().globals, "runtime_source",
                        lambda rel: f'#include "{runtime_files.RUNTIME / rel}"' if rel.endswith((".c", ".h"))
                        else runtime_files.inline(rel))
    pipeline.emit_c_runtime(tmp_path)
    for name in ("ur_off", "skew3"):
        spec = tmp_path / f"{name}.toml"
        spec.write_text(SPECS[name])
        mech = load_spec(spec)
        pipeline.emit_solvers(name, mech, mech.kernels(mech.derive()), tmp_path, tmp_path)
        text = (tmp_path / f"{name}.c").read_text()
        assert f'#include "{CHAIN_C / "ck_interpreter.c"}"' in text
        r = subprocess.run([compiler(), "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-c",
                            str(tmp_path / f"{name}.c"), f"-I{tmp_path}", "-o", str(tmp_path / f"{name}.o")],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
    # an arm whose run-time parameter is its arm angle (ck_arm_angle.c); a held joint on a chain read from the tool
    # (the Panda's joint5: CK_REVERSED with CK_FREE, its spatial3 op)
    for name, path, options in (("iiwa_psi", "iiwa14/iiwa14.urdf", {"redundancy": "arm-angle"}),
                                ("panda_free5", "panda/panda_dh.toml", {"free": "joint5"})):
        mech = own_robot.load(ROOT / "tests" / "robots" / path, name=name, stages="interpreted", **options)
        pipeline.emit_solvers(name, mech, mech.kernels(mech.derive()), tmp_path, tmp_path)
        assert f'#include "{CHAIN_C / "ck_interpreter.c"}"' in (tmp_path / f"{name}.c").read_text()
        r = subprocess.run([compiler(), "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-c",
                            str(tmp_path / f"{name}.c"), f"-I{tmp_path}", "-o", str(tmp_path / f"{name}.o")],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
    assert f'#include "{CHAIN_C / "ck_arm_angle.c"}"' in (tmp_path / "iiwa_psi.c").read_text()


# ------------------------------------------------------------------------------------------------ Python sources
@pytest.fixture(scope="module")
def py():
    """The Python sources imported as they are (their imports above the inlining marker: each other and the
    stand-in robot, tests/test_chain_c.py's ur_t)."""
    sys.path.insert(0, str(ROOT / "runtime" / "python"))
    try:
        import chain_api
        import chain_sp6
        import chain_spatial3
        import chain_subproblems
        import chain_verify
    finally:
        sys.path.remove(str(ROOT / "runtime" / "python"))
    return type("Sources", (), {"sub": chain_subproblems, "sp6": chain_sp6, "spatial3": chain_spatial3,
                                "verify": chain_verify, "api": chain_api})


def test_the_python_square_step_is_the_c_one_to_the_bit(py, lib):
    """_runtime.solve_square is the shared C runtime's wk_square_solve step for step (the polish's square step in
    both languages, the chain's and the serial arms'): equal bits on random 6 x 6 systems, and both refuse a pivot at
    or below the relative threshold (the chain's 1e-8 of the largest entry)."""
    rng = case_rng(2215)
    x = np.zeros(6)
    solve = py.verify._runtime.solve_square
    for _ in range(100):
        a, b = rng.normal(size=(6, 6)) * rng.uniform(1e-3, 1e3), rng.normal(size=6)
        assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 1
        assert solve(a, b, 1e-8) == list(x)
    a[:, 5] = a[:, 4] * (1.0 + 1e-12)
    assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 0 and solve(a, b, 1e-8) is None
    a[:, 5] = 0.0  # a held joint's zeroed column
    assert solve(a, b, 1e-6) is None


def test_one_lu_solves_each_right_hand_side_as_the_square_step_does(lib):
    """wk_lu_factor once, then wk_lu_solve per right-hand side (a calibrated arm's chord steps, and its wrist mirror's
    step on the same LU): each solution the bits of wk_square_solve's on that side (the same operations in the same
    order), and a solution of the system (numpy's, to the conditioning: 1e-13 * cond relative); both refuse the same
    near-singular matrix."""
    rng = case_rng(2216)
    x1, xs = np.zeros(6), np.zeros((4, 6))
    for _ in range(50):
        a, b = rng.normal(size=(6, 6)) * rng.uniform(1e-3, 1e3), rng.normal(size=(4, 6))
        assert lib.wkt_lu_solve_many(_p(a), 6, _p(b), 4, _p(xs)) == 1
        for i in range(4):
            assert lib.wkt_solve_square(_p(a), 6, _p(b[i]), _p(x1)) == 1 and list(xs[i]) == list(x1)
            ref = np.linalg.solve(a, b[i])
            assert np.max(np.abs(xs[i] - ref)) <= 1e-13 * np.linalg.cond(a) * np.max(np.abs(ref))
    a[:, 5] = a[:, 4] * (1.0 + 1e-12)
    assert lib.wkt_lu_solve_many(_p(a), 6, _p(b), 4, _p(xs)) == 0 and lib.wkt_solve_square(_p(a), 6, _p(b[0]),
                                                                                          _p(x1)) == 0


def test_python_subproblems_return_the_generating_angles_and_c_s_roots(py, lib):
    """The Python kernels on the instances of the C tests: the generating angles among their roots, and the same
    roots as the C kernels (one algorithm in both, operation for operation: equal to a few ulps)."""
    rng = case_rng(2210)
    t, f = np.zeros(2), (ctypes.c_uint * 2)()
    t1, t2, has1 = np.zeros(2), np.zeros(2), (ctypes.c_int * 2)()
    for _ in range(200):
        k, h, p1, p2 = _unit(rng), _unit(rng), rng.normal(size=3), rng.normal(size=3)
        t0 = rng.uniform(-math.pi, math.pi)
        assert _angle_gap(py.sub._sp1(k, p1, _rot(k, t0) @ p1, 1.0), t0) < 1e-9
        d = float(np.linalg.norm(_rot(k, t0) @ p1 - p2))
        roots = py.sub._sp3(list(k), list(p1), list(p2), d, 1.0)
        n = lib.wkt_sp3(_p(k), _p(p1), _p(p2), d, _p(t), f)
        assert len(roots) == n and all(abs(r[0] - c) < 1e-13 and r[1] == fc
                                       for r, c, fc in zip(roots, t, f, strict=False))
        assert min(_angle_gap(r[0], t0) for r in roots) < _allowance([roots[0][1]], len(roots))
        e = float(h @ _rot(k, t0) @ p1)
        roots = py.sub._sp4(list(h), list(k), list(p1), e, 1.0)
        n = lib.wkt_sp4(_p(h), _p(k), _p(p1), e, _p(t), f)
        assert len(roots) == n and all(abs(r[0] - c) < 1e-13 for r, c in zip(roots, t, strict=False))
        k2 = _unit(rng)
        b = rng.uniform(-math.pi, math.pi)
        q2 = _rot(k2, b).T @ (_rot(k, t0) @ p1)
        pairs = py.sub._sp2(list(p1), list(k), list(q2), list(k2), 1.0)
        n = lib.wkt_sp2(_p(p1), _p(k), _p(q2), _p(k2), 0, _p(t1), has1, _p(t2), f)
        assert len(pairs) == n
        assert all(abs(a - c1) < 1e-12 and abs(bb - c2) < 1e-12
                   for (a, bb, _), c1, c2 in zip(pairs, t1, t2, strict=False))


def test_python_sp6_and_spatial3_agree_with_c(py, lib):
    rng = case_rng(2211)
    q0s, q4s, f = np.zeros(17), np.zeros(17), (ctypes.c_uint * 17)()  # CK_SP6_MAX
    for _ in range(40):
        n_, h0, h4, h5 = _unit(rng), _unit(rng), _unit(rng), _unit(rng)
        p0, p4 = rng.normal(size=3), rng.normal(size=3)
        a, b = rng.uniform(-math.pi, math.pi, 2)
        d0 = float(n_ @ _rot(h0, -a) @ p0 - n_ @ _rot(h4, b) @ p4)
        g = _rot(h0, a) @ _rot(h4, b) @ h5
        out = py.sp6._sp6(*(list(v) for v in (n_, h0, p0, h4, p4)), d0, 0.0, list(g), list(h5))
        nr = lib.wkt_sp6(_p(n_), _p(h0), _p(p0), _p(h4), _p(p4), d0, _p(g), _p(h5), _p(q0s), _p(q4s), f)
        assert len(out) == nr
        assert all(_angle_gap(x, c0) < 1e-12 and _angle_gap(y, c4) < 1e-12 for (x, y, _, _), c0, c4 in
                   zip(out, q0s, q4s, strict=False))
        assert min(_angle_gap(x, a) + _angle_gap(y, b) for x, y, _, _ in out) < 1e-6


def _sp6_split_allowance(n_, h0, p0, h4, p4, d0, g, h5, a, b):
    """What the split's root at the true (a, b) may be off, from the conditioning there: the first equation (metres)
    and the second read on its parts normal to n, |n x w0|^2 - |n x z5|^2 (~delta, each read to eps), each scaled
    to a distance by its gradient, then through the inverse of the two unit gradients (kappa: large where the two
    curves cross at a small angle; where they touch the pair merges, a double root, read to sqrt(eps))."""
    eps = np.finfo(float).eps
    w, z4 = _rot(h0, -a) @ p0, _rot(h4, b) @ p4
    w0, z5 = _rot(h0, -a) @ g, _rot(h4, b) @ h5
    u, r = np.cross(n_, w0), np.cross(n_, z5)
    g1 = np.array([-n_ @ np.cross(h0, w), -n_ @ np.cross(h4, z4)])
    g2 = 2.0 * np.array([-u @ np.cross(n_, np.cross(h0, w0)), -r @ np.cross(n_, np.cross(h4, z5))])
    scale = max(np.linalg.norm(p0), np.linalg.norm(p4), abs(d0))
    kappa = 1.0 / np.linalg.svd(np.array([g1 / np.linalg.norm(g1), g2 / np.linalg.norm(g2)]), compute_uv=False)[-1]
    reach = max(scale / np.linalg.norm(g1), np.linalg.norm(u) / np.linalg.norm(g2))
    return eps * kappa * reach, math.sqrt(eps) * reach  # a simple root, a merged (double) one


def test_the_sp6_split_resolves_a_near_wrist_pair_to_eps(lib, py):
    """Subproblem 6 with joint 5 delta = 1e-5 .. 1e-12 off the wrist singularity (h5 and n normal to h4, so
    rot(h4, q4*) h5 = n at one q4*; the split is called up to ~1e-6, where the quartic merges the pair or the
    singular candidate's |n x w| is below sqrt(DOUBLE_ROOT_TOL)): from the singular point (a, q4*) the split
    returns the generating (a, q4* + delta) among its two roots within 16 x the conditioning's allowance (seen:
    4.9 x over 250 seeds; the quartic alone: sqrt(eps)); where the two curves touch it returns the merged pair,
    one root, within 16 sqrt(eps) x the same scale (a double root's accuracy). C returns Python's roots."""
    rng = case_rng(2217)
    s0, s4 = np.zeros(2), np.zeros(2)
    for i in range(40):
        h4 = _unit(rng)
        n_ = np.cross(h4, _unit(rng))
        n_ /= np.linalg.norm(n_)
        h5 = _rot(h4, rng.uniform(-math.pi, math.pi)) @ n_  # normal to h4: some q4* turns it onto n
        q4s = math.atan2(float(h4 @ np.cross(h5, n_)), float(h5 @ n_))
        h0, p0, p4 = _unit(rng), rng.normal(size=3), rng.normal(size=3)
        a, delta = rng.uniform(-math.pi, math.pi), (1.0 if i % 2 else -1.0) * 10.0 ** -(5 + i % 8)
        b = q4s + delta
        d0 = float(n_ @ _rot(h0, -a) @ p0 - n_ @ _rot(h4, b) @ p4)
        g = _rot(h0, a) @ _rot(h4, b) @ h5
        args = [list(v) for v in (n_, h0, p0, h4, p4)] + [d0, list(g), list(h5)]
        out = py.sp6._sp6_split(*args[:6], *args[6:], a, q4s, py.sp6.SP6_TOLS)
        nc = lib.wkt_sp6_split(_p(n_), _p(h0), _p(p0), _p(h4), _p(p4), d0, _p(g), _p(h5), a, q4s, _p(s0), _p(s4))
        assert nc == len(out) and len(out) in (1, 2), (i, delta)
        allowance = 16.0 * _sp6_split_allowance(n_, h0, p0, h4, p4, d0, g, h5, a, b)[len(out) == 1]
        assert min(_angle_gap(x, a) + _angle_gap(y, b) for x, y in out) <= allowance, (i, delta, out, allowance)
        assert all(_angle_gap(x, c0) <= 1e-13 and _angle_gap(y, c4) <= 1e-13
                   for (x, y), c0, c4 in zip(out, s0[:nc], s4[:nc], strict=True))


def test_the_api_source_solves_the_stand_in_robot(py):
    """chain_api.py with the stand-in robot (a UR5e type): every round trip returns its generating joints, verified
    on FK, and a singular wrist (q5 = 0) is returned as a flagged family member (status indeterminate)."""
    rng = case_rng(2212)
    api = py.api
    for _ in range(20):
        q = rng.uniform(-math.pi, math.pi, 6)
        sol = api.ik(api.fk_matrix(q))
        assert sol.status == api.STATUS_OK and 1 <= sol.count <= api.MAX_IK
        assert min(float(np.max(np.abs([_angle_gap(a, b) for a, b in zip(v, q, strict=True)]))) for v in sol) < 1e-9
        assert all(np.max(np.abs(api.fk_matrix(v) - api.fk_matrix(q))) < 1e-9 for v in sol)
    q = rng.uniform(-math.pi, math.pi, 6)
    q[4] = 0.0
    sol = api.ik(api.fk_matrix(q))
    assert sol.status == api.STATUS_INDETERMINATE
    assert any(fl & api.FLAG_SINGULAR_INVERSE and fl & api.FLAG_INDETERMINATE for fl in sol.flags[:sol.count])


# ------------------------------------------------------------------------------------------------ the plan's view
@pytest.mark.parametrize("name", ["puma_t", "ur_t", "skew3", "ur_off"])
def test_the_stages_of_a_plan_set_every_joint_and_print_ck_op_rows(name, tmp_path):
    """derive/families/chain/stages.py: every op of the planner's decomposition is a Stage; together they set every
    joint of the solver's chain, and each prints one ck_op initializer of its 15 fields."""
    sys.path.insert(0, str(ROOT / "tests"))
    from test_chain_c import SPECS

    from derive.families.chain.stages import stage

    spec = tmp_path / f"{name}.toml"
    spec.write_text(SPECS[name])
    mech = load_spec(spec)
    plan, _ = mech.plan()
    solver = mech.solver_chain(mech.chain, 0.0, plan.reversed)
    stages = [stage(i, op) for i, op in enumerate(plan.ops)]
    assert [s.op for s in stages] == [op["op"] for op in plan.ops]
    assert {j for s in stages for j in s.solved} == set(range(solver.n))
    for s in stages:
        row = s.c_row()
        # 15 fields at the top level of the initializer (braces nest the arrays)
        depth, fields = 0, 1
        for ch in row:
            depth += (ch == "{") - (ch == "}")
            fields += ch == "," and depth == 0
        assert depth == 0 and fields == 15, row


def test_the_jacobi_smallest_eigenpair_is_lapack_s(lib):
    """wk_jacobi_smallest (a calibrated arm's near-null direction: sr_along_null) against LAPACK's eigh on Gram
    matrices J^T J of 6 x n Jacobians, n = 1 .. 6, with sigma_min / sigma_max from 1 down to 1e-10 (J^T J's smallest
    eigenvalue then below its rounding): the eigenvalue to eps |G| n, the eigenvector to eps |G| n / gap (the gap to
    the next eigenvalue; its sign free), unit length; a bad n gives -1 and leaves v alone."""
    lib.wk_jacobi_smallest.argtypes = [D, ctypes.c_int, D]
    lib.wk_jacobi_smallest.restype = ctypes.c_double
    rng = case_rng(2341)
    eps = np.finfo(float).eps
    for n in range(1, 7):
        for ratio in (1.0, 1e-3, 1e-6, 1e-10):
            u, _ = np.linalg.qr(rng.normal(size=(6, 6)))
            w, _ = np.linalg.qr(rng.normal(size=(n, n)))
            sigma = np.sort(rng.uniform(0.2, 2.0, n))[::-1]
            sigma[-1] = sigma[0] * ratio if n > 1 else sigma[-1]
            jac = u[:, :n] @ np.diag(sigma) @ w.T
            g = jac.T @ jac
            vals, vecs = np.linalg.eigh(g)
            v = np.zeros(n)
            low = lib.wk_jacobi_smallest(_p(g.copy()), n, _p(v))
            scale = np.linalg.norm(g, 2) * n
            assert abs(low - vals[0]) <= 8 * eps * scale, (n, ratio)
            assert abs(np.linalg.norm(v) - 1.0) <= 8 * eps * n
            if n > 1:
                assert 1.0 - abs(float(v @ vecs[:, 0])) <= 8 * eps * scale / (vals[1] - vals[0]), (n, ratio)
    v = np.full(2, 7.0)
    assert lib.wk_jacobi_smallest(_p(np.eye(9)), 9, _p(v)) == -1.0 and lib.wk_jacobi_smallest(_p(np.eye(2)), 0,
                                                                                                _p(v)) == -1.0
    assert list(v) == [7.0, 7.0]
