"""A serial arm's base and tool frames at run time (make_design(base=, tool=)): they replace the chain's own (_BASE,
_TOOL: the catalogue's identity, a user robot's description's), which its derived kernels fold in. The kernels
answer pose0 = left^-1 pose right^-1, with left = base base0^-1 and right = tool0^-1 tool (C: sr_frames.c).

A wristkin runtime source: every serial arm's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants; above the marker, what it reads from them (serial_stand_in.py: the
PUMA-560), so that it is linted and tested as it is (tests/test_serial_runtime.py)."""

from __future__ import annotations

import numpy as np
from serial_stand_in import _BASE, _TOOL, LENGTH_MAX, ROTATION_TOL, InvalidDesign, _array, _as_rotation


# wristkin: inlined from here
def _frame(m, what):
    """A base or tool frame as given: a finite 4x4 whose rotation is within ROTATION_TOL of SO(3) (projected) and
    translation within LENGTH_MAX, as a tuple of rows; else InvalidDesign."""
    a = _array(m, what)
    if a.shape != (4, 4) or not np.all(np.isfinite(a)):
        raise InvalidDesign(f"{what}: expected a finite 4x4 homogeneous matrix, got shape {a.shape}")
    if not np.max(np.abs(a[3] - (0.0, 0.0, 0.0, 1.0))) <= ROTATION_TOL:
        raise InvalidDesign(f"{what}: last row must be (0, 0, 0, 1)")
    if not np.max(np.abs(a[:3, 3])) <= LENGTH_MAX:
        raise InvalidDesign(f"{what}: translation must be within {LENGTH_MAX:g} m, got {a[:3, 3].tolist()}")
    r, _ = _as_rotation(a[:3, :3], what)
    out = np.eye(4)
    out[:3, :3], out[:3, 3] = r, a[:3, 3]
    return tuple(tuple(float(x) for x in row) for row in out)


def _rigid_inverse(m):
    out = np.eye(4)
    out[:3, :3] = m[:3, :3].T
    out[:3, 3] = -m[:3, :3].T @ m[:3, 3]
    return out


def _frames_of(base, tool):
    """(left, right, left^-1, right^-1) as 4x4 arrays, or None where both are the chain's own."""
    if base == _BASE and tool == _TOOL:
        return None
    left = np.array(base) @ _rigid_inverse(np.array(_BASE))
    right = _rigid_inverse(np.array(_TOOL)) @ np.array(tool)
    return left, right, _rigid_inverse(left), _rigid_inverse(right)


def _as4(v12):
    out = np.eye(4)
    out[:3] = np.asarray(v12, dtype=float).reshape(3, 4)
    return out


def _unframe(p12, frames):
    """The pose the kernels answer (12 entries) for one in the design's frames: left^-1 pose right^-1."""
    return tuple(float(x) for x in (frames[2] @ _as4(p12) @ frames[3])[:3].ravel())


def _reframe(v12, frames):
    """The pose in the design's frames (12 entries) of the kernels' pose0: left pose0 right."""
    return (frames[0] @ _as4(v12) @ frames[1])[:3].ravel()


def _reframe_jacobian(j, v12, frames):
    """The geometric Jacobian in the design's frames from the kernels' (6 x n, at their end pose v12): the end frame's
    origin moves by R0 r (r: right's translation), so each linear column gains w x R0 r; then both rows turn by
    left's rotation."""
    a = np.asarray(v12, dtype=float).reshape(3, 4)[:, :3] @ frames[1][:3, 3]
    lin = j[:3] + np.cross(j[3:].T, a).T
    rot = frames[0][:3, :3]
    return np.vstack([rot @ lin, rot @ j[3:]])
