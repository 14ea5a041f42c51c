"""The test suite's own-robot derivations, made once per checkout and reused by its later passes.

`make test`, `make test-portable` and `make test-haswell` run the same tests under other CPU kernels and other random
cases. A derivation does not read the test seed; half of a later pass was SymPy deriving the same robots again (479
of 963 s on 2 cores). So a later pass takes the folder a pass before it derived from the same inputs and spends its
time on what the kernels and the seed change: the solvers' sets against the reference, the emitted code as another
machine runs it (a user derives once and deploys). The derivation's bytes do not depend on the kernels:
test_generated_fresh.py derives a sample of own robots under the other kernels and compares them byte for byte.

An entry is keyed by the description's bytes, the options, the bytes of every file under derive/, runtime/ and
templates/, the versions of Python, SymPy, NumPy and CasADi, and the C compiler: any change derives again. It is
taken only into an empty folder (a derivation into a folder that holds another robot reads that one's API)."""

from __future__ import annotations

import hashlib
import os
import shutil
import sys
import tempfile
from functools import lru_cache
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CACHE = ROOT / ".pytest_cache" / "wristkin-derived"  # .pytest_cache is not committed (.gitignore)


@lru_cache(maxsize=1)
def _tree_key() -> str:
    import casadi
    import numpy
    import sympy

    h = hashlib.sha256()
    for top in ("derive", "runtime", "templates"):
        for path in sorted((ROOT / top).rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                h.update(str(path.relative_to(ROOT)).encode() + b"\0" + path.read_bytes() + b"\0")
    h.update(repr((sys.version, sympy.__version__, numpy.__version__, casadi.__version__,
                   os.environ.get("CC", ""))).encode())
    return h.hexdigest()


def key(source, options: dict) -> str:
    """The entry's name: the source (a description file: its name and bytes; the helpers' descriptions are whole
    in one file, and a file written per process, as the near-special KR 6's, has its folder drawn anew) and the
    options, on this tree."""
    h = hashlib.sha256(_tree_key().encode())
    path = Path(source)
    h.update(path.name.encode() + b"\0" + path.read_bytes())
    h.update(repr(sorted((k, str(v)) for k, v in options.items())).encode())
    return h.hexdigest()[:32]


def _empty(out: Path) -> bool:
    return not out.exists() or not any(out.iterdir())


def derive(source, out: Path, **options) -> None:
    """own_robot.derive(source, out, progress=None, **options), or a copy of the entry an earlier derivation of the
    same inputs left (WRISTKIN_TEST_DERIVE_CACHE=0: always derive)."""
    from derive import own_robot

    out = Path(out)
    if (os.environ.get("WRISTKIN_TEST_DERIVE_CACHE") == "0" or not _empty(out)
            or not isinstance(source, (str, Path)) or not Path(source).is_file()):
        own_robot.derive(source, out, progress=lambda _: None, **options)
        return
    folder = _folder()
    entry = folder / key(source, options)
    if not entry.is_dir():
        fresh = Path(tempfile.mkdtemp(prefix="fresh-", dir=folder))
        try:
            own_robot.derive(source, fresh, progress=lambda _: None, **options)
        except BaseException:
            shutil.rmtree(fresh, ignore_errors=True)
            raise
        try:
            fresh.rename(entry)  # atomic; another worker's entry of the same key may have won
        except OSError:
            shutil.rmtree(fresh, ignore_errors=True)
    shutil.copytree(entry, out, dirs_exist_ok=True)


def _folder() -> Path:
    """This tree's entries (CACHE/<tree key>); the first use on a tree removes the entries of earlier trees, so the
    cache holds one tree's derivations (~30 MB), not every edit's."""
    folder = CACHE / _tree_key()[:16]
    if not folder.is_dir():
        if CACHE.is_dir():
            for old in CACHE.iterdir():
                if old.name != folder.name:
                    shutil.rmtree(old, ignore_errors=True)
        folder.mkdir(parents=True, exist_ok=True)
    return folder
