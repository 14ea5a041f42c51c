"""The subproblem formulas every chain solver evaluates are proven with SymPy (derive/kinematics/subproblems.py):
each proof runs here afresh (not from the cache the derivation keeps), and a wrong formula fails its proof."""

from __future__ import annotations

import sympy as sp

from derive.kinematics import subproblems as proofs


def test_every_subproblem_formula_is_proven():
    results = proofs.prove()
    assert {name for name, _, _ in results} == {"rotation", "sp1_form", "sp1_angle", "sp3", "sp4", "sp2", "trig"}
    assert all(check.passed and check.kind == "symbolic" for _, _, check in results)


def test_a_wrong_formula_fails_its_proof():
    k, p = proofs._vec("k"), proofs._vec("p")
    c, s = sp.symbols("c s", real=True)
    R = proofs.rodrigues(k, c, s)
    perp = p - k.dot(p) * k
    wrong = R * p - (k.dot(p) * k + c * perp - s * k.cross(p))  # sin term with the wrong sign
    assert not proofs._zero(list(wrong), [k], c, s)
    assert proofs._zero(list(R * p - (k.dot(p) * k + c * perp + s * k.cross(p))), [k], c, s)


def test_the_cached_outcome_is_the_proofs(tmp_path, monkeypatch):
    monkeypatch.setenv("WRISTKIN_CACHE", str(tmp_path))
    proofs.subproblem_checks.cache_clear()
    try:
        first = proofs.subproblem_checks()
        assert list(tmp_path.glob("subproblem-proofs-*.json"))
        proofs.subproblem_checks.cache_clear()
        again = proofs.subproblem_checks()
        assert [(n, c.passed) for n, _, c in first] == [(n, c.passed) for n, _, c in again]
    finally:
        proofs.subproblem_checks.cache_clear()
