"""generated/ must equal what the pipeline produces now, byte for byte, on any x86-64 CPU.

The test regenerates into a temporary folder under other numeric kernels and another hash seed than the run's
own, and compares every byte with the committed generated/ (written by `make regenerate` under a random hash
seed with the developer's CPU kernels). Under `make test` it regenerates as a CPU without AVX2 computes
(OpenBLAS's Sandybridge kernels, `NPY_DISABLE_CPU_FEATURES=X86_V3`: numpy's AVX2/FMA3 loops off, so also
unlike an AVX-512 CPU); under `make test-portable`, whose environment is that older CPU, it regenerates with
the Haswell (AVX2 + FMA) kernels. CI runs both, so every run of CI compares three kernel sets byte for byte.
One regeneration per run keeps the suite within its time budget. Audit reports state measured errors as
machine-independent buckets (derive/report_numbers.py), which is what makes this hold.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

MACHINES = {
    "haswell-hashseed0": {"PYTHONHASHSEED": "0", "OPENBLAS_CORETYPE": "Haswell"},
    "sandybridge-no-avx2-hashseed12345": {"PYTHONHASHSEED": "12345", "OPENBLAS_CORETYPE": "Sandybridge",
                                          "NPY_DISABLE_CPU_FEATURES": "X86_V3"},
}
# the other machine than the one this run emulates
OTHER = "haswell-hashseed0" if os.environ.get("OPENBLAS_CORETYPE") == "Sandybridge" else \
    "sandybridge-no-avx2-hashseed12345"


def _files(folder: Path) -> list[str]:
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*")
                  if p.is_file() and "__pycache__" not in p.parts and p.suffix not in (".so", ".pyd", ".o"))


@pytest.mark.parametrize("machine", [OTHER])
def test_generated_is_fresh_on_other_kernels(tmp_path, machine):
    out = tmp_path / "generated"
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES")}
    env.update(MACHINES[machine])
    subprocess.run([sys.executable, "-m", "derive.cli", "regenerate", "--out", str(out)], cwd=ROOT, env=env,
                   check=True, capture_output=True, text=True)
    files = _files(out)
    assert files, "regeneration produced nothing"
    assert _files(ROOT / "generated") == files, "generated/ has missing or extra files: run `make regenerate`"
    stale = [rel for rel in files if (ROOT / "generated" / rel).read_bytes() != (out / rel).read_bytes()]
    assert not stale, f"generated/ differs from a regeneration on {machine} ({stale}): run `make regenerate`; " \
                      "if it still differs, a machine-dependent number reached a generated file"


# Own robots whose derivation makes numeric choices: a general 6R (its reading chosen on sampled poses), a Panda with
# a joint held (a general 6R with fallback readings), a calibrated arm (its true chain's constants). The options are
# the helpers' own, so the modules compared are the ones the solver tests use (tests/derived_cache.py).
OWN_ROBOTS = {
    "ur5e_tilted_g6": (ROOT / "tests" / "robots" / "ur5e_tilted" / "ur5e_tilted_poe.toml",
                       {"name": "ur5e_tilted_g6", "free": None}),
    "panda_free1": (ROOT / "tests" / "robots" / "panda" / "panda_dh.toml",
                    {"name": "panda_free1", "free": "joint1"}),
    "kr6c": (ROOT / "tests" / "robots" / "kr6_calibrated" / "kr6_calibrated.urdf",
             {"name": "kr6c", "native": True}),
}


@pytest.mark.parametrize("robot", sorted(OWN_ROBOTS))
def test_own_robots_derive_to_the_same_bytes_on_other_kernels(tmp_path, robot):
    """A user robot derived under the other machine's kernels (a fresh process) equals its derivation under this
    run's (or an earlier pass's: tests/derived_cache.py), byte for byte, compiled extensions aside (they carry their
    build folder). A description's numbers become the solver's constants, so they are composed with fixed-order sums
    (derive/kinematics/same_bits.py), not numpy's BLAS products and SIMD norms: before, the calibrated KR 6's
    constants differed in their last ulp (-7.000001999999983e-09 against ...9856e-09) and the Panda's SCALE too.
    The other derivation lowers its kernels in two processes (`wristkin derive`'s default on two cores, here one
    process each): the bytes must not depend on that either."""
    import json

    import derived_cache

    source, options = OWN_ROBOTS[robot]
    here, there = tmp_path / "here", tmp_path / "there"
    derived_cache.derive(source, here, **options)
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES")}
    env.update(MACHINES[OTHER])
    code = ("import json, sys; from derive import own_robot; "
            "own_robot.derive(sys.argv[1], sys.argv[2], progress=lambda _: None, jobs=2, **json.loads(sys.argv[3]))")
    subprocess.run([sys.executable, "-c", code, str(source), str(there), json.dumps(options)],
                   cwd=ROOT, env=env, check=True, capture_output=True, text=True)
    assert _files(here) == _files(there)
    differ = [rel for rel in _files(here) if (here / rel).read_bytes() != (there / rel).read_bytes()]
    assert not differ, f"{robot} derives to other bytes on {OTHER}: {differ}"


def test_no_timestamps_paths_or_hosts_in_generated():
    import socket

    host = socket.gethostname()
    for p in (ROOT / "generated").rglob("*"):
        if p.is_file() and p.suffix in {".py", ".c", ".h", ".md", ".json"}:
            text = p.read_text()
            assert str(ROOT) not in text and "/tmp/" not in text, p
            assert host not in text or len(host) < 4, p


def test_every_committed_audit_report_has_every_check_passed():
    """With the drift check above (the reports are what a fresh derivation writes), this proves that every step
    of every catalogue derivation passes its checks, without deriving anything again."""
    reports = sorted((ROOT / "generated" / "audit").glob("*.md"))
    assert len(reports) == 10
    for report in reports:
        text = report.read_text()
        assert "FAILED" not in text, f"{report.name}: a derivation check failed"
        assert "symbolic identity: proven" in text, f"{report.name}: no proven step at all"
