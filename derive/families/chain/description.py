"""A chain's spec file (DH standard / modified, POE, or a URDF it names) -> Chain, with the description's own
forward kinematics kept beside it: the derivation checks the product-of-exponentials form against it."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...kinematics.planner import DEFAULT_GEOMETRY_TOL
from ...kinematics.poe import Chain, dh_link, from_dh, from_frames, rot, rpy_matrix, transform
from ...kinematics.same_bits import norm, unit
from ...spec import COMMON_FIELDS, Spec, common
from . import urdf
from .description_names import JOINT_NAME

SPEC_FIELDS = ("convention", "unit", "joint", "home", "base", "tool", "free", "redundancy", "geometry_tol",
               "urdf", "base_link", "tip_link", "xacro_args", "packages")
DH_FIELDS = ("name", "type", "a", "alpha", "d", "theta", "direction", "lower", "upper")
POE_FIELDS = ("name", "type", "axis", "point", "lower", "upper")
_ALLOWED = set("0123456789.+-*/() epi")


@dataclass
class Description:
    chain: Chain
    fk: Callable  # q -> 4x4 by the description's own products (DH matrices / URDF transforms / POE)
    rule: str  # how the description composes, for the audit
    free: int  # index of the free joint, or -1
    geometry_tol: float
    source: str
    redundancy: str = "joint"  # a 7-joint arm's run-time parameter: a held joint (free), or "arm-angle"


def number(spec: Spec, field: str, default=0.0) -> float:
    """A number, or a string of numbers, pi and + - * / ( ) (e.g. "pi/2", "-pi/2")."""
    v = spec.raw(field, default)
    if isinstance(v, bool):
        raise spec.error(field, "a number or an expression of numbers and pi", v)
    if isinstance(v, int | float):
        return spec.number(field, default)
    if not isinstance(v, str) or not v.strip() or len(v) > 100 or not set(v) <= _ALLOWED or "__" in v:
        raise spec.error(field, "a number or an expression of numbers and pi (e.g. \"pi/2\")", v)
    try:
        x = float(eval(v, {"__builtins__": {}}, {"pi": math.pi, "e": math.e}))  # noqa: S307 - charset checked
    except Exception:  # noqa: BLE001 - any evaluation failure is the same user error
        raise spec.error(field, "a number or an expression of numbers and pi (e.g. \"pi/2\")", v) from None
    if not math.isfinite(x):
        raise spec.error(field, "a finite value", v)
    return x


# An angle of a radian spec beyond this is taken for degrees written without `unit = "deg"` (refused, not guessed):
# a geometric angle (DH alpha / theta, rpy) needs at most one turn, a joint limit at most two.
TURNS = {"angle": 1, "limit": 2}


def to_radians(spec: Spec, field: str, x: float, unit: str, kind: str = "angle") -> float:
    """An angle of the spec in radians: converted from degrees (unit = "deg"), or checked to be a plausible radian
    value (unit = "rad")."""
    if unit == "deg":
        return math.radians(x)
    turns = TURNS[kind]
    if abs(x) > turns * 2 * math.pi * (1 + 1e-9):
        raise spec.error(field, f"an angle in radians within {turns} turn(s) ({turns * 360} degrees): {x:g} rad "
                                "looks like degrees; write unit = \"deg\" at the top of the spec for angles in "
                                "degrees", x)
    return x


def angle(spec: Spec, field: str, unit: str, default=0.0, kind: str = "angle") -> float:
    """An angle field (a number or an expression of pi) in radians, by the spec's `unit`."""
    return to_radians(spec, field, number(spec, field, default), unit, kind)


def _frame(spec: Spec, field: str, unit: str) -> np.ndarray:
    if not spec.has(field):
        return np.eye(4)
    t = spec.table(field)
    t.only(("xyz", "rpy"))
    rpy = [to_radians(t, "rpy", v, unit) for v in t.vector("rpy", 3, [0.0, 0.0, 0.0], unit=unit)]
    return transform(rpy_matrix(rpy), t.vector("xyz", 3, [0.0, 0.0, 0.0], unit="m"))


def _limits(js: Spec, kind: str, unit: str) -> tuple[float, float]:
    """A joint's limits: revolute in the spec's angle unit (numbers or expressions of pi), prismatic in metres."""
    def one(field, default):
        if not js.has(field):
            return default
        return angle(js, field, unit, kind="limit") if kind == "R" else number(js, field)
    lo, hi = one("lower", -math.inf), one("upper", math.inf)
    if lo > hi:
        raise js.error("upper", f"an upper limit >= lower ({lo})", hi)
    return lo, hi


def _unit(spec: Spec, field: str) -> np.ndarray:
    v = np.array(spec.vector(field, 3))
    if not norm(v) > 1e-9:
        raise spec.error(field, "a nonzero direction", list(v))
    return unit(v)


def read(spec: Spec, path_hint: Path | None = None) -> Description:
    spec.only((*COMMON_FIELDS, *SPEC_FIELDS))
    head = common(spec)
    convention = spec.choice("convention", ("standard", "modified", "poe", "urdf"))
    unit = spec.choice("unit", ("rad", "deg"), "rad")  # the spec's angles (lengths are metres)
    base, tool = _frame(spec, "base", unit), _frame(spec, "tool", unit)
    tol = spec.number("geometry_tol", DEFAULT_GEOMETRY_TOL, lo=1e-14, hi=1e-2)
    if convention == "urdf":
        if spec.has("joint") or spec.has("home"):
            raise spec.error("joint", "no [[joint]] or [home] in a URDF spec (the URDF describes the joints)")
        file = Path(spec.text("urdf"))
        file = file if file.is_absolute() else Path(spec.file).parent / file
        try:
            chain, info = urdf.read(file, spec.text("base_link", None) if spec.has("base_link") else None,
                                    spec.text("tip_link", None) if spec.has("tip_link") else None, head["name"],
                                    xacro_args=_strings(spec, "xacro_args"), packages=_strings(spec, "packages"))
        except urdf.URDFError as exc:
            if Path(spec.file).resolve() == file.resolve():
                raise  # the description file itself was given (wristkin derive ROBOT.urdf): its error as it is
            raise spec.error("urdf", f"a URDF with a serial chain ({exc})") from None
        rule = (f"URDF joint origins composed from {info['base_link']} to {info['tip_link']} (fixed joints "
                f"{', '.join(info['folded_fixed_joints']) or 'none'} folded), each movable joint's axis taken "
                "in its joint frame at zero")
        fk_desc = urdf.composed_fk(info["model"], info["path"])
    else:
        joints = spec.tables("joint")
        if not joints:
            raise spec.error("joint", "at least one [[joint]] table")
        names, kinds, lower, upper = [], [], [], []
        for js in joints:
            js.only(DH_FIELDS if convention != "poe" else POE_FIELDS)
            nm = js.text("name")
            if not JOINT_NAME.fullmatch(nm):
                raise js.error("name", "a joint name of letters, digits and _ . - : / (at most 63 characters)", nm)
            if nm in names:
                raise js.error("name", "a joint name not used before", nm)
            names.append(nm)
            kinds.append({"revolute": "R", "prismatic": "P"}[js.choice("type", ("revolute", "prismatic"), "revolute")])
            lo, hi = _limits(js, kinds[-1], unit)
            lower.append(lo)
            upper.append(hi)
        if convention == "poe":
            pairs = [(_unit(js, "axis"), np.array(js.vector("point", 3, [0.0, 0.0, 0.0], unit="m"))) for js in joints]
            home_t = spec.table("home")
            home_t.only(("position", "rpy"))
            home_rpy = [to_radians(home_t, "rpy", v, unit) for v in home_t.vector("rpy", 3, [0.0, 0.0, 0.0], unit=unit)]
            home = transform(rpy_matrix(home_rpy), home_t.vector("position", 3, unit="m"))
            chain = from_frames(head["name"], names, kinds, pairs, home, lower=np.array(lower),
                                upper=np.array(upper), source_format="poe")
            fk_desc = _poe_fk(kinds, pairs, home)
            rule = "product of exponentials: exp(S_1 q_1) ... exp(S_n q_n) M from the spec's axes, points and home"
        else:
            if spec.has("home"):
                raise spec.error("home", "no [home] in a DH spec (use [tool] for a flange offset)")
            rows = []
            for js, nm, kd in zip(joints, names, kinds, strict=True):
                direction = js.number("direction", 1.0)
                if direction not in (1.0, -1.0):
                    raise js.error("direction", "1 or -1", direction)
                rows.append((nm, kd, number(js, "a"), angle(js, "alpha", unit), number(js, "d"),
                             angle(js, "theta", unit), direction))
            chain = from_dh(head["name"], convention, rows, lower=np.array(lower), upper=np.array(upper))
            fk_desc = _dh_fk(convention, rows)
            rule = ("standard DH: A_i = Rz(theta_i + q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)" if convention == "standard" else
                    "modified (Craig) DH: A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i + q_i) Tz(d_i)") + (
                    "; joint axes and points read from the frames at q = 0")
    from dataclasses import replace
    chain = replace(chain, base=base, tool=tool)
    free = -1
    if spec.has("free"):
        fname = spec.text("free")
        if fname not in chain.joint_names:
            raise spec.error("free", f"one of the joints ({', '.join(chain.joint_names)})", fname)
        free = chain.joint_names.index(fname)
    redundancy = spec.choice("redundancy", ("joint", "arm-angle"), "joint")
    if redundancy == "arm-angle":
        if free >= 0:
            raise spec.error("redundancy", "either a free joint or the arm angle as the run-time parameter, not both",
                             redundancy)
        if chain.n != 7 or any(k != "R" for k in chain.kinds):
            raise spec.error("redundancy", f"arm-angle for a 7-joint revolute arm (this chain has {chain.n} joints)",
                             redundancy)
    # more than 6 joints and no free joint: the family names the joints that would work (it needs the planner)
    return Description(chain, lambda q: base @ fk_desc(q) @ tool, rule, free, tol, head["source"], redundancy)


def _poe_fk(kinds, pairs, home):
    """The POE spec as written (its own points, not the chain's normalised ones): each turn as Tr(p) Rot Tr(-p)."""
    def fk(q):
        t = np.eye(4)
        for kind, (axis, point), v in zip(kinds, pairs, q, strict=True):
            if kind == "P":
                t = t @ transform(None, axis * v)
            else:
                t = t @ transform(None, point) @ transform(rot(axis, v)) @ transform(None, -point)
        return t @ home
    return fk


def _dh_fk(convention, rows):
    def fk(q):
        t = np.eye(4)
        for (_, kind, a, alpha, d, theta, direction), v in zip(rows, q, strict=True):
            if kind == "R":
                t = t @ dh_link(convention, a, alpha, d, theta + direction * v)
            else:
                t = t @ dh_link(convention, a, alpha, d + direction * v, theta)
        return t
    return fk


def _strings(spec: Spec, field: str) -> dict[str, str]:
    """A table of NAME = "text" (xacro arguments, package folders)."""
    if not spec.has(field):
        return {}
    raw = spec.raw(field)
    if not isinstance(raw, dict) or not all(isinstance(k, str) and isinstance(v, str | int | float)
                                            and not isinstance(v, bool) for k, v in raw.items()):
        raise spec.error(field, "a table of NAME = \"value\"", raw)
    return {k: str(v) for k, v in raw.items()}
