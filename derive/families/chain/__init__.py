"""Serial chains described as users describe them (DH standard / modified, POE, URDF), solved in closed form by
a decomposition the planner finds from the axes (planner.py), never from the robot's name. Templates:
templates/{python,c}/chain.*.jinja.

Spec fields (docs/specs.md, "chain"): `convention` (standard | modified | poe | urdf), `[[joint]]` rows (DH:
name, type, a, alpha, d, theta, direction, lower, upper; POE: name, type, axis, point, lower, upper), `[home]`
(POE), `urdf`, `base_link`, `tip_link` (URDF), `[base]`, `[tool]`, `free`, `geometry_tol`."""

from pathlib import Path

from ...spec import Spec, common
from .description import SPEC_FIELDS, read
from .mechanism import ChainMechanism

__all__ = ["SOURCE_SUFFIXES", "SPEC_FIELDS", "from_spec", "spec_for_file"]

SOURCE_SUFFIXES = (".urdf",)  # description files `wristkin derive` hands to this family as they are


def spec_for_file(path: Path, name=None, base=None, tip=None, free=None, geometry_tol=None) -> Spec:
    """The spec of a URDF given on the command line (its links and options as the spec's fields)."""
    path = Path(path)
    stem = name or path.stem.lower().replace("-", "_").replace(".", "_")
    if stem and not stem[0].isalpha():
        stem = "robot_" + stem
    data = {"family": "chain", "name": stem, "title": f"{path.name} from {base or 'its root'} to {tip or 'its tip'}",
            "source": f"URDF {path.name}", "convention": "urdf", "urdf": str(path.resolve())}
    for key, value in (("base_link", base), ("tip_link", tip), ("free", free), ("geometry_tol", geometry_tol)):
        if value is not None:
            data[key] = value
    return Spec(data, path)


def from_spec(spec: Spec) -> ChainMechanism:
    desc = read(spec)
    head = common(spec)
    return ChainMechanism(head["name"], head["title"], desc)
