"""Serial chains as finite-screw products (seed 003's 3T2R robots): the screw triangle product, its checks
against products of 4x4 transforms, the seed's numbers, and the staged IK; rendered through the serial family's
templates.

Spec fields (docs/specs.md): `structure` (P1P2P3RaRb or RaRaRaRbRb), `[[joint]]` axes at the initial pose
(type, unit direction, a point on a revolute axis in metres), and `seed = "003"` to derive seed 003's own routes
and check its numbers."""

from __future__ import annotations

import math

from ...spec import COMMON_FIELDS, Spec, common
from .screw_robots import STRUCTURES, ScrewMechanism
from .screw_serial import DESIGN_UNIT_TOL

SPEC_FIELDS = ("structure", "joint", "seed")
SOURCE_SUFFIXES = ()
from_table = None  # `--stages derived` is the serial family's (Family.from_table)
SEEDS = ("003",)


def _joints(spec: Spec, kinds: str, shared) -> list[tuple[tuple[float, ...], tuple[float, ...] | None]]:
    tables = spec.tables("joint")
    got = "".join("P" if t.raw("type", None) == "prismatic" else "R" for t in tables)
    if got != kinds:
        raise spec.error("joint", f"{len(kinds)} [[joint]] blocks of types {' '.join(kinds)} (R revolute, P "
                                  "prismatic) for this structure", got)
    out = []
    for t, kind in zip(tables, kinds, strict=True):
        t.only(("type", "direction", "point") if kind == "R" else ("type", "direction"))
        t.choice("type", ("revolute", "prismatic"))
        direction = t.vector("direction", 3)
        norm = math.sqrt(sum(x * x for x in direction))
        if abs(norm * norm - 1.0) > DESIGN_UNIT_TOL:
            raise t.error("direction", f"a unit vector (|s|^2 - 1 within {DESIGN_UNIT_TOL:g})", list(direction))
        out.append((direction, t.vector("point", 3, unit="m") if kind == "R" else None))
    for group in shared:
        if any(out[i][0] != out[group[0]][0] for i in group):
            raise spec.error("joint", f"joints {', '.join(str(i + 1) for i in group)} about one direction (parallel "
                                      "axes: give the same direction)")
    return out


def from_spec(spec: Spec) -> ScrewMechanism:
    spec.only((*COMMON_FIELDS, *SPEC_FIELDS))
    head = common(spec)
    structure = spec.choice("structure", tuple(STRUCTURES))
    kinds, shared, build = STRUCTURES[structure]
    joints = _joints(spec, kinds, shared)
    if structure == "P1P2P3RaRb":  # (p1, p2, p3, a, ra, b, rb)
        default = (*joints[0][0], *joints[1][0], *joints[2][0], *joints[3][0], *joints[3][1], *joints[4][0],
                   *joints[4][1])
    else:  # (a, r1, r2, r3, b, r4, r5)
        default = (*joints[0][0], *joints[0][1], *joints[1][1], *joints[2][1], *joints[3][0], *joints[3][1],
                   *joints[4][1])
    seed = (spec.choice("seed", SEEDS, None) if spec.has("seed") else None) == "003"
    return ScrewMechanism(head["name"], lambda: build(head["name"], head["title"], head["source"], default, seed))
