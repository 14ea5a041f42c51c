"""Generated C: strict-flag compilation (tested by every C test through cbuild) and ASan/UBSan runs."""

from __future__ import annotations

import importlib
import subprocess
from pathlib import Path

import pytest
from cbuild import RUNTIME_C, SANITIZE_FLAGS, compile_executable, compiler, sanitizer_available

ROOT = Path(__file__).resolve().parent.parent
C_DIR = ROOT / "generated" / "c"


@pytest.mark.skipif(not sanitizer_available(), reason="compiler has no ASan/UBSan runtime")
def test_generated_c_is_clean_under_asan_ubsan():
    exe = compile_executable([ROOT / "tests" / "c" / "uw_sanitize.c", C_DIR / "underactuated_wrist.c", RUNTIME_C],
                             [C_DIR], "uw_sanitize", extra_flags=SANITIZE_FLAGS)
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300,
                         env={"ASAN_OPTIONS": "detect_leaks=1:abort_on_error=1",
                              "UBSAN_OPTIONS": "halt_on_error=1:print_stacktrace=1"})
    assert run.returncode == 0, run.stderr[-4000:]
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr


SERIAL = ["puma560", "rpp_wrist", "scara_wrist", "spherical_wrist", "wrist_1dof", "p1p2p3rarb", "rarararbrb"]


@pytest.mark.skipif(not sanitizer_available(), reason="compiler has no ASan/UBSan runtime")
@pytest.mark.parametrize("name", SERIAL)
def test_serial_chains_are_clean_under_asan_ubsan(name):
    n_joints = importlib.import_module(f"wristkin.{name}").N_JOINTS
    flags = [*SANITIZE_FLAGS, f"-DMECH={name}", f'-DMECH_H="{name}.h"', f"-DN={n_joints}"]
    exe = compile_executable([ROOT / "tests" / "c" / "serial_sanitize.c", C_DIR / f"{name}.c", RUNTIME_C], [C_DIR],
                             f"{name}_sanitize", extra_flags=flags)
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300,
                         env={"ASAN_OPTIONS": "detect_leaks=1:abort_on_error=1",
                              "UBSAN_OPTIONS": "halt_on_error=1:print_stacktrace=1"})
    assert run.returncode == 0, run.stderr[-4000:]
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr


def test_generated_c_compiles_with_strict_flags_as_a_unit():
    for src in sorted(C_DIR.glob("*.c")):
        subprocess.run([compiler(), "-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-c", str(src),
                        "-o", "/dev/null", f"-I{C_DIR}"], check=True, capture_output=True, text=True)


@pytest.mark.skipif(not sanitizer_available(), reason="compiler has no ASan/UBSan runtime")
def test_rsr_wrist_and_hybrid_are_clean_under_asan_ubsan():
    exe = compile_executable([ROOT / "tests" / "c" / "rsr_sanitize.c", C_DIR / "rsr_wrist.c", C_DIR / "scara_rsr.c",
                              RUNTIME_C],
                             [C_DIR], "rsr_sanitize", extra_flags=SANITIZE_FLAGS)
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=300,
                         env={"ASAN_OPTIONS": "detect_leaks=1:abort_on_error=1",
                              "UBSAN_OPTIONS": "halt_on_error=1:print_stacktrace=1"})
    assert run.returncode == 0, run.stderr[-4000:]
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr
