"""The design grid of a sweep: `NAME=START:STOP:N` per swept parameter, the rest fixed (catalogue default or
`NAME=VALUE`). Angles in degrees (the CLI's unit) unless the module calls the parameter a length; the module gets
radians and metres."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np


class SweepError(ValueError):
    """A malformed --sweep / --design argument (the CLI exits 2 with this message)."""


def angle_names(module) -> tuple[str, ...]:
    """Design parameters that are angles: the module's ANGLE_NAMES where it has them, else every design value of a
    mechanism whose DESIGN_NAMES are all angles (the underactuated wrist)."""
    names = getattr(module, "ANGLE_NAMES", None)
    if names is not None:
        return tuple(n for n in module.DESIGN_NAMES if n in names)
    joints = dict(zip(getattr(module, "JOINT_NAMES", ()), getattr(module, "JOINT_KINDS", ()), strict=False))
    if module.DESIGN_NAMES and all(n in joints for n in module.DESIGN_NAMES):  # a derived arm's free joint
        return tuple(n for n in module.DESIGN_NAMES if joints[n] == "R")
    return tuple(module.DESIGN_NAMES)


@dataclass(frozen=True)
class Axis:
    name: str
    values: tuple[float, ...]  # display units (degrees for angles, metres for lengths)
    angle: bool

    @property
    def unit(self) -> str:
        return "deg" if self.angle else "m"


@dataclass(frozen=True)
class Sweep:
    """The swept axes (outer product, first axis slowest) and the fixed parameters (display units)."""

    mechanism: str
    axes: tuple[Axis, ...]
    fixed: dict
    design_names: tuple[str, ...]
    angles: tuple[str, ...]

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    def to_module(self, name: str, value: float) -> float:
        return math.radians(value) if name in self.angles else float(value)

    def to_display(self, name: str, value: float) -> float:
        return math.degrees(value) if name in self.angles else float(value)

    def design_matrix(self) -> np.ndarray:
        """(size, len(DESIGN_NAMES)) design vectors in the module's units, row-major over the axes."""
        rows = []
        names = [a.name for a in self.axes]
        for combo in itertools.product(*(a.values for a in self.axes)):
            values = dict(self.fixed)
            values.update(zip(names, combo, strict=True))
            rows.append([self.to_module(n, values[n]) for n in self.design_names])
        return np.array(rows, dtype=float).reshape(self.size, len(self.design_names))

    def to_json(self) -> dict:
        return {"mechanism": self.mechanism, "axes": [[a.name, list(a.values), a.angle] for a in self.axes],
                "fixed": dict(sorted(self.fixed.items()))}


def _number(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise SweepError(f"{what}: {text!r} is not a number") from None
    if not math.isfinite(value):
        raise SweepError(f"{what}: {text!r} is not finite")
    return value


def parse_sweep(module, sweeps: list[str], designs: list[str] | None = None) -> Sweep:
    """Sweep of `module` from the CLI's `--sweep NAME=START:STOP:N` and `--design NAME=VALUE` strings."""
    names = tuple(module.DESIGN_NAMES)
    angles = angle_names(module)
    default = {n: (math.degrees(v) if n in angles else float(v)) for n, v in zip(names, module.DESIGN_DEFAULT,
                                                                                   strict=True)}
    fixed = dict(default)
    for item in designs or []:
        name, sep, text = item.partition("=")
        if not sep or name not in names:
            raise SweepError(f"--design {item!r}: expected NAME=VALUE with NAME one of {', '.join(names)}")
        fixed[name] = _number(text, f"--design {name}")
    axes = []
    for item in sweeps:
        name, sep, spec = item.partition("=")
        parts = spec.split(":")
        if not sep or name not in names or len(parts) != 3:
            raise SweepError(f"--sweep {item!r}: expected NAME=START:STOP:N with NAME one of {', '.join(names)}")
        if any(a.name == name for a in axes):
            raise SweepError(f"--sweep {name} given twice")
        start, stop = _number(parts[0], f"--sweep {name} START"), _number(parts[1], f"--sweep {name} STOP")
        try:
            n = int(parts[2])
        except ValueError:
            raise SweepError(f"--sweep {item!r}: N must be an integer") from None
        if n < 1 or (n == 1 and start != stop):
            raise SweepError(f"--sweep {item!r}: N must be >= 2 (or 1 with START == STOP)")
        values = tuple(float(v) for v in np.linspace(start, stop, n))
        axes.append(Axis(name, values, name in angles))
        fixed.pop(name)
    if not names:
        raise SweepError(f"{module.NAME} has no design parameters to sweep (a derived arm has one only with a free "
                         "joint: wristkin derive ... --free JOINT)")
    if not axes:
        raise SweepError("at least one --sweep NAME=START:STOP:N is needed")
    return Sweep(module.NAME, tuple(axes), fixed, names, angles)
