"""Spec files: the catalogue is read from catalogue/*.toml, a malformed spec is one error naming the file, the field
and what was expected (never a traceback), and a new mechanism of an existing family is a new spec file alone."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from seeding import case_rng

from derive import catalogue
from derive.spec import SpecError

ROOT = Path(__file__).resolve().parent.parent
PUMA = (ROOT / "catalogue" / "puma560.toml").read_text()
RSR = (ROOT / "catalogue" / "rsr_wrist.toml").read_text()
SCREW = (ROOT / "catalogue" / "rarararbrb.toml").read_text()
WRIST = (ROOT / "catalogue" / "underactuated_wrist.toml").read_text()

# A spherical wrist of another size and other joint names: a new mechanism of the serial family.
NEW_WRIST = """
family = "serial"
name = "tiny_wrist"
title = "A user's spherical wrist"
positive = ["flange"]

[design]
flange = 0.23

[[joint]]
name = "q1"
type = "revolute"
alpha = "-pi/2"

[[joint]]
name = "q2"
type = "revolute"
alpha = "pi/2"

[[joint]]
name = "q3"
type = "revolute"
d = "flange"
"""


def _spec(tmp_path, text, stem="puma560"):
    path = tmp_path / f"{stem}.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("name", sorted(p.stem for p in (ROOT / "catalogue").glob("*.toml")))
def test_every_catalogue_spec_loads_as_itself(name):
    mech = catalogue.load(ROOT / "catalogue" / f"{name}.toml")
    assert mech.NAME == name and callable(mech.derive) and len(mech.TEMPLATES) == 3


BROKEN = [
    # (which spec, edit, field named, words expected in the message)
    (PUMA, lambda t: t.replace('family = "serial"\n', ""), "family", "required"),
    (PUMA, lambda t: t.replace('family = "serial"', 'family = "delta"'), "family", "one of the families"),
    (PUMA, lambda t: t.replace('name = "puma560"', 'name = "Puma 560"'), "name", "identifier"),
    (PUMA, lambda t: t.replace('name = "puma560"', 'name = "cli"'), "name", "runtime"),
    (PUMA, lambda t: t.replace('convention = "standard"', 'convention = "craig"'), "convention", "'modified'"),
    # the IK is found from the axes: a hand-written plan is no longer a field
    (PUMA, lambda t: t.replace('convention = "standard"', 'convention = "standard"\nik = "scara"'), "ik",
     "unknown field"),
    (PUMA, lambda t: t.replace("d1 = 0.6718", 'd1 = "tall"'), "design.d1", "a number (m)"),
    (PUMA, lambda t: t.replace("d1 = 0.6718", "d1 = nan"), "design.d1", "finite"),
    (PUMA, lambda t: t.replace('alpha = "pi/2"\nd = "d1"', 'alpha = "pi/2 + zeta"\nd = "d1"'), "joint[0].alpha",
     "expression"),
    (PUMA, lambda t: t.replace('alpha = "pi/2"\nd = "d1"', 'alpha = "__import__(1)"\nd = "d1"'),
     "joint[0].alpha", "expression"),
    (PUMA, lambda t: t.replace('name = "theta2"', 'name = "theta1"'), "joint[1].name", "not used before"),
    (PUMA, lambda t: t.replace("d1 = 0.6718", "d1 = 0.6718\npi = 1.0"), "design.pi", "not used before"),
    (PUMA, lambda t: t.replace('type = "revolute"\na = "a2"', 'type = "spherical"\na = "a2"'), "joint[1].type",
     "'prismatic'"),
    (PUMA, lambda t: t.replace('a = "a2"', 'a = "a2"\nlength = 3'), "joint[1].length", "unknown field"),
    (PUMA, lambda t: "units = 'mm'\n" + t, "units", "unknown field"),
    (PUMA, lambda t: t.replace("[design]", "[design\n"), "", "valid TOML"),
    (RSR, lambda t: t.replace("lbw_max = 0.11", "lbw_max = 0.5"), "wrist.lbw_max", "2 L"),
    (RSR, lambda t: t.replace("phi_max = 75.0", "phi_max = 20.0"), "wrist.phi_max", "above phi_min"),
    (RSR, lambda t: t.replace('kind = "wrist"', 'kind = "delta"'), "kind", "'scara_hybrid'"),
    (SCREW, lambda t: t.replace("direction = [1.0, 0.0, 0.0]     # b", "direction = [1.0, 0.1, 0.0]"),
     "joint[3].direction", "unit vector"),
    (SCREW, lambda t: t.replace("direction = [1.0, 0.0, 0.0]\npoint = [0.8, 0.2, 0.1]",
                                "direction = [0.0, 1.0, 0.0]\npoint = [0.8, 0.2, 0.1]"), "joint", "one direction"),
    (SCREW, lambda t: t.replace('structure = "RaRaRaRbRb"', 'structure = "P1P2P3RaRb"'), "joint", "types P P P R R"),
    (WRIST, lambda t: t.replace("beta2 = 43.89", "beta2 = 123.0"), "design.beta2", "[0.0, 90.0]"),
    (WRIST, lambda t: t.replace("beta2 = 43.89", "beta2 = 90.0").replace("beta1 = 30.0", "beta1 = 90.0"),
     "design.beta2", "below 180"),
    (WRIST, lambda t: t.replace('seed = "000"', 'seed = "999"'), "seed", "'000'"),
]


@pytest.mark.parametrize("case", range(len(BROKEN)))
def test_a_malformed_spec_names_the_file_the_field_and_what_was_expected(tmp_path, case):
    text, edit, field, words = BROKEN[case]
    edited = edit(text)
    assert edited != text, "the edit did not apply: the case tests nothing"
    path = _spec(tmp_path, edited)
    with pytest.raises(SpecError) as exc:
        catalogue.load(path)
    assert exc.value.file == str(path) and exc.value.field == field, str(exc.value)
    assert words in str(exc.value) and str(path) in str(exc.value)


def test_a_catalogue_spec_is_named_by_its_file(tmp_path):
    folder = tmp_path / "cat"
    folder.mkdir()
    _spec(folder, PUMA, stem="my_arm")
    with pytest.raises(SpecError, match="the file's stem 'my_arm'"):
        catalogue.registry(folder)


def test_the_cli_reports_a_malformed_spec_in_one_line(tmp_path):
    folder = tmp_path / "cat"
    folder.mkdir()
    _spec(folder, PUMA.replace("d1 = 0.6718", 'd1 = "tall"'))
    run = subprocess.run([sys.executable, "-m", "derive.cli", "regenerate", "--catalogue", str(folder), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert run.returncode == 2, run.stderr
    assert "Traceback" not in run.stderr and len(run.stderr.strip().splitlines()) == 1
    assert "puma560.toml: field 'design.d1': expected a number (m), got 'tall'" in run.stderr
    assert not (tmp_path / "out" / "python").exists()


def _dh(a, alpha, d, theta):
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])


def test_a_new_mechanism_of_a_family_is_one_spec_file(tmp_path):
    """tiny_wrist goes through the catalogue's path (derivation, checks, Python, C, CasADi, audit) and its solver
    agrees with a plain numpy product of DH matrices (the independent reference)."""
    from derive import pipeline
    from derive.audit import load_generated

    folder = tmp_path / "cat"
    folder.mkdir()
    _spec(folder, NEW_WRIST, stem="tiny_wrist")
    out = tmp_path / "out"
    written = pipeline.regenerate(out, jobs=1, catalogue=folder)
    rel = sorted(p.relative_to(out).as_posix() for p in written)
    for f in ("python/wristkin/tiny_wrist.py", "c/tiny_wrist.c", "c/tiny_wrist.h", "casadi/tiny_wrist.casadi",
              "audit/tiny_wrist.md"):
        assert f in rel
    report = (out / "audit" / "tiny_wrist.md").read_text()
    assert "A user's spherical wrist" in report and "FAILED" not in report
    # its C runs from Python after one command (python -m derive.cli native --out OUT)
    from derive.native_build import build

    build(out)
    code = ("import numpy as np, wristkin.tiny_wrist as m; T = m.fk_matrix([0.3, 0.4, 0.5]); "
            "print(m.BACKEND, m.ik(T).count, m.ik(T, m.Design(m.make_design().params)).count)")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                         env={**os.environ, "PYTHONPATH": str(out / "python")}, cwd=tmp_path)
    assert run.returncode == 0 and run.stdout.split() == ["c", "2", "2"], run.stdout + run.stderr
    solver = load_generated(out, "tiny_wrist")
    assert solver.DESIGN_NAMES == ("flange",) and solver.JOINT_NAMES == ("q1", "q2", "q3")
    rng = case_rng(41)
    for _ in range(50):
        q = rng.uniform(-math.pi, math.pi, 3)
        ref = _dh(0, -math.pi / 2, 0, q[0]) @ _dh(0, math.pi / 2, 0, q[1]) @ _dh(0, 0, 0.23, q[2])
        np.testing.assert_allclose(solver.fk_matrix(q), ref, atol=1e-14)  # both are exact products: rounding only
        sol = solver.ik(ref)
        # every set reproduces the pose; the generating joints are among them (away from sin q2 = 0)
        assert sol.count == 2 and all(np.allclose(solver.fk_matrix(v), ref, atol=1e-12) for v in sol)
        assert any(np.max(np.abs(np.remainder(v - q + math.pi, 2 * math.pi) - math.pi)) < 1e-9 for v in sol)
