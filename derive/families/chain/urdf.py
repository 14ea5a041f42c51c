"""A URDF reader for description files as their makers ship them: the joint path from a base link to a tip link.

Only the top-level <link> and <joint> elements of <robot> are read (as the URDF specification defines them);
<transmission>, <ros2_control>, <gazebo>, <material>, <sensor>, meshes and any other element are ignored, so the
<joint> names nested in them are never taken for joints. Fixed joints (with any axis, or none) are folded into the
neighbouring transforms; revolute, continuous and prismatic joints become chain joints. A joint that is not on the
base -> tip path may be anything (a mimic gripper finger, a floating caster); one on the path that is a <mimic>,
planar or floating joint is refused with its name, its line and what to do. `package://` mesh paths are never read.

A `.xacro` file is expanded first with the `xacro` package (`xacro_args` as its `$(arg NAME)` values; `$(find PKG)`
resolved by `packages`, then by the package.xml files and folders around the file, then ROS_PACKAGE_PATH /
AMENT_PREFIX_PATH). Every error names the file, the element and its line (for a xacro file: the line in the
expanded document; the element's name finds it in the source).
"""

from __future__ import annotations

import math
import os
import re
import xml.parsers.expat
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...kinematics.poe import from_frames, rpy_matrix, transform
from ...kinematics.same_bits import matmul, norm
from ...model import DescriptionError
from .description_names import JOINT_NAME

MOVABLE = ("revolute", "continuous", "prismatic")
KNOWN_TYPES = (*MOVABLE, "fixed", "floating", "planar")


class URDFError(DescriptionError):
    """A description file that does not give a serial chain between the two links: the message names the file,
    the element and its line."""


# ------------------------------------------------------------------------------------------------- the XML tree
@dataclass
class Element:
    """An XML element with the line it starts on (ElementTree keeps no line numbers)."""

    tag: str
    attrib: dict
    line: int
    children: list[Element] = field(default_factory=list)

    def find(self, tag: str) -> Element | None:
        return next((c for c in self.children if c.tag == tag), None)

    def get(self, key: str, default=None):
        return self.attrib.get(key, default)

    def describe(self) -> str:
        name = self.attrib.get("name")
        return f"<{self.tag} name=\"{name}\">" if name is not None else f"<{self.tag}>"


def parse_xml(data: bytes, where: str) -> Element:
    """The element tree of an XML document, each element with its line; errors name `where` and the line."""
    parser = xml.parsers.expat.ParserCreate()
    stack: list[Element] = []
    root: list[Element] = []

    def start(tag, attrib):
        el = Element(tag, dict(attrib), parser.CurrentLineNumber)
        (stack[-1].children if stack else root).append(el)
        stack.append(el)

    def end(_tag):
        stack.pop()

    parser.StartElementHandler, parser.EndElementHandler = start, end
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as exc:
        raise URDFError(f"{where}: line {exc.lineno}: not well-formed XML ({xml.parsers.expat.ErrorString(exc.code)})"
                        ) from None
    return root[0]


# ------------------------------------------------------------------------------------------------------ xacro
def _package_xml_names(folder: Path, depth: int) -> dict[str, Path]:
    """{package name: folder} of the package.xml files at most `depth` folders below `folder`."""
    found: dict[str, Path] = {}
    todo = [(folder, 0)]
    while todo:
        here, d = todo.pop()
        pkg = here / "package.xml"
        if pkg.is_file():
            m = re.search(r"<name>\s*([^<\s]+)\s*</name>", pkg.read_text(encoding="utf-8", errors="replace"))
            if m:
                found.setdefault(m.group(1), here)
        if d < depth:
            try:
                subs = sorted(p for p in here.iterdir() if p.is_dir() and not p.name.startswith("."))
            except OSError:
                continue
            todo.extend((p, d + 1) for p in subs)
    return found


def package_finder(file: Path, packages: Mapping[str, str | Path]):
    """`$(find PKG)` for a description outside a ROS workspace: the `packages` given (NAME -> folder), then a
    package.xml naming PKG or a folder named PKG near the file (its parents and their subfolders, as a source
    tree lays packages out), then ROS_PACKAGE_PATH and AMENT_PREFIX_PATH (share/PKG)."""
    parents = list(file.resolve().parents)[:4]
    manifests: dict[str, Path] = {}  # package.xml names around the file: scanned once, on the first need

    def find(pkg: str) -> str:
        if pkg in packages:
            return str(Path(packages[pkg]).resolve())
        for up in parents:
            if up.name == pkg:
                return str(up)
            if (up / pkg).is_dir():
                return str(up / pkg)
        if not manifests:
            for up in parents:  # the nearest folder's package first
                for name, folder in _package_xml_names(up, 3).items():
                    manifests.setdefault(name, folder)
        if pkg in manifests:
            return str(manifests[pkg])
        for var, sub in (("ROS_PACKAGE_PATH", ""), ("AMENT_PREFIX_PATH", "share")):
            for entry in filter(None, os.environ.get(var, "").split(os.pathsep)):
                cand = Path(entry) / sub / pkg
                if cand.is_dir():
                    return str(cand)
        raise URDFError(f"{file}: xacro: $(find {pkg}): no package {pkg!r} found near the file or on "
                        f"ROS_PACKAGE_PATH / AMENT_PREFIX_PATH; name its folder with --package {pkg}=DIR")
    return find


def expand_xacro(file: Path, args: Mapping[str, str], packages: Mapping[str, str | Path]) -> bytes:
    """The URDF a xacro file expands to (the `xacro` package of the derive extra)."""
    try:
        import xacro
        from xacro import substitution_args
    except ImportError as exc:
        raise URDFError(f"{file}: reading a .xacro file needs the xacro package ({exc}): "
                        "pip install 'wristkin[derive]'") from None
    # xacro resolves $(find) through ROS's package index; outside ROS this module's finder stands in (xacro keeps
    # it in two places: the $(find) substitution and the names of $(eval ...)). xacro's state is global: restored.
    saved = substitution_args._eval_find, substitution_args._eval_dict["find"]
    find, missing = package_finder(file, packages), []

    def finder(pkg):
        try:
            return find(pkg)
        except URDFError as exc:  # xacro wraps what a substitution raises: kept to be raised as it is
            missing.append(exc)
            raise
    substitution_args._eval_find = substitution_args._eval_dict["find"] = finder
    try:
        doc = xacro.process_file(str(file), mappings={str(k): str(v) for k, v in args.items()})
        return doc.toxml(encoding="utf-8")
    except Exception as exc:  # noqa: BLE001 - xacro raises many kinds; each is the same user error
        if missing:
            raise missing[0] from None
        detail = " ".join((str(exc) or type(exc).__name__).split())  # one line
        if isinstance(exc, KeyError) or type(exc).__name__ == "ArgException":
            detail = f"undefined argument {detail}: give it with --xacro-arg NAME=VALUE"
        raise URDFError(f"{file}: xacro could not expand the file: {detail}") from None
    finally:
        substitution_args._eval_find, substitution_args._eval_dict["find"] = saved


# ------------------------------------------------------------------------------------------------------- model
@dataclass(frozen=True)
class Joint:
    name: str
    type: str
    parent: str
    child: str
    element: Element


@dataclass
class Model:
    """The top-level links and joints of a URDF (nothing else is read)."""

    file: str
    robot: str
    links: dict[str, int]  # name -> line
    joints: dict[str, Joint]  # by child link
    element: Element

    def error(self, el: Element | None, message: str) -> URDFError:
        return URDFError(f"{self.file}: line {el.line}: {el.describe()}: {message}" if el is not None
                         else f"{self.file}: {message}")

    def floats(self, el: Element, attr: str, n: int, default: tuple[float, ...]) -> tuple[float, ...]:
        text = el.get(attr) if el is not None else None
        if text is None:
            return default
        try:
            vals = tuple(float(x) for x in text.split())
        except ValueError:
            vals = ()
        if len(vals) != n or not all(math.isfinite(v) for v in vals):
            raise self.error(el, f"{attr}: expected {n} finite numbers, got {text!r}")
        return vals

    def origin(self, j: Joint) -> np.ndarray:
        o = j.element.find("origin")
        return transform(rpy_matrix(self.floats(o, "rpy", 3, (0.0,) * 3)), self.floats(o, "xyz", 3, (0.0,) * 3))

    def axis(self, j: Joint) -> np.ndarray:
        """The unit axis of a movable joint (URDF's default x)."""
        a = j.element.find("axis")
        v = np.array(self.floats(a, "xyz", 3, (1.0, 0.0, 0.0)))
        n = norm(v)
        if not n > 0.0:
            raise self.error(a, f"joint {j.name!r} is {j.type} with a zero axis")
        return v / n

    def limits(self, j: Joint) -> tuple[float, float]:
        lim = j.element.find("limit")
        if j.type == "continuous" or lim is None or (lim.get("lower") is None and lim.get("upper") is None):
            return -math.inf, math.inf
        lo = self.floats(lim, "lower", 1, (-math.inf,))[0]
        hi = self.floats(lim, "upper", 1, (math.inf,))[0]
        if lo > hi:
            raise self.error(lim, f"joint {j.name!r}: lower limit {lo} above upper limit {hi}")
        return lo, hi

    def path(self, base: str, tip: str) -> list[Joint]:
        """The joints from `base` down to `tip`, in order."""
        out, lk = [], tip
        while lk != base:
            if lk not in self.joints:
                raise URDFError(f"{self.file}: tip link {tip!r} is not below base link {base!r} (the links above "
                                f"{tip!r}: {' <- '.join(self.ancestors(tip))})")
            out.append(self.joints[lk])
            lk = self.joints[lk].parent
        return out[::-1]

    def ancestors(self, link: str) -> list[str]:
        out, seen = [link], {link}
        while link in self.joints and self.joints[link].parent not in seen:
            link = self.joints[link].parent
            out.append(link)
            seen.add(link)
        return out


def load_model(path: str | Path, xacro_args: Mapping[str, str] | None = None,
               packages: Mapping[str, str | Path] | None = None) -> Model:
    """The links and joints of a URDF file, or of the URDF a .xacro file expands to."""
    path = Path(path)
    where = str(path)
    if path.suffix.lower() == ".xacro":
        data = expand_xacro(path, xacro_args or {}, packages or {})
        where = f"{path} (as expanded by xacro)"
    else:
        if xacro_args:
            raise URDFError(f"{path}: --xacro-arg is for .xacro files; this is a plain URDF")
        try:
            data = path.read_bytes()
        except OSError as exc:
            raise URDFError(f"{path}: cannot read the file ({exc.strerror or exc})") from None
    root = parse_xml(data, where)
    if root.tag != "robot":
        raise URDFError(f"{where}: line {root.line}: the root element is <{root.tag}>, expected <robot>")
    model = Model(where, root.get("name", "robot"), {}, {}, root)
    for el in root.children:  # top level only: <joint> inside <transmission> / <gazebo> / ... is not a joint
        if el.tag == "link":
            if el.get("name") is None:
                raise model.error(el, "a <link> without a name")
            model.links.setdefault(el.get("name"), el.line)
        elif el.tag == "joint":
            name, jtype = el.get("name"), el.get("type")
            parent, child = el.find("parent"), el.find("child")
            if name is None or parent is None or child is None or parent.get("link") is None \
                    or child.get("link") is None:
                raise model.error(el, "a <joint> needs a name, <parent link=...> and <child link=...>")
            if jtype not in KNOWN_TYPES:
                raise model.error(el, f"joint type {jtype!r} (URDF joints are {', '.join(KNOWN_TYPES)})")
            if child.get("link") in model.joints:
                other = model.joints[child.get("link")].element
                raise model.error(el, f"link {child.get('link')!r} is the child of two joints (also "
                                      f"{other.describe()} at line {other.line}): a URDF is a tree")
            model.joints[child.get("link")] = Joint(name, jtype, parent.get("link"), child.get("link"), el)
    return model


def _end_links(model: Model, base: str | None, tip: str | None) -> tuple[str, str]:
    links = set(model.links) | set(model.joints) | {j.parent for j in model.joints.values()}
    parents = {j.parent for j in model.joints.values()}
    roots = sorted(lk for lk in links if lk not in model.joints)
    leaves = sorted(lk for lk in links if lk not in parents)
    if base is None:
        if len(roots) != 1:
            raise URDFError(f"{model.file}: name the base link with --base (tree roots: {', '.join(roots)})")
        base = roots[0]
    if tip is None:
        if len(leaves) != 1:
            below = [lk for lk in leaves if base in model.ancestors(lk)]
            raise URDFError(f"{model.file}: name the tip link with --tip: the tree below {base!r} has "
                            f"{len(below)} end links ({', '.join(below)}); the tool flange is usually one of them "
                            "or a link above a gripper")
        tip = leaves[0]
    for what, lk in (("base", base), ("tip", tip)):
        if lk not in links:
            raise URDFError(f"{model.file}: {what} link {lk!r} is not in the file (links: {', '.join(sorted(links))})")
    return base, tip


def chain_path(model: Model, base: str | None, tip: str | None) -> tuple[str, str, list[Joint]]:
    """(base, tip, the joints between them), every joint on the path checked to be a serial joint."""
    base, tip = _end_links(model, base, tip)
    path = model.path(base, tip)
    for j in path:
        mimic = j.element.find("mimic")
        if mimic is not None and j.type != "fixed":
            raise model.error(j.element, f"joint {j.name!r} on the chain {base} -> {tip} mimics joint "
                                         f"{mimic.get('joint')!r} (a coupled joint is not a serial joint): end the "
                                         f"chain above it with --tip {j.parent}, or remove the <mimic>")
        if j.type in ("floating", "planar"):
            raise model.error(j.element, f"joint {j.name!r} on the chain {base} -> {tip} is {j.type}: a serial "
                                         "chain takes revolute, continuous, prismatic and fixed joints; start the "
                                         f"chain below it with --base {j.child}")
    return base, tip, path


def read(path: str | Path, base: str | None = None, tip: str | None = None, name: str | None = None,
         xacro_args: Mapping[str, str] | None = None, packages: Mapping[str, str | Path] | None = None):
    """(Chain, info) for the path base -> tip; base defaults to the tree's root, tip to its only leaf."""
    model = load_model(path, xacro_args, packages)
    base, tip, path_joints = chain_path(model, base, tip)
    t = np.eye(4)
    names, kinds, pairs, lower, upper, folded = [], [], [], [], [], []
    for j in path_joints:
        t = matmul(t, model.origin(j))  # the same bits on every CPU: these numbers become the solver's constants
        if j.type == "fixed":
            folded.append(j.name)
            continue
        if not JOINT_NAME.fullmatch(j.name):
            raise model.error(j.element, f"joint name {j.name!r}: letters, digits and _ . - : / only (at most 63)")
        axis = model.axis(j)
        lo, hi = model.limits(j)
        names.append(j.name)
        kinds.append("P" if j.type == "prismatic" else "R")
        pairs.append((matmul(t[:3, :3], axis), t[:3, 3].copy()))
        lower.append(lo)
        upper.append(hi)
    if not names:
        raise URDFError(f"{model.file}: no movable joint between {base!r} and {tip!r}")
    chain = from_frames(name or model.robot, names, kinds, pairs, t, lower=np.array(lower), upper=np.array(upper),
                        source_format="urdf")
    return chain, {"base_link": base, "tip_link": tip, "folded_fixed_joints": folded, "robot": model.robot,
                   "model": model, "path": path_joints}


def composed_fk(model: Model, path_joints: list[Joint]):
    """The URDF's own composition, origin_i . motion_i(q_i) along the joint path, as a function of the movable
    joints (independent of the product-of-exponentials form the chain is solved in)."""
    from ...kinematics.poe import rot

    steps = [(model.origin(j), j.type, None if j.type == "fixed" else model.axis(j)) for j in path_joints]

    def fk(q):
        t, i = np.eye(4), 0
        for origin, kind, axis in steps:
            t = t @ origin
            if kind == "fixed":
                continue
            t = t @ (transform(None, axis * q[i]) if kind == "prismatic" else transform(rot(axis, q[i])))
            i += 1
        return t
    return fk
