"""Chain spec files written from axes and points (POE convention, docs/specs.md), and description files derived
from the fixtures, for the chain tests (and bench/general6r.py)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

ROBOTS = Path(__file__).resolve().parent / "robots"


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


def dh_spec(name: str, title: str, rows, kinds) -> str:
    """The text of a `chain` spec in standard DH: one [[joint]] per (a, alpha, d) row (alpha a number or a string
    such as "pi/2", theta 0), "R" or "P" per joint (a slide's range +-0.5 m)."""
    text = f'family = "chain"\nname = "{name}"\ntitle = "{title}"\nconvention = "standard"\n'
    for i, ((a, alpha, d), kind) in enumerate(zip(rows, kinds, strict=True)):
        text += (f'[[joint]]\nname = "j{i + 1}"\ntype = "{"revolute" if kind == "R" else "prismatic"}"\n'
                 f'a = {a}\nalpha = "{alpha}"\nd = {d}\ntheta = 0.0\n')
        if kind == "P":
            text += "lower = -0.5\nupper = 0.5\n"
    return text


# The calibrated KR 6's URDF with its calibration 1e-5 (axis 3 tilted 1e-5 rad, axis 5 moved 1e-5 m) instead of
# 2e-7 rad / 3e-8 m: beyond the 1e-6 geometry tolerance, so a general 6R, yet 1e-5 from parallel axes 2, 3 and a
# spherical wrist. Its elimination's readings share eigenvalues (the wrist's flips share the arm's angles to 1e-5,
# q5 = +-delta near the wrist's singularity): `wristkin derive` refused it once (the reading chosen by regularity
# alone missed 2 of 40 random poses).
NEAR_SPECIAL = {'rpy="2e-07 0 0"': 'rpy="1e-05 0 0"', "0.42 0 3e-08": "0.42 0 1e-05", "0 0 -3e-08": "0 0 -1e-05"}


def kr6_near_special(folder: Path) -> Path:
    """kr6_near_special.urdf in folder: the fixture kr6_calibrated.urdf with NEAR_SPECIAL's calibration."""
    text = (ROBOTS / "kr6_calibrated" / "kr6_calibrated.urdf").read_text()
    for old, new in NEAR_SPECIAL.items():
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path = Path(folder) / "kr6_near_special.urdf"
    path.write_text(text)
    return path
