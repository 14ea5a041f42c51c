"""The `wristkin` command line (wristkin/cli.py, from templates/python/cli.py.jinja; the derivation verbs in
derive/cli.py): parsing, output and error paths.

Most tests run against a small fake generated package (`wristkin` with one mechanism,
`toy_wrist`) written to a temporary directory and put first on sys.path, so they do not
depend on the real generated code. The tests at the end use the real
generated/python/wristkin/underactuated_wrist.py and are skipped until it exists.
"""

from __future__ import annotations

import importlib
import json
import math
import os
import subprocess
import sys
import textwrap
import types
from pathlib import Path

import pytest
from wristkin import cli

REPO_ROOT = Path(__file__).resolve().parent.parent
REAL_MODULE = REPO_ROOT / "generated" / "python" / "wristkin" / "underactuated_wrist.py"

# ---------------------------------------------------------------------------- the fake package
FAKE_INIT = '"""Fake generated package for tests/test_cli.py."""\n\nMECHANISMS = ("toy_wrist",)\n'

# The subset of docs/API.md the CLI uses, with trivially predictable numbers:
#   ik row 0 = pose + alpha1, row 1 = pose - alpha1, row 2 invalid, row 3 = pose (flagged);
#   pose theta > pi/2 -> unreachable (empty set); theta outside [0, pi] -> InvalidInput.
#   fk row 0 = joints - alpha1, row 1 = gimbal representative; joints all 0 -> no assembly.
#   motor angle Phi_i = theta_i - THETA0 (THETA0 = 2 rad).
FAKE_MODULE = textwrap.dedent('''
    """Fake mechanism for CLI tests (matches the shape of docs/API.md)."""

    import math
    from dataclasses import dataclass

    import numpy as np

    NAME = "toy_wrist"
    JOINT_NAMES = ("theta1", "theta2", "theta3")
    POSE_NAMES = ("psi", "theta", "phi")
    DESIGN_NAMES = ("alpha1", "alpha2")
    DESIGN_DEFAULT = (math.radians(60.0), math.radians(30.0))
    MAX_IK = 4
    MAX_FK = 2
    IK_AUX_NAMES = ("Phi1", "Phi2", "Phi3", "cond_inverse")
    FK_AUX_NAMES = ("r00", "zeta", "cond_direct")
    STATUS_OK = 0
    STATUS_UNREACHABLE = 1
    STATUS_NO_ASSEMBLY = 2
    STATUS_INDETERMINATE = 3
    FLAG_SINGULAR_INVERSE = 1
    FLAG_SINGULAR_DIRECT = 2
    FLAG_GIMBAL = 4
    FLAG_DOUBLE_ROOT = 8
    FLAG_INDETERMINATE = 16
    THETA0 = 2.0


    class WristkinError(ValueError):
        pass


    class InvalidInput(WristkinError):
        pass


    class InvalidDesign(WristkinError):
        pass


    @dataclass(frozen=True)
    class Design:
        params: tuple


    @dataclass(frozen=True)
    class Solutions:
        values: np.ndarray
        valid: np.ndarray
        flags: np.ndarray
        aux: np.ndarray
        status: int
        reason: str

        @property
        def count(self):
            return int(self.valid.sum())

        def __iter__(self):
            return iter(self.values[self.valid])


    def _vec(v, n, what):
        a = np.asarray(v, dtype=float)
        if a.shape != (n,) or not np.all(np.isfinite(a)):
            raise InvalidInput(f"{what}: expected {n} finite numbers")
        return [float(x) for x in a]


    def make_design(params=None):
        if isinstance(params, Design):
            return params
        if params is None:
            params = DESIGN_DEFAULT
        if isinstance(params, dict):
            params = [params.get(n, d) for n, d in zip(DESIGN_NAMES, DESIGN_DEFAULT)]
        try:
            vals = _vec(params, 2, "design")
        except InvalidInput as exc:
            raise InvalidDesign(str(exc)) from exc
        if not 0.0 < vals[0] < math.pi:
            raise InvalidDesign("alpha1 must lie in (0, pi)")
        return Design(tuple(vals))


    def ik(pose, design=None):
        d = make_design(design)
        p = np.array(_vec(pose, 3, "pose"))
        if not 0.0 <= p[1] <= math.pi:
            raise InvalidInput("pose: theta must lie in [0, pi]")
        values = np.full((MAX_IK, 3), np.nan)
        aux = np.full((MAX_IK, 4), np.nan)
        valid = np.zeros(MAX_IK, dtype=bool)
        flags = np.zeros(MAX_IK, dtype=np.int64)
        if p[1] > 0.5 * math.pi:
            return Solutions(values, valid, flags, aux, STATUS_UNREACHABLE, "theta beyond the cone")
        a1 = d.params[0]
        for k, q in ((0, p + a1), (1, p - a1), (3, p)):
            values[k] = q
            aux[k] = [*(q - THETA0), 0.5]
            valid[k] = True
        flags[3] = FLAG_SINGULAR_INVERSE | FLAG_DOUBLE_ROOT
        return Solutions(values, valid, flags, aux, STATUS_OK, "3 solution sets")


    def fk(joints, design=None):
        d = make_design(design)
        q = np.array(_vec(joints, 3, "joints"))
        values = np.full((MAX_FK, 3), np.nan)
        aux = np.full((MAX_FK, 3), np.nan)
        valid = np.zeros(MAX_FK, dtype=bool)
        flags = np.zeros(MAX_FK, dtype=np.int64)
        if not np.any(q):
            return Solutions(values, valid, flags, aux, STATUS_NO_ASSEMBLY, "no real assembly mode")
        values[0] = q - d.params[0]
        values[1] = [q[0] + q[2], 0.0, 0.0]
        aux[0] = [math.cos(values[0][1]), q[0], 0.25]
        aux[1] = [1.0, q[1], 0.75]
        valid[:] = True
        flags[1] = FLAG_GIMBAL
        return Solutions(values, valid, flags, aux, STATUS_OK, "2 assembly mode(s)")


    def motor_angles(joints, design=None):
        return np.array([math.remainder(t - THETA0, 2.0 * math.pi) for t in _vec(joints, 3, "joints")])


    def joints_from_motor_angles(motor, design=None):
        return np.array([p + THETA0 for p in _vec(motor, 3, "motor angles")])
''')

DEG_THETA0 = math.degrees(2.0)


def _drop_wristkin_modules() -> dict:
    gone = {k: v for k, v in sys.modules.items() if k == "wristkin" or k.startswith("wristkin.")}
    for k in gone:
        del sys.modules[k]
    return gone


@pytest.fixture(scope="session")
def fake_dir(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("fake_generated")
    pkg = root / "wristkin"
    pkg.mkdir()
    (pkg / "__init__.py").write_text(FAKE_INIT)
    (pkg / "toy_wrist.py").write_text(FAKE_MODULE)
    return root


@pytest.fixture
def fake(fake_dir):
    """Make `import wristkin` find the fake package for the duration of a test."""
    saved = _drop_wristkin_modules()
    sys.path.insert(0, str(fake_dir))
    importlib.invalidate_caches()
    try:
        yield importlib.import_module("wristkin.toy_wrist")
    finally:
        _drop_wristkin_modules()
        sys.path.remove(str(fake_dir))
        sys.modules.update(saved)
        importlib.invalidate_caches()


def run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv):
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out, parse_constant=_reject_constant), out


def _reject_constant(name):
    raise AssertionError(f"non-standard JSON constant {name} in CLI output")


def assert_one_line_error(code, out, err, *needles):
    assert code == 2
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("wristkin: error: "), err
    assert "Traceback" not in err
    for n in needles:
        assert n in err, err


# ---------------------------------------------------------------------------- parsing and output
def test_list(fake, capsys):
    code, out, err = run(capsys, "list")
    assert code == 0 and err == ""
    assert out.startswith("toy_wrist ")
    assert "joints=(theta1, theta2, theta3)" in out


def test_ik_human_table(fake, capsys):
    code, out, err = run(capsys, "ik", "toy_wrist", "--pose", "10", "20", "30")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert lines[0] == "toy_wrist ik  psi=10 theta=20 phi=30  (angles in deg)"
    assert lines[1] == "design  alpha1=60 alpha2=30  (angles in deg)"
    assert lines[2] == "status  ok: 3 of 4 valid; 3 solution sets"
    header, rows = lines[3].split(), lines[4:]
    assert header == ["#", "valid", "theta1", "(deg)", "theta2", "(deg)", "theta3", "(deg)", "flags"]
    assert len(rows) == 4
    assert rows[0].split() == ["0", "yes", "70", "80", "90", "-"]
    assert rows[1].split() == ["1", "yes", "-50", "-40", "-30", "-"]
    assert rows[2].split() == ["2", "no", "-", "-", "-", "-"]
    assert rows[3].split() == ["3", "yes", "10", "20", "30",
                               "singular_inverse,double_root"]
    # Aligned: every row has the same width up to the flags column.
    assert len({r.index(r.split()[-1], len(r) - len(r.split()[-1]) - 1) for r in rows[:3]}) == 1


def test_ik_json_layout(fake, capsys):
    data, text = run_json(capsys, "ik", "toy_wrist", "--pose", "10", "20", "30")
    assert text == json.dumps(data, sort_keys=True) + "\n"
    assert set(data) == {"mechanism", "verb", "input", "design", "status", "reason", "count", "solutions"}
    assert data["mechanism"] == "toy_wrist" and data["verb"] == "ik"
    assert data["input"] == {"psi": 10.0, "theta": 20.0, "phi": 30.0}
    assert data["design"] == pytest.approx({"alpha1": 60.0, "alpha2": 30.0})
    assert data["status"] == "ok" and data["reason"] == "3 solution sets" and data["count"] == 3
    sols = data["solutions"]
    assert [s["index"] for s in sols] == [0, 1, 2, 3]
    assert [s["valid"] for s in sols] == [True, True, False, True]
    assert sols[0]["values"] == pytest.approx({"theta1": 70.0, "theta2": 80.0, "theta3": 90.0})
    # Angular aux columns are converted; conditioning measures are not.
    assert sols[0]["aux"] == pytest.approx({"Phi1": 70.0 - DEG_THETA0, "Phi2": 80.0 - DEG_THETA0,
                                            "Phi3": 90.0 - DEG_THETA0, "cond_inverse": 0.5})
    assert sols[2]["values"] == {"theta1": None, "theta2": None, "theta3": None}
    assert all(v is None for v in sols[2]["aux"].values())
    assert sols[3]["flags"] == ["singular_inverse", "double_root"]


def test_ik_radians(fake, capsys):
    data, _ = run_json(capsys, "ik", "toy_wrist", "--pose", "0.1", "0.2", "0.3", "--rad")
    a1 = math.radians(60.0)
    assert data["design"] == pytest.approx({"alpha1": a1, "alpha2": math.radians(30.0)})
    assert data["solutions"][0]["values"] == pytest.approx({"theta1": 0.1 + a1, "theta2": 0.2 + a1,
                                                            "theta3": 0.3 + a1})
    assert data["solutions"][0]["aux"]["Phi1"] == pytest.approx(0.1 + a1 - 2.0)
    code, out, _ = run(capsys, "ik", "toy_wrist", "--pose", "0.1", "0.2", "0.3", "--rad")
    assert code == 0 and "(rad)" in out and f"{0.1 + a1:.8f}" in out


def test_design_override_degrees(fake, capsys):
    data, _ = run_json(capsys, "ik", "toy_wrist", "--pose", "10", "20", "30", "--design", "alpha1=10")
    assert data["design"] == pytest.approx({"alpha1": 10.0, "alpha2": 30.0})
    assert data["solutions"][0]["values"] == pytest.approx({"theta1": 20.0, "theta2": 30.0, "theta3": 40.0})
    # Several overrides, repeated --design, and radians.
    data, _ = run_json(capsys, "ik", "toy_wrist", "--pose", "0", "0", "0", "--rad",
                       "--design", "alpha1=0.5", "--design", "alpha2=0.25")
    assert data["design"] == {"alpha1": 0.5, "alpha2": 0.25}
    assert data["solutions"][0]["values"]["theta1"] == pytest.approx(0.5)


def test_negative_and_exponent_numbers(fake, capsys):
    data, _ = run_json(capsys, "ik", "toy_wrist", "--pose", "-1e-3", "2.5E1", "-.5")
    assert data["input"] == {"psi": -1e-3, "theta": 25.0, "phi": -0.5}


def test_option_order(fake, capsys):
    data, _ = run_json(capsys, "ik", "--rad", "toy_wrist", "--design", "alpha1=1", "--pose", "0", "0", "0")
    assert data["solutions"][0]["values"]["theta1"] == pytest.approx(1.0)


def test_ik_unreachable_is_exit_0(fake, capsys):
    code, out, err = run(capsys, "ik", "toy_wrist", "--pose", "0", "100", "0")
    assert code == 0 and err == ""
    assert "status  unreachable: 0 of 4 valid; theta beyond the cone" in out
    data, _ = run_json(capsys, "ik", "toy_wrist", "--pose", "0", "100", "0")
    assert data["status"] == "unreachable" and data["count"] == 0
    assert not any(s["valid"] for s in data["solutions"])


def test_fk(fake, capsys):
    data, _ = run_json(capsys, "fk", "toy_wrist", "--joints", "70", "80", "90")
    assert data["verb"] == "fk" and data["input"] == {"theta1": 70.0, "theta2": 80.0, "theta3": 90.0}
    s0, s1 = data["solutions"]
    assert s0["values"] == pytest.approx({"psi": 10.0, "theta": 20.0, "phi": 30.0})
    assert s0["aux"] == pytest.approx({"r00": math.cos(math.radians(20.0)), "zeta": 70.0,
                                       "cond_direct": 0.25})
    assert s1["flags"] == ["gimbal"] and s1["values"]["psi"] == pytest.approx(160.0)
    code, out, _ = run(capsys, "fk", "toy_wrist", "--joints", "70", "80", "90")
    assert code == 0 and "gimbal" in out and "psi (deg)" in out


def test_fk_no_assembly_is_exit_0(fake, capsys):
    data, _ = run_json(capsys, "fk", "toy_wrist", "--joints", "0", "0", "0")
    assert data["status"] == "no_assembly" and data["count"] == 0
    assert data["reason"] == "no real assembly mode"


def test_ik_motor(fake, capsys):
    data, _ = run_json(capsys, "ik", "toy_wrist", "--pose", "10", "20", "30", "--motor")
    assert data["solutions"][0]["values"] == pytest.approx(
        {"Phi1": 70.0 - DEG_THETA0, "Phi2": 80.0 - DEG_THETA0, "Phi3": 90.0 - DEG_THETA0})
    code, out, _ = run(capsys, "ik", "toy_wrist", "--pose", "10", "20", "30", "--motor")
    assert code == 0 and "Phi1 (deg)" in out


def test_fk_motor(fake, capsys):
    data, _ = run_json(capsys, "fk", "toy_wrist", "--joints", "1", "2", "3", "--motor")
    assert data["input"] == {"Phi1": 1.0, "Phi2": 2.0, "Phi3": 3.0}
    assert data["solutions"][0]["values"] == pytest.approx(
        {"psi": 1.0 + DEG_THETA0 - 60.0, "theta": 2.0 + DEG_THETA0 - 60.0, "phi": 3.0 + DEG_THETA0 - 60.0})


def test_motor_unsupported(fake, capsys, monkeypatch):
    monkeypatch.delattr(fake, "motor_angles")
    assert_one_line_error(*run(capsys, "ik", "toy_wrist", "--pose", "1", "2", "3", "--motor"), "motor")


# ---------------------------------------------------------------------------- error paths
@pytest.mark.parametrize("pose, needle", [
    (["abc", "2", "3"], "not a number"),
    (["1", "nan", "3"], "not finite"),
    (["inf", "2", "3"], "not finite"),
    (["1", "2", "-inf"], "not finite"),
    (["1", "2"], "takes 3 values"),
    (["1", "2", "3", "4"], "takes 3 values"),
    (["1", "200", "3"], "theta must lie in [0, pi]"),  # rejected by the module (InvalidInput)
])
def test_bad_pose(fake, capsys, pose, needle):
    assert_one_line_error(*run(capsys, "ik", "toy_wrist", "--pose", *pose), needle)


@pytest.mark.parametrize("design, needle", [
    (["gamma=3"], "unknown design parameter 'gamma'"),
    (["alpha1"], "NAME=VALUE"),
    (["=3"], "NAME=VALUE"),
    (["alpha1=x"], "not a number"),
    (["alpha1=nan"], "not finite"),
    (["alpha1=1", "alpha1=2"], "given twice"),
    (["alpha1=0"], "alpha1 must lie in (0, pi)"),  # rejected by make_design (InvalidDesign)
])
def test_bad_design(fake, capsys, design, needle):
    assert_one_line_error(*run(capsys, "fk", "toy_wrist", "--joints", "1", "2", "3", "--design", *design),
                          needle)


@pytest.mark.parametrize("argv, needle", [
    (["ik", "no_such_wrist", "--pose", "1", "2", "3"], "unknown mechanism 'no_such_wrist'"),
    (["ik", "toy_wrist"], "--pose"),
    (["fk", "toy_wrist", "--pose", "1", "2", "3"], ""),
    (["ik", "toy_wrist", "--joints", "1", "2", "3"], ""),
    (["ik", "toy_wrist", "--pose"], "--pose"),
    ([], "required"),
    (["frobnicate"], "invalid choice"),
    (["ik", "toy_wrist", "--pose", "1", "2", "3", "--bogus"], "unrecognized"),
])
def test_usage_errors(fake, capsys, argv, needle):
    assert_one_line_error(*run(capsys, *argv), needle)


def test_help_exits_0(fake, capsys):
    code, out, _ = run(capsys, "ik", "--help")
    assert code == 0 and "--pose" in out and "--motor" in out


def test_missing_generated_package(capsys, monkeypatch, tmp_path):
    saved = _drop_wristkin_modules()
    try:
        monkeypatch.setattr(cli, "PACKAGE", "wristkin_package_that_does_not_exist")
        code, out, err = run(capsys, "ik", "underactuated_wrist", "--pose", "1", "2", "3")
        assert code == 1 and "make regenerate" in err and "Traceback" not in err
    finally:
        sys.modules.update(saved)


# ---------------------------------------------------------------------------- as a process
def _env(*paths: Path) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([*map(str, paths), str(REPO_ROOT), env.get("PYTHONPATH", "")])
    return env


# The real CLI module loaded from its file, so that `import wristkin` inside it finds the fake package first on
# PYTHONPATH (the CLI ships inside the real package, which the fake one shadows).
CLI_FILE = REPO_ROOT / "generated" / "python" / "wristkin" / "cli.py"
RUN_CLI = f"""
import importlib.util, sys
spec = importlib.util.spec_from_file_location("wk_cli_under_test", {str(CLI_FILE)!r})
cli = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cli)
main = cli.main
"""


def test_subprocess_ik_json(fake_dir):
    argv = ["ik", "toy_wrist", "--pose", "-35.99", "0.26", "38.93", "--json"]
    proc = subprocess.run([sys.executable, "-c", RUN_CLI + "sys.exit(main(sys.argv[1:]))", *argv],
                          capture_output=True, text=True, env=_env(fake_dir), cwd=REPO_ROOT,
                          stdin=subprocess.DEVNULL, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["input"] == {"psi": -35.99, "theta": 0.26, "phi": 38.93}


def test_subprocess_error_is_one_line(fake_dir):
    proc = subprocess.run([sys.executable, "-c", RUN_CLI + "sys.exit(main(sys.argv[1:]))", "fk", "toy_wrist",
                           "--joints", "1", "x", "3"], capture_output=True, text=True, env=_env(fake_dir),
                          cwd=REPO_ROOT, stdin=subprocess.DEVNULL, timeout=120)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr


NO_SYMPY = RUN_CLI + """
code = main(sys.argv[1:])
heavy = sorted(m for m in ("sympy", "casadi", "jinja2", "derive.pipeline") if m in sys.modules)
assert not heavy, f"ik/fk imported {heavy}"
sys.exit(code)
"""


def test_subprocess_ik_fk_do_not_import_sympy(fake_dir):
    for argv in (["list"], ["ik", "toy_wrist", "--pose", "1", "2", "3"],
                 ["fk", "toy_wrist", "--joints", "1", "2", "3"]):
        proc = subprocess.run([sys.executable, "-c", NO_SYMPY, *argv], capture_output=True, text=True,
                              env=_env(fake_dir), cwd=REPO_ROOT, stdin=subprocess.DEVNULL, timeout=120)
        assert proc.returncode == 0, proc.stderr


# ---------------------------------------------------------------------------- regenerate / check / audit
@pytest.fixture
def fake_pipeline(monkeypatch, tmp_path):
    import derive

    calls = []
    mod = types.ModuleType("derive.pipeline")
    mod.state = {"ok": True, "diff": ""}

    def regenerate(out_dir, jobs=None):
        calls.append(("regenerate", out_dir))
        return [Path(out_dir) / "a.py", Path(out_dir) / "b.c"]

    def check(out_dir=None, jobs=None):
        calls.append(("check",))
        return mod.state["ok"], mod.state["diff"]

    def audit(names, out_dir=None, jobs=None):
        calls.append(("audit", names))
        return [tmp_path / "audit" / f"{n}.md" for n in (names or ["toy_wrist"])]

    mod.regenerate, mod.check, mod.audit, mod.calls = regenerate, check, audit, calls
    monkeypatch.setitem(sys.modules, "derive.pipeline", mod)
    monkeypatch.setattr(derive, "pipeline", mod, raising=False)
    return mod


def test_regenerate(fake_pipeline, capsys, tmp_path):
    code, out, _ = run(capsys, "regenerate", "--out", str(tmp_path / "g"))
    assert code == 0 and fake_pipeline.calls == [("regenerate", tmp_path / "g")]
    assert "2 file(s)" in out
    run(capsys, "regenerate")
    assert fake_pipeline.calls[-1] == ("regenerate", REPO_ROOT / "generated")


def test_check_ok_and_drift(fake_pipeline, capsys):
    code, out, _ = run(capsys, "check")
    assert code == 0 and "up to date" in out
    fake_pipeline.state.update(ok=False, diff="--- a/x\n+++ b/x\n@@ -1 +1 @@\n-1\n+2\n")
    code, out, err = run(capsys, "check")
    assert code == 1
    assert "+++ b/x" in out and "stale" in err


def test_audit(fake, fake_pipeline, capsys, tmp_path):
    code, out, _ = run(capsys, "audit", "toy_wrist")
    assert code == 0 and fake_pipeline.calls[-1] == ("audit", ["toy_wrist"])
    assert out.strip() == str(tmp_path / "audit" / "toy_wrist.md")
    code, out, _ = run(capsys, "audit")
    assert code == 0 and fake_pipeline.calls[-1] == ("audit", None)
    assert_one_line_error(*run(capsys, "audit", "nope"), "unknown mechanism 'nope'")


# ---------------------------------------------------------------------------- the real generated module
real = pytest.mark.skipif(not REAL_MODULE.exists(), reason="generated/python/wristkin/underactuated_wrist.py "
                                                           "not generated yet")

DEMO_POSE = ("-35.99", "0.26", "38.93")  # paper Table 2, t = 1 s (degrees)
DEMO_JOINTS = ("137.92", "138.44", "137.82")


@pytest.fixture
def real_wristkin():
    saved = _drop_wristkin_modules()  # nothing fake may shadow the real package
    try:
        cli.mechanism_names()  # imports the installed package, or generated/python from the checkout
        yield importlib.import_module("wristkin.underactuated_wrist")
    finally:
        _drop_wristkin_modules()
        sys.modules.update(saved)


def _rotation(uw, pose_deg):
    return uw.rotation_from_pose([math.radians(v) for v in pose_deg])


@real
def test_real_list(real_wristkin, capsys):
    code, out, _ = run(capsys, "list")
    assert code == 0 and "underactuated_wrist" in out


@real
def test_real_demo_ik(real_wristkin, capsys):
    data, _ = run_json(capsys, "ik", "underactuated_wrist", "--pose", *DEMO_POSE)
    assert data["status"] == "ok" and data["count"] >= 1
    want = [float(v) for v in DEMO_JOINTS]
    best = min(max(abs(s["values"][n] - w) for n, w in zip(("theta1", "theta2", "theta3"), want, strict=True))
               for s in data["solutions"] if s["valid"])
    assert best < 0.05  # the paper prints two decimals


@real
def test_real_demo_fk(real_wristkin, capsys):
    import numpy as np

    data, _ = run_json(capsys, "fk", "underactuated_wrist", "--joints", *DEMO_JOINTS)
    assert data["status"] == "ok" and data["count"] >= 1
    want = _rotation(real_wristkin, [float(v) for v in DEMO_POSE])
    names = [f"r{i}{j}" for i in range(3) for j in range(3)]
    # Compare rotations, not Euler angles: at a nutation of 0.26 deg psi and phi are ill-conditioned.
    best = min(np.abs(np.array([s["aux"][n] for n in names]).reshape(3, 3) - want).max()
               for s in data["solutions"] if s["valid"])
    assert best < 2e-3


@real
def test_real_ik_fk_round_trip_radians(real_wristkin, capsys):
    import numpy as np

    pose = (0.2, 0.3, -0.1)  # reachable: 8 solution sets
    data, _ = run_json(capsys, "ik", "underactuated_wrist", "--rad", "--pose", *map(str, pose))
    want = _rotation(real_wristkin, [math.degrees(v) for v in pose])
    assert data["count"] == 8
    for s in data["solutions"]:
        if not s["valid"]:
            continue
        q = [repr(s["values"][n]) for n in ("theta1", "theta2", "theta3")]
        fk, _ = run_json(capsys, "fk", "underactuated_wrist", "--rad", "--joints", *q)
        names = ("psi", "theta", "phi")
        errs = [np.abs(_rotation(real_wristkin, [math.degrees(m["values"][n]) for n in names]) - want).max()
                for m in fk["solutions"] if m["valid"]]
        assert errs and min(errs) < 1e-6, (s["index"], errs)


@real
def test_real_motor_round_trip(real_wristkin, capsys):
    ik, _ = run_json(capsys, "ik", "underactuated_wrist", "--motor", "--pose", *DEMO_POSE)
    plain, _ = run_json(capsys, "ik", "underactuated_wrist", "--pose", *DEMO_POSE)
    s = next(s for s in ik["solutions"] if s["valid"])
    assert list(s["values"]) == ["Phi1", "Phi2", "Phi3"]
    assert s["values"] == pytest.approx({n: plain["solutions"][s["index"]]["aux"][n] for n in s["values"]})
    fk_motor, _ = run_json(capsys, "fk", "underactuated_wrist", "--motor", "--joints",
                           *(repr(v) for v in s["values"].values()))
    q = plain["solutions"][s["index"]]["values"]
    fk_plain, _ = run_json(capsys, "fk", "underactuated_wrist", "--joints", *(repr(v) for v in q.values()))
    assert [m["valid"] for m in fk_motor["solutions"]] == [m["valid"] for m in fk_plain["solutions"]]
    for a, b in zip(fk_motor["solutions"], fk_plain["solutions"], strict=True):
        if a["valid"]:
            assert a["aux"] == pytest.approx(b["aux"], abs=1e-9)


@real
def test_real_design_override_and_rejection(real_wristkin, capsys):
    default, _ = run_json(capsys, "ik", "underactuated_wrist", "--pose", *DEMO_POSE)
    same, _ = run_json(capsys, "ik", "underactuated_wrist", "--pose", *DEMO_POSE,
                       "--design", "alpha1=60", "alpha2=60", "beta1=30", "beta2=43.89")
    assert same["solutions"] == default["solutions"]
    assert_one_line_error(*run(capsys, "ik", "underactuated_wrist", "--pose", *DEMO_POSE,
                               "--design", "alpha1=200"), "alpha1")


@real
def test_real_cli_does_not_import_sympy():
    proc = subprocess.run([sys.executable, "-c", NO_SYMPY, "ik", "underactuated_wrist", "--pose", *DEMO_POSE],
                          capture_output=True, text=True, env=_env(REPO_ROOT / "generated" / "python"),
                          cwd=REPO_ROOT, stdin=subprocess.DEVNULL, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "underactuated_wrist ik" in proc.stdout



# ---------------------------------------------------------------------------- a DH chain through the CLI
def test_dh_chain_round_trip_and_bad_input(real_wristkin, capsys):
    """Pose values of a serial chain are matrix entries and metres, never converted as degrees."""
    data, _ = run_json(capsys, "fk", "puma560", "--joints", "10", "20", "30", "40", "50", "60")
    pose = data["solutions"][0]["values"]
    names = ("r00", "r01", "r02", "px", "r10", "r11", "r12", "py", "r20", "r21", "r22", "pz")
    flat = [repr(pose[n]) for n in names]
    back, _ = run_json(capsys, "ik", "puma560", "--pose", *flat)
    assert back["count"] == 8
    assert any(all(abs(s["values"][f"theta{i}"] - 10.0 * i) < 1e-6 for i in range(1, 7))
               for s in back["solutions"] if s["valid"])
    code, _, err = run(capsys, "ik", "puma560", "--pose", *flat[:11])
    assert code == 2 and "error" in err
    sheared = list(flat)
    sheared[1] = "0.9"  # r01: no longer a rotation
    code, _, err = run(capsys, "ik", "puma560", "--pose", *sheared)
    assert code == 2 and "rotation" in err
    far = ["1", "0", "0", "50", "0", "1", "0", "0", "0", "0", "1", "0"]
    data, _ = run_json(capsys, "ik", "scara_wrist", "--pose", *far)
    assert data["count"] == 0 and data["status"] == "unreachable" and "not reachable" in data["reason"]


def real_wristkin_names(name):
    import importlib

    return importlib.import_module(f"wristkin.{name}").POSE_NAMES


@real
def test_real_rsr_wrist_degrees_round_trip(real_wristkin, capsys):
    data, _ = run_json(capsys, "ik", "rsr_wrist", "--pose", "17", "28", "0.08")
    assert data["status"] == "ok" and data["count"] == 8
    q = [str(data["solutions"][0]["values"][n]) for n in ("phi1", "phi2", "phi3")]
    back, _ = run_json(capsys, "fk", "rsr_wrist", "--joints", *q)
    vals = back["solutions"][0]["values"]
    assert abs(vals["alpha"] - 17) < 1e-9 and abs(vals["beta"] - 28) < 1e-9 and abs(vals["l_bw"] - 0.08) < 1e-12


@real
def test_real_scara_rsr_twelve_or_thirteen_numbers(real_wristkin, capsys):
    fk, _ = run_json(capsys, "fk", "scara_rsr", "--joints", "17", "57", "0.1", "11", "46", "52", "57")
    pose = [str(fk["solutions"][0]["values"][n]) for n in real_wristkin_names("scara_rsr")]
    full, _ = run_json(capsys, "ik", "scara_rsr", "--pose", *pose)
    assert full["count"] == 16
    assert any(abs(s["values"]["theta1"] - 17) < 1e-7 and abs(s["values"]["phi3"] - 57) < 1e-7
               for s in full["solutions"] if s["valid"])
    mid, _ = run_json(capsys, "ik", "scara_rsr", "--pose", *pose[:12])
    assert mid["count"] == 16 and "l_bw" in mid["reason"]
    code, _, err = run(capsys, "ik", "scara_rsr", "--pose", *pose[:11])
    assert code == 2 and "takes 13 values" in err


# ---------------------------------------------------------------------------- finite-screw robots through the CLI
def test_screw_robots_round_trip_design_and_bad_input(real_wristkin, capsys):
    """Revolute joints in degrees, slides and pose entries in metres; design = axis directions and points."""
    names = ("r00", "r01", "r02", "px", "r10", "r11", "r12", "py", "r20", "r21", "r22", "pz")
    data, _ = run_json(capsys, "fk", "p1p2p3rarb", "--joints", "0.3", "-0.2", "0.5", "40", "-70")
    flat = [repr(data["solutions"][0]["values"][n]) for n in names]
    back, _ = run_json(capsys, "ik", "p1p2p3rarb", "--pose", *flat)
    assert back["count"] == 1
    got = back["solutions"][0]["values"]
    assert max(abs(got[k] - v) for k, v in {"t1": 0.3, "t2": -0.2, "t3": 0.5, "theta_a": 40, "theta_b": -70}.items()
               ) < 1e-9
    data, _ = run_json(capsys, "fk", "rarararbrb", "--joints", "10", "20", "30", "40", "50")
    flat = [repr(data["solutions"][0]["values"][n]) for n in names]
    back, _ = run_json(capsys, "ik", "rarararbrb", "--pose", *flat)
    assert back["count"] in (2, 4) and any(
        all(abs(s["values"][f"theta{i}"] - 10.0 * i) < 1e-6 for i in range(1, 6)) for s in back["solutions"]
        if s["valid"])
    off = ["1", "0", "0", "0", "0", "0", "-1", "0", "0", "1", "0", "0"]  # Rot(x, 90 deg): not Rot(a) Rot(b)
    data, _ = run_json(capsys, "ik", "p1p2p3rarb", "--pose", *off)
    assert data["count"] == 0 and data["status"] == "unreachable" and "image" in data["reason"]
    code, _, err = run(capsys, "ik", "rarararbrb", "--pose", *flat, "--design", "bx=0.5")
    assert code == 2 and "unit vector" in err


@pytest.mark.skipif(not REAL_MODULE.exists(), reason="generated package not present")
def test_printed_fk_pose_pastes_back_into_ik_and_huge_joints_are_wrapped():
    """The table prints 12 significant digits: the FK pose pasted into `ik`
    finds the joints again; 1e308 joints are wrapped exactly (no traceback, no NaN)."""
    import subprocess
    import sys

    def run_cli(*argv):
        return subprocess.run([sys.executable, "-m", "wristkin", *argv], cwd=REPO_ROOT, capture_output=True,
                              text=True, timeout=120)

    q = ["0.1", "0.2", "0.3", "0.4", "0.5", "0.6"]
    out = run_cli("fk", "puma560", "--rad", "--joints", *q)
    assert out.returncode == 0, out.stderr
    row = [line for line in out.stdout.splitlines() if line.startswith("0  yes")][0].split()
    back = run_cli("ik", "puma560", "--rad", "--pose", *row[2:14])
    assert back.returncode == 0, back.stderr
    found = [line.split()[2:8] for line in back.stdout.splitlines() if " yes " in f" {line} "]
    assert any(max(abs(float(a) - float(b)) for a, b in zip(f, q, strict=True)) < 1e-9 for f in found), back.stdout
    huge = run_cli("fk", "puma560", "--rad", "--joints", "1e308", "1e308", "1e308", "0", "0", "0")
    assert huge.returncode == 0 and "Traceback" not in huge.stderr and "nan" not in huge.stdout.lower()


def _derivation_arguments(parser) -> dict:
    """verb -> its arguments as (option strings or dest, nargs, type, required, help, metavar), from a parser."""
    import argparse

    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return {verb: [(tuple(a.option_strings) or a.dest, a.nargs, a.type, a.required, a.help, a.metavar)
                   for a in p._actions if not isinstance(a, argparse._HelpAction)]
            for verb, p in sub.choices.items() if verb in ("regenerate", "check", "audit", "derive")}


def test_the_wristkin_command_and_derive_cli_take_the_same_derivation_arguments():
    """The runtime's parser is generated from derive/cli_commands.py's table and builds it with a copy of its loop
    (the runtime cannot import derive): both parsers take the same arguments, with the same help."""
    from derive import cli as derive_cli
    from derive import cli_commands

    ours, theirs = _derivation_arguments(cli.build_parser()), _derivation_arguments(derive_cli.build_parser())
    assert sorted(ours) == sorted(theirs) == sorted(verb for verb, _, _ in cli_commands.COMMANDS)
    assert ours == theirs
    assert cli._DERIVATION_COMMANDS == cli_commands.COMMANDS, "generated/ is stale: make regenerate"
