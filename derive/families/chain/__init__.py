"""Serial chains described as users describe them (DH standard / modified, POE, URDF), solved in closed form by
a decomposition the planner finds from the axes (planner.py), never from the robot's name. Templates:
templates/{python,c}/chain.*.jinja.

Spec fields (docs/specs.md, "chain"): `convention` (standard | modified | poe | urdf), `[[joint]]` rows (DH:
name, type, a, alpha, d, theta, direction, lower, upper; POE: name, type, axis, point, lower, upper), `[home]`
(POE), `urdf`, `base_link`, `tip_link` (URDF), `[base]`, `[tool]`, `free`, `redundancy`, `geometry_tol`.
The chain family reads and plans; it emits nothing itself: own_robot.load hands ChainDescription.robot_table to the
family with from_table (the serial family), which derives the robot's stages."""

from dataclasses import replace
from pathlib import Path

from ...model import NoDecomposition
from ...spec import Spec, common
from .description import SPEC_FIELDS, read
from .robot import ChainDescription

__all__ = ["SOURCE_SUFFIXES", "SPEC_FIELDS", "from_spec", "spec_for_file"]

SOURCE_SUFFIXES = (".urdf", ".xacro")  # description files `wristkin derive` hands to this family as they are
from_table = None  # a robot's stages are derived by the serial family (Family.from_table)


def solver_name(path: Path) -> str:
    """A solver name from a description file's name: ur5e.urdf, panda_arm.urdf.xacro -> ur5e, panda_arm."""
    stem = path.name
    for suffix in (".xacro", ".urdf"):
        if stem.lower().endswith(suffix):
            stem = stem[: -len(suffix)]
    stem = "".join(c if c.isalnum() else "_" for c in stem.lower()).strip("_") or "robot"
    return stem if stem[0].isalpha() else "robot_" + stem


def spec_for_file(path: Path, name=None, base=None, tip=None, free=None, geometry_tol=None, xacro_args=None,
                  packages=None, redundancy=None) -> Spec:
    """The spec of a URDF (or xacro) file given on the command line (its links and options as the spec's fields)."""
    path = Path(path)
    kind = "xacro" if path.suffix.lower() == ".xacro" else "URDF"
    data = {"family": "chain", "name": name or solver_name(path),
            "title": f"{path.name} from {base or 'its root'} to {tip or 'its tip'}",
            "source": f"{kind} {path.name}", "convention": "urdf", "urdf": str(path.resolve())}
    # every field of this spec stands for a command-line option: its errors name the option
    spec = Spec(data, path, options={"base_link": "--base", "tip_link": "--tip", "free": "--free",
                                     "redundancy": "--redundancy",
                                     "geometry_tol": "--geometry-tol", "name": "--name"})
    for key, option, value in (("base_link", "--base", base), ("tip_link", "--tip", tip), ("free", "--free", free),
                               ("redundancy", "--redundancy", redundancy),
                               ("geometry_tol", "--geometry-tol", geometry_tol),
                               ("xacro_args", "--xacro-arg", xacro_args or None),
                               ("packages", "--package", packages or None)):
        if value is not None:
            spec.given(key, value, option)
    return spec


def free_joint_choices(name: str, title: str, desc) -> list[tuple[tuple, str, ChainDescription]]:
    """Every joint that, held as the run-time parameter, leaves a chain solved in closed form, cheapest first:
    (cost, joint name, mechanism), cost = (a self-motion, the general 6R elimination, branches, position in the
    chain). A self-motion (an S-R-S arm's elbow held: its poses only where the wrist centre is at the elbow's reach,
    each a family) comes last and is never picked without --free."""
    out = []
    for k, jname in enumerate(desc.chain.joint_names):
        mech = ChainDescription(name, title, replace(desc, free=k))
        try:
            plan, _ = mech.plan()
        except NoDecomposition:
            continue
        general = any(op["op"] == "general6r" for op in plan.ops)
        out.append(((mech.held_elbow, general, plan.branches, k), jname, mech))
    return sorted(out, key=lambda c: c[0])


def workable_free_joints(name: str, title: str, desc) -> list[str]:
    """The joints that, held as the run-time parameter, leave a chain solved in closed form, cheapest first."""
    return [jname for _, jname, _ in free_joint_choices(name, title, desc)]


def from_spec(spec: Spec) -> ChainDescription:
    desc = read(spec)
    head = common(spec)
    mech = ChainDescription(head["name"], head["title"], desc)
    if (desc.chain.n <= 6 and desc.free < 0) or desc.redundancy == "arm-angle":
        if desc.redundancy == "arm-angle":
            mech.plan()  # an arm that is no S-R-S: refused here, naming what is missing
        return mech
    if desc.free < 0:
        choices = free_joint_choices(head["name"], head["title"], desc)
        if desc.chain.n > 7 or not choices or choices[0][0][0]:
            raise spec.error("free", f"the joint held as a run-time parameter (the chain has {desc.chain.n} joints; a "
                                     f"closed form solves at most 6): "
                                     f"{_choice_text([c[1] for c in choices])}")
        # no --free: the cheapest choice, said in the solver's decomposition text with the others
        (_, general, branches, _), jname, chosen = choices[0]
        others = ", ".join(c[1] for c in choices[1:]) or "none"
        how = "the general 6R elimination" if general else f"a decomposition with {branches} branches"
        chosen.free_note = (f"free joint {jname} chosen (no --free given): the cheapest closed form ({how}); the "
                            f"other choices that work: {others}")
        return chosen
    try:
        mech.plan()  # a free joint that leaves no decomposition: said here with the choices that work
    except NoDecomposition as exc:
        choices = workable_free_joints(head["name"], head["title"], desc)
        raise NoDecomposition(f"{exc} (with {desc.chain.joint_names[desc.free]} held: "
                              f"{_choice_text(choices)})") from None
    return mech


def _choice_text(choices: list[str]) -> str:
    if not choices:
        return "no choice of the free joint gives a closed-form decomposition"
    return f"joints that give a closed form: {', '.join(choices)} (e.g. --free {choices[0]})"
