"""One runtime for every generated module: the same error classes, result types, flags and `select`.

`except wristkin.InvalidInput` must catch bad input from any mechanism, and `wristkin.puma560.Solutions` must be
the class `wristkin.underactuated_wrist` returns too (each module once declared its own)."""

from __future__ import annotations

import importlib
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import wristkin

ROOT = Path(__file__).resolve().parent.parent
SHARED = ("WristkinError", "InvalidInput", "InvalidDesign", "Solutions", "BatchSolutions", "STATUS_OK",
          "STATUS_UNREACHABLE", "STATUS_NO_ASSEMBLY", "STATUS_INDETERMINATE", "FLAG_SINGULAR_INVERSE",
          "FLAG_SINGULAR_DIRECT", "FLAG_GIMBAL", "FLAG_DOUBLE_ROOT", "FLAG_INDETERMINATE", "FLAG_PROJECTED")


def module(name):
    return importlib.import_module(f"wristkin.{name}")


@pytest.mark.parametrize("name", wristkin.MECHANISMS)
def test_every_module_uses_the_shared_classes_and_constants(name):
    mod = module(name)
    for attr in SHARED:
        assert getattr(mod, attr) is getattr(wristkin, attr), attr
    assert issubclass(wristkin.InvalidInput, wristkin.WristkinError)
    assert issubclass(wristkin.InvalidDesign, wristkin.WristkinError)
    assert issubclass(wristkin.WristkinError, ValueError)  # code that caught ValueError keeps working


@pytest.mark.parametrize("name", wristkin.MECHANISMS)
def test_one_except_clause_catches_bad_input_and_designs_of_every_mechanism(name):
    mod = module(name)
    n_pose = 16 if len(mod.POSE_NAMES) == 12 else len(mod.POSE_NAMES)
    for call, arg in ((mod.ik, [math.nan] * n_pose), (mod.fk, [math.inf] * len(mod.JOINT_NAMES)),
                      (mod.fk, ["a"] * len(mod.JOINT_NAMES))):
        with pytest.raises(wristkin.InvalidInput):
            call(arg)
    with pytest.raises(wristkin.InvalidDesign):
        mod.make_design([math.nan] * len(mod.DESIGN_NAMES))
    with pytest.raises(wristkin.InvalidDesign):
        mod.make_design({"no_such_parameter": 1.0})
    q = np.zeros(len(mod.JOINT_NAMES))
    assert isinstance(mod.fk(q), wristkin.Solutions)
    assert isinstance(mod.fk_batch(q[None, :]), wristkin.BatchSolutions)


def test_package_select_wraps_revolute_and_not_prismatic_values():
    sol = wristkin.Solutions(np.array([[3.0, 0.0], [-3.0, 6.0]]), np.array([True, True]), np.zeros(2, np.int64),
                             np.zeros((2, 1)), wristkin.STATUS_OK, "2 solution(s)")
    # every value revolute by default: 6.0 - 2 pi is 0 rad from 6.0 and -3.0 is 0.01 rad from 2 pi - 3.01
    assert wristkin.select(sol, previous=[-3.0 + 2 * math.pi - 0.01, 6.0 - 2 * math.pi]) == 1
    # a prismatic second value keeps plain distances
    assert wristkin.select(sol, previous=[3.1, 5.9], joint_kinds="RP") == 1
    assert wristkin.select(sol, previous=[3.1, 0.5], joint_kinds="RP") == 0
    assert wristkin.select(sol, previous=[3.1, 0.5], lower=[-4, -1], upper=[4, 1]) == 0
    assert wristkin.select(sol, lower=[4, 4], upper=[5, 5]) == -1
    with pytest.raises(wristkin.InvalidInput):
        wristkin.select(sol, previous=[0.0, 0.0], joint_kinds="RX")


def test_module_select_is_the_package_select_with_its_joint_kinds():
    from wristkin import scara_wrist as m

    pose = m.fk_matrix([0.4, -0.7, 0.05, 1.2])
    sol = m.ik(pose)
    prev = [0.3, -0.6, 0.04, 1.1]
    assert m.select(sol, previous=prev) == wristkin.select(sol, previous=prev, joint_kinds=m.JOINT_KINDS)


def test_mechanisms_are_attributes_of_the_package():
    assert set(wristkin.MECHANISMS) <= set(dir(wristkin))
    assert wristkin.puma560 is module("puma560")
    with pytest.raises(AttributeError):
        _ = wristkin.no_such_mechanism


def test_a_module_copied_out_of_the_package_uses_the_installed_runtime(tmp_path):
    shutil.copy(ROOT / "generated" / "python" / "wristkin" / "puma560.py", tmp_path / "my_puma.py")
    code = ("import math, wristkin, my_puma\n"
            "assert my_puma.InvalidInput is wristkin.InvalidInput\n"
            "try:\n    my_puma.fk([math.nan] * 6)\nexcept wristkin.InvalidInput:\n    print('caught')\n")
    run = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stdout.strip() == "caught", run.stderr


def test_generated_and_hand_written_python_pass_ruff():
    ruff = shutil.which("ruff", path=str(Path(sys.executable).parent))
    if ruff is None:
        pytest.skip("ruff is installed by the dev extra (make venv)")
    run = subprocess.run([ruff, "check", "derive", "tests", "generated/python"], cwd=ROOT, capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr


# ---------------------------------------------------------------------------- the numpy-only install
BLOCKER = """
import importlib.abc, sys
HEAVY = ("sympy", "casadi", "jinja2", "matplotlib", "mpmath", "scipy", "derive")
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in HEAVY:
            raise ImportError(f"blocked for this test: {name}", name=name)
sys.meta_path.insert(0, Block())
"""


def test_install_requires_numpy_alone_on_python_3_10():
    import tomllib

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert [d.split(">")[0].split("=")[0].split("<")[0].strip() for d in project["dependencies"]] == ["numpy"]
    assert not any("==" in d for d in project["dependencies"]), "a range, not a pin"
    assert project["requires-python"] == ">=3.10"
    assert project["scripts"]["wristkin"] == "wristkin.cli:main"
    assert "sympy==1.14.0" in project["optional-dependencies"]["derive"]


def test_solving_from_python_and_the_cli_needs_no_derivation_stack():
    code = BLOCKER + """
import numpy as np
import wristkin
from wristkin import cli
for name in wristkin.MECHANISMS:
    m = getattr(wristkin, name)
    q = np.full(len(m.JOINT_NAMES), 0.3)
    sol = m.fk(q)
    assert sol.count >= 1, name
pose = ["1", "0", "0", "0.5", "0", "1", "0", "0.1", "0", "0", "1", "0.6"]
assert cli.main(["ik", "puma560", "--rad", "--pose", *pose]) == 0
assert cli.main(["fk", "underactuated_wrist", "--joints", "137.92", "138.44", "137.82"]) == 0
assert cli.main(["list"]) == 0
print("solved without", ", ".join(sorted(m for m in ("sympy", "casadi", "jinja2") if m not in sys.modules)))
"""
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "solved without casadi, jinja2, sympy" in run.stdout


def test_derivation_verbs_without_the_derivation_stack_name_the_extra():
    code = BLOCKER + """
from wristkin import cli
sys.exit(cli.main(sys.argv[1:]))
"""
    for argv in (["regenerate", "--out", "x"], ["check"], ["audit", "puma560"]):
        run = subprocess.run([sys.executable, "-c", code, *argv], cwd=ROOT, capture_output=True, text=True,
                             timeout=120)
        assert run.returncode == 1 and "pip install 'wristkin[derive]'" in run.stderr, run.stderr
        assert "Traceback" not in run.stderr and run.stderr.count("\n") == 1
