"""The serial family's IK stages from the geometric planner (derive/kinematics/planner.py): the planner
reads the DH chain's axes at its default design and finds the decomposition; each op becomes a symbolic stage
over the pose, the design and the joints solved before it, in the stage kinds dh_serial emits. Each stage is
then checked against the chain's own FK by the derivation (dh_serial._ik_steps) at sampled designs, so a
relation that held only at the defaults fails there, with the stage named.

  first/last_plane, first/last_dist (revolute)  -> trig_linear  (subproblems 4 and 3)
  single (revolute)                             -> rotation2d   (subproblem 1)
  prismatic plane and single ops, orient (one axis) -> value
  prismatic distance ops                        -> quadratic    ((q + B)^2 = D, both roots: the Stanford arm's d3)
  orient (three axes at the end)                -> wrist        (dh_serial.wrist_stage)
  orient (a parallel group, then two axes)      -> trig_linear + rotation2d  (_GroupThenTwo: the UR type)
  orient (three axes, not the DH wrist's form)  -> trig_linear + 2 rotation2d  (_GroupThenTwo, a group of one)
  orient (two axes at the end, a 5-joint arm)   -> 2 rotation2d  (_two_axes)
  group_rest (the group's last joint)           -> rotation2d   (from the group's rotation)
  a held joint (a 7-joint arm's)                -> value        (the design's value; the rest planned with it held)
  spatial3 (three axes placing a point)         -> spatial3     (every real root: the lines, the point and its
                                                                 target as kernel outputs)
  no decomposition (six revolute joints)        -> general6r    (every joint by elimination: the axes, points and
                                                                 the product of exponentials as kernel outputs)

A plan read from the tool solves the reversed chain (its axes and home from the same DH frames, turned by M^-1) for
the pose T^-1; its three-axis orientation is read from its axes (_GroupThenTwo), the DH wrist's form being the
base-side rows'.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import sympy as sp

from ...identities.dh import chain as dh_chain
from ...identities.frames import rodrigues
from ...kinematics import general6r
from ...kinematics.planner import NoClosedForm, arm_angle_plan, find_plan, held_elbow_plan
from ...kinematics.poe import Chain, reverse
from ...model import NoDecomposition
from ...serial_core.stages import P_POSE, POSE_SYMBOLS, R_POSE, Stage
from .dh_serial import draw_design, wrist_stage

# the held joint's value the decomposition is planned at (any value where no two axes line up by accident)
HELD_PLAN_VALUE = 0.7
# the held values the general 6R's labelling must stay regular at (the elimination reads the chain the held joint
# turns)
HELD_LABELLING_VALUES = (0.7, -1.9, 2.6, -0.4)
# the general 6R's readings tried after the chosen one where none of its candidates verifies (the Panda with joint1
# held at joint4 = 0, joints 3 and 5 aligned: the chosen reading's eigenproblem fails in C there, 12 of the 36 others
# give the family's members)
FALLBACK_READINGS = 2
SUPPORTED = {"begin", "first_plane", "last_plane", "first_dist", "last_dist", "single", "linear", "orient",
             "group_rest", "spatial3", "sp6", "arm_angle", "held_elbow"}


class PlanError(ValueError):
    """No decomposition of the planner fits the chain in the serial family's stage kinds."""


def _rodrigues(h, q):
    return rodrigues(h, sp.cos(q), sp.sin(q))


class _Motion:
    """A rigid motion (R, t) over symbols."""

    def __init__(self, r, t):
        self.r, self.t = r, t

    def __mul__(self, o):
        return _Motion(self.r * o.r, self.r * o.t + self.t)

    def inv(self):
        return _Motion(self.r.T, -self.r.T * self.t)

    def apply(self, x):
        return self.r * x + self.t


def _screw(kind, h, r, q):
    if kind == "P":
        return _Motion(sp.eye(3), h * q)
    rot = _rodrigues(h, q)
    return _Motion(rot, r - rot * r)


def _perp(h, about=None):
    """A unit vector normal to the axis direction h, exact when h is. An axis turned by a held joint (h in its
    symbol) takes h x `about`, the held joint's axis: the turn keeps its length, so it is normal to h at every held
    value (h along `about` does not turn)."""
    if h.free_symbols:
        v = h.cross(about)
        return (v / sp.sqrt(sp.simplify(v.dot(v)))).applyfunc(sp.simplify)
    hn = np.array([float(v) for v in h])
    e = sp.Matrix([1, 0, 0]) if abs(hn[0]) <= min(abs(hn[1]), abs(hn[2])) + 1e-12 else (
        sp.Matrix([0, 1, 0]) if abs(hn[1]) <= abs(hn[2]) + 1e-12 else sp.Matrix([0, 0, 1]))
    v = h.cross(e)
    return sp.simplify(v / sp.sqrt(v.dot(v)))


class _GroupThenTwo:
    """The orientation R_d = rot(h_g, phi) rot(h_a, q_a) rot(h_b, q_b) of three parallel axes (the group, one
    direction h_g) followed by two axes a, b (a UR-type arm), read without the group's sum phi (a group of one: any
    three-axis wrist, from its axes; the DH wrist stage takes the 90-degree ones):

    - q_a from h_g . rot(h_a, q_a) h_b = h_g . R_d h_b (the group and b turn about h_g and h_b, which they keep:
      subproblem 4 on unit vectors, two roots);
    - q_b from rot(h_b, q_b) (R_d^T h_g) = rot(h_a, -q_a) h_g (subproblem 1; a family where R_d^T h_g is on h_b,
      the wrist singularity sin q_a = 0);
    - the group's last joint, once the planar pair set the others, from the group's rotation
      R_g = R_d rot(h_b, q_b)^T rot(h_a, q_a)^T (subproblem 1 about its axis)."""

    def __init__(self, rd, grp, ja, jb, axes, joints, about=None):
        self.rd, self.grp, self.ja, self.jb, self.axes, self.joints = rd, list(grp), ja, jb, axes, joints
        self.about = about  # a held joint's axis (_perp)
        hg, ha, hb = axes[grp[0]], axes[ja], axes[jb]
        hab = ha.dot(hb)
        a, b = hg.dot(hb - ha * hab), hg.dot(ha.cross(hb))
        c = hg.dot(rd * hb) - hab * hg.dot(ha)
        e1 = _perp(hb, about)
        e2 = hb.cross(e1)
        p0, p1 = rd.T * hg, _rodrigues(ha, -joints[ja]) * hg
        exprs, rule = (a, b, -c), ("subproblem 4 on the rotation: h_g . rot(h_a, q) h_b = h_g . R_d h_b (the "
                                   "parallel group and the last axis keep their own axes)")
        cross = hg.cross(rd * hb)
        sq = sum(x ** 2 for x in cross)
        if sp.simplify(hg.dot(ha)) == 0 and sp.simplify(hab) == 0:
            # h_a normal to both (the UR type): A^2 + B^2 = 1 and A^2 + B^2 - C^2 = |h_g x w|^2, w = R_d h_b, the sine
            # of the roots' half-gap to eps (from the cosine alone: sqrt(eps), and a wrist 1e-7 rad from singular
            # read as singular); Dm = 2 |h_g x w|^2 with Dp = 2, its rounding 4 |h_g x w| eps
            exprs += (2 * sq, sp.Integer(2), 4 * sp.sqrt(sq))
            rule += "; the roots' half-gap from |h_g x R_d h_b| (A^2 + B^2 - C^2 = |h_g x R_d h_b|^2)"
        elif sp.simplify(hg.dot(ha) - hab) == 0:
            # h_a at the same angle b to both (a 60-degree wrist: h_g and h_b align at its singularity, n.w = 1):
            # A^2 + B^2 = sin^4 b, C = cos^2 b - n.w, and A^2 + B^2 - C^2 = (1 - n.w)(n.w - cos 2b) with
            # 1 - n.w = |n x w|^2 / (1 + n.w) to eps near the singularity (n.w near -1 is out of reach: the stage
            # refuses the pose before it reads these)
            nw = hg.dot(rd * hb)
            exprs += (2 * sq / (1 + nw), 2 * (nw - (2 * hab ** 2 - 1)), 4 * sp.sqrt(sq) / (1 + nw))
            rule += ("; the roots' half-gap from (1 - n.w)(n.w - cos 2b), 1 - n.w = |h_g x R_d h_b|^2 / "
                     "(1 + n.w), the wrist's equal angles b")
        self.stages = [
            Stage("trig_linear", (ja,), exprs, f"angle {joints[ja]} (two roots)", rule,
                  gap="wrist" if len(exprs) == 6 else "distance"),
            Stage("rotation2d", (jb,), (e1.dot(p1), e2.dot(p1), e1.dot(p0), e2.dot(p0)), f"angle {joints[jb]}",
                  "subproblem 1: rot(h_b, q) (R_d^T h_g) = rot(h_a, -q_a) h_g in the plane normal to h_b",
                  probe_next=len(self.grp) > 1)]

    def rest(self, j) -> Stage:
        """The group's joint j, the group's other joints solved, from the group's rotation R_g = R_d rot(h_b, q_b)^T
        rot(h_a, q_a)^T (_group_rest)."""
        rg = (self.rd * _rodrigues(self.axes[self.jb], self.joints[self.jb]).T
              * _rodrigues(self.axes[self.ja], self.joints[self.ja]).T)
        return _group_rest(rg, self.grp, j, self.axes, self.joints, self.about,
                           "the parallel group's rotation R_d rot(h_b, q_b)^T rot(h_a, q_a)^T")


class _Group:
    """A parallel group whose rotation R_g the solved joints around it give (an offset wrist's: R_0^T T M^-1
    R_5^T R_4^T, the orient op's R_d): its last joint once the planar pair set the others (_group_rest)."""

    def __init__(self, rg, grp, axes, joints, about=None):
        self.rg, self.grp, self.axes, self.joints, self.about = rg, list(grp), axes, joints, about

    def rest(self, j) -> Stage:
        return _group_rest(self.rg, self.grp, j, self.axes, self.joints, self.about,
                           "the parallel group's rotation, the joints before and after it undone from the target")


def _group_rest(rg, grp, j, axes, joints, about, source) -> Stage:
    """The group's joint j, the group's other joints solved: the group turns about one direction, so R_g =
    rot(h_j, S + q_j) with S the others' angles signed by their axes' sense along h_j (parallel DH axes may point
    either way): q_j is the angle of R_g about h_j less S (subproblem 1 on e1 normal to h_j, against (cos S, sin S)).
    Reading S from the solved joints' cos and sin keeps the stage small: undoing each joint's rotation in the matrix
    made the UR5e's stage 1,100 lines of C."""
    h = axes[j]
    others = sum((sp.sign(sp.simplify(axes[o].dot(h))) * joints[o] for o in grp if o != j), sp.Integer(0))
    e1 = _perp(h, about)
    e2 = h.cross(e1)
    v = rg * e1
    return Stage("rotation2d", (j,), (e1.dot(v), e2.dot(v), sp.cos(others), sp.sin(others)), f"angle {joints[j]}",
                 f"subproblem 1: {source} about the joint's axis, less the group's other joints (signed by their "
                 "axes' sense)")


def stages(rows, joints, kinds, design, defaults, convention="standard", names=None, base=None, tool=None,
           held=None, general=False, arm_angle=None, held_elbow=False):
    """(stages, strategy) for the DH rows (after the constant `base`, before the constant `tool`, 4x4 each): the
    planner's decomposition as symbolic stages. `held`: (joint index, design symbol) of a joint held at a run-time
    value (a 7-joint arm's free joint): its stage reads the value, and the others are planned on the chain with it
    held, its rotation kept as its symbol (so every stage holds at every held value, which the derivation checks).
    `general`: where no decomposition fits, six revolute joints are solved by elimination (a robot whose own plan
    is the general 6R's; one that a decomposition outside these stage kinds fits is refused instead: its
    decomposition is exact and cheaper). `arm_angle`: the design symbol of an S-R-S arm's arm angle, its run-time
    parameter (kinematics/planner.arm_angle_plan: the shoulder and the elbow from the wrist centre and it, then the
    wrist). `held_elbow`: the held joint is an S-R-S arm's elbow, the others a self-motion (planner.held_elbow_plan:
    the shoulder at previous's arm angle, then the wrist)."""
    if convention != "standard":
        raise PlanError("the serial family's stages are built for standard DH tables")
    ts = dh_chain(rows, convention, None, base)
    hj = None if held is None else held[0]
    idx = [i for i in range(len(rows)) if i != hj]  # the solved joints (all but a held one)
    zero = {joints[i]: 0 for i in idx}
    frames = [sp.eye(4) if base is None else base] + [sp.simplify(t.subs(zero)) for t in ts]
    # the solved chain: axis i is z of the frame before row i; after a held joint, turned by its symbol
    axes = [sp.simplify(frames[i][:3, 2]) for i in idx]
    points = [frames[i][:3, 3] for i in idx]
    about = None if hj is None else sp.simplify(frames[hj][:3, 2])  # the held joint's axis (_perp)
    all_joints, joints, kinds = joints, tuple(joints[i] for i in idx), tuple(kinds[i] for i in idx)
    end = frames[-1] if tool is None else sp.simplify(frames[-1] * tool)
    home = _Motion(end[:3, :3], end[:3, 3])
    untool = sp.eye(3) if tool is None else tool[:3, :3].T  # R_POSE = R_n R_tool
    # planned at a generic held value: at a special one two axes can line up (parallel at 0) where no other value
    # has them; the stages are then checked at random held values
    at = dict(zip(design, defaults, strict=True)) | ({} if hj is None else {all_joints[hj]: HELD_PLAN_VALUE})

    labels = tuple(names or (str(q) for q in all_joints))

    def num(v, values=at):
        return np.array([float(sp.sympify(x).subs(values)) for x in v])

    def numeric_chain(values):
        return Chain("dh", tuple(labels[i] for i in idx), tuple(kinds), np.array([num(a, values) for a in axes]),
                     np.array([num(p, values) for p in points]),
                     np.vstack([np.hstack([np.array(end[:3, :3].subs(values), dtype=float),
                                           num(end[:3, 3], values)[:, None]]), [0, 0, 0, 1]]))
    numeric = numeric_chain(at)
    try:
        if arm_angle is not None:
            plan = arm_angle_plan(numeric, 1e-9)
        elif held_elbow:
            plan = held_elbow_plan(numeric, 1e-9)
        else:
            plan = find_plan(numeric, 1e-9, lambda _c, p: all(o["op"] in SUPPORTED for o in p.ops)
                             and all(o["op"] != "orient" or len(o["units"]) in (1, 3) or (
                                 len(o["units"]) == 2 and all(len(u) == 1 for u in o["units"])) for o in p.ops))
    except NoClosedForm as exc:
        if not general or len(idx) != 6 or any(k != "R" for k in kinds):
            raise PlanError(str(exc)) from None
        chains = [numeric] if hj is None else [numeric_chain(at | {all_joints[hj]: v}) for v in HELD_LABELLING_VALUES]
        try:
            labelling = general6r.choose_labelling(chains, np.random.default_rng(11))
        except NoDecomposition as exc6:
            raise PlanError(f"{exc}; {exc6}") from None
        stage = replace(_general6r_stage(axes, points, joints, _Motion(R_POSE, P_POSE) * home.inv(), labelling),
                        elimination=(numeric, labelling))
        out = [replace(stage, joints=tuple(idx))]
        if hj is not None:
            out.insert(0, _held_stage(all_joints[hj], hj, held[1]))
        return out, f"{general6r.STRATEGY}, {labelling.text([labels[i] for i in idx])}"
    n = len(idx)
    pose = _Motion(R_POSE, P_POSE)
    origins = [f[:3, 3] for f in frames]  # where axes meet: a DH frame's origin
    if plan.reversed:
        # the chain read from the tool: T^-1 = M^-1 exp(-S_n q_n) ... exp(-S_1 q_1), each axis turned by M^-1 and
        # flipped (the values stay), its home M^-1, its pose T^-1 = (R^T, -R^T p)
        minv = home.inv()
        order = list(range(n))[::-1]
        axes = [(-(minv.r * axes[i])).applyfunc(sp.simplify) for i in order]
        points = [minv.apply(points[i]).applyfunc(_trig_reduced) for i in order]
        joints, kinds, idx = tuple(joints[i] for i in order), tuple(kinds[i] for i in order), [idx[i] for i in order]
        origins = [minv.apply(o).applyfunc(_trig_reduced) for o in origins]
        about = None if about is None else (minv.r * about).applyfunc(sp.simplify)  # constant: M turns about it
        home, pose, numeric = minv, pose.inv(), reverse(numeric)
    target = pose * home.inv()  # the product of the joints' exponentials

    varied_rng = np.random.default_rng(17)

    def on_axes_at_any_design(o, js):
        """Whether the point o lies on every axis js at other designs too (two drawn as the derivation's checks draw
        them): a frame origin can sit on the meeting point at the defaults by coincidence (a random POE arm's o_1 and
        o_4 both at (0, 0, 0.3)), and a stage built on it failed its check at every other design."""
        for _ in range(2):
            vals = at | draw_design(design, defaults, varied_rng,
                                    tuple(v for v in (held[1] if held else None, arm_angle) if v is not None))
            p = num(o, vals)
            for j in js:
                h, r = num(axes[j], vals), num(points[j], vals)
                if np.linalg.norm(np.cross(p - r, h)) > 1e-9 * max(1.0, float(np.linalg.norm(p))):
                    return False
        return True

    def point(spec):
        if spec[0] == "home":
            return home.t
        if spec[0] == "on":
            return points[spec[1]]
        w = numeric_point(numeric, spec[1:])
        for o in origins:  # the meeting point as the frame origin it is (exact, design-symbolic)
            if np.allclose(num(o), w, atol=1e-9) and on_axes_at_any_design(o, spec[1:]):
                return o
        # axes that meet across a held joint (the Panda's 5 and 7 with joint6 held): the foot on the first of the
        # common normal to the second, p_i + t u_i (their common point, wherever the held joint is)
        t = _foot(axes[spec[1]], points[spec[1]], axes[spec[2]], points[spec[2]])
        if t is None:
            raise PlanError(f"axes {spec[1:]} meet at {w} but are parallel")
        o = (points[spec[1]] + axes[spec[1]] * t).applyfunc(_trig_reduced)
        if not np.allclose(num(o), w, atol=1e-9):
            raise PlanError(f"axes {spec[1:]} meet at {w}, which neither a DH frame origin nor their common normal "
                            "gives")
        return o

    def direction(spec):
        if spec[0] == "dir":
            return axes[spec[1]]
        c = axes[spec[1]].cross(axes[spec[2]])
        return sp.simplify(c / sp.sqrt(c.dot(c)))

    def distance_point(spec, j):
        """The fixed point of a distance op. On a lone axis i any point will do, and the planner's (the axis's DH
        origin) may fall on the solved axis j at some designs (the PUMA's base origin with d1 = 0): then the distance
        no longer depends on q_j and the stage degenerates. One unit along axis i from its point nearest axis j is on
        axis j at no design (the two axes meet at most at that nearest point), and |s - r| stays O(1)."""
        if spec[0] != "on":
            return point(spec)
        i = spec[1]
        t = _foot(axes[i], points[i], axes[j], points[j])
        if t is None:  # parallel axes: no point of axis i is on axis j unless they coincide
            return points[i]
        return (points[i] + axes[i] * (t + 1)).applyfunc(sp.simplify)

    def prefix(js):
        m = _Motion(sp.eye(3), sp.zeros(3, 1))
        for j in js:
            m = m * _screw(kinds[j], axes[j], points[j], joints[j])
        return m
    out = []
    x = y = None
    slides = {}  # a solved slide -> its value: later stages take the value, not the symbol (see _without_slides)
    for op in plan.ops:
        k = op["op"]
        j = op.get("j")
        if k == "begin":
            x = point(op["x"])
            # the joints' part reduced (the home offset and its undoing cancel symbolically, not in floating point at
            # run time), the pose applied to it and the prefix undone as products: the stages' kernels then read
            # the target point as a few shared values (expanded, a UR's elbow stage took 278 operations)
            u = (home.inv() * prefix(range(op["hi"] + 1, n)).inv()).apply(x).applyfunc(_trig_reduced)
            y = _reduced_motion(prefix(range(op["lo"])).inv()).apply(pose.apply(u))
            continue
        if k == "linear":
            js = op["js"]
            a = sp.Matrix.hstack(*[axes[i] for i in js])
            sol = (a.T * a).inv() * a.T * (y - x)
            out += [Stage("value", (i,), (sol[m],), f"slide {joints[i]}", "the slides add: x + sum q_i h_i = y")
                    for m, i in enumerate(js)]
            slides.update({joints[i]: sol[m] for m, i in enumerate(js)})
            continue
        if k == "spatial3":  # three axes in general position place x: every real solution, by the runtime
            out.append(_spatial3_stage(op["js"], axes, points, joints, x, y))
            continue
        if k == "arm_angle":  # an S-R-S arm: the shoulder and the elbow from the wrist centre and the arm angle
            out.append(_arm_angle_stage(op, axes, points, joints, x, y, point(op["s"]), arm_angle, prefix))
            continue
        if k == "held_elbow":  # the elbow held: the shoulder at previous's arm angle, where the wrist centre is reached
            out.append(_held_elbow_stage(op, axes, joints, x, y, point(op["s"]), about, frames[hj][:3, 3], prefix))
            continue
        if k == "sp6":  # an offset wrist: two joints from the parallel group's invariants, then the last about them
            out += _sp6_stages(op, axes, points, joints, x, y, target.r, direction(op["n"]), about)
            continue
        if k == "orient":
            units = [u[0] for u in op["units"]]
            rd = (prefix(range(op["lo"])).inv() * target * prefix(range(op["hi"] + 1, n)).inv()).r
            if len(op["units"]) == 1 and len(op["units"][0]) == 3:  # a parallel group alone (after subproblem 6):
                group = _Group(rd, op["units"][0], axes, joints, about)  # its last joint once the pair set the rest
                continue
            if len(op["units"]) == 3 and len(op["units"][0]) == 3:  # a parallel group, then two axes (UR type)
                group = _GroupThenTwo(rd, op["units"][0], units[1], units[2], axes, joints, about)
                out += group.stages
                continue
            if len(units) == 2:
                out += _two_axes(rd, units[0], units[1], axes, joints, about)
                continue
            if len(units) == 1:
                h = axes[units[0]]
                w = _perp(h, about)
                v = rd * w
                out.append(Stage("value", (units[0],), (sp.atan2(h.dot(w.cross(v)), w.dot(v)),),
                                 f"turn {joints[units[0]]} from the rotation", "subproblem 1: rot(h, q) w = R_d w "
                                 "for w normal to h"))
            else:
                lo = op["lo"]
                row = idx[lo]  # the wrist's first row (a held joint before it is part of the arm)
                m = (frames[0][:3, :3].T if row == 0 else ts[row - 1][:3, :3].T) * R_POSE * untool
                try:
                    if plan.reversed or (hj is not None and hj >= row):
                        raise ValueError("not the DH wrist's rows (read from the tool, or a held joint among them)")
                    out.append(wrist_stage(list(rows[row:]), joints[lo:], tuple(m), "spherical wrist from R_6^3 = "
                                           "(R_3^0)^T R (flip / no flip)" if lo else "spherical wrist from R",
                                           "kinematic decoupling at the wrist centre" if lo else "three "
                                           "intersecting axes", tuple(range(lo, n))))
                except ValueError:  # a wrist of another form (twists off 90 degrees): read from its axes
                    wrist = _GroupThenTwo(rd, [units[0]], units[1], units[2], axes, joints, about)
                    out += [*wrist.stages, wrist.rest(units[0])]
            continue
        if k == "group_rest":
            out.append(group.rest(j))
            continue
        h, r, q = axes[j], points[j], joints[j]
        first = k.startswith("first")
        if kinds[j] == "P":
            if k.endswith("dist"):  # |m + g q - s| = |f - s|: a quadratic in the slide's value, two roots
                out.append(_slide_distance(j, h if not first else -h, point(op["s"]),
                                           *((y, x) if first else (x, y)), q, k))
                y, x = ((y - h * q).applyfunc(sp.expand), x) if first else (y, (x + h * q).applyfunc(sp.expand))
                continue
            if k == "single":
                val = h.dot(y - x)
            else:
                nv = direction(op["n"])
                val = nv.dot(y - x) / nv.dot(h)
            out.append(Stage("value", (j,), (val,), f"slide {q}", f"{k}: the slide's component"))
            slides[q] = val
            if k != "single":
                y, x = ((y - h * q).applyfunc(sp.expand), x) if first else (y, (x + h * q).applyfunc(sp.expand))
            continue
        if k == "single":
            e1 = _perp(h, about)
            e2 = h.cross(e1)
            p0, p1 = x - r, y - r
            out.append(Stage("rotation2d", (j,), (e1.dot(p1), e2.dot(p1), e1.dot(p0), e2.dot(p0)), f"angle {q}",
                             "subproblem 1: (u, v) = Rot(q) (u0, v0) in the plane normal to the axis"))
            continue
        moving, fixed = (y, x) if first else (x, y)
        p = moving - r
        hp = h.dot(p)
        if k.endswith("plane"):
            nv = direction(op["n"])
            a, b = nv.dot(p - h * hp), nv.dot(h.cross(p))
            c = nv.dot(fixed - r) - hp * nv.dot(h)
            rule = "subproblem 4: n . rot(h, q) p = d (the other joints keep the component along n)"
            extra = ()
        else:
            s = distance_point(op["s"], j)
            p2 = s - r
            a, b = p2.dot(p - h * hp), p2.dot(h.cross(p))
            c = (p.dot(p) + p2.dot(p2) - (fixed - s).dot(fixed - s)) / 2 - hp * h.dot(p2)
            rule = "subproblem 3: |rot(h, q) p1 - p2| = d (the other joints keep the distance to s)"
            extra = _distance_factors(p, p2, h, fixed - s, y, slides)  # slides substituted in their parts
            rule += ("; sin^2 of the half-gap of its roots from the factors Dm Dp / 4 = A^2 + B^2 - C^2, Dm = "
                     "e^2 - (|p1'| - |p2'|)^2, Dp = (|p1'| + |p2'|)^2 - e^2 (primes: the parts normal to the axis, e: "
                     "the distance normal to it), Em the scale of Dm's rounding")
        # A cos t + B sin t = C with t = -q (first: the joint is undone from y) or t = q
        a, b, c = (_without_slides(v, slides) for v in (a, b, c))
        out.append(Stage("trig_linear", (j,), (a, -b if first else b, -c, *extra), f"angle {q} ({'two roots'})",
                         rule))
        e = _screw("R", h, r, q)
        if first:
            y = _reduced_motion(e.inv()).apply(y).applyfunc(_tidy)
        else:
            x = _reduced_motion(e).apply(x).applyfunc(_tidy)
    out = [replace(st, joints=tuple(idx[j] for j in st.joints)) for st in out]  # the solved chain's -> the rows'
    if hj is not None:
        out.insert(0, _held_stage(all_joints[hj], hj, held[1]))
    return out, plan.strategy


def _held_stage(q, hj, value) -> Stage:
    return Stage("value", (hj,), (value,), f"the held joint {q}", f"{q} is held at the design's value {value} (a "
                 "run-time parameter); the other stages are planned on the chain with it held, its rotation kept as "
                 "its symbol")


def _spatial3_stage(js, axes, points, joints, x, y) -> Stage:
    """Three revolute axes in general position placing the point x on y (no invariant point or direction of the
    others for any of them): the kernel gives the three lines (the design's lengths and a held joint's value in
    them) and x, y; the runtime (wk_spatial3.c, spatial3.py) returns every real solution."""
    exprs = (tuple(sp.simplify(v) for i in js for v in axes[i]) + tuple(_trig_reduced(v) for i in js for v in points[i])
             + tuple(x) + tuple(y))
    names = ", ".join(str(joints[i]) for i in js)
    return Stage("spatial3", tuple(js), exprs, f"joints {names} placing a point (up to four sets)",
                 "three revolute axes in general position (subproblem 5 in effect): the distance to the first axis's "
                 "point and the component along it, bilinear in (cos, sin) of the other two; cos^2 + sin^2 = 1 of the "
                 "third's is a degree-8 polynomial in tan(q_b / 2) with the extraneous (1 + t^2)^2 of the substitution "
                 "(at most four real roots, Pieper), every real root isolated at run time, the first joint by "
                 "subproblem 1")


def _srs_parts(axes, shoulder, s, he, pe, x, y, prefix, wrist_movers) -> tuple[tuple, tuple]:
    """What an S-R-S arm's arm_angle and held_elbow stages share: the kernel's outputs (the shoulder's axes h_a, h_b,
    h_c, its centre s, the elbow's axis h_e and point p_e, the wrist centre x at home and its target y) and the
    reader, the arm angle of joint values: the first axis, s, the elbow point (the elbow axis's point nearest s) and
    the wrist centre the joints place (`wrist_movers`: the shoulder's, and the elbow where it is solved), and the
    elbow axis's direction there (derive/kinematics/arm_angle.py)."""
    ja = shoulder[0]
    e0 = (pe + he * he.dot(s - pe)).applyfunc(_trig_reduced)
    turn = prefix(shoulder)
    reader = (tuple(sp.simplify(v) for v in axes[ja]) + tuple(s) + tuple(turn.apply(e0)) +
              tuple(prefix(wrist_movers).apply(x)) + tuple(turn.r * he))
    exprs = (tuple(sp.simplify(v) for i in shoulder for v in axes[i]) + tuple(s) +
             tuple(sp.simplify(v) for v in he) + tuple(pe) + tuple(x) + tuple(y))
    return exprs, reader


def _arm_angle_stage(op, axes, points, joints, x, y, s, psi, prefix) -> Stage:
    """An S-R-S arm's shoulder (three axes meeting at s) and elbow for the wrist centre's target y and the arm angle
    psi, every set by the runtime (wk_arm_angle.c, arm_angle.py: two elbows, two shoulders each): the kernel gives
    _srs_parts's outputs, then psi; its reader, _srs_parts's."""
    (ja, jb, jc), je = op["shoulder"], op["elbow"]
    exprs, reader = _srs_parts(axes, (ja, jb, jc), s, axes[je], points[je], x, y, prefix, (ja, jb, jc, je))
    names = ", ".join(str(joints[i]) for i in (ja, jb, jc))
    return Stage("arm_angle", (ja, jb, jc, je), exprs + (psi,), f"shoulder {names} and elbow {joints[je]} at the arm "
                 "angle (up to four sets)", "the arm angle psi places the elbow on its circle about the shoulder-wrist "
                 "line (derive/kinematics/arm_angle.py): the elbow from |rot(h_e, q_e) (x - p_e) - (s - p_e)| = "
                 "|y - s| (subproblem 3, two roots), the shoulder's rotation about s from the two frames (s -> y and "
                 "the side psi gives, against s -> the turned wrist centre and the elbow point), its joints by "
                 "subproblem 2 then 1 (two sets); at run time by the runtime's core", reader=reader)


def _held_elbow_stage(op, axes, joints, x, y, s, he, pe, prefix) -> Stage:
    """An S-R-S arm's shoulder (three axes meeting at s) with its elbow held (axis he through pe, its turn in the
    solved chain's axes after it, so x, the wrist centre at home, is where the held elbow puts it): a self-motion. The
    runtime's arm-angle core with the elbow held (wk_arm_angle.c, arm_angle.py): no set unless |y - s| = |x - s|
    within its tangent band; else the shoulder's two sets at the arm angle of previous (else 0), flagged
    indeterminate. The kernel gives _srs_parts's outputs; its reader, _srs_parts's."""
    shoulder = tuple(op["shoulder"])
    exprs, reader = _srs_parts(axes, shoulder, s, he, pe, x, y, prefix, shoulder)
    names = ", ".join(str(joints[i]) for i in shoulder)
    return Stage("held_elbow", shoulder, exprs, f"shoulder {names} with the elbow held (a self-motion, up to two "
                 "sets)", "the held elbow leaves the wrist centre |x - s| from the shoulder centre, which the shoulder "
                 "keeps: the pose is reached only where |y - s| = |x - s|, and there at every arm angle "
                 "(derive/kinematics/arm_angle.py): previous's (else 0), the shoulder's rotation about s from the two "
                 "frames, its joints by subproblem 2 then 1 (two sets); at run time by the runtime's core",
                 reader=reader)


def _sp6_stages(op, axes, points, joints, x, y, rt, nv, about) -> list[Stage]:
    """Subproblem 6 (an offset wrist: the parallel group's axes, direction n, keep the component along n of a point
    and of a direction): joints j and k from n.rot(h_j, -q_j) p_j - n.rot(h_k, q_k) p_k = d_j and n.rot(h_j, -q_j) g =
    n.rot(h_k, q_k) h_l, every real solution by the runtime (wk_sp6.c, sp6.py); then joint l about its axis from the
    group keeping n (subproblem 1), its family at the wrist singularity (h_l along n) placed where the planar pair
    after it reaches. x is on axis l (its turn leaves it), y = T M^-1 x its target, R_t = T M^-1's rotation."""
    j, kk, ll = op["j"], op["k"], op["l"]
    h0, h4, h5 = axes[j], axes[kk], axes[ll]
    p0, p4 = y - points[j], x - points[kk]
    d0 = nv.dot(points[kk]) - nv.dot(points[j])
    g = rt * h5
    exprs = (tuple(sp.simplify(v) for v in (*nv, *h0)) + tuple(p0) + tuple(sp.simplify(v) for v in h4) + tuple(p4)
             + (_trig_reduced(d0),) + tuple(g) + tuple(sp.simplify(v) for v in h5))
    sp6 = Stage("sp6", (j, kk), exprs, f"joints {joints[j]}, {joints[kk]} (up to four sets)",
                "subproblem 6: the group keeps n . p of a point and of the last axis; (cos q_k, sin q_k) affine in "
                "(cos q_j, sin q_j) by Cramer's rule, cos^2 + sin^2 = 1 a quartic in tan(q_j / 2), every real root "
                "isolated at run time (a merged pair near the wrist singularity split, its roots to eps)")
    # the group keeps n: n^T R_k R_l = n^T R_j^T R_t, so rot(h_l, q_l) (R_t^T R_j n) = R_k^T n
    a = _rodrigues(h4, joints[kk]).T * nv
    b = rt.T * _rodrigues(h0, joints[j]) * nv
    e1 = _perp(h5, about)
    e2 = h5.cross(e1)
    last = Stage("rotation2d", (ll,), (e1.dot(a), e2.dot(a), e1.dot(b), e2.dot(b)), f"angle {joints[ll]}",
                 "subproblem 1: rot(h_l, q_l) (R_t^T R_j n) = R_k^T n (the group keeps n); at the wrist singularity "
                 "(h_l along n) a family, its member where the planar pair reaches", probe_next=True)
    return [sp6, last]


def _general6r_stage(axes, points, joints, target: _Motion, labelling) -> Stage:
    """Every joint by elimination (derive/kinematics/general6r.py, run by the runtime's general6r.py /
    wk_general6r.c): the kernel gives the six axes' directions and points (the design's lengths and a held joint's
    value in them, the rest folded) and the product of exponentials exp(S_1 q_1) ... exp(S_6 q_6) = T M^-1 they must
    reach; the runtime's elimination returns the candidates."""
    readings = tuple((sh, int(rev), hid) for sh, rev, hid in labelling.readings(1 + FALLBACK_READINGS))
    exprs = tuple(sp.simplify(x) for a in axes for x in a) + tuple(_trig_reduced(x) for p in points for x in p) + tuple(
        target.r[i, j] if j < 3 else target.t[i] for i in range(3) for j in range(4))
    names = ", ".join(str(q) for q in joints)
    return Stage("general6r", tuple(range(6)), exprs, f"every joint ({names}) by elimination (up to 16 sets)",
                 "Raghavan-Roth's 14 equations of the loop exp(S_1 q_1) ... exp(S_6 q_6) (T M^-1)^-1 = I, two angles "
                 "eliminated, Manocha-Canny's eigenproblem in the hidden angle's half-angle tangent; labelling "
                 f"shift {labelling.shift}, reverse {int(labelling.reverse)}, hidden {labelling.hidden}; where no "
                 "candidate of it verifies (a pose where its equations degenerate), the next readings (each hiding "
                 "another joint) "
                 f"{', '.join(str(r) for r in readings[1:])} in turn", labelling=readings)


def _slide_distance(j, g, s, m, f, q, op) -> Stage:
    """A slide from a distance: |m + g q - s| = |f - s| (g its unit direction, signed by which side moves) is
    (q + B)^2 = D with B = g . (m - s), D = |f - s|^2 - |(m - s) x g|^2 (the target's distance squared less the
    moving point's squared distance from the slide's line through s): q = -B +- sqrt(D). E, the scale of D's
    rounding, is |f - s|^2 + |m - s|^2."""
    w, t = m - s, f - s
    b = g.dot(w)
    perp = w - g * b
    d = sp.expand(t.dot(t) - perp.dot(perp))
    e = t.dot(t) + w.dot(w)
    return Stage("quadratic", (j,), (b, d, e), f"slide {q} (two roots)", f"{op} for a slide: |m + g q - s| = |f - s| "
                 "is (q + B)^2 = D, q = -B +- sqrt(D)")


def _foot(u, p, v, r):
    """t such that p + t u is the foot on the axis (p, u) of its common normal with the axis (r, v) (their common
    point where they meet); None for parallel axes."""
    d, uv = r - p, sp.simplify(u.dot(v))
    if sp.simplify(1 - uv ** 2) == 0:
        return None
    return sp.simplify((d.dot(u) - uv * d.dot(v)) / (1 - uv ** 2))


def _two_axes(rd, ja, jb, axes, joints, about=None) -> list[Stage]:
    """The orientation R_d = rot(h_a, q_a) rot(h_b, q_b) of two axes (a 5-joint arm's last two: the pose's
    orientation has one degree of freedom more than they control, and the FK check refuses a pose they miss):

    - q_a from rot(h_a, q_a) h_b = R_d h_b (b keeps its own axis; subproblem 1 in the plane normal to h_a, whose
      projections vanish only for parallel axes, which the decomposition excludes);
    - q_b from rot(h_b, q_b) w = rot(h_a, -q_a) R_d w for w normal to h_b (subproblem 1)."""
    ha, hb = axes[ja], axes[jb]
    e1 = _perp(ha, about)
    e2 = ha.cross(e1)
    wb = rd * hb
    f1 = _perp(hb, about)
    f2 = hb.cross(f1)
    p1 = _rodrigues(ha, -joints[ja]) * rd * f1
    return [Stage("rotation2d", (ja,), (e1.dot(wb), e2.dot(wb), e1.dot(hb), e2.dot(hb)), f"angle {joints[ja]}",
                  "subproblem 1: rot(h_a, q_a) h_b = R_d h_b in the plane normal to h_a (the last axis keeps its own "
                  "direction)"),
            Stage("rotation2d", (jb,), (f1.dot(p1), f2.dot(p1), sp.Integer(1), sp.Integer(0)), f"angle {joints[jb]}",
                  "subproblem 1: rot(h_b, q_b) w = rot(h_a, -q_a) R_d w for w normal to h_b")]


def _reduced_motion(m: _Motion) -> _Motion:
    """The motion with its entries (joints and design only) in their reduced form (_trig_reduced)."""
    return _Motion(m.r.applyfunc(_trig_reduced), m.t.applyfunc(_trig_reduced))


def _tidy(expr):
    """Joints and design only: the reduced form; with the pose in it: as built (products the kernels share)."""
    return _trig_reduced(expr) if not sp.sympify(expr).free_symbols & set(POSE_SYMBOLS) else expr


def _trig_reduced(expr):
    """expr expanded, each sin(a)^k with k >= 2 written as sin(a)^(k mod 2) (1 - cos(a)^2)^(k // 2) and expanded
    again: its normal form modulo sin^2 + cos^2 = 1 (a solved wrist's rotation and its transpose meet in the target
    point, and the terms that cancel only by that identity made a UR's elbow stage 1,450 operations per coefficient)."""
    expr = sp.expand(expr)

    def reduce(power):
        k = int(power.exp)
        return sp.sin(power.base.args[0]) ** (k % 2) * (1 - sp.cos(power.base.args[0]) ** 2) ** (k // 2)
    return sp.expand(expr.replace(lambda e: e.is_Pow and isinstance(e.base, sp.sin) and e.exp.is_Integer
                                  and e.exp >= 2, reduce))


def _distance_factors(p, p2, h, d, y, slides):
    """(Dm, Dp, Em) of a distance stage |rot(h, t) p - p2| = |d|: 1 - u^2 of its roots (u = -C / R, R = |p'| |p2'|,
    primes: the parts normal to the axis h) is Dm Dp / (4 R^2) with Dm = e^2 - (|p'| - |p2'|)^2,
    Dp = (|p'| + |p2'|)^2 - e^2, e^2 = |d|^2 - (h.(p - p2))^2 (the target's distance normal to the axis: the
    rotation keeps the axial gap).

    1 - u^2 from u loses everything below eps of R: a SCARA with a1 = a2 folded to 1e-8 has e^2 = 1e-17 next to
    a1 a2 = 0.09, so its two roots merged at sqrt(eps) and the shoulder after them became a family. Here |p'| - |p2'|
    is a difference of lengths (exactly 0 for a1 = a2) and e^2, where the axial gap is the target's own component
    along h identically (the axis stays put: a SCARA's), a sum of squares of d's normal part, so Dm keeps e^2 to its
    own relative precision. Em is the scale of Dm's rounding: its terms' sizes, and what the pose point's rounding
    (eps |y|) does to them."""
    def sub(v):
        return v.applyfunc(lambda x: _tidy(sp.sympify(x).subs(slides)) if slides else _tidy(x))

    def length(v):
        v = sub(v - h * h.dot(v))
        if not v.free_symbols & set(POSE_SYMBOLS):  # design and joints only: one exact expression (a1 = a2 gives 0)
            # sqrt(a^2) is a for a design declared positive; given negative at run time, the two factors trade
            # places with their signs flipped, so the runtime reads their product and |Dm| <= |Dp|
            return sp.sqrt(sp.factor(sp.trigsimp(sp.expand(v.dot(v)))))
        return sp.sqrt(sum(x ** 2 for x in v))

    pn, sn = length(p), length(p2)
    dv = sub(d)
    d2 = sum(x ** 2 for x in dv)
    gap = sp.expand(sp.sympify(h.dot(p - p2)).subs(slides))
    planar = sum(x ** 2 for x in sub(d - h * h.dot(d)))
    # planar = d2 - (h.d)^2 for the unit axis: the gap is the target's own axial part when h.d = +-gap, checked on
    # the linear forms (expanding the squares of a UR's pose expressions took 2.5 s)
    axial = sp.expand(sp.sympify(h.dot(d)).subs(slides))
    if sp.expand(axial - gap) == 0 or sp.expand(axial + gap) == 0:
        e2, size, root = planar, planar, sp.sqrt(planar)
    else:  # the axis moves with unsolved joints: the difference (a true double root's cancellation)
        e2, size, root = d2 - gap ** 2, d2 + gap ** 2, sp.sqrt(d2) + sp.Abs(gap)
    ymag = sp.sqrt(sum(x ** 2 for x in sub(y)))
    diff = pn - sn
    em = size + diff ** 2 + 2 * (root + sp.Abs(diff)) * ymag
    return e2 - diff ** 2, (pn + sn) ** 2 - e2, em


def _without_slides(expr, slides):
    """expr with each solved slide replaced by its value, the terms that then cancel cancelled symbolically.

    A slide along the axis of a later distance stage enters |p|^2 as q^2 and the target's distance as the same
    length squared: as two numbers they cancel in floating point, and at a stroke of 6.5e5 m their rounding (1e-4 m^2)
    swallows the planar a1 a2 (the SCARA elbow lost). Substituted and expanded, they cancel in the algebra."""
    if not slides or not (expr.free_symbols & set(slides)):
        return expr
    return sp.expand(expr.subs(slides))


def numeric_point(c: Chain, js) -> np.ndarray:
    from ...kinematics.geometry import common_point

    return common_point([c.points[j] for j in js], [c.axes[j] for j in js])[0]
