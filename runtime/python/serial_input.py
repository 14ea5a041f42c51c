"""A serial arm's inputs: the pose (pose_forms.py's forms), the joints and the design, validated (the typed errors of
docs/API.md).

A wristkin runtime source: every serial arm's generated module (the catalogue's DH chains, the finite-screw chains'
serial view) inlines it from the marker line on (derive/runtime_files.py), after its constants, derived kernels
and stage functions; above the marker, what it reads from them and from the other sources (serial_stand_in.py:
the PUMA-560), so that it is linted and tested as it is (tests/test_serial_runtime.py)."""

from __future__ import annotations

import numpy as np
from pose_forms import pose_matrix
from serial_frames import _frame, _frames_of
from serial_stand_in import (
    _BASE,
    _DESIGN_CHECK,
    _TOOL,
    DESIGN_CHECKS,
    DESIGN_NAMES,
    DESIGN_SCALE_MIN,
    IK_VERIFY_TOL,
    JOINT_KINDS,
    JOINT_NAMES,
    LENGTH_MAX,
    LENGTH_MIN,
    LENGTHS_FLOOR,
    N_JOINTS,
    N_LENGTHS,
    ROTATION_TOL,
    Design,
    InvalidDesign,
    InvalidInput,
    _as_rotation,
    _c_design,
    _design_values,
    _vector,
    _wrap,
)


# wristkin: inlined from here
# ---------------------------------------------------------------------------- input handling
def _pose(pose):
    """A pose in any of pose_matrix's forms -> (the 12 entries of [R | p], rotation deviation); the rotation is
    projected onto SO(3) when it deviates by at most ROTATION_PROJECT_TOL."""
    a = pose_matrix(pose)
    if not np.max(np.abs(a[3] - (0.0, 0.0, 0.0, 1.0))) <= ROTATION_TOL:
        raise InvalidInput(f"pose: last row must be (0, 0, 0, 1) (within {ROTATION_TOL:g}), got {a[3].tolist()}")
    if not np.max(np.abs(a[:3, 3])) <= LENGTH_MAX:
        raise InvalidInput(f"pose: translation must be within {LENGTH_MAX:g} m, got {a[:3, 3].tolist()}")
    r, dev = _as_rotation(a[:3, :3])
    return tuple(float(x) for x in np.column_stack([r, a[:3, 3]]).ravel()), dev


def _joints(joints, what="joints"):
    """Validated joints: revolute angles wrapped exactly to [-pi, pi] (any finite value), prismatic offsets
    within LENGTH_MAX."""
    q = _vector(joints, N_JOINTS, what)
    for v, kind, name in zip(q, JOINT_KINDS, JOINT_NAMES, strict=True):
        if kind == "P" and not abs(v) <= LENGTH_MAX:
            raise InvalidInput(f"{what}: prismatic joint {name} must be within {LENGTH_MAX:g} m, got {v!r}")
    return tuple(_wrap(v) if kind == "R" else v for v, kind in zip(q, JOINT_KINDS, strict=True))


def make_design(params=None, base=None, tool=None) -> Design:
    """Validate design parameters (sequence in DESIGN_NAMES order or dict; lengths in metres), and optionally the
    base and tool frames (4x4) replacing the chain's own (_BASE, _TOOL): poses are then the tool's in the base's
    frame, T = base base0^-1 T0(q) tool0^-1 tool."""
    if isinstance(params, Design):
        if base is None and tool is None:
            return params
        params, base, tool = params.params, params.base if base is None else base, params.tool if tool is None else tool
    vals = _design_values(params)
    # the lengths (a held joint's angle after them is any finite value: the stage wraps it)
    scale = max((abs(v) for v in vals[:N_LENGTHS]), default=0.0)  # a chain without lengths: none
    if scale > LENGTH_MAX:
        raise InvalidDesign(f"design values must be within {LENGTH_MAX:g} m, got {scale:g}")
    if 0.0 < scale < DESIGN_SCALE_MIN:
        raise InvalidDesign(f"design scale {scale:.3g} m is below {DESIGN_SCALE_MIN:g} m: the solver's absolute "
                            f"tolerances (IK_VERIFY_TOL = {IK_VERIFY_TOL:g} m) assume robots of a millimetre and "
                            "more; express the lengths in smaller units (e.g. millimetres)")
    if LENGTHS_FLOOR:
        # a nonzero DH length below LENGTH_MIN makes products of two lengths (stage coefficients) vanish against
        # DEGENERATE_EPS: a near-degenerate design whose IK would come back empty
        tiny = [f"{n} = {v!r}" for n, v in zip(DESIGN_NAMES[:N_LENGTHS], vals[:N_LENGTHS], strict=True)
                if 0.0 < abs(v) < LENGTH_MIN]
        if tiny:
            raise InvalidDesign(f"DH lengths must be 0 or at least {LENGTH_MIN:g} m in magnitude, got "
                                f"{', '.join(tiny)}: set a vanishing length to exactly 0 (a different structure) "
                                "or express the lengths in smaller units")
    why = _design_refusal(vals)
    if why:
        raise InvalidDesign(why)
    return _built(vals, base, tool)


def _design_refusal(vals, held=False):
    """The first design condition (DESIGN_CHECKS) the values violate, in words, or None: "zero" and "nonzero" ones
    (make_design), or with `held` the "held" ones (a held joint's values ik refuses; fk takes them)."""
    if _DESIGN_CHECK is not None:
        for v, (kind, tol, what) in zip(_DESIGN_CHECK(vals), DESIGN_CHECKS, strict=True):
            if (kind == "held") != held:
                continue
            if (abs(v) > tol) if kind == "zero" else (abs(v) <= tol):
                return f"design violates: {what} (value {v:.3g}, tolerance {tol:g})"
    return None


def _built(vals, base, tool):
    b = _BASE if base is None else _frame(base, "base")
    t = _TOOL if tool is None else _frame(tool, "tool")
    frames = _FRAME_VALUES0 if b is _BASE and t is _TOOL else tuple(v for m in (b, t) for row in m[:3] for v in row)
    # a held joint's values ik refuses (read here once: ik raises the reason, fk takes the design)
    refused = _design_refusal(vals, held=True) if _HELD_CHECKS else None
    return Design(vals, _c_design(vals + frames), b, t, _frames_of(b, t), refused)


_FRAME_VALUES0 = tuple(v for m in (_BASE, _TOOL) for row in m[:3] for v in row)  # the chain's own frames' 24
# a held joint's values the IK refuses (the iiwa's a2 at 0: the others a self-motion), its default among them: ik
# refuses them, not make_design (fk takes them)
_HELD_CHECKS = any(kind == "held" for kind, _, _ in DESIGN_CHECKS)
_DEFAULT_DESIGN = make_design()
_JOINT_SHAPE = ((N_JOINTS,),)
_POSE_SHAPES = ((4, 4), (3, 4), (12,), (16,))
_REVOLUTE = tuple(k == "R" for k in JOINT_KINDS)
_HAS_PRISMATIC = "P" in JOINT_KINDS  # IK then returns only the sets whose prismatic values fk accepts


def _design(design):
    global _LAST_BUILT
    if design is None:
        return _DEFAULT_DESIGN
    if isinstance(design, Design):
        return design
    # a sequence of floats equal to the last one built gives its Design again: a held joint's ik(pose, [v]) in a
    # controller loop builds its design once, not per call (4 us, three times a derived stage's IK)
    key = tuple(design) if design.__class__ in (list, tuple) else None
    last = _LAST_BUILT
    if key is not None and key == last[0] and all(v.__class__ is float for v in key):
        return last[1]
    d = make_design(design)
    if key is not None:
        _LAST_BUILT = (key, d)  # one assignment: a thread reads the old pair or the new one, never a mix
    return d


_LAST_BUILT = (None, None)  # (the last float sequence _design built a Design from, that Design)
