"""The CPython binding's hand-written helpers (runtime/c/native/wkn_*.c) compiled strictly as they are (with the
headers the generated binding includes first) and, where they need no interpreter state, called through ctypes
on cases whose answer is written out here; the generated binding carries them verbatim."""

from __future__ import annotations

import ctypes
import math
import subprocess
import sysconfig
from pathlib import Path

import numpy as np
import pytest
from cbuild import BUILD_DIR, compiler

from derive import runtime_files
from derive.pipeline import NATIVE_RUNTIME_FILES

ROOT = Path(__file__).resolve().parent.parent
# strict but for -pedantic: numpy's C API macros call through its table of object pointers converted to function
# pointers, which ISO C does not define (the generated binding compiles them the same way; every other warning is
# an error here)
CSTRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "-fPIC"]
D = ctypes.POINTER(ctypes.c_double)
IP = ctypes.POINTER(ctypes.c_int)
U = ctypes.POINTER(ctypes.c_uint)


@pytest.fixture(scope="module")
def lib():
    BUILD_DIR.mkdir(parents=True, exist_ok=True)
    out = BUILD_DIR / "native_helpers.so"
    cmd = [compiler(), *CSTRICT, "-shared", "-o", str(out), str(ROOT / "tests" / "c" / "native_helpers_harness.c"),
           f"-I{sysconfig.get_paths()['include']}", f"-I{np.get_include()}", f"-I{ROOT / 'runtime' / 'c'}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    L = ctypes.PyDLL(str(out))  # its Python symbols resolve in this interpreter
    L.wkt_summary.argtypes = [ctypes.c_int, IP, U, ctypes.c_int]
    L.wkt_last_row_ok.argtypes = [D]
    L.wkt_last_row.argtypes = [D]
    L.wkt_fill.argtypes = [ctypes.c_int] * 3 + [IP, U, D, D, D, ctypes.POINTER(ctypes.c_ubyte),
                                                 ctypes.POINTER(ctypes.c_int64), D]
    return L


def test_summary_packs_status_count_and_projection(lib):
    valid = np.array([1, 0, 1, 1], np.int32)
    flags = np.array([0, 32, 0, 0], np.uint32)  # 32 = WK_FLAG_PROJECTED, on an invalid row: not counted
    s = lib.wkt_summary(3, valid.ctypes.data_as(IP), flags.ctypes.data_as(U), 4)
    assert (s & 0xFF, s >> 8 & 0xFF, s >> 16) == (3, 3, 0)
    flags[2] = 32
    s = lib.wkt_summary(0, valid.ctypes.data_as(IP), flags.ctypes.data_as(U), 4)
    assert (s & 0xFF, s >> 8 & 0xFF, s >> 16) == (0, 3, 1)


def test_fill_copies_valid_rows_and_nans_the_others(lib):
    rng = np.random.default_rng(7)
    max_, nv, na = 4, 3, 2
    valid = np.array([1, 0, 1, 0], np.int32)
    flags = np.array([1, 2, 8, 16], np.uint32)
    values, aux = rng.normal(size=(max_, nv)), rng.normal(size=(max_, na))
    ov, oa = np.zeros((max_, nv)), np.zeros((max_, na))
    ovalid, oflags = np.zeros(max_, np.uint8), np.zeros(max_, np.int64)
    lib.wkt_fill(max_, nv, na, valid.ctypes.data_as(IP), flags.ctypes.data_as(U), values.ctypes.data_as(D),
                 aux.ctypes.data_as(D), ov.ctypes.data_as(D), ovalid.ctypes.data_as(ctypes.POINTER(ctypes.c_ubyte)),
                 oflags.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)), oa.ctypes.data_as(D))
    assert list(ovalid) == [1, 0, 1, 0]
    assert np.array_equal(ov[[0, 2]], values[[0, 2]]) and np.all(np.isnan(ov[[1, 3]]))
    assert np.array_equal(oa[[0, 2]], aux[[0, 2]]) and np.all(np.isnan(oa[[1, 3]]))


def test_last_row_check_and_fill(lib):
    t = np.zeros(16)
    t[:12] = np.arange(12.0)
    lib.wkt_last_row(t.ctypes.data_as(D))
    assert list(t[12:]) == [0.0, 0.0, 0.0, 1.0]
    assert lib.wkt_last_row_ok(t.ctypes.data_as(D)) == 1
    for k, v in ((12, 1e-3), (15, 1.0 + 1e-3), (13, math.nan)):
        u = t.copy()
        u[k] = v
        assert lib.wkt_last_row_ok(u.ctypes.data_as(D)) == 0


def test_the_binding_carries_the_helpers_verbatim_and_its_template_is_thin():
    text = (ROOT / "generated" / "native" / "_native.c").read_text()
    assert all(runtime_files.inline(rel) in text for rel in NATIVE_RUNTIME_FILES)
    sources = (ROOT / "runtime" / "c" / "native").glob("*.c")
    assert sorted(NATIVE_RUNTIME_FILES) == sorted(f"c/native/{p.name}" for p in sources)
    assert len((ROOT / "templates" / "c" / "native.c.jinja").read_text().splitlines()) <= 400
