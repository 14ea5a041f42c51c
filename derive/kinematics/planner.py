"""Closed-form IK from geometry: find a decomposition of a chain into subproblems, never from a robot's name.

The planner looks only at the axes (parallel, intersecting, within the geometry tolerance) and searches a
small set of decompositions, read from the base or from the tool (the chain reversed):

  wrist at the end      the last r revolute axes meet in one point W (r = 3: a spherical wrist, r = 2, 1)
                        or r = 0: the first n - r joints place W (a point problem, below), the last r
                        orient the end frame (subproblem 2, then 1);
  three parallel axes   joints 2-4 parallel (UR type): joint 1 from the plane normal to them (subproblem 4),
                        the orientation of (the parallel group's sum, joint 5, joint 6) by subproblems 2 + 1,
                        then the planar pair by subproblem 3 + 1 and the third from the sum; when the last
                        two axes do not meet (an offset wrist), joints 1 and 5 from two equations along the
                        group's direction n (the component of the wrist point and of axis 6), each linear in
                        the cosines and sines of both: a quartic in tan(q1/2), every real root (subproblem 6),
                        then joint 6 about n (subproblem 1), the group's sum and the planar pair.

A point problem e_a ... e_c x = y (x fixed by the joints after c) is solved one joint at a time from an
invariant of the others: a point S on the axes of all the others keeps its distance (subproblem 3, or a
quadratic for a prismatic joint), a direction n along all the others' axes (and normal to their slides) keeps
x's component along n (subproblem 4, or linear), two intersecting axes at the end (subproblem 2), one axis
(subproblem 1), slides only (linear least squares); three revolute axes where none of these applies (general
position) by the distance to and the component along the first axis, bilinear in the other two joints: a
degree-8 polynomial in tan(q/2) of the middle joint, every real root kept (subproblem 5 in effect). Each op's
equation is checked on sampled configurations of the chain by `replay` before the plan is accepted.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..model import NoDecomposition
from .arm_angle import ELBOW, SHOULDER, WRIST, centres
from .arm_angle import residual as arm_angle_residual
from .geometry import common_point, line_distance, parallel_deviation
from .poe import Chain, reverse, screw

DEFAULT_GEOMETRY_TOL = 1e-6  # metres and radians (sin of an angle): documented in docs/specs.md


class NoClosedForm(NoDecomposition):
    """No decomposition fits the chain's axes; the message names what each one needed."""


@dataclass(frozen=True)
class Relation:
    kind: str  # "parallel" | "meet"
    joints: tuple[int, ...]
    deviation: float

    def text(self, names) -> str:
        js = ", ".join(names[j] for j in self.joints)
        what = "parallel" if self.kind == "parallel" else "meet in one point"
        unit = "sin of the largest angle" if self.kind == "parallel" else "largest distance from the common point, m"
        return f"axes {js} {what} (deviation {self.deviation:.1e}, {unit})"


@dataclass
class Plan:
    ops: list[dict]
    reversed: bool
    strategy: str
    relations: list[Relation] = field(default_factory=list)

    @property
    def branches(self) -> int:
        out = 1
        for op in self.ops:
            out *= op_branches(op)
        return out


def op_branches(op: dict) -> int:
    if op["op"] in ("first_plane", "last_plane"):
        return 2 if op["kind"] == "R" else 1
    if op["op"] in ("first_dist", "last_dist", "pair"):
        return 2
    if op["op"] == "spatial3":
        return 4  # a general 3R positioning problem has at most 4 solutions (Pieper)
    if op["op"] == "sp6":
        return 4  # two equations linear in (cos, sin) of two angles: a quartic
    if op["op"] == "orient":
        return 2 if len(op["units"]) == 3 else 1
    if op["op"] == "arm_angle":
        return 4  # the elbow bent either way, two shoulder sets for each
    if op["op"] == "held_elbow":
        return 2  # the shoulder's two sets (the elbow held)
    if op["op"] == "general6r":
        return 16  # the general 6R has at most 16 solutions (Lee and Liang; Raghavan and Roth)
    return 1


class Geometry:
    """The chain's axis relations under a tolerance (every relation the plan relies on is recorded)."""

    def __init__(self, chain: Chain, tol: float):
        self.c, self.tol = chain, tol
        self.used: dict[tuple, Relation] = {}

    def rev(self, j) -> bool:
        return self.c.kinds[j] == "R"

    def parallel(self, js) -> bool:
        js = tuple(js)
        dev = max(parallel_deviation(self.c.axes[js[0]], self.c.axes[j]) for j in js[1:])
        if dev <= self.tol:
            self.used[("parallel", js)] = Relation("parallel", js, dev)
            return True
        return False

    def not_parallel(self, a, b) -> bool:
        return parallel_deviation(a, b) > 10 * self.tol

    def meet(self, js, record: bool = True) -> np.ndarray | None:
        """Their common point within the tolerance, else None; `record`: as a relation the plan relies on."""
        js = tuple(js)
        dirs = [self.c.axes[j] for j in js]
        if all(parallel_deviation(dirs[0], d) <= self.tol for d in dirs[1:]):
            return None  # parallel axes do not meet in one point
        w, dev = common_point([self.c.points[j] for j in js], dirs)
        if dev <= self.tol:
            if record:
                self.used[("meet", js)] = Relation("meet", js, dev)
            return w
        return None

    def on_axis(self, p, j) -> bool:
        return line_distance(self.c.points[j], self.c.axes[j], p, self.c.axes[j]) <= 10 * self.tol

    def point(self, spec) -> np.ndarray:
        if spec[0] == "meet":
            return common_point([self.c.points[j] for j in spec[1:]], [self.c.axes[j] for j in spec[1:]])[0]
        if spec[0] == "on":
            return self.c.points[spec[1]]
        return self.c.home[:3, 3]

    def direction(self, spec) -> np.ndarray:
        if spec[0] == "dir":
            return self.c.axes[spec[1]]
        n = np.cross(self.c.axes[spec[1]], self.c.axes[spec[2]])
        return n / np.linalg.norm(n)


# ------------------------------------------------------------------------------------------------ point problems
def _invariant_point(g: Geometry, js):
    """A point fixed by every joint in js (all revolute): their common point, or any point on a lone axis."""
    if not js or not all(g.rev(j) for j in js):
        return None
    if len(js) == 1:
        return ("on", js[0])
    return ("meet", *js) if g.meet(js) is not None else None


def _invariant_direction(g: Geometry, js):
    """A direction n whose component every joint in js keeps: along their (parallel) axes, normal to their slides."""
    revs = [j for j in js if g.rev(j)]
    slides = [j for j in js if not g.rev(j)]
    if revs:
        if len(revs) > 1 and not g.parallel(revs):
            return None
        n = g.c.axes[revs[0]]
        if all(abs(float(np.dot(n, g.c.axes[j]))) <= g.tol for j in slides):
            return ("dir", revs[0])
        return None
    if len(slides) == 2 and g.not_parallel(g.c.axes[slides[0]], g.c.axes[slides[1]]):
        return ("cross", slides[0], slides[1])
    return None


def _plane_ok(g: Geometry, j, nspec) -> bool:
    n = g.direction(nspec)
    if g.rev(j):
        return g.not_parallel(g.c.axes[j], n)
    return abs(float(np.dot(g.c.axes[j], n))) > 10 * g.tol


def _planar(g: Geometry, j, others) -> bool:
    """A distance op's other joints all turn or slide along joint j's axis: they keep every point's part normal to
    it, so the runtime reads the target's distance there as a sum of squares (a SCARA folded onto its first axis)."""
    return all(g.parallel([i, j]) for i in others)


def plan_point(g: Geometry, js: list[int], x: np.ndarray) -> list[list[dict]]:
    """Every op sequence solving e_js x = y (x at home), best first."""
    if not js:
        return [[]]
    if len(js) > 3:
        return []
    if all(not g.rev(j) for j in js):
        dirs = np.array([g.c.axes[j] for j in js])
        return [[{"op": "linear", "js": list(js)}]] if np.linalg.matrix_rank(dirs, tol=10 * g.tol) == len(js) else []
    if len(js) == 1:
        j = js[0]
        if g.rev(j) and g.on_axis(x, j):
            return []
        return [[{"op": "single", "j": j, "kind": g.c.kinds[j]}]]
    out = []
    a, c = js[0], js[-1]
    if len(js) == 2 and g.rev(a) and g.rev(c):
        s = g.meet((a, c))
        if s is not None and g.not_parallel(g.c.axes[a], g.c.axes[c]) and not g.on_axis(x, c):
            out.append([{"op": "pair", "j": a, "k": c, "s": ("meet", a, c)}])
    sspec = _invariant_point(g, js[:-1])
    if sspec is not None:
        s = g.point(sspec)
        if not g.rev(c) or (not g.on_axis(s, c) and not g.on_axis(x, c)):
            step = {"op": "last_dist", "j": c, "kind": g.c.kinds[c], "s": sspec, "planar": _planar(g, c, js[:-1])}
            # x moves with joint c at run time; the structural checks below read it at home, where it is x
            out += [[step] + rest for rest in plan_point(g, js[:-1], x)]
    sspec = _invariant_point(g, js[1:])
    if sspec is not None:
        s = g.point(sspec)
        if not g.rev(a) or not g.on_axis(s, a):
            out += [[{"op": "first_dist", "j": a, "kind": g.c.kinds[a], "s": sspec, "planar": _planar(g, a, js[1:])}]
                    + rest for rest in plan_point(g, js[1:], x)]
    nspec = _invariant_direction(g, js[1:])
    if nspec is not None and _plane_ok(g, a, nspec):
        out += [[{"op": "first_plane", "j": a, "kind": g.c.kinds[a], "n": nspec}] + rest
                for rest in plan_point(g, js[1:], x)]
    nspec = _invariant_direction(g, js[:-1])
    if nspec is not None and _plane_ok(g, c, nspec):
        out += [[{"op": "last_plane", "j": c, "kind": g.c.kinds[c], "n": nspec}] + rest
                for rest in plan_point(g, js[:-1], x)]
    if not out and len(js) == 3 and all(g.rev(j) for j in js) and g.not_parallel(g.c.axes[a], g.c.axes[js[1]]) \
            and not g.on_axis(x, c) and g.meet(js, record=False) is None:
        # no invariant applies: the general 3R positioning problem, a polynomial with every real root. Not where x
        # lies on the last axis (that joint does not move it) or the three axes meet in one point (they keep x on a
        # sphere about it): two constraints on three joints, a self-motion, where the polynomial vanishes
        # identically and the solver read every reachable pose as unreachable
        out.append([{"op": "spatial3", "js": list(js)}])
    return sorted(out, key=_cost)


def _cost(ops) -> tuple:
    """Fewest branches, then fewest distance ops, then fewest ops. A distance op reads the target's distance
    squared, so a small offset that tells its two roots apart (the PUMA's wrist centre 2e-9 m off the shoulder axis)
    is lost to the rounding of the metre-sized squares: the roots merge to sqrt(eps) and the joint solved after them
    from that offset becomes a family. A plane op reads the offset linearly and keeps it."""
    b = 1
    for op in ops:
        b *= op_branches(op)
    return (b, sum(op["op"] in ("first_dist", "last_dist") for op in ops), len(ops))


def _x_spec(g: Geometry, fixed: list[int]):
    """The point the position joints place: fixed by the joints after them (their common point / an axis point),
    or the end frame's origin when no joint follows."""
    if not fixed:
        return ("home",)
    return _invariant_point(g, fixed)


def _orient_ok(g: Geometry, units: list[list[int]]) -> bool:
    dirs = [g.c.axes[u[0]] for u in units]
    if len(dirs) == 3:
        return g.not_parallel(dirs[0], dirs[1]) and g.not_parallel(dirs[1], dirs[2])
    if len(dirs) == 2:
        return g.not_parallel(dirs[0], dirs[1])
    return len(dirs) == 1


# ------------------------------------------------------------------------------------------------ strategies
def _wrist_at_end(g: Geometry) -> list[Plan]:
    n = g.c.n
    plans = []
    for r in (3, 2, 1, 0):
        if r > n or n - r > 3:
            continue
        tail = list(range(n - r, n))
        if not all(g.rev(j) for j in tail):
            continue
        xspec = _x_spec(g, tail)
        if xspec is None or (r and not _orient_ok(g, [[j] for j in tail])):
            continue
        head = list(range(n - r))
        for ops in plan_point(g, head, g.point(xspec)):
            begin = [{"op": "begin", "x": xspec, "lo": 0, "hi": n - 1}] if head else []
            orient = [{"op": "orient", "units": [[j] for j in tail], "lo": n - r, "hi": n - 1}] if r else []
            what = {3: "a spherical wrist at the end (the last three axes meet in one point)",
                    2: "two intersecting axes at the end", 1: "one axis at the end", 0: "no wrist"}[r]
            plans.append(Plan(begin + ops + orient, False, f"{what}: position of "
                              f"{_x_text(g, xspec)} by joints {_names(g, head)}, then orientation by joints "
                              f"{_names(g, tail)}" if head else f"{what}: orientation by joints {_names(g, tail)}"))
    return plans


def _three_parallel(g: Geometry) -> list[Plan]:
    n = g.c.n
    plans = []
    for i in (0, 1):
        grp = list(range(i, i + 3))
        if grp[-1] >= n or not all(g.rev(j) for j in grp) or not g.parallel(grp):
            continue
        tail = list(range(i + 3, n))
        if len(tail) > 2 or not all(g.rev(j) for j in tail):
            continue
        xspec = _x_spec(g, tail)
        if xspec is None:
            # the two joints after the group do not meet (a UR-type arm with an offset wrist): joints 1 and 5 from
            # two equations, each linear in the cosines and sines of both (subproblem 6), joint 6 from the
            # group's axis, then the group's sum and the planar pair
            # (the second equation reads how joint k turns joint l's axis about the group's: none where joint l's
            # axis or the group's is parallel to joint k's, and every pose was then unreachable)
            if i != 1 or len(tail) != 2 or not _plane_ok(g, 0, ("dir", grp[0])) or \
                    not g.not_parallel(g.c.axes[tail[0]], g.c.axes[tail[1]]) or \
                    not g.not_parallel(g.c.axes[tail[0]], g.c.axes[grp[0]]):
                continue
            ops = [{"op": "begin", "x": ("on", tail[1]), "lo": 0, "hi": n - 1},
                   {"op": "sp6", "j": 0, "k": tail[0], "l": tail[1], "n": ("dir", grp[0])},
                   {"op": "orient", "units": [grp], "lo": grp[0], "hi": grp[2]},
                   {"op": "begin", "x": ("on", grp[2]), "lo": grp[0], "hi": grp[2]},
                   {"op": "last_dist", "j": grp[1], "kind": "R", "s": ("on", grp[0])},
                   {"op": "single", "j": grp[0], "kind": "R"},
                   {"op": "group_rest", "j": grp[2], "group": grp}]
            plans.append(Plan(ops, False, f"three parallel axes {_names(g, grp)} with an offset wrist (the last "
                              f"two axes apart): joints {g.c.joint_names[0]} and {g.c.joint_names[tail[0]]} from two "
                              f"equations along the parallel axes (subproblem 6, a quartic), "
                              f"{g.c.joint_names[tail[1]]} about them (subproblem 1), then the group's angle and "
                              f"the planar pair"))
            continue
        ops = []
        if i == 1:
            nspec = ("dir", grp[0])
            if not _plane_ok(g, 0, nspec):
                continue
            ops += [{"op": "begin", "x": xspec, "lo": 0, "hi": n - 1},
                    {"op": "first_plane", "j": 0, "kind": g.c.kinds[0], "n": nspec}]
        units = [grp] + [[j] for j in tail]
        if not _orient_ok(g, units):
            continue
        ops.append({"op": "orient", "units": units, "lo": i, "hi": n - 1})
        ops += [{"op": "begin", "x": ("on", grp[2]), "lo": grp[0], "hi": grp[2]},
                {"op": "last_dist", "j": grp[1], "kind": "R", "s": ("on", grp[0])},
                {"op": "single", "j": grp[0], "kind": "R"},
                {"op": "group_rest", "j": grp[2], "group": grp}]
        plans.append(Plan(ops, False, f"three parallel axes {_names(g, grp)}: "
                          + (f"joint {g.c.joint_names[0]} from the plane normal to them, " if i else "")
                          + f"the orientation by (their sum, {_names(g, tail) or 'nothing'}), then the planar pair"))
    return plans


def _names(g: Geometry, js) -> str:
    return ", ".join(g.c.joint_names[j] for j in js)


def _x_text(g: Geometry, xspec) -> str:
    if xspec[0] == "meet":
        return f"the point where axes {_names(g, xspec[1:])} meet"
    if xspec[0] == "on":
        return f"a point on axis {g.c.joint_names[xspec[1]]}"
    return "the end frame's origin"


def arm_angle_plan(c: Chain, tol: float) -> Plan:
    """The plan of an S-R-S arm whose run-time parameter is its arm angle (derive/kinematics/arm_angle.py): the
    wrist centre placed by the whole chain, the shoulder and the elbow from it and psi, then the wrist's orientation.
    Refused (NoClosedForm, naming what is missing) unless the chain is S-R-S."""
    if c.n != 7 or any(k != "R" for k in c.kinds):
        raise NoClosedForm(f"the arm angle needs 7 revolute joints (this chain: {c.n} joints, {''.join(c.kinds)})")
    g = Geometry(c, tol)
    names = c.joint_names
    missing = [f"axes {', '.join(names[j] for j in js)} meet in no point (a spherical {what})"
               for js, what in ((SHOULDER, "shoulder"), (WRIST, "wrist")) if g.meet(js) is None]
    if missing:
        raise NoClosedForm("the arm angle needs a spherical shoulder and a spherical wrist: " + "; ".join(missing))
    s, e, w = centres(c)
    offset = abs(float(np.dot(c.axes[ELBOW], w - e)))  # e is the elbow axis's point nearest s
    if offset > tol:
        raise NoClosedForm(f"the arm angle needs the shoulder and wrist centres level along the elbow axis "
                           f"{names[ELBOW]} (an S-R-S arm): they are {offset:.3g} m apart along it")
    d_se, d_ew = float(np.linalg.norm(s - e)), float(np.linalg.norm(w - e))
    if min(d_se, d_ew) <= 10 * tol:
        raise NoClosedForm(f"the arm angle needs the shoulder and wrist centres off the elbow axis {names[ELBOW]} "
                           f"(upper arm {d_se:.3g} m, forearm {d_ew:.3g} m)")
    ops = [{"op": "begin", "x": ("meet", *WRIST), "lo": 0, "hi": 6},
           {"op": "arm_angle", "shoulder": list(SHOULDER), "elbow": ELBOW, "s": ("meet", *SHOULDER)},
           {"op": "orient", "units": [[j] for j in WRIST], "lo": 4, "hi": 6}]
    strategy = (f"the arm angle of an S-R-S arm (axes {', '.join(names[j] for j in SHOULDER)} meet at the shoulder, "
                f"{', '.join(names[j] for j in WRIST)} at the wrist, elbow {names[ELBOW]}; upper arm {d_se:.4g} m, "
                f"forearm {d_ew:.4g} m): the wrist centre from the pose, the elbow on its circle about the "
                f"shoulder-wrist line at the design's arm angle (0: in the plane of {names[0]}'s axis), "
                f"{names[ELBOW]} from the distance, the shoulder's rotation from two directions, then the wrist's "
                "orientation")
    return Plan(ops, False, strategy, list(g.used.values()))


def held_elbow_plan(c: Chain, tol: float) -> Plan:
    """The plan of an S-R-S arm with its elbow held (the six joints left: a spherical shoulder, axes 0-2, and a
    spherical wrist, axes 3-5): a self-motion, the shoulder turning the arm about the shoulder-wrist line and the wrist
    undoing the turn. A pose is reached only where its wrist centre is as far from the shoulder centre as the held
    elbow leaves it; there, at the arm angle of previous (else 0), the shoulder's two sets, then the wrist's
    orientation (kinematics/arm_angle.py; the runtime's arm-angle core with the elbow held). Refused (NoClosedForm)
    unless the six joints are two spherical groups."""
    if c.n != 6 or any(k != "R" for k in c.kinds):
        raise NoClosedForm(f"a held elbow needs the six other joints revolute (this chain: {''.join(c.kinds)})")
    g = Geometry(c, tol)
    names = c.joint_names
    for js, what in (((0, 1, 2), "shoulder"), ((3, 4, 5), "wrist")):
        if g.meet(js) is None:
            raise NoClosedForm(f"a held elbow needs a spherical shoulder and wrist: axes "
                               f"{', '.join(names[j] for j in js)} meet in no point (the {what})")
    ops = [{"op": "begin", "x": ("meet", 3, 4, 5), "lo": 0, "hi": 5},
           {"op": "held_elbow", "shoulder": [0, 1, 2], "s": ("meet", 0, 1, 2)},
           {"op": "orient", "units": [[3], [4], [5]], "lo": 3, "hi": 5}]
    strategy = (f"the held elbow of an S-R-S arm (axes {', '.join(names[j] for j in (0, 1, 2))} meet at the shoulder, "
                f"{', '.join(names[j] for j in (3, 4, 5))} at the wrist): a self-motion, reached only where the wrist "
                "centre is as far from the shoulder centre as the held elbow leaves it; there every arm angle reaches "
                "the pose: the member at previous's arm angle (else 0), flagged indeterminate, the shoulder's two "
                "sets, then the wrist's orientation")
    return Plan(ops, False, strategy, list(g.used.values()))


def find_plan(chain: Chain, tol: float = DEFAULT_GEOMETRY_TOL, check=None) -> Plan:
    """The best decomposition (fewest branches, then from the base) whose ops pass `check(chain, plan)`."""
    tried = []
    for rev, c in ((False, chain), (True, reverse(chain))):
        for strategy in (_wrist_at_end, _three_parallel):
            g = Geometry(c, tol)
            for plan in strategy(g):
                plan.reversed = rev
                plan.relations = list(g.used.values())
                if rev:
                    plan.strategy = "from the tool (the chain reversed): " + plan.strategy
                tried.append(plan)
    tried.sort(key=lambda p: (p.branches, p.reversed, len(p.ops)))
    for plan in tried:
        if check is None or check(chain, plan):
            return plan
    raise NoClosedForm(refusal(chain, tol))


def refusal(chain: Chain, tol: float) -> str:
    """Why no decomposition fits, naming the axes."""
    n = chain.n
    facts = []
    for i in range(n - 1):
        a, b = chain.axes[i], chain.axes[i + 1]
        if chain.kinds[i] == chain.kinds[i + 1] == "R":
            dev = parallel_deviation(a, b)
            dist = line_distance(chain.points[i], a, chain.points[i + 1], b)
            facts.append(f"{chain.joint_names[i]}/{chain.joint_names[i + 1]}: angle sin {dev:.2e}, distance "
                         f"{dist:.2e} m")
    return (f"no closed-form decomposition for the {n}-joint chain {chain.name!r} at geometry tolerance {tol:g}: "
            "it needs the last 3 (or 2, 1) revolute axes to meet in a point with at most 3 joints before them "
            "(or the same from the base), or three consecutive parallel axes (joints 1-3 or 2-4); neighbouring "
            "axes: " + "; ".join(facts) + ". Raise --geometry-tol if the axes are meant to be parallel or to meet.")


# ------------------------------------------------------------------------------------------------ replay
def replay(chain: Chain, plan: Plan, q) -> list[float]:
    """The residual of every op's equation at the true joint values q (0 up to rounding when the op's invariant
    holds on this chain): the derivation's numeric check of each step."""
    c = reverse(chain) if plan.reversed else chain
    qv = list(q)[::-1] if plan.reversed else list(q)
    g = Geometry(c, 1.0)
    e = [screw(k, a, p, v) for k, a, p, v in zip(c.kinds, c.axes, c.points, qv, strict=True)]
    G = c.fk(qv) @ np.linalg.inv(c.home)

    def prod(js):
        t = np.eye(4)
        for j in js:
            t = t @ e[j]
        return t

    def app(t, x):
        return t[:3, :3] @ x + t[:3, 3]

    out = []
    x = y = None
    for op in plan.ops:
        kind = op["op"]
        if kind == "begin":
            lo, hi = op["lo"], op["hi"]
            x = g.point(op["x"])
            gp = np.linalg.inv(prod(range(lo))) @ G @ np.linalg.inv(prod(range(hi + 1, c.n)))
            y = app(gp, x)
            out.append(float(np.linalg.norm(y - app(prod(range(lo, hi + 1)), x))))
        elif kind == "first_plane":
            n = g.direction(op["n"])
            y = app(np.linalg.inv(e[op["j"]]), y)
            out.append(float(abs(np.dot(n, y) - np.dot(n, x))))
        elif kind == "last_plane":
            n = g.direction(op["n"])
            x = app(e[op["j"]], x)
            out.append(float(abs(np.dot(n, y) - np.dot(n, x))))
        elif kind == "first_dist":
            s = g.point(op["s"])
            y = app(np.linalg.inv(e[op["j"]]), y)
            out.append(float(abs(np.linalg.norm(y - s) - np.linalg.norm(x - s))))
        elif kind == "last_dist":
            s = g.point(op["s"])
            x = app(e[op["j"]], x)
            out.append(float(abs(np.linalg.norm(y - s) - np.linalg.norm(x - s))))
        elif kind == "pair":
            out.append(float(np.linalg.norm(app(e[op["j"]] @ e[op["k"]], x) - y)))
        elif kind == "single":
            out.append(float(np.linalg.norm(app(e[op["j"]], x) - y)))
        elif kind in ("linear", "spatial3"):
            out.append(float(np.linalg.norm(app(prod(op["js"]), x) - y)))
        elif kind == "orient":
            lo, hi = op["lo"], op["hi"]
            rd = (np.linalg.inv(prod(range(lo))) @ G @ np.linalg.inv(prod(range(hi + 1, c.n))))[:3, :3]
            units = np.eye(3)
            for u in op["units"]:
                units = units @ prod(u)[:3, :3]
            out.append(float(np.max(np.abs(units - rd))))
        elif kind == "group_rest":
            out.append(0.0)
        elif kind == "arm_angle":
            out.append(arm_angle_residual(c, e, x, y))
        elif kind == "sp6":
            n = g.direction(op["n"])
            y = app(np.linalg.inv(e[op["j"]]), y)
            pos = abs(np.dot(n, y) - np.dot(n, app(e[op["k"]], x)))
            rg = G[:3, :3]
            h5 = c.axes[op["l"]]
            ori = abs(n @ e[op["j"]][:3, :3].T @ rg @ h5 - n @ e[op["k"]][:3, :3] @ h5)
            out.append(float(max(pos, ori)))
    return out
