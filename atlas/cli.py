"""`wristkin atlas MECHANISM --sweep NAME=START:STOP:N ... --out DIR`: run (or resume) a design sweep, then write
the summary table and the report (docs/atlas.md). Exit codes: 0 done, 1 a missing extra or a failed run, 2 bad
arguments (an unknown mechanism or parameter, a malformed --sweep, a store holding another sweep)."""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise _Usage(message)


class _Usage(Exception):
    pass


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="wristkin atlas", description="Design atlas: sweep design parameters, measure every design over "
                "a seeded sample of its workspace (generated C batch solvers on Dask), write a Zarr store, a summary "
                "table and a report. Angles in degrees, lengths in metres.")
    p.add_argument("mechanism", metavar="MECHANISM|SPEC",
                   help="a catalogue mechanism (wristkin list), or a spec file / URDF: derived into DIR/derived "
                        "first (needs wristkin[derive]), then swept")
    p.add_argument("--free", metavar="JOINT", help="SPEC: a redundant arm's joint held as the design parameter")
    p.add_argument("--sweep", action="append", required=True, metavar="NAME=START:STOP:N",
                   help="a swept design parameter: N values from START to STOP (repeat for more; outer product)")
    p.add_argument("--design", nargs="+", action="extend", metavar="NAME=VALUE",
                   help="fixed design parameters (the others keep the catalogue default)")
    p.add_argument("--samples", type=int, default=1000, metavar="N",
                   help="pose samples and joint samples per design (default 1000)")
    p.add_argument("--grid", action="store_true", help="a regular grid of about N points instead of random samples")
    p.add_argument("--seed", type=int, default=0, help="sample seed (default 0)")
    p.add_argument("--threshold", type=float, default=0.1,
                   help="conditioning below which a solution counts as near-singular (default 0.1)")
    p.add_argument("--tilt-max", type=float, default=90.0, metavar="DEG",
                   help="largest platform tilt / swing sampled (default 90)")
    p.add_argument("--workers", type=int, metavar="N", help="a local Dask cluster of N worker processes")
    p.add_argument("--scheduler", metavar="ADDRESS", help="an existing dask.distributed scheduler (tcp://host:8786)")
    p.add_argument("--design-chunk", type=int, metavar="N", help="designs per task (default: about 65536 solves)")
    p.add_argument("--sample-chunk", type=int, metavar="N", help="samples per task (rounded up to 1024)")
    p.add_argument("--focus", nargs="+", action="extend", metavar="NAME=VALUE",
                   help="the design whose workspace maps the report draws (default: the catalogue design)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder (resumed when it holds this sweep)")
    p.add_argument("--overwrite", action="store_true", help="discard a store in DIR that holds another sweep")
    p.add_argument("--no-report", action="store_true", help="write the store and summary only")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    return p


class _Failed(Exception):
    def __init__(self, message: str, code: int):
        super().__init__(message)
        self.code = code


def _derived(target: str, out: str, free: str | None) -> str:
    """A catalogue name as it is; a spec file / URDF derived into OUT/derived (once: a resumed sweep reuses it),
    named by its solver's path (workers import it from there: a shared folder on a cluster)."""
    from pathlib import Path

    from .mechanisms import FILE_PREFIX

    path = Path(target)
    if path.suffix.lower() not in (".toml", ".urdf"):
        return target
    if not path.is_file():
        raise _Failed(f"{target}: no such file (a spec file or a URDF)", EXIT_USAGE)
    try:
        from derive import own_robot
        from derive.spec import SpecError
    except ImportError as exc:
        raise _Failed(f"a spec file is derived first, which needs the derivation stack ({exc}): pip install "
                      "'wristkin[derive]'", EXIT_FAILED) from exc
    try:
        name = own_robot.description(path, free=free).NAME  # the name alone: nothing derived
        folder = Path(out) / "derived"
        solver = folder / "python" / f"{name}.py"
        if not solver.is_file():
            own_robot.derive(path, folder, free=free, progress=lambda text: print(text, file=sys.stderr))
    except SpecError as exc:
        raise _Failed(str(exc), EXIT_USAGE) from None
    return FILE_PREFIX + str(solver.resolve())


def main(argv: Sequence[str] | None = None) -> int:
    try:
        args = build_parser().parse_args(argv)
    except _Usage as exc:
        print(f"wristkin atlas: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except SystemExit as exc:  # --help
        return exc.code if isinstance(exc.code, int) else EXIT_OK
    try:
        import dask  # noqa: F401
        import distributed  # noqa: F401
        import xarray  # noqa: F401
        import zarr  # noqa: F401
    except ImportError as exc:
        print(f"wristkin atlas: error: the atlas needs the `atlas` extra ({exc.name} is missing): "
              "pip install 'wristkin[atlas]'", file=sys.stderr)
        return EXIT_FAILED
    from .mechanisms import Options, UnknownMechanism
    from .runner import StoreMismatch, run_sweep
    from .sweep import SweepError

    if args.samples < 1 or not (0.0 < args.tilt_max <= 180.0) or not (0.0 < args.threshold < 1.0):
        print("wristkin atlas: error: need --samples >= 1, 0 < --tilt-max <= 180, 0 < --threshold < 1",
              file=sys.stderr)
        return EXIT_USAGE
    options = Options(threshold=args.threshold, tilt_max=math.radians(args.tilt_max))
    try:
        target = _derived(args.mechanism, args.out, args.free)
    except _Failed as exc:
        print(f"wristkin atlas: error: {exc}", file=sys.stderr)
        return exc.code
    try:
        ds = run_sweep(target, args.sweep, args.out, designs=args.design, samples=args.samples,
                       seed=args.seed, grid=args.grid, options=options, workers=args.workers,
                       scheduler=args.scheduler, design_chunk=args.design_chunk, sample_chunk=args.sample_chunk,
                       progress=not args.quiet, overwrite=args.overwrite)
    except (SweepError, UnknownMechanism, StoreMismatch) as exc:
        print(f"wristkin atlas: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    from .report import write_outputs

    paths = write_outputs(args.out, ds, focus=args.focus, report=not args.no_report)
    for path in paths:
        print(path)
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
