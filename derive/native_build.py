"""Compile a generated folder's C into its package's extension: OUT/native/_native.c and OUT/c/*.c ->
OUT/python/wristkin/_native<EXT_SUFFIX>. One command for solvers derived from a user's own specs
(`python -m derive.cli native --out OUT`); the catalogue's extension is built by pip install (setup.py)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sysconfig
import tempfile
from pathlib import Path


class BuildError(RuntimeError):
    """No compiler, or the compile failed (the solvers then run on numpy)."""


def build(out: Path, cc: str | None = None, target: Path | None = None) -> Path:
    """Compile; `target` (default OUT/python/wristkin/_native<EXT_SUFFIX>) is where the extension goes."""
    return start(out, cc, target).wait()


class PendingBuild:
    """A build under way: one compiler process per source (they run side by side on the machine's cores, and beside
    the caller's own work), linked by `wait`."""

    def __init__(self, cc: str, flags: list[str], sources: list[Path], target: Path):
        self._cc, self._target = cc, target
        self._dir = tempfile.TemporaryDirectory(prefix="wristkin_build_")
        self._objects = [Path(self._dir.name) / f"{i}_{src.stem}.o" for i, src in enumerate(sources)]
        self._jobs = [(src, subprocess.Popen([cc, *flags, "-c", str(src), "-o", str(obj)], stdout=subprocess.PIPE,
                                             stderr=subprocess.PIPE, text=True))
                      for src, obj in zip(sources, self._objects, strict=True)]

    def cancel(self) -> None:
        """Stop the compilers and remove their objects (the caller failed before it needed the extension)."""
        for _, job in self._jobs:
            if job.poll() is None:
                job.kill()
            job.communicate()
        self._dir.cleanup()

    def wait(self) -> Path:
        """The extension, once every source compiled and the objects linked; BuildError naming the first failure."""
        try:
            for src, job in self._jobs:
                _, err = job.communicate()
                if job.returncode != 0:
                    _fail([self._cc, "-c", str(src)], err)
            cmd = [self._cc, "-shared", *map(str, self._objects), "-o", str(self._target), "-lm"]
            run = subprocess.run(cmd, capture_output=True, text=True)
            if run.returncode != 0:
                _fail(cmd, run.stderr)
            return self._target
        finally:
            self.cancel()  # after a failure the other compilers are stopped, not left to finish


def start(out: Path, cc: str | None = None, target: Path | None = None) -> PendingBuild:
    """Begin the build of `build` and return at once: the caller waits for it when it needs the extension."""
    out = Path(out)
    binding = out / "native" / "_native.c"
    if not binding.is_file():
        raise BuildError(f"{binding} not found: derive the solvers into {out} first (regenerate --out)")
    cc = cc or os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    if not cc:
        raise BuildError("no C compiler found (set CC): the solvers run on numpy")
    target = target or out / "python" / "wristkin" / f"_native{sysconfig.get_config_var('EXT_SUFFIX') or '.so'}"
    import numpy

    flags = ["-O2", "-std=c99", "-fPIC", f"-I{sysconfig.get_paths()['include']}", f"-I{numpy.get_include()}",
             f"-I{out / 'c'}"]
    try:
        return PendingBuild(cc, flags, [binding, *generated_sources(out / "c")], target)
    except OSError as exc:  # the compiler named by CC does not run
        raise BuildError(f"{cc} could not be run: {exc}") from exc


def _fail(cmd: list[str], stderr: str):
    errors = [ln for ln in stderr.splitlines() if "error" in ln.lower()] or stderr.splitlines() or [""]
    raise BuildError(f"{' '.join(cmd[:2])} ... failed: {errors[0].strip()}\n{stderr.strip()}")


def generated_sources(cdir: Path) -> list[Path]:
    """The folder's C files wristkin wrote (its header in their first lines): a user's own file beside them (a test
    harness with its main) is not part of the extension (it made the build fail, and the solvers fall back to numpy)."""
    from .render import GENERATED_MARK

    def head(f: Path) -> str:
        with f.open(errors="replace") as fh:
            return fh.read(400)
    return [f for f in sorted(cdir.glob("*.c")) if GENERATED_MARK in head(f)]
