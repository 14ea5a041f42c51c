"""As a user installs it: a wheel built from the checkout, installed with the derive extra into a fresh venv, run
from a folder outside the checkout (so nothing is imported from the source tree): `wristkin derive` of a real
description file and `wristkin regenerate --out DIR` work. (A package left out of pyproject.toml's list fails
here, not on the user's machine.)"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
pytestmark = pytest.mark.slow


def _run(cmd, cwd, timeout=900):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV", "WRISTKIN_BACKEND")}
    r = subprocess.run([str(c) for c in cmd], cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)
    assert r.returncode == 0, f"{cmd}: exit {r.returncode}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("wheel")
    # from a copy without the checkout's build outputs: setuptools reuses ./build, whose stale files (a module moved
    # since) would go into the wheel, as they would for a user building in an old checkout after `git pull`
    src = tmp / "src"
    shutil.copytree(ROOT, src, ignore=shutil.ignore_patterns("build", ".venv", ".git", "__pycache__", "*.egg-info",
                                                             ".pytest_cache", ".ruff_cache", ".hypothesis", "*.so"))
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", tmp / "dist", src], cwd=tmp)
    (wheel,) = (tmp / "dist").glob("wristkin-*.whl")
    venv.create(tmp / "venv", with_pip=True)
    py = tmp / "venv" / "bin" / "python"
    _run([py, "-m", "pip", "install", "-q", f"{wheel}[derive]"], cwd=tmp)
    return tmp, tmp / "venv" / "bin"


def test_the_wheel_holds_every_package_of_the_source_tree():
    """pyproject.toml lists derive's packages by hand (derive.templates and derive.specs are mapped folders):
    every folder of derive/ with an __init__.py is among them."""
    import tomllib

    listed = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    on_disk = {".".join(p.parent.relative_to(ROOT).parts) for p in (ROOT / "derive").rglob("__init__.py")}
    assert on_disk <= listed, f"not in pyproject.toml's packages: {sorted(on_disk - listed)}"


def test_an_installed_wheel_derives_a_urdf_and_regenerates(installed):
    tmp, bin_ = installed
    work = tmp / "work"
    work.mkdir()
    r = _run([bin_ / "wristkin", "derive", ROOT / "tests/robots/ur5e/ur5e.urdf", "--base", "base_link", "--tip",
              "tool0", "--out", work / "my_ur", "--name", "my_ur"], cwd=work)
    assert "wrote" in r.stdout
    r = _run([bin_ / "python", work / "my_ur/python/my_ur.py", "ik", "--pose", "0.4", "0.1", "0.3", "3.14", "0",
              "0"], cwd=work)
    assert r.stdout.strip()
    r = _run([bin_ / "wristkin", "regenerate", "--out", work / "g"], cwd=work)
    assert (work / "g" / "python" / "wristkin" / "puma560.py").is_file()
    # what the wheel regenerates is what the checkout commits
    for rel in ("c/puma560.c", "python/wristkin/underactuated_wrist.py"):
        assert (work / "g" / rel).read_bytes() == (ROOT / "generated" / rel).read_bytes(), rel
