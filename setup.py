"""Builds wristkin._native, the generated C solvers as a CPython extension (metadata is in pyproject.toml).

A plain CPython extension (numpy's C API for the result arrays; numpy is the one runtime dependency anyway):
one shared object for every mechanism, and the generated C compiled as it is.
Where no compiler works the install goes on without it and the solvers run on numpy (wristkin.M.BACKEND).
"""

from __future__ import annotations

import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
C_DIR = Path("generated") / "c"
BINDING = Path("generated") / "native" / "_native.c"


class OptionalBuildExt(build_ext):
    """A failed compile leaves the numpy fallback instead of failing the install."""

    def run(self):
        try:
            super().run()
        except Exception as exc:  # noqa: BLE001 - any build failure means: no extension
            print(f"wristkin: the C extension was not built ({exc}); the solvers run on numpy", file=sys.stderr)

    def build_extension(self, ext):
        try:
            super().build_extension(ext)
        except Exception as exc:  # noqa: BLE001
            print(f"wristkin: the C extension was not built ({exc}); the solvers run on numpy", file=sys.stderr)


def extensions() -> list[Extension]:
    if not (ROOT / BINDING).is_file():  # generated/ not there yet (make regenerate writes it)
        return []
    import numpy

    sources = [BINDING.as_posix(), *sorted(p.as_posix() for p in C_DIR.glob("*.c"))]
    return [Extension("wristkin._native", sources=sources, include_dirs=[C_DIR.as_posix(), numpy.get_include()],
                      extra_compile_args=["-O2", "-std=c99"], libraries=["m"])]


setup(ext_modules=extensions(), cmdclass={"build_ext": OptionalBuildExt})
