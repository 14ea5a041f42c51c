"""A typed view of a decomposition (planner ops, derive/kinematics/planner.py): one Stage per op, with the joints
it solves and the point or direction it reads. The only place that reads an op's dict by its kind; the emitters
(views.py) print Stages field by field."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Spec:
    """A point (meet: where axes meet, on: a point on an axis, home: the end frame's origin) or a direction (dir:
    an axis, cross: the normal of two axes) on the chain, named by its joints."""

    kind: str
    joints: tuple[int, ...]

    def c(self) -> str:
        """kind, count, joints: ck_op's spec, n_spec, spec_js."""
        return f"CK_{self.kind.upper()}, {len(self.joints)}, {_c_list(self.joints or (0,))}"


@dataclass(frozen=True)
class Stage:
    """One op of the decomposition (ck_op's fields: runtime/c/chain/ck_types.h)."""

    index: int
    op: str               # begin, first_plane, last_plane, first_dist, last_dist, pair, single, linear, sp6,
                          # spatial3, orient, group_rest, general6r, arm_angle
    j: int = -1           # its joint(s) in the solver's chain (pair, sp6: j then k)
    k: int = -1
    slide: bool = False   # joint j is prismatic (linear: all its joints are)
    spec: Spec | None = None
    lo: int = 0           # begin / orient: the joints lo..hi left in the product
    hi: int = 0
    units: tuple[tuple[int, ...], ...] = ()  # orient: one joint, or a parallel group turning as one
    js: tuple[int, ...] = ()                  # linear: its slides; spatial3: its joints; sp6: the group's axis
                                              # joint; group_rest: the group
    planar: bool = False  # first/last_dist: the other joints keep the parts normal to j's axis (planner._planar)

    @property
    def solved(self) -> tuple[int, ...]:
        """The joints of the solver's chain this stage sets (orient: each unit's first joint; a group's angle)."""
        if self.op == "begin":
            return ()
        if self.op == "orient":
            return tuple(u[0] for u in self.units)
        if self.op in ("linear", "spatial3", "general6r"):
            return self.js
        if self.op == "arm_angle":
            return (*self.js, self.j)
        return tuple(x for x in (self.j, self.k, *(self.js if self.op == "sp6" else ())) if x >= 0)

    def c_row(self) -> str:
        """The ck_op initializer: op, j, k, prismatic, spec, lo, hi, units, js, planar."""
        spec = self.spec.c() if self.spec else "CK_NONE, 0, { 0 }"
        units = (f"{len(self.units)}, {_c_list([len(u) for u in self.units])},\n      "
                 f"{{ {', '.join(_c_list(u) for u in self.units)} }}") if self.units else "0, { 0 }, { { 0 } }"
        return (f"CK_{self.op.upper()}, {self.j}, {self.k}, {int(self.slide)}, {spec}, {self.lo}, {self.hi}, {units}, "
                f"{len(self.js)}, {_c_list(self.js or (0,))}, {int(self.planar)}")


def _c_list(v) -> str:
    return "{ " + ", ".join(str(x) for x in v) + " }"


def _spec(s) -> Spec:
    return Spec(s[0], tuple(s[1:]))


def stage(index: int, op: dict) -> Stage:
    """The Stage of one planner op."""
    o = op["op"]
    slide = op.get("kind") == "P"
    if o == "begin":
        return Stage(index, o, spec=_spec(op["x"]), lo=op["lo"], hi=op["hi"])
    if o in ("first_plane", "last_plane"):
        return Stage(index, o, j=op["j"], slide=slide, spec=_spec(op["n"]))
    if o in ("first_dist", "last_dist"):
        return Stage(index, o, j=op["j"], slide=slide, spec=_spec(op["s"]), planar=bool(op.get("planar")))
    if o == "pair":
        return Stage(index, o, j=op["j"], k=op["k"], spec=_spec(op["s"]))
    if o == "single":
        return Stage(index, o, j=op["j"], slide=slide)
    if o == "linear":
        return Stage(index, o, slide=True, js=tuple(op["js"]))
    if o == "sp6":
        return Stage(index, o, j=op["j"], k=op["k"], spec=_spec(op["n"]), js=(op["l"],))
    if o == "spatial3":
        return Stage(index, o, js=tuple(op["js"]))
    if o == "orient":
        return Stage(index, o, lo=op["lo"], hi=op["hi"], units=tuple(tuple(u) for u in op["units"]))
    if o == "group_rest":
        return Stage(index, o, j=op["j"], js=tuple(op["group"]))
    if o == "arm_angle":  # j: the elbow; js: the shoulder's three joints; spec: their common point
        return Stage(index, o, j=op["elbow"], spec=_spec(op["s"]), js=tuple(op["shoulder"]))
    if o == "general6r":  # j: the loop's first joint, k: the hidden angle, lo: read backwards; it sets all six
        return Stage(index, o, j=op["shift"], k=op["hidden"], lo=int(op["reverse"]), js=tuple(range(6)))
    raise ValueError(f"no stage for the planner op {o!r}")
