"""A small URDF reader: the joint path from a base link to a tip link as a Chain.

Reads <joint> elements only (type, parent, child, origin xyz / rpy, axis, limit); links need no content.
Fixed joints are folded into the neighbouring transforms; revolute, continuous and prismatic joints become
chain joints (planar / floating joints and <mimic> are refused: they are not serial joints). The path must go
from the base link down the tree to the tip link.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from .description_names import JOINT_NAME
from .robot import from_frames, rpy_matrix, transform


class URDFError(ValueError):
    """A URDF that does not describe a serial chain between the two links."""


def _floats(text: str | None, n: int, what: str, default) -> tuple[float, ...]:
    if text is None:
        return default
    try:
        vals = tuple(float(x) for x in text.split())
    except ValueError:
        raise URDFError(f"{what}: expected {n} numbers, got {text!r}") from None
    if len(vals) != n or not all(np.isfinite(vals)):
        raise URDFError(f"{what}: expected {n} finite numbers, got {text!r}")
    return vals


def read(path: str | Path, base: str | None = None, tip: str | None = None, name: str | None = None):
    """(Chain, info) for the path base -> tip; base defaults to the tree's root, tip to its only leaf."""
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise URDFError(f"{path}: not a readable URDF ({exc})") from None
    if root.tag != "robot":
        raise URDFError(f"{path}: the root element is <{root.tag}>, expected <robot>")
    joints = {}
    for j in root.iter("joint"):
        jname = j.get("name")
        parent, child = j.find("parent"), j.find("child")
        if jname is None or parent is None or child is None:
            raise URDFError(f"{path}: a <joint> without name, <parent> or <child>")
        if j.find("mimic") is not None:
            raise URDFError(f"{path}: joint {jname!r} has <mimic> (a coupled joint is not a serial joint)")
        joints[child.get("link")] = j
    links = {lk.get("name") for lk in root.iter("link")} | set(joints) | {
        j.find("parent").get("link") for j in joints.values()}
    parents = {c: j.find("parent").get("link") for c, j in joints.items()}
    roots = sorted(lk for lk in links if lk not in parents)
    leaves = sorted(lk for lk in links if lk not in set(parents.values()))
    base = base or (roots[0] if len(roots) == 1 else None)
    tip = tip or (leaves[0] if len(leaves) == 1 else None)
    if base is None or tip is None:
        raise URDFError(f"{path}: name the links with --base and --tip (roots {roots}, leaves {leaves})")
    for what, lk in (("base", base), ("tip", tip)):
        if lk not in links:
            raise URDFError(f"{path}: {what} link {lk!r} is not in the URDF (links: {', '.join(sorted(links))})")
    chain_joints, lk = [], tip
    while lk != base:
        if lk not in joints:
            raise URDFError(f"{path}: tip link {tip!r} is not below base link {base!r}")
        chain_joints.append(joints[lk])
        lk = parents[lk]
    chain_joints.reverse()
    t = np.eye(4)
    names, kinds, pairs, lower, upper, folded = [], [], [], [], [], []
    for j in chain_joints:
        jname, jtype = j.get("name"), j.get("type")
        origin = j.find("origin")
        xyz = _floats(None if origin is None else origin.get("xyz"), 3, f"joint {jname!r} origin xyz", (0.0,) * 3)
        rpy = _floats(None if origin is None else origin.get("rpy"), 3, f"joint {jname!r} origin rpy", (0.0,) * 3)
        t = t @ transform(rpy_matrix(rpy), xyz)
        if jtype == "fixed":
            folded.append(jname)
            continue
        if jtype not in ("revolute", "continuous", "prismatic"):
            raise URDFError(f"{path}: joint {jname!r} is {jtype!r}; a serial chain takes revolute, continuous, "
                            "prismatic and fixed joints")
        ax = j.find("axis")
        axis = np.array(_floats(None if ax is None else ax.get("xyz"), 3, f"joint {jname!r} axis", (1.0, 0.0, 0.0)))
        if not np.linalg.norm(axis) > 0:
            raise URDFError(f"{path}: joint {jname!r} has a zero axis")
        lim = j.find("limit")
        lo, hi = -np.inf, np.inf
        if jtype != "continuous" and lim is not None:
            lo = float(lim.get("lower", "-inf"))
            hi = float(lim.get("upper", "inf"))
            if jtype == "revolute" and lim.get("lower") is None and lim.get("upper") is None:
                lo, hi = -np.inf, np.inf
        if not JOINT_NAME.fullmatch(jname):
            raise URDFError(f"{path}: joint name {jname!r}: letters, digits and _ . - : / only (at most 63)")
        names.append(jname)
        kinds.append("P" if jtype == "prismatic" else "R")
        pairs.append((t[:3, :3] @ (axis / np.linalg.norm(axis)), t[:3, 3].copy()))
        lower.append(lo)
        upper.append(hi)
    if not names:
        raise URDFError(f"{path}: no movable joint between {base!r} and {tip!r}")
    chain = from_frames(name or root.get("name", "robot"), names, kinds, pairs, t, lower=np.array(lower),
                        upper=np.array(upper), source_format="urdf")
    return chain, {"base_link": base, "tip_link": tip, "folded_fixed_joints": folded, "robot": root.get("name")}
