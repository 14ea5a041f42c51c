"""The `wristkin` command line (docs/API.md, section "CLI"), the solving part of the numpy-only runtime package.

A wristkin runtime source: the generated wristkin/cli.py is the usage text templates/python/cli.py.jinja
prints, this file from the marker line on (derive/runtime_files.py), then the derivation commands' table
(_DERIVATION_COMMANDS, from derive/cli_commands.py: the generated runtime cannot import derive). Above the
marker, that table from cli_stand_in.py, so that the source is linted and tested as it is
(tests/test_cli_source.py)."""

# the stand-in's import above the marker, the module's own below it: one block to isort, kept in this order
from __future__ import annotations  # noqa: I001

from cli_stand_in import _DERIVATION_COMMANDS

# wristkin: inlined from here
import argparse
import importlib
import json
import math
import re
import sys
from collections.abc import Sequence

PACKAGE = "wristkin"
DERIVATION_VERBS = ("regenerate", "check", "audit", "derive")

EXIT_OK = 0
EXIT_FAILED = 1  # generated/ stale, generated package missing
EXIT_USAGE = 2  # bad input or design

# Aux columns that are not angles when a module does not say (see `_is_angle`).
_NON_ANGLE_AUX = re.compile(r"^(cond_.*|r\d\d)$")


class UsageError(Exception):
    """Bad command-line input: reported as one line on stderr, exit code 2."""


class Failure(Exception):
    """Environment problem (e.g. generated package missing): one line on stderr, exit code 1."""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors and negative numbers such as -1e-3 or -inf taken as values."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # The default only accepts -12 and -1.5; angles are often -1e-3, and -inf/-nan must
        # reach our own validation (one clear error) instead of being taken for options.
        self._negative_number_matcher = re.compile(
            r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)

    def error(self, message):
        raise UsageError(message)


# ---------------------------------------------------------------------------- generated package
def _import_package():
    """The mechanism package (looked up by name at each call, so tests can put a fake one in its place)."""
    try:
        return importlib.import_module(PACKAGE)
    except ImportError as exc:
        raise Failure(f"the generated package '{PACKAGE}' is not importable ({exc}): run `make regenerate`") from exc


def mechanism_names() -> tuple[str, ...]:
    names = getattr(_import_package(), "MECHANISMS", None)
    if names is None:
        raise Failure(f"the generated package '{PACKAGE}' defines no MECHANISMS: run `make regenerate`")
    return tuple(names)


def load_mechanism(name: str):
    names = mechanism_names()
    if name not in names:
        raise UsageError(f"unknown mechanism {name!r} (known: {', '.join(names) or 'none'})")
    return importlib.import_module(f"{PACKAGE}.{name}")


# ---------------------------------------------------------------------------- units and names
def _is_angle(module, name: str, group: str) -> bool:
    """Whether the quantity `name` (in `group`: joint, pose, design, aux, motor) is an angle.

    A module may declare `ANGLE_NAMES` (every angular name it uses). Without it: joint, pose,
    design and motor quantities are angles (true of every mechanism in docs/API.md so far) and
    aux columns are angles unless named cond_* (conditioning) or rIJ (rotation entries).
    """
    declared = getattr(module, "ANGLE_NAMES", None)
    if declared is not None:
        return name in declared
    if group == "aux":
        return not _NON_ANGLE_AUX.match(name)
    return True


def _to_internal(module, names, values, group, rad: bool) -> list[float]:
    return [v if rad or not _is_angle(module, n, group) else math.radians(v)
            for n, v in zip(names, values, strict=True)]


def _to_user(module, names, values, group, rad: bool) -> list[float]:
    return [float(v) if rad or not _is_angle(module, n, group) else math.degrees(float(v))
            for n, v in zip(names, values, strict=True)]


def motor_names(module) -> tuple[str, ...]:
    names = getattr(module, "MOTOR_NAMES", None)
    if names is not None:
        return tuple(names)
    return tuple(f"Phi{i + 1}" for i in range(len(module.JOINT_NAMES)))


def status_name(module, code: int) -> str:
    table = getattr(module, "STATUS_NAMES", None)
    if table is None:
        table = {v: a[len("STATUS_"):].lower() for a in dir(module)
                 if a.startswith("STATUS_") and isinstance(v := getattr(module, a), int)}
    return table.get(int(code), f"status_{int(code)}")


def flag_names(module, bits: int) -> list[str]:
    table = getattr(module, "FLAG_NAMES", None)
    if table is None:
        table = {v: a[len("FLAG_"):].lower() for a in dir(module)
                 if a.startswith("FLAG_") and isinstance(v := getattr(module, a), int)}
    bits = int(bits)
    out = [table[b] for b in sorted(table) if bits & b]
    rest = bits & ~sum(table)
    out += [f"bit{i}" for i in range(rest.bit_length()) if rest >> i & 1]
    return out


# ---------------------------------------------------------------------------- input parsing
def parse_number(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise UsageError(f"{what}: {text!r} is not a number") from None
    if not math.isfinite(value):
        raise UsageError(f"{what}: {text!r} is not finite")
    return value


def parse_vector(texts: Sequence[str], names: Sequence[str], option: str) -> list[float]:
    if len(texts) != len(names):
        raise UsageError(f"{option} takes {len(names)} values ({' '.join(names)}), got {len(texts)}")
    return [parse_number(t, f"{option} {n}") for t, n in zip(texts, names, strict=True)]


def parse_design(items: Sequence[str] | None, module) -> dict[str, float]:
    """`k=v` overrides (user units) keyed by design name; unknown or repeated keys are errors."""
    out: dict[str, float] = {}
    for item in items or ():
        key, sep, text = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise UsageError(f"--design expects NAME=VALUE, got {item!r}")
        if key not in module.DESIGN_NAMES:
            raise UsageError(f"unknown design parameter {key!r} for {module.NAME} "
                             f"(known: {', '.join(module.DESIGN_NAMES)})")
        if key in out:
            raise UsageError(f"design parameter {key!r} given twice")
        out[key] = parse_number(text, f"--design {key}")
    return out


# ---------------------------------------------------------------------------- solve
def solve(verb: str, module, values_text: Sequence[str], design_items, rad: bool, motor: bool) -> dict:
    """Run ik/fk; return the JSON-ready result (angles in degrees unless rad)."""
    err = getattr(module, "WristkinError", ValueError)
    if verb == "ik":
        in_names, in_group, option = tuple(module.POSE_NAMES), "pose", "--pose"
        out_names, out_group = tuple(module.JOINT_NAMES), "joint"
        aux_names = tuple(module.IK_AUX_NAMES)
    else:
        in_names, in_group, option = tuple(module.JOINT_NAMES), "joint", "--joints"
        out_names, out_group = tuple(module.POSE_NAMES), "pose"
        aux_names = tuple(module.FK_AUX_NAMES)
    if motor:
        if not (hasattr(module, "motor_angles") and hasattr(module, "joints_from_motor_angles")):
            raise UsageError(f"{module.NAME} has no motor angles (--motor)")
        if verb == "ik":
            out_names, out_group = motor_names(module), "motor"
        else:
            in_names, in_group = motor_names(module), "motor"

    short = getattr(module, "POSE_MIN_LEN", None)
    if verb == "ik" and short is not None and len(values_text) == short:  # optional trailing pose entries
        in_names = in_names[:short]
    user_in = parse_vector(values_text, in_names, option)
    overrides = parse_design(design_items, module)
    user_design = dict(zip(module.DESIGN_NAMES,
                           _to_user(module, module.DESIGN_NAMES, module.DESIGN_DEFAULT, "design", rad),
                           strict=True))
    user_design.update(overrides)
    params = _to_internal(module, module.DESIGN_NAMES, [user_design[n] for n in module.DESIGN_NAMES],
                          "design", rad)
    x = _to_internal(module, in_names, user_in, in_group, rad)
    try:
        design = module.make_design(params)
        if motor and verb == "fk":
            x = [float(v) for v in module.joints_from_motor_angles(x, design)]
        sols = module.ik(x, design) if verb == "ik" else module.fk(x, design)
        rows = []
        for k in range(len(sols.valid)):
            valid = bool(sols.valid[k])
            vals = aux = None
            if valid:
                vals = [float(v) for v in sols.values[k]]
                if motor and verb == "ik":
                    vals = [float(v) for v in module.motor_angles(vals, design)]
                vals = _to_user(module, out_names, vals, out_group, rad)
                aux = _to_user(module, aux_names, sols.aux[k], "aux", rad)
            rows.append({
                "index": k,
                "valid": valid,
                "values": {n: _finite_or_none(vals[i] if vals else None) for i, n in enumerate(out_names)},
                "aux": {n: _finite_or_none(aux[i] if aux else None) for i, n in enumerate(aux_names)},
                "flags": flag_names(module, sols.flags[k]),
            })
    except err as exc:
        raise UsageError(f"{module.NAME} {verb}: {exc}") from None
    return {
        "mechanism": module.NAME,
        "verb": verb,
        "input": dict(zip(in_names, user_in, strict=True)),
        "design": user_design,
        "status": status_name(module, sols.status),
        "reason": str(sols.reason),
        "count": int(sum(r["valid"] for r in rows)),
        "solutions": rows,
    }


def _finite_or_none(v):
    return v if v is not None and math.isfinite(v) else None


# ---------------------------------------------------------------------------- human output
def _num(v: float) -> str:
    return format(v, ".10g")


def format_human(result: dict, rad: bool, angles=None) -> str:
    """The result as a table; `angles` = the output names that carry the angle unit (None: all)."""
    unit = "rad" if rad else "deg"
    lines = [
        f"{result['mechanism']} {result['verb']}  "
        + " ".join(f"{k}={_num(v)}" for k, v in result["input"].items()) + f"  (angles in {unit})",
        "design  " + " ".join(f"{k}={_num(v)}" for k, v in result["design"].items()) + f"  (angles in {unit})",
        f"status  {result['status']}: {result['count']} of {len(result['solutions'])} valid"
        + (f"; {result['reason']}" if result["reason"] else ""),
    ]
    rows = result["solutions"]
    if not rows:
        return "\n".join(lines) + "\n"
    names = list(rows[0]["values"])
    angles = set(names if angles is None else angles)
    cells = [["#", "valid", *(f"{n} ({unit})" if n in angles else n for n in names), "flags"]]
    for r in rows:
        # 12 significant digits: a printed pose pastes back into `ik` (its rotation is then within 1e-11 of SO(3),
        # well inside the 1e-6 that is projected) and joints read back to 1e-12 relative
        vals = [("-" if r["values"][n] is None else format(float(r["values"][n]), ".12g")) for n in names]
        cells.append([str(r["index"]), "yes" if r["valid"] else "no", *vals, ",".join(r["flags"]) or "-"])
    widths = [max(len(c[j]) for c in cells) for j in range(len(cells[0]))]
    for c in cells:
        parts = [c[0].rjust(widths[0]), c[1].ljust(widths[1])]
        parts += [c[j].rjust(widths[j]) for j in range(2, len(c) - 1)]
        parts.append(c[-1])
        lines.append("  ".join(parts).rstrip())
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------- commands
def cmd_list(args) -> int:
    for name in mechanism_names():
        try:
            m = importlib.import_module(f"{PACKAGE}.{name}")
        except ImportError as exc:
            print(f"{name}  (cannot import: {exc})")
            continue
        print(f"{name}  joints=({', '.join(m.JOINT_NAMES)})  pose=({', '.join(m.POSE_NAMES)})  "
              f"design=({', '.join(m.DESIGN_NAMES)})  max_ik={m.MAX_IK}  max_fk={m.MAX_FK}")
    return EXIT_OK


def cmd_solve(args) -> int:
    module = load_mechanism(args.mechanism)
    values = args.pose if args.verb == "ik" else args.joints
    result = solve(args.verb, module, values, args.design, args.rad, args.motor)
    if args.json:
        print(json.dumps(result, sort_keys=True, allow_nan=False))
    else:
        group = "joint" if args.verb == "ik" else "pose"
        names = list(result["solutions"][0]["values"]) if result["solutions"] else []
        sys.stdout.write(format_human(result, args.rad, [n for n in names if _is_angle(module, n, group)]))
    return EXIT_OK


def _derivation_cli():
    """derive/cli.py, or a Failure naming the extra that installs it."""
    try:
        from derive import cli as derive_cli
    except ImportError as exc:
        raise Failure("the derivation verbs (regenerate, check, audit, derive) need the derivation stack: "
                      "pip install 'wristkin[derive]' (in a checkout: make venv)") from exc
    return derive_cli


def cmd_derivation(args) -> int:
    return _derivation_cli().run(args)


def cmd_atlas(argv: Sequence[str]) -> int:
    """`wristkin atlas ...`: the design atlas parses its own arguments (wristkin_atlas/cli.py); it exits 1 naming
    the `atlas` extra when dask, distributed, xarray or zarr is missing."""
    try:
        from wristkin_atlas import cli as atlas_cli
    except ImportError as exc:
        raise Failure(f"the design atlas is not installed ({exc}): pip install 'wristkin[atlas]'") from exc
    return atlas_cli.main(list(argv))


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("wristkin")
    except Exception:  # not installed (run from a source tree): no version to report
        return "(not installed)"


# the derivation commands and their arguments: _DERIVATION_COMMANDS, printed after this source from
# derive/cli_commands.py (the runtime cannot import derive): `python -m derive.cli` builds its parser from the
# same table
_TYPES = {"int": int, "float": float}


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="wristkin", description="Closed-form IK/FK of robot wrists (generated solvers).",
                epilog="Units of ik / fk: angles in degrees unless --rad (the modules' Python API and each derived "
                       "robot's own NAME.py command take radians unless --deg); lengths in metres.")
    p.add_argument("--version", action="version", version=f"wristkin {_version()}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    s = sub.add_parser("list", help="list the generated mechanisms")
    s.set_defaults(func=cmd_list)

    for verb, option, meta, what in (("ik", "--pose", "POSE", "inverse kinematics: every solution set"),
                                     ("fk", "--joints", "JOINT", "forward kinematics: every assembly mode")):
        s = sub.add_parser(verb, help=what)
        s.add_argument("mechanism", metavar="M")
        s.add_argument(option, nargs="+", required=True, metavar=meta,
                       help="degrees unless --rad (underactuated_wrist: "
                            + ("psi theta phi, ZXZ Euler)" if verb == "ik" else "theta1 theta2 theta3)"))
        units = s.add_mutually_exclusive_group()
        units.add_argument("--deg", action="store_true", help="angles in and out in degrees (the default)")
        units.add_argument("--rad", action="store_true", help="angles in and out in radians")
        s.add_argument("--design", nargs="+", action="extend", metavar="NAME=VALUE",
                       help="design overrides (degrees unless --rad); others keep the paper default")
        s.add_argument("--json", action="store_true", help="print one JSON object")
        s.add_argument("--motor", action="store_true",
                       help="joint values are motor/sensor angles Phi_i = theta_i - theta0")
        s.set_defaults(func=cmd_solve, verb=verb)

    # listed for --help; main() hands everything after `atlas` to the atlas's own parser
    sub.add_parser("atlas", help="design atlas: sweep design parameters over the workspace on Dask (needs "
                   "wristkin[atlas]; wristkin atlas --help)", add_help=False)

    for verb, helptext, arguments in _DERIVATION_COMMANDS:  # derive/cli_commands.py's add_commands, with func
        s = sub.add_parser(verb, help=helptext + " (needs wristkin[derive])")
        for flags, options in arguments:
            s.add_argument(*flags, **{k: _TYPES.get(v, v) if k == "type" else v for k, v in options.items()})
        s.set_defaults(verb=verb, func=cmd_derivation)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser()
    try:
        if argv[:1] == ["atlas"]:
            return cmd_atlas(argv[1:])
        args = parser.parse_args(argv)
        return args.func(args)
    except UsageError as exc:
        print(f"wristkin: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except Failure as exc:
        print(f"wristkin: error: {exc}", file=sys.stderr)
        return EXIT_FAILED
    except SystemExit as exc:  # --help / --version
        return exc.code if isinstance(exc.code, int) else EXIT_OK
    except BrokenPipeError:
        # `wristkin list | head`: the reader went away; not an error of ours.
        sys.stderr.close()
        return EXIT_OK
