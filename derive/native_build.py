"""Compile a generated folder's C into its package's extension: OUT/native/_native.c and OUT/c/*.c ->
OUT/python/wristkin/_native<EXT_SUFFIX>. One command for solvers derived from a user's own specs
(`python -m derive.cli native --out OUT`); the catalogue's extension is built by pip install (setup.py)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sysconfig
from pathlib import Path


class BuildError(RuntimeError):
    """No compiler, or the compile failed (the solvers then run on numpy)."""


def build(out: Path, cc: str | None = None, target: Path | None = None) -> Path:
    """Compile; `target` (default OUT/python/wristkin/_native<EXT_SUFFIX>) is where the extension goes."""
    out = Path(out)
    binding = out / "native" / "_native.c"
    if not binding.is_file():
        raise BuildError(f"{binding} not found: derive the solvers into {out} first (regenerate --out)")
    cc = cc or os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    if not cc:
        raise BuildError("no C compiler found (set CC): the solvers run on numpy")
    target = target or out / "python" / "wristkin" / f"_native{sysconfig.get_config_var('EXT_SUFFIX') or '.so'}"
    sources = [binding, *generated_sources(out / "c")]
    import numpy

    cmd = [cc, "-O2", "-std=c99", "-shared", "-fPIC", f"-I{sysconfig.get_paths()['include']}",
           f"-I{numpy.get_include()}", f"-I{out / 'c'}",
           *map(str, sources), "-o", str(target), "-lm"]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        errors = [ln for ln in run.stderr.splitlines() if "error" in ln.lower()] or run.stderr.splitlines() or [""]
        raise BuildError(f"{' '.join(cmd[:2])} ... failed: {errors[0].strip()}\n{run.stderr.strip()}")
    return target


def generated_sources(cdir: Path) -> list[Path]:
    """The folder's C files wristkin wrote (its header in their first lines): a user's own file beside them (a test
    harness with its main) is not part of the extension (it made the build fail, and the solvers fall back to numpy)."""
    from .render import GENERATED_MARK

    def head(f: Path) -> str:
        with f.open(errors="replace") as fh:
            return fh.read(400)
    return [f for f in sorted(cdir.glob("*.c")) if GENERATED_MARK in head(f)]
