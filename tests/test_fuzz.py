"""Fuzzing the generated C under ASan/UBSan: every mechanism, hostile and near-singular inputs.

tests/c/fuzz.c states the invariants (error returns leave no valid row, valid rows are finite, FK -> IK
keeps the joints or a flagged set stands in, IK -> FK reproduces the pose, hostile values never crash).
The suite runs WRISTKIN_FUZZ_CASES cases per mechanism (default 10 000: 10 mechanisms give 1e5 inputs,
each case several calls); `make fuzz` runs 1e6 per mechanism (1e7 in all). The cases follow
WRISTKIN_TEST_SEED, and the reproducers of the issue that asked for this test are its seed corpus
(tests/test_fuzz_python.py replays them through Python and C).
"""

from __future__ import annotations

import importlib
import os
import subprocess
from pathlib import Path

import pytest
from cbuild import RUNTIME_C, SANITIZE_FLAGS, compile_executable
from seeding import TEST_SEED

ROOT = Path(__file__).resolve().parent.parent
C_DIR = ROOT / "generated" / "c"
CASES = int(os.environ.get("WRISTKIN_FUZZ_CASES", "10000"))

POSE_KIND = {"underactuated_wrist": "POSE_EULER", "rsr_wrist": "POSE_RSR", "scara_rsr": "POSE_HYBRID"}
# prismatic joints are drawn from [-span, span] (metres): the scale of each chain's own links
JOINT_SPAN = {"rpp_wrist": 0.5, "scara_wrist": 0.3, "p1p2p3rarb": 1.0, "scara_rsr": 0.15}


def mechanisms() -> list[str]:
    return sorted(p.stem for p in C_DIR.glob("*.c") if p.stem != "wristkin_runtime")


def build(name: str) -> Path:
    mod = importlib.import_module(f"wristkin.{name}")
    kinds = "".join(getattr(mod, "JOINT_KINDS", "R" * len(mod.JOINT_NAMES)))
    flags = [*SANITIZE_FLAGS, f"-DMECH={name}", f'-DMECH_H="{name}.h"', f"-DUPPER={name.upper()}",
             f'-DKINDS="{kinds}"', f"-DPOSE_KIND={POSE_KIND.get(name, 'POSE_MATRIX12')}",
             f"-DJOINT_SPAN={JOINT_SPAN.get(name, 0.5)}"]
    return compile_executable([ROOT / "tests" / "c" / "fuzz.c", C_DIR / f"{name}.c", RUNTIME_C], [C_DIR],
                              name=f"fuzz_{name}", extra_flags=flags)


@pytest.mark.c_only  # no numpy result enters: the repeated passes on other kernels skip it
@pytest.mark.parametrize("name", mechanisms())
def test_generated_c_survives_fuzzing(name):
    exe = build(name)
    env = {**os.environ, "ASAN_OPTIONS": "abort_on_error=1:detect_leaks=1",
           "UBSAN_OPTIONS": "halt_on_error=1:print_stacktrace=1"}
    run = subprocess.run([str(exe), str(CASES), str(TEST_SEED)], capture_output=True, text=True, env=env, timeout=900)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr, run.stderr
    print(run.stdout.strip())
