"""`wristkin derive --stages derived`: a user's robot, as its family reads it (a RobotTable: its ideal axes as a
standard DH table, kinematics/dh_table.py), derived as this family's straight-line stages and emitted as the
PUMA-560's are (no plan interpreted at run time). The table's lengths stay design parameters (defaults: the
robot's), its angles are made exact, and a derivation step proves the table is the user's robot.

The robot's family refuses what the table cannot hold (a held joint, more than six joints, a calibrated robot, a
slide); here the angles must be multiples of pi / 36 and the planner's decomposition must fit the stage kinds
dh_serial emits (a spherical wrist at the end), else the robot is refused with the reason."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import sympy as sp

from ...checks import numeric_predicate, sampler
from ...identities.dh import DHRow
from ...kinematics.dh_table import RobotTable
from ...model import NotDerivable, Step
from .dh_serial import SerialSpec
from .mechanism import SerialMechanism
from .planned import SUPPORTED, PlanError
from .planned import stages as planned_stages

# an angle of the table within this of a multiple of pi / 36 (5 degrees) is that multiple (the ideal axes are exact
# to rounding, ~1e-16; a calibrated robot's are not and is refused before)
ANGLE_SNAP = 1e-9
ANGLE_GRID = 36
# a length below this (relative to the robot's size) is zero: two axes that meet, a wrist without offset
LENGTH_ZERO = 1e-12
# entries of a constant rotation (the base's, the tool's) within this of 0, +-1/2, +-sqrt(2)/2, +-sqrt(3)/2, +-1 are
# those numbers; others stay floating point
ENTRY_SNAP = 1e-12
_ENTRIES = (sp.Integer(0), sp.Integer(1), sp.Rational(1, 2), sp.sqrt(2) / 2, sp.sqrt(3) / 2)


def _refuse(name: str, why: str) -> NotDerivable:
    return NotDerivable(f"{name}: --stages derived does not cover this robot ({why}); without --stages derived the "
                        "plan interpreter solves it")


def _angle(v: float) -> sp.Expr | None:
    k = round(v * ANGLE_GRID / math.pi)
    return sp.pi * sp.Rational(k, ANGLE_GRID) if abs(v - k * math.pi / ANGLE_GRID) <= ANGLE_SNAP else None


def _entry(v: float) -> sp.Expr:
    for e in _ENTRIES:
        if abs(abs(v) - float(e)) <= ENTRY_SNAP:
            return e if v >= 0 else -e
    return sp.Float(v)


def _constant(m: np.ndarray) -> sp.Matrix | None:
    """A constant 4x4 as an exact rotation block where its entries are special values; None for the identity."""
    if np.max(np.abs(m - np.eye(4))) <= ENTRY_SNAP:
        return None
    out = sp.eye(4)
    for i in range(3):
        for j in range(3):
            out[i, j] = _entry(float(m[i, j]))
        out[i, 3] = sp.Integer(0) if abs(m[i, 3]) <= ENTRY_SNAP else sp.Float(float(m[i, 3]))
    return out


def _identifier(name: str, taken: set[str]) -> str:
    s = "".join(c if c.isalnum() else "_" for c in name).strip("_") or "q"
    s = s if s[0].isalpha() else "q_" + s
    while s in taken:
        s += "_"
    taken.add(s)
    return s


def from_table(robot: RobotTable) -> SerialMechanism:
    """The robot as a serial-family mechanism with derived stages, or NotDerivable with the reason."""
    name, table = robot.name, robot.table
    n = len(robot.joint_names)
    taken: set[str] = set()
    joints = [sp.Symbol(_identifier(j, taken), real=True) for j in robot.joint_names]
    design, defaults, rows = [], [], []
    for k, ((a, alpha, d, theta), q) in enumerate(zip(table.rows, joints, strict=True), start=1):
        angles = [_angle(alpha), _angle(theta)]
        if any(x is None for x in angles):
            raise _refuse(name, f"joint {robot.joint_names[k - 1]}'s DH angles ({alpha:.6g}, {theta:.6g} rad) are "
                                f"no multiple of pi/{ANGLE_GRID}")
        lengths = []
        for label, v in (("a", a), ("d", d)):
            if abs(v) <= LENGTH_ZERO * robot.size:
                lengths.append(sp.Integer(0))
                continue
            sym = sp.Symbol(_identifier(f"{label}{k}", taken), real=True)
            design.append(sym)
            defaults.append(float(v))
            lengths.append(sym)
        rows.append(DHRow(lengths[0], angles[0], lengths[1], q + angles[1], q, "R"))
    base, tool = _constant(robot.base), _constant(table.tool)
    spec = SerialSpec(name, robot.title, robot.source, rows, tuple(joints), ("R",) * n, tuple(design),
                      tuple(defaults), [], notes=f"standard DH table read from the description ({robot.rule})",
                      tool=tool, base=base)
    try:
        stage_list, _ = planned_stages(rows, tuple(joints), spec.kinds, tuple(design), tuple(defaults), "standard",
                                       [str(q) for q in joints], base, tool)
    except (PlanError, ValueError) as exc:
        missing = sorted(robot.ops - SUPPORTED)
        if missing or robot.reversed_:  # say what the interpreter's decomposition needs, not the search's refusal
            what = f"the ops {', '.join(missing)}" if missing else "the chain solved from the tool"
            raise _refuse(name, f"its decomposition, {robot.strategy.split(':')[0]}, needs {what}, which the "
                                "derived stages do not have yet") from None
        raise _refuse(name, f"no decomposition in the derived stage kinds: {exc}") from None
    mech = _DerivedRobot(name, lambda: replace(spec, stages=stage_list))
    mech.DERIVE_SECONDS = 0.2 * 2 ** n
    mech.description_fk = robot.description_fk
    return mech


class _DerivedRobot(SerialMechanism):
    """The serial family's derivation plus the step that proves the DH table is the user's robot."""

    description_fk = None

    def derive(self):
        dv = super().derive()
        spec = self.spec
        at = dict(zip(spec.design, spec.design_default, strict=True))
        table_fk = sampler(spec.joints, dv.exports["T"].subs(at))
        n = len(spec.joints)

        def err(rng):
            q = rng.uniform(-math.pi, math.pi, n)
            return float(np.max(np.abs(np.array(table_fk(*q), dtype=float) - self.description_fk(q))))
        dv.add(Step("description", "The DH table is the description's robot",
                    "the table's product at the design defaults equals the description's own product (its URDF "
                    "transforms, DH matrices or exponentials, base and tool included)", ("T",), {},
                    (numeric_predicate(err, "same end frame at random joints", samples=200, tol=1e-12),)))
        return dv
