"""A user robot's named branches, joint limits and command line: what its module offers beyond the serial family's
verbs (its IK derived as straight-line stages; serial_own.py the chain its branches are read on).

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants and verbs; above the marker, what it reads from them
(own_stand_in.py and serial_stand_in.py: stand-in robots), so that it is linted and tested as it is
(tests/test_shared_runtime.py). A module provides _branch_chain(design) (the ideal chain the branches are read on, with
its joints' index) and _fk_design(q) (the design fk takes with the command line's full joints)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from chain_poe import _product
from chain_rigid import _apply, _dot, _mv, _rot, _scale, _sub
from own_stand_in import (
    _ARM_ANGLE,
    _FREE,
    _ROLES,
    BRANCHES,
    JOINT_KINDS,
    JOINT_NAMES,
    LOWER,
    N_JOINTS,
    NAME,
    ROTATION_TOL,
    STATUS_NAMES,
    UPPER,
    InvalidInput,
    Solutions,
    WristkinError,
)
from serial_fk import fk
from serial_ik import ik
from serial_input import _design, _joints
from serial_own import _branch_chain, _fk_design


# wristkin: inlined from here
# ---------------------------------------------------------------------------- branches and limits
def branch_of(joints, design=None) -> dict:
    """The named branches of a configuration: {branch: label} for every branch in BRANCHES (e.g. elbow up /
    down), read from the configuration itself (a held joint at its value there unless `design` gives one)."""
    q = _joints(joints)
    d = _design(_fk_design(q) if design is None else design)
    ideal = _branch_chain(d)
    qc = [q[i] for i in ideal.index]
    out = {}
    for name, kind, j, ref in _ROLES:
        labels = BRANCHES[name]
        if kind in ("wrist", "sign"):  # the middle wrist joint's sign; a joint's sign (the arm angle's elbow, shoulder)
            out[name] = labels[0] if math.sin(qc[j]) >= 0.0 else labels[1]
        elif kind == "elbow":  # the elbow axis above / below the line shoulder -> placed point (along ref)
            s, e, w = (_apply(_product(ideal, qc, range(i)), p) for i, p in
                       ((ref[0], ref[1]), (j, ideal.points[j]), (ref[2], ref[3])))
            sw = _sub(w, s)
            off = _sub(_sub(e, s), _scale(sw, _dot(_sub(e, s), sw) / max(_dot(sw, sw), 1e-300)))
            out[name] = labels[0] if _dot(off, ref[4]) >= 0.0 else labels[1]
        else:  # shoulder: the placed point in front of / behind the first axis, along the arm's own direction
            w = _apply(_product(ideal, qc, range(ref[0])), ref[1])
            fwd = _mv(_rot(ideal.axes[j], qc[j]), ref[2])
            out[name] = labels[0] if _dot(_sub(w, ideal.points[j]), fwd) >= 0.0 else labels[1]
    return out


def select(solutions: Solutions, previous=None, lower=None, upper=None, weights=None, branch=None) -> int:
    """Index of the solution to use, or -1: valid, within [lower, upper] (default: the description's limits
    LOWER / UPPER) and of the named branches (branch={"elbow": "up"}). With `previous`, the nearest such set;
    without it, the first non-singular such set, else the first one."""
    lo = tuple(max(v, -1e300) for v in LOWER) if lower is None else lower  # a continuous joint: no limit
    hi = tuple(min(v, 1e300) for v in UPPER) if upper is None else upper
    sol = solutions
    if branch:
        unknown = sorted(set(branch) - set(BRANCHES))
        if unknown:
            raise InvalidInput(f"branch: unknown branch(es) {unknown}; this chain has {sorted(BRANCHES)}")
        keep = np.array([bool(v) and all(branch_of(row)[b] == lab for b, lab in branch.items())
                         for row, v in zip(sol.values, sol.valid, strict=True)])
        sol = Solutions(sol.values, sol.valid & keep, sol.flags, sol.aux, sol.status, sol.reason)
    return _runtime.select(sol, previous, lo, hi, weights, joint_kinds=JOINT_KINDS)


# ---------------------------------------------------------------------------- command line
CLI_EPILOG = ("Units: lengths in metres; angles (rpy, revolute joints, a revolute --free) in radians unless --deg. "
              "A pose is xyz + rpy (6 numbers, R = Rz(y) Ry(p) Rx(r)), xyz + quaternion x y z w (7; normalised when "
              f"its norm is within {ROTATION_TOL:g} of 1) or a 3x4 / 4x4 matrix row-major (12 / 16; projected onto "
              f"SO(3) within {ROTATION_TOL:g} in max|R^T R - I|, else refused).")


def _cli_joints(values, free, deg):
    """The --joints of `fk` in radians and metres (`free` already is): all N_JOINTS, or the others with the free
    joint from --free."""
    kinds = [k for i, k in enumerate(JOINT_KINDS) if i != _FREE] if len(values) == N_JOINTS - 1 else JOINT_KINDS
    q = [math.radians(v) if deg and kind == "R" else v for v, kind in zip(values, kinds, strict=False)]
    if _FREE >= 0 and len(q) == N_JOINTS - 1:
        if free is None:
            raise InvalidInput(f"joints: {len(q)} values given: give all {N_JOINTS}, or --free for "
                               f"{JOINT_NAMES[_FREE]}")
        q.insert(_FREE, free)
    elif _FREE >= 0 and free is not None and len(q) == N_JOINTS and q[_FREE] != free:
        raise InvalidInput(f"joints: {JOINT_NAMES[_FREE]} differs between --joints and --free: give it once (--joints "
                           "without it, or the same value)")
    return q


def _cli_pose(values, deg):
    if deg and len(values) == 6:  # xyz + rpy: the angles
        return [*values[:3], *(math.radians(v) for v in values[3:])]
    return list(values)


def main(argv=None) -> int:
    """python NAME.py ik --pose POSE [--free V] [--deg | --rad] [--json]
    python NAME.py fk --joints Q1 ... Qn (or the others and --free V) [--deg | --rad] [--json]"""
    import argparse
    import json
    import os
    import sys

    p = argparse.ArgumentParser(prog=f"{NAME}.py", description=f"{NAME}: closed-form IK / FK (generated)",
                                epilog=CLI_EPILOG)
    sub = p.add_subparsers(dest="verb", required=True)
    for verb, opt, meta, what in (("ik", "--pose", "P", "every IK solution set of a pose"),
                                  ("fk", "--joints", "Q", "the pose of joint values")):
        s = sub.add_parser(verb, help=what, description=what, epilog=CLI_EPILOG)
        s.add_argument(opt, nargs="+", type=float, required=True, metavar=meta,
                       help="xyz + rpy / quaternion, or a matrix (see below)" if verb == "ik" else
                       f"{', '.join(JOINT_NAMES)} (radians / metres unless --deg)")
        units = s.add_mutually_exclusive_group()
        units.add_argument("--rad", action="store_true", help="angles in and out in radians (the default)")
        units.add_argument("--deg", action="store_true", help="angles in and out in degrees")
        s.add_argument("--json", action="store_true", help="print one JSON object")
        if _FREE >= 0:
            s.add_argument("--free", type=float, default=None,
                           help=f"the free joint {JOINT_NAMES[_FREE]} (default 0; radians unless --deg)")
        elif _ARM_ANGLE and verb == "ik":
            s.add_argument("--arm-angle", type=float, default=0.0, dest="free",
                           help="the arm angle: the elbow's place on its circle about the shoulder-wrist line (default "
                                "0: in the plane of the first axis; radians unless --deg)")
    args = p.parse_args(argv)
    deg = args.deg
    held = _FREE >= 0 or _ARM_ANGLE  # a run-time parameter the command line takes (--free / --arm-angle)
    free = None if not held or getattr(args, "free", None) is None else (
        math.radians(args.free) if deg and (_ARM_ANGLE or JOINT_KINDS[_FREE] == "R") else args.free)
    try:
        if args.verb == "ik":
            value = 0.0 if free is None else free
            # by name: the held joint's value (a derived module's design also has the lengths), or the arm angle
            design = ({JOINT_NAMES[_FREE]: value} if _FREE >= 0 else [value]) if held else None
            out = ik(_cli_pose(args.pose, deg), design)
        else:
            q = _cli_joints(args.joints, free, deg)
            design = _fk_design(q)
            out = fk(q, design)
    except WristkinError as exc:
        print(f"{NAME}: error: {exc}", file=sys.stderr)
        return 2
    try:
        print(_cli_text(args.verb, out, design, deg) if not args.json else
              json.dumps(_cli_json(args.verb, out, design, deg)))
        sys.stdout.flush()
    except BrokenPipeError:  # `python NAME.py ... | head`: the reader left; not an error of ours
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 0


def _cli_rows(verb, out, design, deg):
    rows = []
    for k, v in enumerate(out.values):
        if not out.valid[k]:
            continue
        vals = [float(x) for x in v]
        row = {"flags": out.flag_names(k)}
        if verb == "ik":
            row["branches"] = branch_of(v, design)
            row["values"] = [math.degrees(x) if deg and kind == "R" else x for x, kind in
                             zip(vals, JOINT_KINDS, strict=True)]
        else:
            row["values"] = vals
        rows.append(row)
    return rows


def _cli_json(verb, out, design, deg):
    unit = "deg" if deg else "rad"
    head = {"status": STATUS_NAMES[out.status], "reason": out.reason}
    if verb == "ik":
        head["columns"] = [f"{n} ({unit if k == 'R' else 'm'})" for n, k in zip(JOINT_NAMES, JOINT_KINDS, strict=True)]
    else:
        head["columns"] = ["r11", "r12", "r13", "px (m)", "r21", "r22", "r23", "py (m)", "r31", "r32", "r33",
                           "pz (m)"]
    return {**head, "solutions": _cli_rows(verb, out, design, deg)}


def _cli_text(verb, out, design, deg):
    unit = "deg" if deg else "rad"
    lines = [f"{STATUS_NAMES[out.status]}: {out.reason}"]
    rows = _cli_rows(verb, out, design, deg)
    if verb == "ik":
        cols = [f"{n} ({unit if k == 'R' else 'm'})" for n, k in zip(JOINT_NAMES, JOINT_KINDS, strict=True)]
        width = max(14, *(len(c) for c in cols))
        lines.append("  " + " ".join(f"{c:>{width}}" for c in cols) + "  branches  [flags]")
        for r in rows:
            extra = " ".join(f"{b}={lab}" for b, lab in r["branches"].items())
            lines.append("  " + " ".join(f"{x:>{width}.9f}" for x in r["values"]) + (f"  {extra}" if extra else "")
                         + (f"  [{', '.join(r['flags'])}]" if r["flags"] else ""))
    else:
        for r in rows:
            m = np.array(r["values"]).reshape(3, 4)
            lines.append("  pose of the tool in the base frame: rotation R | position p (m)")
            lines += [f"    {a: .12f} {b: .12f} {c: .12f} | {t: .12f}" for a, b, c, t in m]
            rpy = _cli_rpy(m[:, :3])
            lines.append(f"    rpy ({unit}, R = Rz(y) Ry(p) Rx(r)): " + " ".join(
                f"{math.degrees(x) if deg else x: .12f}" for x in rpy) + (
                f"  [{', '.join(r['flags'])}]" if r["flags"] else ""))
    return "\n".join(lines)


def _cli_rpy(r):
    """URDF roll, pitch, yaw of a rotation (R = Rz(y) Ry(p) Rx(r)); at pitch +-pi/2 roll is taken as 0."""
    p = math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0]))
    if math.hypot(r[0, 0], r[1, 0]) < 1e-12:
        return 0.0, p, math.atan2(-r[0, 1], r[1, 1])
    return math.atan2(r[2, 1], r[2, 2]), p, math.atan2(r[1, 0], r[0, 0])


if __name__ == "__main__":
    raise SystemExit(main())
