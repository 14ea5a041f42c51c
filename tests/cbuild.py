"""Compile C sources into a shared library for ctypes tests.

One place owns the strict flag set so every C test compiles the way the
design card demands (-std=c99 -pedantic -Wall -Wextra -Werror).
"""

from __future__ import annotations

import ctypes
import hashlib
import os
import shutil
import subprocess
from pathlib import Path

STRICT_FLAGS = ["-std=c99", "-pedantic", "-Wall", "-Wextra", "-Werror", "-O2", "-fPIC"]
SANITIZE_FLAGS = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-g", "-O1"]
C_DIR = Path(__file__).resolve().parent.parent / "generated" / "c"
RUNTIME_C = C_DIR / "wristkin_runtime.c"  # every generated mechanism links the shared runtime
BUILD_DIR = Path(os.environ.get("WRISTKIN_BUILD_DIR", Path(__file__).resolve().parent.parent / "build" / "c"))


def compiler() -> str:
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    if not cc:
        raise RuntimeError("no C compiler found (set CC)")
    return cc


def sanitizer_available() -> bool:
    """The compiler links ASan / UBSan (some toolchains ship without their runtimes)."""
    probe = subprocess.run([compiler(), "-fsanitize=address,undefined", "-x", "c", "-", "-o", "/dev/null"],
                           input="int main(void){return 0;}", capture_output=True, text=True)
    return probe.returncode == 0


def compile_shared(sources: list[Path], include_dirs: list[Path] = (), name: str = "lib",
                   extra_flags: list[str] = ()) -> Path:
    """Build a shared library from `sources`; cached by a hash of inputs and flags."""
    flags = STRICT_FLAGS + list(extra_flags)
    digest = hashlib.sha256()
    for src in sorted(map(Path, sources)):
        digest.update(src.read_bytes())
    for inc in include_dirs:
        for hdr in sorted(Path(inc).glob("*.h")):
            digest.update(hdr.read_bytes())
    digest.update(" ".join(flags).encode())
    BUILD_DIR.mkdir(parents=True, exist_ok=True)
    out = BUILD_DIR / f"{name}-{digest.hexdigest()[:16]}.so"
    if not out.exists():
        # Built under a private name, then renamed: parallel test workers that need the same library build it
        # at most once each and never load a half-written file.
        tmp = out.with_name(f"{out.stem}.{os.getpid()}.tmp.so")
        cmd = [compiler(), *flags, "-shared", "-o", str(tmp), *map(str, sources)]
        cmd += [f"-I{inc}" for inc in include_dirs] + ["-lm"]
        subprocess.run(cmd, check=True, capture_output=True, text=True)
        os.replace(tmp, out)
    return out


def compile_executable(sources: list[Path], include_dirs: list[Path] = (), name: str = "prog",
                       extra_flags: list[str] = ()) -> Path:
    """Build an executable (used for sanitizer runs, where ctypes loading is awkward)."""
    flags = STRICT_FLAGS + list(extra_flags)
    BUILD_DIR.mkdir(parents=True, exist_ok=True)
    out = BUILD_DIR / name
    tmp = out.with_name(f"{out.name}.{os.getpid()}.tmp")
    cmd = [compiler(), *flags, "-o", str(tmp), *map(str, sources)]
    cmd += [f"-I{inc}" for inc in include_dirs] + ["-lm"]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    os.replace(tmp, out)
    return out


def load(path: Path) -> ctypes.CDLL:
    return ctypes.CDLL(str(path))
