"""The user-robot solver's design (free joint value, base and tool frames) and its C counterpart.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

from dataclasses import dataclass, field

import _runtime
import numpy as np
from chain_stand_in import (
    _BASE,
    _C,
    _TOOL,
    DESIGN_DEFAULT,
    DESIGN_NAMES,
    N_JOINTS,
    NAME,
    ROTATION_TOL,
    InvalidDesign,
    _array,
    _as_rotation,
)


# wristkin: inlined from here
def _c_design(vals):
    """The C design (bytes) of the free joint's value and the base and tool frames' 24 numbers, or None."""
    if _C is None:
        return None
    out = getattr(_C, NAME + "_design")(np.array(vals, dtype=float))
    return out if isinstance(out, bytes) else None


def _design_values(params):
    """A sequence in DESIGN_NAMES order, a dict (missing names take the default) or None -> finite tuple."""
    return _runtime._design_values(params, DESIGN_NAMES, DESIGN_DEFAULT)


def make_design(params=None, base=None, tool=None) -> Design:
    """The call's parameters: the free joint's value (DESIGN_NAMES; a sequence or dict), and optionally the base
    and tool transforms (4x4) replacing the description's."""
    if isinstance(params, Design) and base is None and tool is None:
        return params
    vals = _design_values(None if isinstance(params, Design) else params)
    b = _BASE if base is None else _frame(base, "base")
    t = _TOOL if tool is None else _frame(tool, "tool")
    return Design(vals, _c_design(vals + tuple(v for m in (b, t) for row in m[:3] for v in row)), b, t)


@dataclass(frozen=True)
class Design:
    """The call's parameters: the free joint's value (if any) and the base and tool transforms."""

    params: tuple
    native: bytes | None = field(default=None, compare=False, repr=False)
    base: tuple = _BASE
    tool: tuple = _TOOL


def _frame(m, what):
    a = _array(m, what)
    if a.shape != (4, 4) or not np.all(np.isfinite(a)):
        raise InvalidDesign(f"{what}: expected a finite 4x4 homogeneous matrix, got shape {a.shape}")
    r, _ = _as_rotation(a[:3, :3], what)
    if not np.max(np.abs(a[3] - (0.0, 0.0, 0.0, 1.0))) <= ROTATION_TOL:
        raise InvalidDesign(f"{what}: last row must be (0, 0, 0, 1)")
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = r, a[:3, 3]
    return tuple(tuple(float(x) for x in row) for row in out)


_DEFAULT_DESIGN = None
_JOINT_SHAPE = ((N_JOINTS,),)
_POSE_SHAPES = ((4, 4), (3, 4), (12,), (16,))


def _design(design):
    global _DEFAULT_DESIGN
    if design is None:
        if _DEFAULT_DESIGN is None:
            _DEFAULT_DESIGN = make_design()
        return _DEFAULT_DESIGN
    return design if isinstance(design, Design) else make_design(design)

