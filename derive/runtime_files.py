"""The hand-written runtime sources (runtime/c/*.c|h, runtime/python/*.py): compiled, linted and tested as they
are, and copied into the generated outputs, never rendered.

A source names where the generated banner goes with a line holding MARKER (inside its first comment or
docstring): `emit` replaces that line by the banner, each line with the marker line's prefix (" * " in C). A
Python source that generated modules inline from a marker line on (`INLINE_FROM`) keeps its own imports above
that line, for its own lint and tests; `inline` returns the part below it (a C source is inlined whole)."""

from __future__ import annotations

import functools
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# a checkout's runtime/, else the copy an install ships as derive/runtime
RUNTIME = ROOT / "runtime" if (ROOT / "runtime").is_dir() else Path(__file__).resolve().parent / "runtime"
MARKER = "@generated-by@"
INLINE_FROM = "# wristkin: inlined from here\n"
SUFFIXES = (".c", ".h", ".py")


@functools.cache
def source(rel: str) -> str:
    return (RUNTIME / rel).read_text(encoding="utf-8")


def emit(rel: str, header: list[str]) -> str:
    """The runtime file `rel` with the generated banner in place of its MARKER line."""
    lines = source(rel).splitlines(keepends=True)
    (at,) = [i for i, ln in enumerate(lines) if MARKER in ln]
    prefix = lines[at][: lines[at].index(MARKER)]
    banner = [(prefix + h).rstrip() + "\n" for h in header]
    return "".join(lines[:at] + banner + lines[at + 1:])


def inline(rel: str) -> str:
    """What a generated file includes of the runtime source `rel` (a Python source from INLINE_FROM on)."""
    text = source(rel)
    return text.split(INLINE_FROM, 1)[1] if rel.endswith(".py") else text


@functools.cache
def load_python(rel: str):
    """The Python runtime source `rel` as a module: the derivation runs the very numerics the outputs carry (to
    choose among their options and to check them on the robot)."""
    import importlib.util

    path = RUNTIME / rel
    spec = importlib.util.spec_from_file_location(f"wristkin_runtime_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # registered before it runs: its dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def files() -> list[Path]:
    return sorted(p for p in RUNTIME.rglob("*") if p.suffix in SUFFIXES and "__pycache__" not in p.parts)
