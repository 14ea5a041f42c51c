"""The spatial 3R's core (runtime/c/wk_spatial3.c, runtime/python/spatial3.py) tested as it is, on random lines whose
answer is known by construction (numpy's rotation matrices here, never the generated code): the generating joints
among the candidates, at most four distinct ones (Pieper's bound), every candidate on the point, and C equal to
Python."""

from __future__ import annotations

import ctypes
import hashlib
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from cbuild import RUNTIME_C, compile_shared, load
from seeding import case_rng

from derive.tolerances import TOLERANCES

ROOT = Path(__file__).resolve().parent.parent
D = ctypes.POINTER(ctypes.c_double)
U = ctypes.POINTER(ctypes.c_uint)
MAX = 12  # WK_S3_MAX
FLAG_INDETERMINATE = 16
ON_AXIS = float(TOLERANCES["on_axis"])  # the derived solvers' on-axis band, 64 eps


def _rot(k, t):
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(t) * kx + (1 - math.cos(t)) * kx @ kx


def _place(h, r, q, x):
    """rot_a rot_b rot_c x by 3 x 3 rotation matrices about the lines (h_i, r_i)."""
    p = np.asarray(x, float)
    for i in (2, 1, 0):
        p = r[i] + _rot(h[i], q[i]) @ (p - r[i])
    return p


def _smin(h, r, q, x):
    """sigma_min of the point's Jacobian in (q_a, q_b, q_c): columns h_i x (p - r_i) of the lines the joints before
    each moved."""
    p, cols, rot, off = _place(h, r, q, x), [], np.eye(3), np.zeros(3)
    for i in range(3):
        hi, ri = rot @ h[i], rot @ r[i] + off
        cols.append(np.cross(hi, p - ri))
        turn = _rot(h[i], q[i])
        rot, off = rot @ turn, rot @ (r[i] - turn @ r[i]) + off
    return np.linalg.svd(np.array(cols).T, compute_uv=False)[-1]


def _gap(a, b):
    return max(abs(math.remainder(u - v, 2 * math.pi)) for u, v in zip(a, b, strict=True))


def _p(a):
    return np.ascontiguousarray(a, dtype=float).ctypes.data_as(D)


@pytest.fixture(scope="module")
def lib():
    sources = [ROOT / "runtime" / "c" / n
               for n in ("poly_real_roots.c", "wk_poly_ops.c", "wk_geom3.c", "wk_spatial3.c")]
    h = hashlib.sha256(b"".join(p.read_bytes() for p in sources)).hexdigest()[:16]  # included: name the build
    so = compile_shared([ROOT / "tests" / "c" / "spatial3_harness.c", RUNTIME_C], [ROOT / "runtime" / "c"], "spatial3",
                        extra_flags=[f"-DWKT_SOURCES={h}"])
    L = load(so)
    L.wkt_spatial3_lines.argtypes = [D, D, D, D, ctypes.c_double, ctypes.c_double, ctypes.c_double, D, U]
    return L


@pytest.fixture(scope="module")
def py():
    sys.path.insert(0, str(ROOT / "runtime" / "python"))
    try:
        import spatial3
    finally:
        sys.path.remove(str(ROOT / "runtime" / "python"))
    return spatial3


def _c(lib, h, r, x, y, scale=1.0):
    q, f = np.zeros((MAX, 3)), (ctypes.c_uint * MAX)()
    n = lib.wkt_spatial3_lines(_p(h), _p(r), _p(x), _p(y), scale, 1e-12, ON_AXIS, _p(q), f)
    return [(tuple(q[i]), f[i]) for i in range(n)]


def test_random_lines_give_the_generating_joints_and_at_most_four_positions(lib, py):
    """400 random 3R instances: the generating joints among the candidates (1e-9 + 1e-13 / sigma_min of the point's
    Jacobian: two Newton steps leave a simple root at the point's rounding over sigma_min), every candidate places x on
    y (1e-9 m), at most four distinct positions, C's candidates Python's to 1e-12 + 1e-14 / sigma_min (the same
    operations; libm's last bit may differ)."""
    rng = case_rng(2320)
    for _ in range(400):
        h = np.array([v / np.linalg.norm(v) for v in rng.normal(size=(3, 3))])
        r, x = rng.normal(size=(3, 3)) * 0.4, rng.normal(size=3) * 0.4
        q = rng.uniform(-math.pi, math.pi, 3)
        y = _place(h, r, q, x)
        c = _c(lib, h, r, x, y)
        p = py._spatial3_lines([tuple(v) for v in h], [tuple(v) for v in r], tuple(x), tuple(y), 1.0, 1e-12, ON_AXIS)
        assert 1 <= len(c) <= 4 and len(c) == len(p)
        smin = _smin(h, r, q, x)
        assert min(_gap(cand, q) for cand, _ in c) <= 1e-9 + 1e-13 / smin
        assert all(np.max(np.abs(_place(h, r, cand, x) - y)) <= 1e-9 for cand, _ in c)
        assert all(_gap(a, b) <= 1e-12 + 1e-14 / smin and fa == fb for (a, fa), (b, fb) in zip(c, p, strict=True))


@pytest.mark.parametrize("sense", [1.0, -1.0])
def test_first_and_last_axes_parallel_give_every_solution(lib, py, sense):
    """Axes a and c parallel (a 5R arm's j5 and j3 read from the tool): the distance and component equations are
    one equation in q_c at every q_b, and the general polynomial (nc^2 + ns^2 - det^2 with det = 0) has only double
    roots, from which the candidates were never read (every reachable pose reported unreachable). 60 random
    instances, each against a 24-start least-squares reference (scipy, on numpy's rotation matrices): no solution
    missed, every candidate on the point (1e-9 m), at most four distinct, C equal to Python."""
    from scipy.optimize import least_squares

    rng = case_rng(2322)
    for _ in range(60):
        h = np.array([v / np.linalg.norm(v) for v in rng.normal(size=(3, 3))])
        h[2] = sense * h[0]
        r, x = rng.normal(size=(3, 3)) * 0.4, rng.normal(size=3) * 0.4
        q = rng.uniform(-math.pi, math.pi, 3)
        y = _place(h, r, q, x)
        c = _c(lib, h, r, x, y)
        p = py._spatial3_lines([tuple(v) for v in h], [tuple(v) for v in r], tuple(x), tuple(y), 1.0, 1e-12, ON_AXIS)
        assert 1 <= len(c) <= 4 and len(c) == len(p)
        assert all(np.max(np.abs(_place(h, r, cand, x) - y)) <= 1e-9 for cand, _ in c)
        smin = _smin(h, r, q, x)
        assert all(_gap(a, b) <= 1e-12 + 1e-14 / smin and fa == fb for (a, fa), (b, fb) in zip(c, p, strict=True))
        for _start in range(24):
            fit = least_squares(lambda v, h=h, r=r, x=x, y=y: _place(h, r, v, x) - y,
                                rng.uniform(-math.pi, math.pi, 3), xtol=1e-15, ftol=1e-15, gtol=1e-15)
            res = float(np.max(np.abs(fit.fun)))
            if res <= 1e-11:  # a solution: among the candidates, within both residuals over sigma_min
                assert min(_gap(cand, fit.x) for cand, _ in c) <= 1e-9 + (1e-13 + res) / _smin(h, r, fit.x, x)


def test_a_point_on_the_first_axis_leaves_that_joint_undetermined(lib, py):
    """y on axis a (and x placed there by b and c): every turn of a keeps it, so q_a is flagged indeterminate (0)
    and q_b, q_c still place the point."""
    rng = case_rng(2321)
    h = np.array([v / np.linalg.norm(v) for v in rng.normal(size=(3, 3))])
    r, x = rng.normal(size=(3, 3)) * 0.4, rng.normal(size=3) * 0.4
    q = np.array([0.0, 0.7, -1.1])
    y = _place(h, r, q, x)
    r[0] = y - 0.3 * h[0]  # axis a through y: rot_a keeps y
    for cands in (_c(lib, h, r, x, y),
                  py._spatial3_lines([tuple(v) for v in h], [tuple(v) for v in r], tuple(x), tuple(y), 1.0, 1e-12,
                                     ON_AXIS)):
        assert cands and all(f & FLAG_INDETERMINATE and cand[0] == 0.0 for cand, f in cands)
        assert min(_gap(cand[1:], q[1:]) for cand, _ in cands) <= 1e-9


@pytest.mark.parametrize("rho", [1e-5, 1e-7, 1e-9, 1e-11, 1e-13])
def test_a_target_near_the_first_axis_splits_the_merged_pair(lib, py, rho):
    """The target rho from axis a: the image w = rot_b rot_c x lies on a circle of radius rho about that axis, which
    the surface w(q_b, q_c) crosses twice close together, so the polynomial's two roots merge below its resolution
    (flagged double) or come out a hair apart, each to its sqrt(eps) with its image near the axis, where q_a is
    noise. Split (from the merged root, or the near pair's midpoint, along the surface's line through the circle:
    starts on the surface and the circle; damped Newton from both), the generating joints are among the candidates
    (1e-9 + 1e-13 / sigma_min), in C and Python, down to 1e-13 (the emitted on-axis band is 64 eps). Measured,
    random seeds, 1,000 poses per rho from 1e-5 to 1e-13 and 300 at 1e-15: none missed, C = Python. Before the
    starts moved onto the surface and near pairs were split: 17 and 51 of 1,000 missed at 1e-9 and 1e-11;
    unsplit: 10, 134, 199 and 187 of 200 at 1e-5, 1e-7, 1e-9, 1e-11."""
    rng = case_rng(2322)
    for _ in range(100):
        h = np.array([v / np.linalg.norm(v) for v in rng.normal(size=(3, 3))])
        r, x = rng.normal(size=(3, 3)) * 0.4, rng.normal(size=3) * 0.4
        q = rng.uniform(-math.pi, math.pi, 3)
        w = r[1] + _rot(h[1], q[1]) @ (r[2] + _rot(h[2], q[2]) @ (x - r[2]) - r[1])
        e = np.cross(h[0], rng.normal(size=3))
        r[0] = w - rho * e / np.linalg.norm(e) + rng.normal() * h[0]  # axis a rho from w
        y = _place(h, r, q, x)
        allowance = 1e-9 + 1e-13 / _smin(h, r, q, x)
        for cands in (_c(lib, h, r, x, y), py._spatial3_lines([tuple(v) for v in h], [tuple(v) for v in r],
                                                               tuple(x), tuple(y), 1.0, 1e-12, ON_AXIS)):
            assert len(cands) <= 4 and min(_gap(cand, q) for cand, _ in cands) <= allowance
            assert all(np.max(np.abs(_place(h, r, cand, x) - y)) <= 1e-9 for cand, _ in cands)


def test_the_polynomials_rounding_is_within_the_touch_bound(py, monkeypatch):
    """The touch tolerance's contract: every coefficient of the polynomial as computed in doubles is within S3_ROUNDING
    eps of its terms' sizes of the same polynomial computed exactly (mpmath at 40 digits, from the same double inputs),
    on 80 random instances: general lines with the target from 1e-13 to 1 off axis a, and axes a and c parallel."""
    import mpmath

    mpmath.mp.dps = 40
    seen = {}
    monkeypatch.setattr(py, "_s3_touch_tol", lambda poly, terms: seen.update(poly=poly, terms=terms) or 1e-12)
    monkeypatch.setattr(py, "_poly_real_roots", lambda poly, tol=None: ([], [], 0))  # the polynomial only
    rng = case_rng(2323)
    for k in range(80):
        h = np.array([v / np.linalg.norm(v) for v in rng.normal(size=(3, 3))])
        r, x = rng.normal(size=(3, 3)) * 0.4, rng.normal(size=3) * 0.4
        q = rng.uniform(-math.pi, math.pi, 3)
        if k % 4 == 3:
            h[2] = h[0] * (1.0 if k % 8 == 3 else -1.0)
        else:
            w = r[1] + _rot(h[1], q[1]) @ (r[2] + _rot(h[2], q[2]) @ (x - r[2]) - r[1])
            e = np.cross(h[0], rng.normal(size=3))
            r[0] = w - 10.0 ** rng.uniform(-13, 0) * e / np.linalg.norm(e) + rng.normal() * h[0]
        y = _place(h, r, q, x)
        polys = []
        for num in (float, mpmath.mpf):
            py._spatial3_lines([tuple(num(c) for c in v) for v in h], [tuple(num(c) for c in v) for v in r],
                               tuple(num(c) for c in x), tuple(num(c) for c in y), 1.0, 1e-12, ON_AXIS)
            polys.append((seen["poly"], seen["terms"]))
        (double, terms), (exact, _) = polys
        bound = [py.S3_ROUNDING * py._POLY_EPS * t for t in terms]
        assert all(abs(float(a - b)) <= e for a, b, e in zip(double, exact, bound, strict=True))


def test_a_pair_merged_under_the_polynomials_rounding_is_found(lib, py):
    """A target 1e-11 from axis a (from seed 327992 under OpenBLAS's Haswell kernels, the inputs to the bit): the two
    roots the target makes merge, and the exact polynomial of these doubles has a complex pair (Im 1.9e-7, min
    6e-18); as computed, cancellation in nc^2 + ns^2 - det^2 left its coefficients 7e-12 off (relative), its minimum
    1.3e-12 of its norm, over the root finder's default 1e-12, so no root was reported and the pose came back
    unreachable. With the touch tolerance from the polynomial's own rounding it is a touching root, split: the
    generating joints among the candidates (1e-9 + 1e-13 / sigma_min), in C and Python."""
    v = [float.fromhex(c) for c in (
        "0x1.c7ca11334e80ep-3", "0x1.6c4097a56efdbp-3", "0x1.eac855de4235bp-1", "-0x1.408c1e8e1b633p-4",
        "0x1.780f153369fa6p-1", "0x1.5922939444226p-1", "0x1.f19a096ac6afcp-2", "-0x1.692faf5c96e0fp-4",
        "-0x1.bd3368c7fd3cep-1", "-0x1.75f7ae4617f92p-3", "0x1.e43e8a42a4b5cp-3", "-0x1.19696547dd96ap+1",
        "0x1.56b2a556be3e6p-2", "0x1.23f7f07c689b7p-1", "-0x1.e8db90824535dp-4", "0x1.2de87ae034cf8p-3",
        "0x1.a8c174f754cefp-3", "-0x1.daa4c2221106dp-3", "0x1.f2a0ef8110b04p-2", "0x1.4422d98c35351p-5",
        "0x1.a83b7e3d035dfp-4", "0x1.45750e9cd4c95p-2", "0x1.45d308008f75dp-1", "-0x1.61457464572c0p-5",
        "0x1.c6a75172116d0p+0", "-0x1.46bc287ca53fcp+0", "-0x1.64e72d154cafdp+0")]
    h, r = np.array(v[:9]).reshape(3, 3), np.array(v[9:18]).reshape(3, 3)
    x, y, q = np.array(v[18:21]), np.array(v[21:24]), np.array(v[24:27])
    assert np.max(np.abs(_place(h, r, q, x) - y)) <= 1e-15  # the pose is the joints' (to rounding)
    allowance = 1e-9 + 1e-13 / _smin(h, r, q, x)
    for cands in (_c(lib, h, r, x, y), py._spatial3_lines([tuple(v) for v in h], [tuple(v) for v in r], tuple(x),
                                                          tuple(y), 1.0, 1e-12, ON_AXIS)):
        assert cands and min(_gap(cand, q) for cand, _ in cands) <= allowance
        assert all(np.max(np.abs(_place(h, r, cand, x) - y)) <= 1e-9 for cand, _ in cands)
