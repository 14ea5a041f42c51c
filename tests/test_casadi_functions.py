"""CasADi functions of the underactuated wrist (derive/to_casadi.py) against an independent numpy model.

The numpy model below is built only from rotation matrices (docs/API.md, module docstrings):
    B_i = Rz(delta_i) Rx(pi - beta1),  Zi1 = B_i e_z,  Zi2(t) = B_i Rz(t) Rx(alpha1) e_z,
    p_i = Rz(delta_i) Rx(beta2) e_z,   Zi3 = R p_i,    R = Rz(psi) Rx(theta) Rz(phi),
    loop i: Zi2(theta_i) . Zi3 - cos(alpha2).
It never touches the kernels; derivatives are checked by finite differences.
"""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
import sympy as sp
from seeding import case_rng

from derive import to_casadi as tc
from derive.mechanisms import underactuated_wrist as uw

DELTAS = (0.0, 2 * math.pi / 3, 4 * math.pi / 3)
PAPER = np.radians([60.0, 60.0, 30.0, 43.89])
EZ = np.array([0.0, 0.0, 1.0])


# ------------------------------------------------------------------------------ fixtures
@pytest.fixture(scope="session")
def dv():
    return uw.derive()


@pytest.fixture(scope="session")
def kernels(dv):
    return uw.kernels(dv)


@pytest.fixture(scope="session")
def fns(dv, kernels):
    return tc.casadi_functions(dv, kernels)


# ------------------------------------------------------------------------------ numpy model
def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0], [0, 0, 1]])


def rot(e):
    return rz(e[0]) @ rx(e[1]) @ rz(e[2])


def skew(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def expm_so3(w):
    th = float(np.linalg.norm(w))
    K = skew(w)
    if th < 1e-12:
        return np.eye(3) + K
    return np.eye(3) + math.sin(th) / th * K + (1 - math.cos(th)) / th**2 * K @ K


def axes(q, R, p):
    a1, _, b1, b2 = p
    Bi = [rz(d) @ rx(math.pi - b1) for d in DELTAS]
    z1 = np.array([B @ EZ for B in Bi])
    z2 = np.array([Bi[i] @ rz(q[i]) @ rx(a1) @ EZ for i in range(3)])
    z3 = np.array([R @ rz(d) @ rx(b2) @ EZ for d in DELTAS])
    return z1, z2, z3


def loop_np(q, R, p):
    _, z2, z3 = axes(q, R, p)
    return np.einsum("ij,ij->i", z2, z3) - math.cos(p[1])


def abc_np(R, p):
    """A, B, C of g_i(t) = A cos t + B sin t + C from samples of the numpy loop (no kernels)."""
    g0, gpi = loop_np([0.0] * 3, R, p), loop_np([math.pi] * 3, R, p)
    gp, gm = loop_np([math.pi / 2] * 3, R, p), loop_np([-math.pi / 2] * 3, R, p)
    return (g0 - gpi) / 2, (gp - gm) / 2, (g0 + gpi) / 2


def ik_np(R, p, sigma):
    A, B, C = abc_np(R, p)
    return np.arctan2(B, A) + np.asarray(sigma) * np.arccos(-C / np.hypot(A, B))


def margin_np(R, p):
    A, B, C = abc_np(R, p)
    return float(np.min(np.hypot(A, B) - np.abs(C)))


def call(f, *args):
    out = f(*args)
    out = out if isinstance(out, tuple) else (out,)
    return [np.array(o, dtype=float) for o in out]


def rand_design(rng):
    return np.array([rng.uniform(0.5, 2.4), rng.uniform(0.5, 2.4), rng.uniform(0.1, 1.3),
                     rng.uniform(0.2, 1.3)])


def reachable_samples(rng, n, min_margin=0.05, max_tries=20000):
    """(design, pose) pairs, every branch reachable by at least `min_margin`, 0.2 < theta < 1.2."""
    out = []
    for k in range(max_tries):
        p = PAPER if k % 2 == 0 else rand_design(rng)
        e = np.array([rng.uniform(-math.pi, math.pi), rng.uniform(0.2, 1.2), rng.uniform(-math.pi, math.pi)])
        if margin_np(rot(e), p) > min_margin:
            out.append((p, e))
            if len(out) == n:
                return out
    raise AssertionError("not enough reachable samples")


def d1(f, x, h):
    """5-point central first derivative of f at x (f returns arrays)."""
    return (f(x - 2 * h) - 8 * f(x - h) + 8 * f(x + h) - f(x + 2 * h)) / (12 * h)


def d2(f, x, h):
    """5-point central second derivative."""
    return (-f(x - 2 * h) + 16 * f(x - h) - 30 * f(x) + 16 * f(x + h) - f(x + 2 * h)) / (12 * h * h)


# ------------------------------------------------------------------------------ to_sx
def test_to_sx_numbers_powers_functions():
    x, y, z = sp.symbols("x y z", real=True)
    X, Y, Z = (ca.SX.sym(n) for n in "XYZ")
    exprs = [x**2, x**-3, sp.sqrt(x), x ** sp.Rational(-1, 2), x ** sp.Rational(3, 2),
             x ** sp.Rational(-5, 2), x ** sp.Rational(7, 2), x ** sp.Rational(1, 3), sp.pi * x / 3,
             sp.Float(1.25) * y - 2 * x / 7,
             sp.atan2(y, x), sp.acos(x / 2), sp.asin(x / 3), sp.atan(y), sp.tan(z), -x * y / (3 * z**2),
             sp.sqrt(3) / 2 * x, x**y, sp.exp(x), sp.E**y, sp.log(z), sp.Abs(x - y), sp.Max(x, y, z),
             sp.Min(x, y), sp.Piecewise((x, x > 1), (y, True)), sp.Integer(5), sp.Rational(1, 3), -sp.pi,
             1 / (x + y) - x / (y - z), sp.cosh(y) * sp.sinh(x), sp.sign(y)]
    f_np = sp.lambdify((x, y, z), exprs, "math")
    sx = tc.to_sx(exprs, {x: X, y: Y, z: Z})
    assert sx.shape == (len(exprs), 1) and sx.sparsity().is_dense()
    F = ca.Function("F", [X, Y, Z], [sx])
    for v in [(0.7, 0.3, 1.9), (1.3, -0.4, 0.5), (1.9, 1.1, 2.7)]:
        want = np.array(f_np(*v), dtype=float)
        got = np.array(F(*v), dtype=float).ravel()
        np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-15)
    # Matrix shape is kept, structural zeros become explicit, constants need no symbols.
    m = tc.to_sx(sp.Matrix([[x, 0], [0, y]]), {x: X, y: Y})
    assert m.shape == (2, 2) and m.nnz() == 4
    assert float(tc.to_sx(sp.sqrt(2) * sp.pi, {})) == float(sp.N(sp.sqrt(2) * sp.pi, 30))
    with pytest.raises(KeyError):
        tc.to_sx(x + y, {x: X})


def test_to_sx_deterministic(kernels):
    k = next(k for k in kernels if k.name == "ik_abc")
    syms = [s for _, g in k.inputs for s in g]

    def build():
        v = ca.SX.sym("v", len(syms))
        out = tc.to_sx([e for _, e in k.outputs], dict(zip(syms, ca.vertsplit(v), strict=True)))
        return ca.Function("abc", [v], [out]).serialize()
    assert build() == build()


# ------------------------------------------------------------------------------ functions
def test_signatures_and_dense_outputs(fns):
    want = {
        "uw_loop": ([("q", 3, 1), ("e", 3, 1), ("p", 4, 1)], [("g", 3, 1)]),
        "uw_ik_branch": ([("e", 3, 1), ("p", 4, 1), ("sigma", 3, 1)], [("q", 3, 1)]),
        "uw_fk_rotation": ([("tze", 3, 1), ("p", 4, 1)], [("R", 3, 3)]),
        "uw_jacobians": ([("q", 3, 1), ("e", 3, 1), ("p", 4, 1)], [("jq", 3, 1), ("jx", 3, 3)]),
        "uw_rates": ([("q", 3, 1), ("e", 3, 1), ("qd", 3, 1), ("qdd", 3, 1), ("p", 4, 1)],
                     [("w", 3, 1), ("wdot", 3, 1), ("ed", 3, 1), ("edd", 3, 1)]),
        "uw_loop_jac": ([("q", 3, 1), ("e", 3, 1), ("p", 4, 1)], [("dg_dq", 3, 3), ("dg_de", 3, 3)]),
        "uw_singularity": ([("q", 3, 1), ("e", 3, 1), ("p", 4, 1)], [("det_jq", 1, 1), ("det_jx", 1, 1)]),
    }
    assert set(fns) == set(want)
    for name, (ins, outs) in want.items():
        f = fns[name]
        assert f.name() == name
        assert [(f.name_in(i), *f.size_in(i)) for i in range(f.n_in())] == ins
        assert [(f.name_out(i), *f.size_out(i)) for i in range(f.n_out())] == outs
        assert all(f.sparsity_out(i).is_dense() for i in range(f.n_out())), name
        assert not f.has_free()


def test_loop_matches_numpy(fns):
    rng = case_rng(1)
    for _ in range(200):
        p = rand_design(rng)
        q, e = rng.uniform(-math.pi, math.pi, 3), rng.uniform(-math.pi, math.pi, 3)
        (g,) = call(fns["uw_loop"], q, e, p)
        np.testing.assert_allclose(g.ravel(), loop_np(q, rot(e), p), atol=1e-13)


def test_ik_branch_zeroes_loop_for_all_sigma(fns):
    rng = case_rng(2)
    for p, e in reachable_samples(rng, 40):
        sols = []
        for sigma in itertools.product((1.0, -1.0), repeat=3):
            (q,) = call(fns["uw_ik_branch"], e, p, sigma)
            q = q.ravel()
            assert np.all(np.isfinite(q))
            np.testing.assert_allclose(loop_np(q, rot(e), p), 0.0, atol=1e-12)
            (g,) = call(fns["uw_loop"], q, e, p)
            np.testing.assert_allclose(g.ravel(), 0.0, atol=1e-12)
            np.testing.assert_allclose(q, ik_np(rot(e), p, sigma), atol=1e-9)
            sols.append(q)
        # the 8 sets are distinct (branches not at a double root)
        s = np.array(sols)
        dist = [np.max(np.abs(np.angle(np.exp(1j * (a - b))))) for a, b in itertools.combinations(s, 2)]
        assert min(dist) > 1e-3


def test_ik_branch_nan_exactly_where_unreachable(fns):
    p = np.array([0.4, 0.4, 0.5, 0.6])  # short links: a small workspace
    n_nan = 0
    for e in itertools.product(np.linspace(-3, 3, 5), np.linspace(0.1, 3.0, 6), np.linspace(-3, 3, 5)):
        A, B, C = abc_np(rot(e), p)
        gap = np.hypot(A, B) - np.abs(C)
        (q,) = call(fns["uw_ik_branch"], e, p, [1, -1, 1])
        isnan = np.isnan(q.ravel())
        clear = np.abs(gap) > 1e-9
        assert np.array_equal(isnan[clear], (gap < 0)[clear])
        n_nan += int(isnan.sum())
    assert n_nan > 0


def test_ik_branch_jacobian_matches_finite_differences(fns):
    f = fns["uw_ik_branch"]
    e_s, p_s, s_s = ca.SX.sym("e", 3), ca.SX.sym("p", 4), ca.SX.sym("s", 3)
    qx = f(e_s, p_s, s_s)
    jac = ca.Function("ik_jac", [e_s, p_s, s_s], [ca.jacobian(qx, e_s), ca.jacobian(qx, p_s)])
    rng = case_rng(3)
    h = 1e-6
    for k, (p, e) in enumerate(reachable_samples(rng, 16, min_margin=0.1)):
        sigma = [1.0 if (k >> i) & 1 == 0 else -1.0 for i in range(3)]
        je, jp = (np.array(m, dtype=float) for m in jac(e, p, sigma))

        def q_of(e_, p_, sigma=sigma):
            return np.array(f(e_, p_, sigma), dtype=float).ravel()
        fd_e = np.column_stack([(q_of(e + h * u, p) - q_of(e - h * u, p)) / (2 * h) for u in np.eye(3)])
        fd_p = np.column_stack([(q_of(e, p + h * u) - q_of(e, p - h * u)) / (2 * h) for u in np.eye(4)])
        scale = 1 + np.max(np.abs(je)) + np.max(np.abs(jp))
        np.testing.assert_allclose(je, fd_e, atol=1e-7 * scale)
        np.testing.assert_allclose(jp, fd_p, atol=1e-7 * scale)
        # implicit-function consistency with the loop Jacobians: dq/de = -(dg/dq)^-1 dg/de
        q = q_of(e, p)
        dg_dq, dg_de = call(fns["uw_loop_jac"], q, e, p)
        np.testing.assert_allclose(je, -np.linalg.solve(dg_dq, dg_de), atol=1e-9 * scale)


def test_loop_jac_matches_finite_differences(fns):
    rng = case_rng(4)
    h = 1e-6
    for _ in range(30):
        p = rand_design(rng)
        q, e = rng.uniform(-math.pi, math.pi, 3), rng.uniform(-math.pi, math.pi, 3)
        dg_dq, dg_de = call(fns["uw_loop_jac"], q, e, p)
        fd_q = np.column_stack([(loop_np(q + h * u, rot(e), p) - loop_np(q - h * u, rot(e), p)) / (2 * h)
                                for u in np.eye(3)])
        fd_e = np.column_stack([(loop_np(q, rot(e + h * u), p) - loop_np(q, rot(e - h * u), p)) / (2 * h)
                                for u in np.eye(3)])
        np.testing.assert_allclose(dg_dq, fd_q, atol=1e-9)
        np.testing.assert_allclose(dg_de, fd_e, atol=1e-9)
        assert np.count_nonzero(dg_dq - np.diag(np.diag(dg_dq))) == 0  # loop i depends on q_i only


def test_fk_rotation_matches_numpy_construction(fns):
    rng = case_rng(5)
    for _ in range(100):
        p = rand_design(rng)
        a1, a2, b1, b2 = p
        t1, ze, et = rng.uniform(-math.pi, math.pi, 3)
        (R,) = call(fns["uw_fk_rotation"], [t1, ze, et], p)
        np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-13)
        assert abs(np.linalg.det(R) - 1) < 1e-13
        P = np.array([rz(d) @ rx(b2) @ EZ for d in DELTAS])
        a3 = math.acos(P[0] @ P[1])
        chain = rx(math.pi - b1) @ rz(t1) @ rx(a1) @ rz(ze) @ rx(a2)
        # R p1 = Z13 = chain e_z and R p2 = Z23 = chain Rz(eta) Rx(alpha3) e_z fix R
        np.testing.assert_allclose(R @ P[0], chain @ EZ, atol=1e-13)
        np.testing.assert_allclose(R @ P[1], chain @ rz(et) @ rx(a3) @ EZ, atol=1e-13)
        # branch 1 closes for theta1 by construction
        assert abs(loop_np([t1, 0, 0], R, p)[0]) < 1e-13


def test_jacobians_match_loop_derivative(fns):
    """d/dt loop(q + t qdot, expm(t [w]) R) at t = 0 equals jq * qdot - jx @ w at any configuration."""
    rng = case_rng(6)
    h = 1e-6
    for _ in range(60):
        p = rand_design(rng)
        q, e = rng.uniform(-math.pi, math.pi, 3), rng.uniform(-math.pi, math.pi, 3)
        qdot, w = rng.normal(size=3), rng.normal(size=3)
        R = rot(e)
        jq, jx = call(fns["uw_jacobians"], q, e, p)
        fd = (loop_np(q + h * qdot, expm_so3(h * w) @ R, p)
              - loop_np(q - h * qdot, expm_so3(-h * w) @ R, p)) / (2 * h)
        np.testing.assert_allclose(jq.ravel() * qdot - jx @ w, fd, atol=1e-9)
        # and the numpy axes directly
        z1, z2, z3 = axes(q, R, p)
        dets = [np.linalg.det(np.array([z1[i], z2[i], z3[i]])) for i in range(3)]
        np.testing.assert_allclose(jq.ravel(), dets, atol=1e-13)
        np.testing.assert_allclose(jx, np.cross(z2, z3), atol=1e-13)
        det_jq, det_jx = call(fns["uw_singularity"], q, e, p)
        assert det_jq.item() == pytest.approx(float(np.prod(jq)), abs=1e-14)
        assert det_jx.item() == pytest.approx(float(np.linalg.det(np.cross(z2, z3))), abs=1e-13)


def _motion(rng):
    """A smooth platform motion e(t) = e0 + e1 t + e2 t^2 / 2 (exact Euler rates at t = 0)."""
    p, e0 = reachable_samples(rng, 1, min_margin=0.1)[0]
    e1, e2 = rng.normal(size=3) * 0.5, rng.normal(size=3) * 0.5
    return p, e0, e1, e2, (lambda t: e0 + e1 * t + 0.5 * e2 * t * t)


def _motion_derivatives(p, e_of, sigma, h):
    """Joint and platform rates at t = 0 of the motion e(t), joints by IK on branch signs sigma.

    Returns q0, qd, qdd (5-point differences of the unwrapped IK branch) and w, wdot with
    skew(w) = R' R^T (5-point differences of R(t) = Rz Rx Rz, then of w(t)).
    """
    q0 = ik_np(rot(e_of(0.0)), p, sigma)

    def q_of(t):
        q = ik_np(rot(e_of(t)), p, sigma)
        return q0 + np.angle(np.exp(1j * (q - q0)))

    def w_of(t):
        W = d1(lambda s: rot(e_of(s)), t, h) @ rot(e_of(t)).T
        return np.array([W[2, 1], W[0, 2], W[1, 0]])
    return q0, d1(q_of, 0.0, h), d2(q_of, 0.0, h), w_of(0.0), d1(w_of, 0.0, h)


def test_rates_match_finite_differences_along_consistent_motion(fns):
    rng = case_rng(7)
    checked = 0
    for k in range(24):
        p, e0, e1, e2, e_of = _motion(rng)
        sigma = [1.0 if (k >> i) & 1 == 0 else -1.0 for i in range(3)]
        q0, qd, qdd, w_fd, wdot_fd = _motion_derivatives(p, e_of, sigma, 1e-3)
        jq, jx = call(fns["uw_jacobians"], q0, e0, p)
        if abs(np.linalg.det(jx)) < 1e-2:
            continue  # near a direct singularity the rates are ill-conditioned
        checked += 1
        # the motion is consistent: d/dt loop = jq qdot - jx w = 0
        np.testing.assert_allclose(jq.ravel() * qd - jx @ w_fd, 0.0, atol=1e-9)
        w, wdot, ed, edd = (v.ravel() for v in call(fns["uw_rates"], q0, e0, qd, qdd, p))
        scale = 1 + np.max(np.abs(wdot_fd))
        np.testing.assert_allclose(w, w_fd, atol=1e-8 * scale)
        np.testing.assert_allclose(ed, e1, atol=1e-8 * scale)  # e(t) is quadratic: exact rates
        np.testing.assert_allclose(wdot, wdot_fd, atol=1e-6 * scale)
        np.testing.assert_allclose(edd, e2, atol=1e-6 * scale)
    assert checked >= 16


# ------------------------------------------------------------------------------ serialisation
def test_serialisation_round_trip_and_determinism(fns, dv, kernels, tmp_path):
    paths = tc.write_casadi(fns, tmp_path)
    assert [p.relative_to(tmp_path).as_posix() for p in paths] == ["underactuated_wrist.casadi",
                                                                   "underactuated_wrist.json"]
    blob = paths[0].read_bytes()
    # regenerating (fresh kernels, fresh SX graphs) gives the same bytes
    again = tc.casadi_functions(dv, uw.kernels(dv))
    assert tc.serialize_functions(again) == blob
    paths2 = tc.write_casadi(again, tmp_path / "second")
    assert paths2[0].read_bytes() == blob and paths2[1].read_bytes() == paths[1].read_bytes()

    idx = json.loads(paths[1].read_text())
    assert paths[1].read_text() == json.dumps(idx, sort_keys=True, indent=2) + "\n"
    assert sorted(idx["functions"]) == sorted(fns)
    assert idx["functions"]["uw_rates"]["inputs"][4] == {"name": "p", "shape": [4, 1]}
    assert idx["functions"]["uw_jacobians"]["outputs"][1] == {"name": "jx", "shape": [3, 3]}
    import hashlib
    assert idx["sha256"] == hashlib.sha256(blob).hexdigest()

    loaded = tc.load_casadi(paths[0])
    assert sorted(loaded) == sorted(fns)
    rng = case_rng(8)
    for name, f in fns.items():
        g = loaded[name]
        assert [g.name_in(i) for i in range(g.n_in())] == [f.name_in(i) for i in range(f.n_in())]
        assert [g.name_out(i) for i in range(g.n_out())] == [f.name_out(i) for i in range(f.n_out())]
        for _ in range(5):
            args = [rng.uniform(-1.5, 1.5, f.size_in(i)) for i in range(f.n_in())]
            a, b = call(f, *args), call(g, *args)
            for x, y in zip(a, b, strict=True):
                assert np.array_equal(x, y, equal_nan=True), name


CASADI_INDEXES = sorted((Path(__file__).resolve().parent.parent / "generated" / "casadi").glob("*.json"))


@pytest.mark.parametrize("index", CASADI_INDEXES, ids=lambda p: p.stem)
def test_index_names_the_mechanism_and_its_design_parameters(index):
    """Each CasADi index names its own mechanism and the design parameters of that mechanism, in the order of
    the functions' design input (a fixed list once stood in every index)."""
    import importlib

    doc = json.loads(index.read_text())
    mod = importlib.import_module(f"wristkin.{index.stem}")
    assert doc["mechanism"] == index.stem
    names = doc["design_names"]
    # every design input of every function has one entry per listed name: the whole design ("p") or the one
    # named parameter it takes; the names are the module's, in its order
    assert names == [n for n in mod.DESIGN_NAMES if n in names] and names
    for fn in tc.load_casadi(index.with_suffix(".casadi")).values():
        for i in range(fn.n_in()):
            if fn.name_in(i) == "p":
                assert fn.size_in(i) == (len(names), 1), (fn.name(), fn.name_in(i))
            elif fn.name_in(i) in mod.DESIGN_NAMES:
                assert names == [fn.name_in(i)], (fn.name(), fn.name_in(i))
