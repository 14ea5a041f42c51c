"""derive/native_build.py: a folder's C compiled one process per source, beside the caller's work (wristkin derive
waits for it after the audit), with a failure named and a cancelled build leaving nothing running."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from derive.native_build import BuildError, start
from derive.render import GENERATED_MARK


def _folder(tmp_path, body: str):
    (tmp_path / "native").mkdir()
    (tmp_path / "c").mkdir()
    (tmp_path / "native" / "_native.c").write_text("int wk_binding_probe(void) { return 1; }\n")
    (tmp_path / "c" / "solver.c").write_text(f"/* x\n * {GENERATED_MARK} */\n{body}\n")
    (tmp_path / "c" / "user_main.c").write_text("int main(void) { return syntax error here; }\n")  # not ours: left out
    return tmp_path


def test_the_sources_compile_side_by_side_and_link(tmp_path):
    out = _folder(tmp_path, "double wk_solver_probe(double x) { return 2.0 * x; }")
    target = start(out, target=tmp_path / "ext.so").wait()
    assert target.is_file() and target.stat().st_size > 0


def test_a_failing_source_is_named(tmp_path):
    out = _folder(tmp_path, "double wk_solver_probe(double x) { return 2.0 * ; }")
    with pytest.raises(BuildError, match="solver.c"):
        start(out, target=tmp_path / "ext.so").wait()
    assert not (tmp_path / "ext.so").exists()


def test_a_cancelled_build_stops_its_compilers(tmp_path):
    """A compiler that would take a minute (a stand-in that sleeps) is killed, not waited for, and its objects'
    folder removed."""
    out = _folder(tmp_path, "double wk_solver_probe(double x) { return 2.0 * x; }")
    slow = tmp_path / "slow-cc"
    slow.write_text("#!/bin/sh\nexec sleep 60\n")
    slow.chmod(0o755)
    pending = start(out, cc=str(slow), target=tmp_path / "ext.so")
    objects = Path(pending._dir.name)
    assert objects.is_dir()
    t0 = time.perf_counter()
    pending.cancel()
    assert time.perf_counter() - t0 < 10.0
    assert not objects.exists() and not (tmp_path / "ext.so").exists()


def test_no_compiler_is_a_build_error(tmp_path):
    out = _folder(tmp_path, "double wk_solver_probe(double x) { return 2.0 * x; }")
    with pytest.raises(BuildError):
        start(out, cc=str(tmp_path / "no-such-cc"), target=tmp_path / "ext.so")
