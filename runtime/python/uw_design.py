"""The underactuated wrist's design: validated parameters, their derived constants and home angle, and
the angle wraps every verb uses.

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from uw_stand_in import (
    _C,
    _C_DESIGN,
    _TWO_PI,
    DESIGN_DEFAULT,
    DESIGN_MARGIN,
    DESIGN_NAMES,
    TANGENT_TOL,
    InvalidDesign,
    InvalidInput,
    _k_design_constants,
    _vector,
    _wrap,
)


# wristkin: inlined from here
@dataclass(frozen=True)
class Design:
    params: tuple  # radians, DESIGN_NAMES order
    constants: tuple  # precomputed design constants (kernel design_constants)
    theta0: float  # home joint angle (root in [0, pi])
    native: bytes | None = field(default=None, compare=False, repr=False)  # the C design, when C runs


_VEC3 = ((3,),)


def _c_design(vals):
    """The C design of validated `vals` (bytes), or None when C is not in use or rejects it."""
    if _C is None:
        return None
    out = _C_DESIGN(np.array(vals, dtype=float))
    return out if isinstance(out, bytes) else None


# ---------------------------------------------------------------------------- input handling
def _matrix(v, n, what):
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InvalidInput(f"{what}: expected an (N, {n}) array") from exc
    if a.ndim != 2 or a.shape[1] != n:
        raise InvalidInput(f"{what}: expected an (N, {n}) array, got shape {a.shape}")
    return a


def make_design(params=None) -> Design:
    """Validate design parameters (radians; sequence in DESIGN_NAMES order or dict) and precompute."""
    if isinstance(params, Design):
        return params
    if params is None:
        vals = DESIGN_DEFAULT
    elif isinstance(params, dict):
        unknown = sorted(set(params) - set(DESIGN_NAMES))
        if unknown:
            raise InvalidDesign(f"unknown design parameter(s) {unknown}; expected {DESIGN_NAMES}")
        vals = tuple(params.get(n, d) for n, d in zip(DESIGN_NAMES, DESIGN_DEFAULT, strict=True))
    else:
        vals = params
    try:
        vals = _vector(vals, 4, "design")
    except InvalidInput as exc:
        raise InvalidDesign(str(exc)) from exc
    al1, al2, be1, be2 = vals
    m = DESIGN_MARGIN
    if not (m <= al1 <= math.pi - m and m <= al2 <= math.pi - m):
        raise InvalidDesign(f"alpha1 and alpha2 must lie in [{m:g}, pi - {m:g}] rad, got ({al1!r}, {al2!r})")
    if not 0.0 <= be1 <= 0.5 * math.pi:
        raise InvalidDesign("beta1 must lie in [0, pi/2] (the seed's range for a spherical mechanism)")
    if not m <= be2 <= 0.5 * math.pi:
        raise InvalidDesign(f"beta2 must lie in [{m:g}, pi/2] rad, got {be2!r}")
    if not be1 + be2 <= math.pi - m:
        # the home loop is -sin(alpha1) sin(beta1 + beta2) (cos theta - cos theta0): with sin(beta1 + beta2) -> 0 it
        # fixes no theta0 (every angle closes it when alpha1 = alpha2: the home pose is a self-motion)
        raise InvalidDesign(f"beta1 + beta2 must be at most pi - {m:g} rad, got {be1 + be2!r}: the home loop then "
                            "does not fix theta0 (a singular design)")
    dc = _k_design_constants(vals)
    if not all(math.isfinite(c) for c in dc):
        raise InvalidDesign(f"design {list(vals)} gives non-finite link constants (a degenerate spherical chain)")
    cth0 = dc[-1]
    if not math.isfinite(cth0) or abs(cth0) > 1.0 + TANGENT_TOL:
        raise InvalidDesign(f"no spherical closure at the home pose: cos(theta0) = {cth0:.6g} is outside [-1, 1]")
    return Design(vals, tuple(dc), math.acos(max(-1.0, min(1.0, cth0))), _c_design(vals))


_DEFAULT_DESIGN = make_design()


def _design(design):
    if design is None:
        return _DEFAULT_DESIGN
    return design if isinstance(design, Design) else make_design(design)


def _wrap_2pi(a):
    """The angle in [0, 2 pi), reduced exactly (_wrap), then a turn added to a negative one."""
    a = _wrap(a)
    return a + _TWO_PI if a < 0.0 else a


_wrap_pi = _wrap  # to [-pi, pi], exactly for every finite double
