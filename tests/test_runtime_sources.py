"""The hand-written runtime sources (runtime/): compiled and linted as they are, their derived constants equal to
a high-precision computation, and copied into the outputs with nothing but the banner changed."""

from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from derive import runtime_files
from derive.angle_reduction import runtime_context
from derive.render import header_lines

ROOT = Path(__file__).resolve().parent.parent
RUNTIME = ROOT / "runtime"
CSTRICT = ["-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror"]


# the root finder is static code inlined into the mechanisms that use it: compiled as its test harness includes it
@pytest.mark.parametrize("source", ["runtime/c/wristkin_runtime.c", "tests/c/poly_roots_harness.c",
                                    "runtime/c/wk_eigen.c", "tests/c/eigen_sanitize.c", "runtime/c/wk_general6r.c",
                                    "tests/c/spatial3_harness.c",
                                    "tests/c/general6r_sanitize.c"])
def test_c_sources_compile_strictly_as_they_are(source, tmp_path):
    cc = shutil.which("gcc") or shutil.which("cc")
    r = subprocess.run([cc, *CSTRICT, "-c", str(ROOT / source), "-I", str(RUNTIME / "c"), "-o",
                        str(tmp_path / "x.o")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_python_sources_pass_ruff():
    r = subprocess.run([sys.executable, "-m", "ruff", "check", str(RUNTIME / "python")], capture_output=True,
                       text=True, cwd=ROOT)
    assert r.returncode == 0, r.stdout + r.stderr


def test_angle_reduction_constants_are_the_derived_ones():
    """2 pi split in two doubles, the bits of 1 / (2 pi) and 2 pi in fixed point: as mpmath computes them."""
    ar = runtime_context()["angle_reduction"]
    c = (RUNTIME / "c" / "wristkin_runtime.c").read_text()
    assert re.search(r"#define WK_TWO_PI_HI (\S+)", c).group(1) == ar["two_pi_hi"]
    assert re.search(r"#define WK_TWO_PI_LO (\S+)", c).group(1) == ar["two_pi_lo"]
    assert re.search(r"#define WK_ONE_TURN_MAX (\S+)", c).group(1) == ar["one_turn_max"]
    assert int(re.search(r"#define WK_WINDOW_WORDS (\d+)", c).group(1)) == ar["window_words"]
    table = re.search(r"wk_inv_two_pi\[(\d+)\] = \{(.*?)\};", c, re.S)
    assert int(table.group(1)) == len(ar["inv_two_pi_words"])
    assert re.findall(r"0x[0-9a-f]{8}u", table.group(2)) == ar["inv_two_pi_words"]
    spec = importlib.util.spec_from_file_location("_wk_runtime_source", RUNTIME / "python" / "_runtime.py")
    py = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = py  # its dataclasses look their module up there
    spec.loader.exec_module(py)
    assert (repr(py._TWO_PI_HI), repr(py._TWO_PI_LO)) == (ar["two_pi_hi_repr"], ar["two_pi_lo_repr"])
    assert py._TWO_PI_FIX_BITS == ar["two_pi_fix_bits"] and repr(py._ONE_TURN_MAX) == ar["one_turn_max"]
    assert py._TWO_PI_FIX == int("".join(ar["two_pi_fix_hex"]), 16)


@pytest.mark.parametrize("rel,out", [("c/wristkin_runtime.c", "c/wristkin_runtime.c"),
                                     ("c/wristkin_common.h", "c/wristkin_common.h"),
                                     ("python/_runtime.py", "python/wristkin/_runtime.py")])
def test_outputs_are_the_sources_with_the_banner(rel, out):
    src = (RUNTIME / rel).read_text().splitlines()
    emitted = runtime_files.emit(rel, header_lines()).splitlines()
    assert len(emitted) == len(src) - 1 + len(header_lines())
    assert [ln for ln in emitted if not any(h in ln for h in header_lines())] == \
           [ln for ln in src if runtime_files.MARKER not in ln]
    assert (ROOT / "generated" / out).read_text().splitlines() == emitted


def test_runtime_sources_hold_no_template_syntax():
    """They are compiled and linted as they are: a Jinja delimiter in one would reach the outputs verbatim."""
    for path in runtime_files.files():
        text = path.read_text()
        assert not any(d in text for d in ("{{", "{%", "{#")), path


@pytest.mark.parametrize("template", ["c/serial.c.jinja", "python/serial.py.jinja"])
def test_the_own_robot_templates_print_data_not_numerics(template):
    """A user robot's solver (the serial family's templates, its stages derived) prints the robot's kernels and data
    and inlines the runtime sources: at most 400 lines, no dispatch on a stage kind (derive/serial_core/views.py
    chooses the sources and renders the stage rows in Python)."""
    text = (ROOT / "templates" / template).read_text()
    assert len(text.splitlines()) <= 400
    assert not re.search(r"\{%-?\s*(el)?if\s+(o|op|kind)\b", text)
    assert "runtime_source(" in text
