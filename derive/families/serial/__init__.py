"""Serial chains from DH tables (seed 001's wrists and arms, the PUMA-560): chain products, Jacobians, staged
closed-form IK from the geometric planner (planned.py), audit numbers and CasADi functions. Templates:
templates/{python,c}/serial.*.jinja.

Spec fields (docs/specs.md): `convention`, `[design]` (metres), `positive`,
`[[joint]]` rows (name, type, a, alpha, d, theta), the seed's `[[printed]]` matrices and `[[finding]]` notes."""

import dataclasses

from ...spec import Spec
from .dh_spec import SPEC_FIELDS, load
from .from_table import from_table
from .mechanism import SerialMechanism

__all__ = ["SOURCE_SUFFIXES", "SPEC_FIELDS", "from_spec", "from_table"]

SOURCE_SUFFIXES = ()  # spec files only


def from_spec(spec: Spec) -> SerialMechanism:
    base, stages = load(spec)
    mech = SerialMechanism(base.name, lambda: dataclasses.replace(base, stages=stages()))
    # simplifying the chain's T dominates and about doubles per revolute joint (the PUMA ~10 s, a 3R wrist ~1 s)
    mech.DERIVE_SECONDS = 0.2 * 2 ** base.kinds.count("R")
    return mech
