"""derive/native_build.py: a folder's C compiled one process per source, beside the caller's work (wristkin derive
waits for it after the audit), with a failure named and a cancelled build leaving nothing running."""

from __future__ import annotations

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


def test_a_cancelled_build_leaves_no_compiler_running(tmp_path):
    out = _folder(tmp_path, "double wk_solver_probe(double x) { return 2.0 * x; }")
    pending = start(out, target=tmp_path / "ext.so")
    pending.cancel()
    assert all(job.poll() is not None for _, job in pending._jobs)
    assert not (tmp_path / "ext.so").exists()


def test_no_compiler_is_a_build_error(tmp_path):
    out = _folder(tmp_path, "double wk_solver_probe(double x) { return 2.0 * x; }")
    with pytest.raises(BuildError):
        start(out, cc=str(tmp_path / "no-such-cc"), target=tmp_path / "ext.so")
