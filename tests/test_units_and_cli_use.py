"""Units stated, never guessed, and the first uses of a derived robot's command line (issue 21, items 10 and 11):
a spec's `unit = "deg"`, a radian spec's angle that looks like degrees refused, "-pi" as a limit; the emitted
NAME.py's --deg / --rad, fk with --free, a rounded quaternion treated as a rounded matrix is, labelled output, and
no traceback when the output is piped into `head`."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

from derive import own_robot
from derive.families import chain as chain_family
from derive.spec import Spec, SpecError

ROBOTS = Path(__file__).resolve().parent / "robots"


def _kr6_spec(edit=None, file="kr6_dh.toml") -> Spec:
    data = tomllib.loads((ROBOTS / "kr6" / file).read_text())
    if edit:
        edit(data)
    return Spec(data, ROBOTS / "kr6" / file)


def _in_degrees(data):
    data["unit"] = "deg"
    for j in data["joint"]:
        for key in ("alpha", "theta", "lower", "upper"):
            if key in j:
                v = j[key]
                x = eval(v, {"pi": math.pi}) if isinstance(v, str) else v  # noqa: S307 - the test's own file
                j[key] = math.degrees(x)


def test_a_spec_in_degrees_describes_the_same_robot():
    rad = chain_family.from_spec(_kr6_spec()).chain
    deg = chain_family.from_spec(_kr6_spec(_in_degrees)).chain
    np.testing.assert_allclose(deg.axes, rad.axes, atol=1e-15)
    np.testing.assert_allclose(deg.points, rad.points, atol=1e-15)
    np.testing.assert_allclose(deg.lower, rad.lower, rtol=1e-15)


def test_a_radian_spec_with_an_angle_in_degrees_is_refused():
    def alpha_90(data):
        data["joint"][1]["alpha"] = -90
    with pytest.raises(SpecError, match=r"joint\[1\]\.alpha.*looks like degrees; write unit = \"deg\""):
        chain_family.from_spec(_kr6_spec(alpha_90))

    def limit_170(data):
        data["joint"][0]["upper"] = 170
    with pytest.raises(SpecError, match=r"upper.*2 turn"):
        chain_family.from_spec(_kr6_spec(limit_170))


def test_limits_take_expressions_of_pi():
    def pi_limits(data):
        data["joint"][0]["lower"], data["joint"][0]["upper"] = "-pi", "pi"
    c = chain_family.from_spec(_kr6_spec(pi_limits)).chain
    assert (c.lower[0], c.upper[0]) == (-math.pi, math.pi)


# ---------------------------------------------------------------------------------------- the module CLI
@pytest.fixture(scope="module")
def iiwa(tmp_path_factory):
    out = tmp_path_factory.mktemp("iiwa")
    own_robot.derive(ROBOTS / "iiwa14" / "iiwa14.urdf", out, name="iiwa", free="a3", progress=lambda _: None,
                     native=False)
    return out / "python" / "iiwa.py", own_robot.import_solver(out, "iiwa")


def _run(script, *args):
    return subprocess.run([sys.executable, str(script), *map(str, args)], capture_output=True, text=True, timeout=60)


def test_fk_takes_the_free_joint_from_free_and_degrees(iiwa):
    script, m = iiwa
    q = [10, 20, 30, 40, 50, 60, 70]
    expect = m.fk_matrix(np.radians(q), [math.radians(30)])
    for args in (["--joints", *q[:2], *q[3:], "--free", 30, "--deg"], ["--joints", *q, "--deg"],
                 ["--joints", *q, "--free", 30, "--deg"], ["--joints", *np.radians(q), "--rad"]):
        r = _run(script, "fk", *args, "--json")
        assert r.returncode == 0, r.stderr
        out = json.loads(r.stdout)
        assert out["columns"][3] == "px (m)"
        np.testing.assert_allclose(np.reshape(out["solutions"][0]["values"], (3, 4)), expect[:3], atol=1e-12)
    r = _run(script, "fk", "--joints", *q, "--free", 31, "--deg")
    assert r.returncode == 2 and "differs between --joints and --free" in r.stderr
    r = _run(script, "fk", "--joints", *q[:6])
    assert r.returncode == 2 and "or --free for a3" in r.stderr
    r = _run(script, "fk", "--joints", *q, "--deg")
    assert "rotation R | position p (m)" in r.stdout and "rpy (deg" in r.stdout


def test_ik_columns_and_degrees(iiwa):
    script, m = iiwa
    q = np.radians([10, 20, 30, 40, 50, 60, 70])
    T = m.fk_matrix(q, [q[2]])  # the pose given as its 12 row-major numbers [R | p]
    r = _run(script, "ik", "--pose", *T[:3].ravel(), "--free", 30, "--deg", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["columns"][0] == "a1 (deg)"
    assert min(np.max(np.abs(np.array(s["values"]) - np.degrees(q))) for s in out["solutions"]) < 1e-6
    text = _run(script, "ik", "--pose", *T[:3].ravel(), "--free", q[2]).stdout
    assert "a1 (rad)" in text.splitlines()[1]
    # the text lists the same sets as the JSON, one row each below the status and the column header
    assert len(text.strip().splitlines()) - 2 == len(out["solutions"])


def test_a_rounded_quaternion_is_refused_like_a_rounded_matrix(iiwa):
    script, m = iiwa
    r = _run(script, "ik", "--pose", 0.3, 0.2, 0.5, 0.7071, 0, 0, 0.7071)
    assert r.returncode == 2 and "quaternion's norm is 0.99999041" in r.stderr and "within 1e-06 of 1" in r.stderr
    r = _run(script, "ik", "--pose", 0.3, 0.2, 0.5, 0.7071, 0.0, 0.0, math.sqrt(1 - 0.7071 ** 2))
    assert r.returncode == 0, r.stderr
    r = _run(script, "ik", "--pose", 1, 0, 0, 0.3, 0, 0.7071, -0.7071, 0.2, 0, 0.7071, 0.7071, 0.5)
    assert r.returncode == 2 and "not a rotation" in r.stderr


def test_piping_into_head_leaves_no_traceback(iiwa):
    script, _ = iiwa
    # `true` reads nothing and exits at once: every write finds the pipe closed (head would race with the writer)
    cmd = f"'{sys.executable}' '{script}' ik --pose 0.3 0.2 0.5 3.1 0 0 | true"
    r = subprocess.run(cmd, shell=True, capture_output=True, text=True, timeout=60)
    assert r.stderr == "", r.stderr
    wk = Path(sys.executable).parent / "wristkin"
    r = subprocess.run(f"'{wk}' fk puma560 --joints 1 2 3 4 5 6 | true; '{wk}' list | true", shell=True,
                       capture_output=True, text=True, timeout=60)
    assert r.stderr == "", r.stderr


def test_every_cli_states_its_angle_unit(iiwa):
    script, _ = iiwa
    for args in (["ik", "--help"], ["fk", "--help"]):
        text = _run(script, *args).stdout
        assert "--deg" in text and "radians (the default)" in text
    wk = Path(sys.executable).parent / "wristkin"
    text = subprocess.run([str(wk), "ik", "--help"], capture_output=True, text=True).stdout
    assert "degrees (the default)" in text and "--rad" in text


def test_a_catalogue_dh_spec_with_alpha_in_degrees_is_refused():
    """The serial family's DH angles are radians (expressions of pi): alpha = 90 is refused, naming the field."""
    import copy

    from derive.families.serial import dh_spec

    root = Path(__file__).resolve().parent.parent
    data = tomllib.loads((root / "catalogue" / "puma560.toml").read_text())
    dh_spec.load(Spec(copy.deepcopy(data), "puma560.toml"))
    data["joint"][0]["alpha"] = 90
    with pytest.raises(SpecError, match=r"joint\[0\]\.alpha.*90 looks like degrees"):
        dh_spec.load(Spec(data, "puma560.toml"))
