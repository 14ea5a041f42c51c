"""The derivation's verbs of the `wristkin` command line: regenerate, check, audit (docs/API.md, "CLI").

    python -m derive.cli regenerate [--out DIR] [--jobs N] [--catalogue DIR]
    python -m derive.cli check [--jobs N]
    python -m derive.cli audit [M] [--out DIR] [--jobs N] [--catalogue DIR]
    python -m derive.cli native [--out DIR]
    python -m derive.cli derive SOURCE --out DIR [--name N] [--base LINK] [--tip LINK] [--free JOINT]
                                [--geometry-tol TOL] [--no-native] [--jobs N]

`native` compiles DIR's generated C into DIR/python/wristkin/_native (the solvers of DIR then run the C; needs a
C compiler and the Python headers, not the derivation stack).

--catalogue DIR derives the spec files (*.toml, docs/specs.md) in DIR instead of the catalogue; a malformed spec
is reported as one line naming the file, the field and what was expected.

`wristkin regenerate|check|audit` (the runtime's CLI, wristkin/cli.py) hands its parsed arguments to `run`;
`python -m derive.cli` parses them itself, so the derivation never depends on the generated CLI it rebuilds.
The pipeline (SymPy, CasADi, Jinja2) is imported only when a verb runs.

Exit codes: 0 done, 1 generated/ is stale (`check`) or the derivation stack is missing, 2 bad arguments or a
malformed spec file.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from .cli_commands import add_commands
from .spec import SpecError  # standard library only: imports without the derivation stack

ROOT = Path(__file__).resolve().parent.parent
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


class _Error(Exception):
    def __init__(self, message: str, code: int):
        super().__init__(message)
        self.code = code


def checkout_generated() -> Path | None:
    """The checkout's generated/ when derive/ runs from a source checkout (templates/ beside it), else None."""
    return ROOT / "generated" if (ROOT / "templates").is_dir() and (ROOT / "pyproject.toml").is_file() else None


def _out(args) -> Path:
    if getattr(args, "out", None):
        return Path(args.out)
    default = checkout_generated()
    if default is None:
        raise _Error("--out DIR is required outside a source checkout (derivation verbs write only where told)",
                     EXIT_USAGE)
    return default


def _stack_missing(exc: ImportError) -> _Error:
    """The error for an import that failed: a third-party module of the derive extra missing is the user's to
    install; a module of wristkin's own missing is a broken installation, said as such."""
    name = getattr(exc, "name", None) or ""
    if name == "derive" or name.startswith("derive."):
        return _Error(f"this installation of wristkin lacks its own module {name!r} ({exc}): reinstall it; if it "
                      "persists, the package is built without it (a defect: please report it)", EXIT_FAILED)
    return _Error(f"the derivation stack is not installed ({exc}): pip install 'wristkin[derive]' "
                  "(in a checkout: make venv)", EXIT_FAILED)


def _pipeline():
    try:
        return importlib.import_module("derive.pipeline")
    except ImportError as exc:
        raise _stack_missing(exc) from exc


def _known_mechanisms() -> tuple[str, ...] | None:
    try:
        return tuple(importlib.import_module("wristkin").MECHANISMS)
    except (ImportError, AttributeError):
        return None  # no generated package yet: the pipeline judges the name


def _catalogue(args) -> dict:
    """The pipeline's catalogue argument: {} for the default catalogue."""
    folder = getattr(args, "catalogue", None)
    if folder is None:
        return {}
    if not Path(folder).is_dir():
        raise _Error(f"--catalogue {folder}: not a directory", EXIT_USAGE)
    return {"catalogue": Path(folder)}


def cmd_regenerate(args) -> int:
    pipeline = _pipeline()
    out = _out(args)
    t0 = time.perf_counter()
    files = pipeline.regenerate(out, jobs=args.jobs, **_catalogue(args))
    print(f"regenerated {len(files)} file(s) in {out} ({time.perf_counter() - t0:.1f} s)")
    return EXIT_OK


def cmd_check(args) -> int:
    pipeline = _pipeline()
    ok, diff = pipeline.check(jobs=args.jobs)
    if ok:
        print("generated/ is up to date")
        return EXIT_OK
    sys.stdout.write(diff if diff.endswith("\n") or not diff else diff + "\n")
    print("generated/ is stale: run `make regenerate` and commit the result", file=sys.stderr)
    return EXIT_FAILED


def cmd_audit(args) -> int:
    where = _catalogue(args)
    pipeline = _pipeline()
    names = None
    if args.mechanism:
        known = tuple(pipeline.registry(where["catalogue"])) if where else _known_mechanisms()
        if known is not None and args.mechanism not in known:
            raise _Error(f"unknown mechanism {args.mechanism!r} (known: {', '.join(known)})", EXIT_USAGE)
        names = [args.mechanism]
    out = _out(args)
    for path in pipeline.audit(names, out, jobs=args.jobs, **where):
        print(path)
    return EXIT_OK


def _pairs(values, option: str, what: str) -> dict[str, str]:
    """NAME=VALUE options (repeated) as a dict."""
    out = {}
    for item in values or ():
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise _Error(f"{option} {item!r}: expected NAME={what}", EXIT_USAGE)
        out[name.strip()] = value
    return out


def cmd_derive(args) -> int:
    try:
        from . import own_robot
    except ImportError as exc:
        raise _stack_missing(exc) from exc
    from .model import CheckFailed, DescriptionError, NoDecomposition

    if not Path(args.source).is_file():
        raise _Error(f"{args.source}: no such file (a URDF, a xacro file or a spec file)", EXIT_USAGE)
    try:
        own_robot.derive(args.source, Path(args.out), args.name, args.base, args.tip, args.free, args.geometry_tol,
                         native=not args.no_native, xacro_args=_pairs(args.xacro_args, "--xacro-arg", "VALUE"),
                         packages=_pairs(args.packages, "--package", "DIR"), redundancy=args.redundancy,
                         jobs=args.jobs or _pipeline().default_jobs())
    except NoDecomposition as exc:
        raise _Error(str(exc), EXIT_FAILED) from None
    except CheckFailed as exc:  # the robot's derivation did not prove out: no solver is written for it
        raise _Error(f"{args.source}: refused, the derivation for this robot failed a check ({exc}), so no "
                     "solver is written", EXIT_FAILED) from None
    except DescriptionError as exc:
        raise _Error(str(exc), EXIT_USAGE) from None
    return EXIT_OK


def cmd_native(args) -> int:
    from .native_build import BuildError, build

    try:
        print(build(_out(args)))
    except BuildError as exc:
        raise _Error(str(exc), EXIT_FAILED) from None
    return EXIT_OK


COMMANDS = {"regenerate": cmd_regenerate, "check": cmd_check, "audit": cmd_audit, "native": cmd_native,
            "derive": cmd_derive}


def run(args) -> int:
    """Run the verb `args.verb` with parsed arguments (out, jobs, mechanism); errors: one line on stderr."""
    try:
        return COMMANDS[args.verb](args)
    except _Error as exc:
        print(f"wristkin: error: {exc}", file=sys.stderr)
        return exc.code
    except SpecError as exc:
        print(f"wristkin: error: {exc}", file=sys.stderr)
        return EXIT_USAGE


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m derive.cli", description="Derive and write wristkin's generated files.")
    sub = p.add_subparsers(dest="verb", metavar="VERB", required=True)
    add_commands(sub)  # regenerate, check, audit, derive: the table the wristkin command is generated with
    s = sub.add_parser("native", help="compile DIR's generated C into the extension its Python modules call")
    s.add_argument("--out", metavar="DIR", help="output directory (default: the checkout's generated/)")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    return run(build_parser().parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
