"""The generic DH module itself: modified (Craig) DH, tool transforms, and that a chain described in either
convention gets the same FK, Jacobian and proven IK stages."""

from __future__ import annotations

import math

import numpy as np
import sympy as sp
from reference.dh import dh_matrix
from seeding import case_rng

from derive.catalogue import registry
from derive.families.serial import dh_serial
from derive.identities.dh import (
    DHRow,
    chain,
    dh_modified,
    dh_modified_explicit,
    dh_standard,
    dh_standard_explicit,
    hrot_x,
    trans,
)
from derive.serial_core import stages


def test_link_transforms_equal_their_closed_forms():
    a, al, d, t = sp.symbols("a alpha d theta", real=True)
    assert sp.simplify(dh_standard(a, al, d, t) - dh_standard_explicit(a, al, d, t)) == sp.zeros(4, 4)
    assert sp.simplify(dh_modified(a, al, d, t) - dh_modified_explicit(a, al, d, t)) == sp.zeros(4, 4)


def _modified_scara():
    """The seed-001 SCARA re-described in modified DH: row i takes (a, alpha) of standard row i-1; the last
    standard (a, alpha) becomes the tool transform Tx(a_n) Rx(alpha_n)."""
    std = registry()["scara_wrist"].spec  # catalogue/scara_wrist.toml
    rows, prev_a, prev_alpha = [], 0, 0
    for r in std.rows:
        rows.append(DHRow(prev_a, prev_alpha, r.d, r.theta, r.joint, r.kind))
        prev_a, prev_alpha = r.a, r.alpha
    tool = trans(prev_a, 0, 0) * hrot_x(prev_alpha)
    mod = dh_serial.SerialSpec("scara_mdh", "SCARA in modified DH", std.seed, rows, std.joints, std.kinds,
                               std.design, std.design_default, std.stages, convention="modified", tool=tool)
    return std, mod


def test_modified_dh_chain_equals_standard_chain():
    std, mod = _modified_scara()
    dv_std, dv_mod = dh_serial.derive_spec(std), dh_serial.derive_spec(mod)  # IK stages proven on both FKs
    assert dv_mod.all_passed and "modified" in dv_mod["A1"].rule
    args = (*std.joints, *std.design)
    f = [sp.lambdify(args, dv.exports[k], "numpy") for dv in (dv_std, dv_mod) for k in ("T", "jacobian")]
    rng = case_rng(0)
    for _ in range(50):
        vals = [*rng.uniform(-math.pi, math.pi, 2), rng.uniform(-0.5, 0.5), rng.uniform(-math.pi, math.pi),
                0.4, 0.3, 0.1]
        np.testing.assert_allclose(np.array(f[0](*vals), dtype=float), np.array(f[2](*vals), dtype=float),
                                   atol=1e-12)
        np.testing.assert_allclose(np.array(f[1](*vals), dtype=float), np.array(f[3](*vals), dtype=float),
                                   atol=1e-12)


def _rx(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rz(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _shift(x, z):
    m = np.eye(4)
    m[0, 3], m[2, 3] = x, z
    return m


def test_the_folded_chain_is_the_product_of_its_links():
    """identities/dh.chain writes each run of parallel axes with the sum of its angles (twists 0 and +-pi keep the
    run, pi flipping the sign the later angles enter with); every cumulative frame must still be the plain product of
    the link matrices. Reference: numpy products of tests/reference/dh.dh_matrix (standard) and of elementary
    rotations and shifts (modified), at random tables whose twists mix 0, +-pi, +-pi/2 and a generic angle."""
    rng = case_rng(2402)
    twists = (0, sp.pi, -sp.pi, sp.pi / 2, -sp.pi / 2, sp.Rational(7, 10))
    for convention in ("standard", "modified"):
        for _ in range(8):
            n = 6
            qs = sp.symbols(f"q1:{n + 1}", real=True)
            alphas = [twists[i] for i in rng.integers(0, len(twists), n)]
            a = rng.uniform(-0.5, 0.5, n)
            d = rng.uniform(-0.5, 0.5, n)
            off = rng.uniform(-math.pi, math.pi, n)
            rows = [DHRow(sp.Float(a[i]), alphas[i], sp.Float(d[i]), qs[i] + sp.Float(off[i]), qs[i]) for i in range(n)]
            base = trans(0.1, -0.2, 0.3) * hrot_x(sp.Rational(3, 10))
            tool = trans(0.0, 0.05, 0.12) * hrot_x(-sp.pi / 2)
            frames = chain(rows, convention, tool, base)
            fns = [sp.lambdify(qs, f, "numpy") for f in frames]
            for _ in range(5):
                q = rng.uniform(-math.pi, math.pi, n)
                t = np.array(base, dtype=float)
                for i in range(n):
                    al, th = float(alphas[i]), q[i] + off[i]
                    link = (dh_matrix(a[i], al, d[i], th) if convention == "standard" else
                            _rx(al) @ _shift(a[i], 0.0) @ _rz(th) @ _shift(0.0, d[i]))
                    t = t @ link
                    want = t @ np.array(tool, dtype=float) if i == n - 1 else t
                    np.testing.assert_allclose(np.array(fns[i](*q), dtype=float), want, atol=1e-13, rtol=0)


def test_mirrored_wrist_set_has_its_base_sets_fk_bit_for_bit():
    """The C solver reuses an even IK set's FK check for the odd set that mirrors its wrist (q4 + pi, -q5, q6 + pi),
    on the strength of stages.mirror_keeps_fk: every temporary of fk_cs unchanged or exactly negated by the flip.
    The proof holds for the spherical wrist and fails for a flip that is no symmetry (q5 left alone); and the
    generated fk_cs kernels of the three wrist-stage chains give bit-identical poses for mirrored random sets."""
    import importlib

    mech = registry()["spherical_wrist"]
    spec = mech.spec
    fk_cs = next(k for k in mech.kernels(mech.derive()) if k.name == "fk_cs")
    assert stages.mirror_keeps_fk(spec, fk_cs)
    wrist = next(st for st in spec.stages if st.kind == "wrist")
    cs, ss = stages.cs_symbols(spec)
    j4, j5, j6 = wrist.joints
    from derive.lower import cse_kernel

    temps, reduced = cse_kernel(fk_cs)
    known, wrong = {}, {cs[j4], ss[j4], cs[j6], ss[j6]}
    for sym, e in temps:
        known[sym] = stages.flip_parity(sp.sympify(e), wrong, known)
    assert any(stages.flip_parity(e, wrong, known) != 0 for e in reduced)

    rng = case_rng(5)
    for name in ("spherical_wrist", "rpp_wrist", "puma560"):
        mod = importlib.import_module(f"wristkin.{name}")
        j4, j6 = mod._WRIST_JOINTS
        j5 = j4 + 1
        dp = np.array(mod.DESIGN_DEFAULT)
        for _ in range(200):
            q = rng.uniform(-math.pi, math.pi, mod.N_JOINTS)
            c, s = np.cos(q), np.sin(q)
            cm, sm = c.copy(), s.copy()
            cm[[j4, j6]] *= -1.0
            sm[[j4, j5, j6]] *= -1.0
            a = np.array(mod._k_fk_cs(q, c, s, dp), dtype=float)
            b = np.array(mod._k_fk_cs(q, cm, sm, dp), dtype=float)
            assert np.array_equal(a, b), (name, q)


def test_the_cs_form_of_a_chain_is_its_angle_sum_expansion():
    """stages.on_cs_all (a kernel's outputs in c_i, s_i: one walk over their distinct nodes) equals the plain
    expand_trig-and-substitute form, exactly (sympy's difference expands to 0), on the catalogue's PUMA-560 FK and
    Jacobian and on a chain whose offsets and twists are numbers off the grid (a calibrated arm's true chain: theta
    offsets 1e-20, twists 1.5708), where the joint trig is cos(q + c) with c a Float."""
    mech = registry()["puma560"]
    spec = mech.spec
    dv = mech.derive()
    cs, ss = stages.cs_symbols(spec)
    rep = {f(q): v for q, c, s in zip(spec.joints, cs, ss, strict=True) for f, v in ((sp.cos, c), (sp.sin, s))}
    puma = [dv.exports["jacobian"][r, c] for r in range(6) for c in range(6)][:18]
    rows = [DHRow(sp.Float(0.05 * k), sp.Float(1.5708) * (-1) ** k, sp.Float(0.3), q + sp.Float(1.4e-20 * k), q, "R")
            for k, q in enumerate(spec.joints)]
    numeric = list(chain(rows)[-1][:3, :])
    assert stages._shifted_trig(numeric, spec, cs, ss) is not None  # the one-walk path (the PUMA's q2 + q3 is not)
    for exprs in (puma, numeric):
        expected = [sp.expand_trig(e).xreplace(rep) for e in exprs]
        got = stages.on_cs_all(exprs, spec)
        assert all(sp.expand(a - b) == 0 for a, b in zip(got, expected, strict=True))
        assert not any(e.atoms(sp.cos, sp.sin) & {f(q) for q in spec.joints for f in (sp.cos, sp.sin)} for e in got)
