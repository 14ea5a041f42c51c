"""Chain spec files written from axes and points (POE convention, docs/specs.md), for the chain tests."""

from __future__ import annotations

import numpy as np


def _unit(v) -> list[float]:
    v = np.array(v, dtype=float)
    return (v / np.linalg.norm(v)).tolist()


# a general 3R arm (no two of its first three axes meet or are parallel: the polynomial op) + a ZYZ wrist
SKEW3 = {"axes": [[0.0, 0.0, 1.0], _unit([1.0, 0.2, 0.1]), _unit([0.3, 1.0, 0.2]), [0.0, 0.0, 1.0],
                  [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
         "points": [[0.0, 0.0, 0.0], [0.1, 0.0, 0.4], [0.15, 0.05, 0.8]] + [[0.6, 0.1, 0.9]] * 3,
         "position": [0.6, 0.1, 1.0]}


def poe_spec(name: str, title: str, axes, points, position, rpy=None, joint_names=None) -> str:
    """The text of a `chain` spec in the POE convention: one [[joint]] per axis and point, then [home]."""
    names = joint_names or [f"j{i + 1}" for i in range(len(axes))]
    text = f'family = "chain"\nname = "{name}"\ntitle = "{title}"\nconvention = "poe"\n'
    for nm, a, p in zip(names, axes, points, strict=True):
        text += f'[[joint]]\nname = "{nm}"\naxis = {[float(x) for x in a]}\npoint = {[float(x) for x in p]}\n'
    text += f"[home]\nposition = {[float(x) for x in position]}\n"
    return text + ("" if rpy is None else f"rpy = {[float(x) for x in rpy]}\n")
