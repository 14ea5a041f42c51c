"""Serial chains described as users describe them (DH standard / modified, POE, URDF), solved in closed form by
a decomposition the planner finds from the axes (planner.py), never from the robot's name. Templates:
templates/{python,c}/chain.*.jinja.

Spec fields (docs/specs.md, "chain"): `convention` (standard | modified | poe | urdf), `[[joint]]` rows (DH:
name, type, a, alpha, d, theta, direction, lower, upper; POE: name, type, axis, point, lower, upper), `[home]`
(POE), `urdf`, `base_link`, `tip_link` (URDF), `[base]`, `[tool]`, `free`, `geometry_tol`."""

from ...spec import Spec, common
from .description import SPEC_FIELDS, read
from .mechanism import ChainMechanism

__all__ = ["SPEC_FIELDS", "from_spec"]


def from_spec(spec: Spec) -> ChainMechanism:
    desc = read(spec)
    head = common(spec)
    return ChainMechanism(head["name"], head["title"], desc)
