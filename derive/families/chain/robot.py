"""The chain family's robot description: a description's chain -> the planner's decomposition -> the robot's
DH table on its ideal axes (robot_table), which the serial family derives and emits."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...kinematics import general6r
from ...kinematics.arm_angle import ELBOW
from ...kinematics.dh_table import NoDHTable, OwnRobotApi, RobotTable, standard_dh
from ...kinematics.geometry import common_point
from ...kinematics.planner import (
    Geometry,
    NoClosedForm,
    Plan,
    arm_angle_plan,
    find_plan,
    held_elbow_plan,
    op_branches,
    replay,
)
from ...kinematics.poe import Chain, normalised, reduce_free, reverse
from ...kinematics.same_bits import dot, norm
from ...model import NoDecomposition, NotDerivable
from .description import Description

FREE_SAMPLES = (0.0, 0.7, -1.9, 2.6)  # values of a free joint the decomposition must hold at
# true axes off the ideal ones by more than this (rounding of a description's angles is ~1e-16): a calibrated robot,
# whose derived stages solve the ideal table and polish on the true chain (derive/families/serial/from_table.py)
CALIBRATED_DEVIATION = 1e-13
# the arm angle is read on the ideal S-R-S geometry: an arm whose axes are farther from it than this (metres and sines;
# a description's rounded angles are ~1e-12 off, pybullet's iiwa 5e-13) would see its arm angle off by as much
ARM_ANGLE_DEVIATION = 1e-9
# the held six joints' Jacobian at or below this (sigma_min / sigma_max) at every sampled configuration: a
# self-motion (rank < 6 everywhere; rounding leaves ~1e-16, a regular arm's random configurations ~1e-2)
SELF_MOTION_RATIO = 1e-9


class ChainDescription:
    """A serial chain from a description (DH, POE, URDF) and the planner's decomposition of it: a
    derive.mechanism.RobotDescription, whose robot_table the serial family derives as straight-line stages."""

    def __init__(self, name: str, title: str, desc: Description):
        self.NAME, self.title, self.desc = name, title, desc
        self._plan: Plan | None = None
        self._ideal: Chain | None = None
        self._degenerate: tuple[tuple[float, str], ...] | None = None
        self._samples: tuple[float, ...] | None = None  # _held_samples, computed once
        self._held_elbow: bool | None = None  # held_elbow, computed once
        self._everywhere: float | None = None  # _everywhere_ratio, computed once
        self.free_note = ""  # how the free joint was chosen when the user gave none

    # ------------------------------------------------------------------------------------------ planning
    @property
    def chain(self) -> Chain:
        return self.desc.chain

    def solver_chain(self, chain: Chain, free_value: float = 0.0, reversed_: bool = False) -> Chain:
        c = reduce_free(chain, self.desc.free, free_value) if self.desc.free >= 0 else chain
        return reverse(c) if reversed_ else c

    def plan(self) -> tuple[Plan, Chain]:
        """The decomposition and the ideal chain it runs on (cached)."""
        if self._plan is None and self.desc.redundancy == "arm-angle":
            self._plan = arm_angle_plan(self.chain, self.desc.geometry_tol)
            self._ideal = self.idealise(self._plan)
            deviation = self.deviation()
            if deviation > ARM_ANGLE_DEVIATION:
                raise NoClosedForm(f"the arm angle needs an S-R-S arm within {ARM_ANGLE_DEVIATION:g}: its axes are "
                                   f"{deviation:.2g} off meeting (a calibrated arm: hold a joint instead, --free)")
        if self._plan is None and self.held_elbow:
            self._plan = held_elbow_plan(self.solver_chain(self.chain, FREE_SAMPLES[1]), self.desc.geometry_tol)
            self._ideal = self.idealise(self._plan)
        if self._plan is None:
            self._refuse_self_motion()
            samples = self._held_samples()
            base = self.solver_chain(self.chain, samples[0])
            scale = self.scale()

            def holds(_c, plan):
                ideal = self.idealise(plan)
                rng = np.random.default_rng(7)
                kept = [v for v in samples if self._relations_hold(plan, v)]
                if len(kept) < min(2, len(samples)):
                    return False
                for v in kept:  # a value where a relation across the held joint breaks is refused at run time
                    c = self.solver_chain(ideal, v, plan.reversed)
                    for _ in range(20):
                        q = _random_joints(c, rng)
                        if max(replay(c, replace(plan, reversed=False), q)) > 1e-9 * scale:
                            return False
                return True
            refused = None
            # planned at each held value in turn until one plans: at a special value two axes can line up (the
            # Panda's joints 5 and 7 are parallel with joint6 held at 0), which rules out the op (subproblem 5) every
            # other value needs; the plan must still hold at every value (holds)
            for v in samples:
                try:
                    self._plan = find_plan(self.solver_chain(self.chain, v), self.desc.geometry_tol, holds)
                    break
                except NoClosedForm as exc:
                    refused = refused or exc
            if self._plan is None:
                self._plan = self._general_plan(base, refused)
            self._ideal = self.idealise(self._plan)
        return self._plan, self._ideal

    def _spanning(self, plan: Plan) -> list:
        """The plan's relations between joints on both sides of the held one (solver-chain indices)."""
        free, n = self.desc.free, self.chain.n - 1
        if free < 0:
            return []
        reduced_to_full = [i for i in range(self.chain.n) if i != free]

        def full(j):
            return reduced_to_full[n - 1 - j if plan.reversed else j]
        return [r for r in plan.relations if min(full(j) for j in r.joints) < free < max(full(j) for j in r.joints)]

    def _relations_hold(self, plan: Plan, v: float) -> bool:
        """Whether the plan's relations across the held joint hold on the true chain with it held at v."""
        g = Geometry(self.solver_chain(self.chain, v, plan.reversed), self.desc.geometry_tol)
        return all(g.meet(r.joints) is not None if r.kind == "meet" else g.parallel(r.joints)
                   for r in self._spanning(plan))

    @property
    def held_elbow(self) -> bool:
        """The free joint is an S-R-S arm's elbow (the iiwa's a4), which leaves the other six a self-motion: solved by
        the derived stages at previous's arm angle (kinematics/planner.held_elbow_plan), flagged indeterminate."""
        if self._held_elbow is None:
            self._held_elbow = False
            if self.desc.free == ELBOW and self.chain.n == 7 and self.desc.redundancy != "arm-angle":
                try:
                    arm_angle_plan(self.chain, self.desc.geometry_tol)
                    self._held_elbow = self._everywhere_ratio() <= SELF_MOTION_RATIO
                except NoClosedForm:
                    pass
        return self._held_elbow

    @property
    def arm_angle(self) -> bool:
        """The run-time parameter is the arm angle (an S-R-S arm, derive/kinematics/arm_angle.py)."""
        return self.desc.redundancy == "arm-angle"

    def plan_samples(self, plan: Plan | None = None) -> tuple[float, ...]:
        """The held values the plan is checked at: _held_samples without those where a relation across the held
        joint breaks (refused at run time: degenerate_held_reasons)."""
        plan = plan or self.plan()[0]
        return tuple(v for v in self._held_samples() if self._relations_hold(plan, v))

    def _breaking_held(self, plan: Plan) -> tuple[float, ...]:
        """The held values (in (-pi, pi]) at which axes that meet across the held joint turn parallel (the Panda's
        joints 5 and 7 with joint6 at 0 or pi): their meeting point, which the decomposition places, goes to
        infinity there. The smallest sine of the angle between two of them, scanned and refined by _isolated_minima,
        kept when it reaches the geometry tolerance."""
        meets = [r.joints for r in self._spanning(plan) if r.kind == "meet"]
        if not meets:
            return ()

        def sine(v):
            c = self.solver_chain(self.chain, v, plan.reversed)
            return min(float(np.linalg.norm(np.cross(c.axes[a], c.axes[b])))
                       for js in meets for i, a in enumerate(js) for b in js[i + 1:])
        return _isolated_minima(sine, self.desc.geometry_tol)

    def _held_samples(self) -> tuple[float, ...]:
        """The free joint's values the decomposition is planned at and must hold at: FREE_SAMPLES, without a value
        at which the held chain is a self-motion (the Panda's joint2 or the iiwa's a2 at 0 line up the joints on
        either side: an isolated held value with infinitely many solutions per pose, which planned the arm as
        degenerate for every value and refused it)."""
        if self.desc.free < 0:
            return (0.0,)
        if self.held_elbow:  # a self-motion at every value, which its plan solves
            return FREE_SAMPLES
        if self._samples is None:  # two SVDs per value: read by the plan, its checks and the derivation
            self._samples = tuple(v for v in FREE_SAMPLES if self._self_motion_ratio([v], 2) > SELF_MOTION_RATIO)
        return self._samples

    def degenerate_held(self) -> tuple[float, ...]:
        """The free joint's values the emitted IK refuses (InvalidDesign / WK_ERR_DESIGN), sorted: see
        degenerate_held_reasons."""
        return tuple(v for v, _ in self.degenerate_held_reasons())

    def degenerate_held_reasons(self) -> tuple[tuple[float, str], ...]:
        """(value, why) for each free joint value (in (-pi, pi]) the emitted IK refuses:
        - a self-motion: two joints on either side line up (the Panda's joint2 at 0) and every pose there has
          infinitely many solutions; found as the largest sigma_min / sigma_max over two random configurations
          reaching SELF_MOTION_RATIO (_isolated_minima);
        - a value where axes the decomposition meets across the held joint turn parallel (_breaking_held)."""
        if self.desc.free < 0 or self.chain.n != 7 or self.held_elbow:
            return ()
        if self._degenerate is None:
            motion = _isolated_minima(lambda v: self._self_motion_ratio([v], 2), SELF_MOTION_RATIO)
            plan, _ = self.plan()
            names = self.solver_chain(self.chain, 0.0, plan.reversed).joint_names
            meets = ", ".join(" and ".join(names[j] for j in r.joints) for r in self._spanning(plan)
                              if r.kind == "meet")
            why = {v: "the other six joints are a self-motion (two of them line up), so every pose has infinitely "
                      "many solutions" for v in motion}
            for v in self._breaking_held(plan):
                why.setdefault(v, f"axes {meets} turn parallel, so the point where they meet, which the "
                                  "decomposition places, is at infinity")
            self._degenerate = tuple(sorted(why.items()))
        return self._degenerate

    def _self_motion_ratio(self, values, per_value: int) -> float:
        """The largest sigma_min / sigma_max of the held chain's Jacobian at random configurations."""
        rng = np.random.default_rng(5)
        ratios = []
        for v in values:
            c = self.solver_chain(self.chain, v)
            for _ in range(per_value):
                s = np.linalg.svd(c.jacobian(_random_joints(c, rng)), compute_uv=False)
                ratios.append(s[-1] / s[0])
        return max(ratios)

    def _everywhere_ratio(self) -> float:
        """_self_motion_ratio at held values away from 0 (where joints may line up), four configurations each: at or
        below SELF_MOTION_RATIO the held chain is a self-motion at every value (computed once: held_elbow and
        _refuse_self_motion read it)."""
        if self._everywhere is None:
            self._everywhere = self._self_motion_ratio(FREE_SAMPLES[1:], 4)
        return self._everywhere

    def _refuse_self_motion(self) -> None:
        """Holding the free joint can leave the other six a self-motion (the iiwa's elbow a4 held: its spherical
        shoulder turns the arm about the shoulder-wrist line and its spherical wrist undoes the turn): the held
        chain's Jacobian has rank < 6 at every configuration, every reachable pose has infinitely many solutions,
        and a decomposition that reads it as six joints finds none (the solver said "unreachable" for every pose).
        Refused here, so that a 7-joint arm without --free never picks it and lists the choices that work. A chain of
        at most six joints singular at every configuration is refused too: its joints' twists span fewer directions
        than there are joints (two axes on one line; axes 1-3 meeting in one point and 4-6 in another, whose turns
        about the line through both repeat), and its decomposition read every pose it reaches as unreachable."""
        if self.desc.free < 0 and self.chain.n <= 6:
            ratio = self._self_motion_ratio((0.0,), 8)
            if ratio <= SELF_MOTION_RATIO:
                s = np.linalg.svd(self.chain.jacobian(_random_joints(self.chain, np.random.default_rng(5))),
                                  compute_uv=False)
                rank = int(np.sum(s > SELF_MOTION_RATIO * s[0]))
                raise NoClosedForm(f"the {self.chain.n}-joint chain is singular at every configuration: its Jacobian "
                                   f"has rank {rank} < {self.chain.n} (sigma_min / sigma_max <= {ratio:.1e} at 8 "
                                   "random configurations), so its joints repeat a motion (two axes on one line, or "
                                   "two triples of axes each meeting in a point) and every pose it reaches has "
                                   "infinitely many solutions; check the description's axes")
            return
        if self.desc.free < 0 or self.chain.n != 7:
            return
        ratio = self._everywhere_ratio()
        if ratio <= SELF_MOTION_RATIO:
            name = self.chain.joint_names[self.desc.free]
            raise NoClosedForm(f"holding {name} leaves the other six joints a self-motion: their Jacobian has rank < 6 "
                               f"at every configuration (sigma_min / sigma_max <= {ratio:.1e} at "
                               f"{4 * (len(FREE_SAMPLES) - 1)} random ones), so every reachable pose has infinitely "
                               "many solutions; hold another joint")

    def _general_plan(self, base: Chain, refused: NoClosedForm) -> Plan:
        """No decomposition fits: a 6R chain (after the free joint is held) is solved by elimination where some
        reading of its loop is regular at every held value sampled (its stage chooses the reading on the chain it
        solves: serial/planned.py); anything else keeps the planner's refusal."""
        if base.n != 6 or any(k != "R" for k in base.kinds):
            raise refused
        chains = [self.solver_chain(self.chain, v) for v in self._held_samples()]
        try:
            general6r.check_regular(chains, np.random.default_rng(11))
        except NoDecomposition as exc:
            raise NoClosedForm(f"{refused}; {exc}") from None
        return Plan([{"op": "general6r"}], False, general6r.STRATEGY)

    def idealise(self, plan: Plan) -> Chain:
        """The full chain with the relations the plan relies on made exact: parallel axes get their mean
        direction, axes meeting in a point pass through their least-squares common point."""
        c = self.chain
        n_solver = c.n - (1 if self.desc.free >= 0 else 0)
        reduced_to_full = [i for i in range(c.n) if i != self.desc.free]

        def full(j):
            r = n_solver - 1 - j if plan.reversed else j
            return reduced_to_full[r]
        axes, points = c.axes.copy(), c.points.copy()
        # a relation across the held joint (the Panda's joints 5 and 7 meet with joint6 held anywhere but 0 and pi)
        # holds on the held chain, not on the full chain at home (there joint6 is 0, the lines are parallel and
        # their "common point" is anywhere): it is left as it is, and the plan's check (holds) reads it at every
        # held value sampled
        spanning = self._spanning(plan)
        relations = [r for r in plan.relations if r not in spanning]
        for rel in relations:
            js = [full(j) for j in rel.joints]
            if rel.kind == "parallel":
                ref = axes[js[0]]
                mean = sum(np.sign(dot(ref, axes[j])) * axes[j] for j in js)
                mean /= norm(mean)
                for j in js:
                    axes[j] = np.sign(dot(ref, axes[j])) * mean
        for rel in relations:
            if rel.kind == "meet":
                js = [full(j) for j in rel.joints]
                w, _ = common_point([points[j] for j in js], [axes[j] for j in js])
                for j in js:
                    points[j] = w
        return normalised(replace(c, axes=axes, points=points))

    def robot_table(self):
        """The robot as a DH table for its derived stages (kinematics/dh_table.RobotTable) on its ideal axes, with
        its held joint, the held values the IK refuses and its true chain; the arm angle or more than six solved
        joints refused with the reason (the deviation of the true axes from the ideal ones goes with it: the
        deriving family decides what it takes). An S-R-S arm whose run-time parameter is its arm angle goes with
        it too (its seven joints solved: the arm angle stands for the seventh)."""
        desc = self.desc
        arm_angle = desc.redundancy == "arm-angle"
        if self.chain.n - (desc.free >= 0) - arm_angle > 6:
            raise NotDerivable.because(self.NAME, f"{self.chain.n} joints")
        plan, ideal = self.plan()
        try:
            table = standard_dh(ideal)
        except NoDHTable as exc:
            raise NotDerivable.because(self.NAME, str(exc)) from None
        c = self.chain
        api = self._own_api(plan, ideal)
        return RobotTable(self.NAME, self.title, desc.source, desc.rule, c.joint_names, table, c.base @ table.frame0,
                          desc.fk, self.scale(), frozenset(o["op"] for o in plan.ops),
                          self.deviation(), api, desc.free, self.degenerate_held_reasons(), c, arm_angle)

    def _own_api(self, plan, ideal) -> OwnRobotApi:
        """The module's constants beyond the verbs (robot_table)."""
        c = self.chain
        roles, labels = _roles(plan, self.solver_chain(c, 0.0, plan.reversed))
        deviation = self.deviation()
        return OwnRobotApi(c.lower, c.upper, labels, tuple(roles), ideal.axes, ideal.points, ideal.home,
                           plan.strategy, self.controls(), c.base, c.tool, self.scale(), self.desc.geometry_tol,
                           deviation, deviation > CALIBRATED_DEVIATION, 1e-12 * self.scale(),  # the chain step's
                           self.free_note)

    def scale(self) -> float:
        c = self.chain
        # same_bits: a generated constant (SCALE), the same on every CPU
        return max(1e-3, *(norm(p) for p in c.points), norm(c.home[:3, 3]))

    def deviation(self) -> float:
        _, ideal = self.plan()
        return float(max(np.max(np.abs(ideal.axes - self.chain.axes)),
                         np.max(np.abs(ideal.points - self.chain.points))))

    def controls(self) -> str:
        n = self.chain.n - (1 if self.desc.free >= 0 else 0)
        if n >= 6:
            return "the full pose (position and orientation)"
        plan, _ = self.plan()
        ch = self.solver_chain(self.chain, 0.0, plan.reversed)
        parts = []
        for op in plan.ops:
            if op["op"] == "begin":
                parts.append(f"the position of {_x_words(op['x'], ch.joint_names)}")
            if op["op"] == "orient":
                k = len(op["units"])
                parts.append({3: "the orientation", 2: "the direction of the last axis and the turn about it, "
                              "as far as two joints reach", 1: "the turn about the last axis"}[k])
        return f"{n} of the 6 pose components: " + ", ".join(parts)


# ---------------------------------------------------------------------------------------------- helpers
def _random_joints(c: Chain, rng) -> np.ndarray:
    return np.array([rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in c.kinds])


def _x_words(spec, names) -> str:
    if spec[0] == "meet":
        return "the point where axes " + ", ".join(names[j] for j in spec[1:]) + " meet"
    if spec[0] == "on":
        return f"a point on axis {names[spec[1]]}"
    return "the end frame's origin"


def _roles(plan: Plan, ch: Chain):
    """Named branches: (name, kind, joint, reference data) per branching op, and name -> two labels."""
    geometry = Geometry(ch, 1.0)  # its points only: the chain's meeting points, axis points, home origin
    roles, labels = [], {}
    x_home, count = None, 0
    place_end = 0
    for op in plan.ops:
        if op["op"] == "begin":
            x_home = geometry.point(op["x"])
            place_end = op["hi"] + 1
        if op["op"] == "held_elbow":  # the shoulder's two sets (the elbow held): its middle joint's sign
            roles.append(("shoulder", "sign", op["shoulder"][1], ()))
            labels["shoulder"] = ("positive", "negative")
            count += 1
            continue
        if op["op"] == "arm_angle":  # the elbow bent either way, the shoulder's two sets: their joints' signs
            roles += [("elbow", "sign", op["elbow"], ()), ("shoulder", "sign", op["shoulder"][1], ())]
            labels.update({"elbow": ("positive", "negative"), "shoulder": ("positive", "negative")})
            count += 1
            continue
        if op_branches(op) < 2 or op["op"] == "general6r":  # the elimination's sets have no geometric names
            continue
        count += 1
        if op["op"] == "orient":
            name, kind, j = "wrist", "wrist", op["units"][1][0]
            ref = ()
            lab = ("noflip", "flip")
        elif op["op"] in ("first_dist", "last_dist") and op["kind"] == "R":
            name, kind, j = "elbow", "elbow", op["j"]
            s = geometry.point(op["s"])
            s_index = min(op["s"][1:]) if op["s"][0] != "home" else 0
            ref = (s_index, tuple(float(v) for v in s), place_end, tuple(float(v) for v in x_home),
                   tuple(float(v) for v in ch.axes[0]))
            lab = ("up", "down")
        else:
            j = op["js"][0] if op["op"] == "spatial3" else op["j"]
            name, kind = "shoulder", "shoulder"
            fwd = x_home - ch.points[j]
            fwd = fwd - np.dot(fwd, ch.axes[j]) * ch.axes[j]
            nf = np.linalg.norm(fwd)
            fwd = fwd / nf if nf > 0 else np.array([1.0, 0.0, 0.0])
            ref = (place_end, tuple(float(v) for v in x_home), tuple(float(v) for v in fwd))
            lab = ("front", "back")
        if name in labels:
            name = f"{name}{count}"
        labels[name] = lab
        roles.append((name, kind, j, ref))
    return roles, labels


def _isolated_minima(f, level: float) -> tuple[float, ...]:
    """The values v in (-pi, pi] at which f(v) >= 0 reaches `level`: f scanned on a 240-point grid (cyclic), each
    local minimum below 3e-2 refined by golden section (the bracket shrinks to ~1e-17), snapped to 0, +-pi/2 or pi
    when within 1e-7 of one where f reaches the level too (the value a description's zero convention gives).
    The functions scanned (a Jacobian's sigma_min / sigma_max, the sine between two axes) fall at most linearly
    with slope ~1 towards a zero: a grid point within half a step (0.013 rad) of it is below 3e-2 (a 720-point grid
    and 1e-2 took 1.2 s of an xArm7's derivation)."""
    grid = np.linspace(-math.pi, math.pi, 240, endpoint=False)
    vals = [f(v) for v in grid]
    found = []
    step = grid[1] - grid[0]
    gold = (math.sqrt(5.0) - 1.0) / 2.0
    for i in range(len(grid)):  # cyclic: -pi is pi
        before, after = vals[i - 1], vals[(i + 1) % len(grid)]
        if not (vals[i] <= before and vals[i] < after and vals[i] < 3e-2):
            continue
        lo, hi = grid[i] - step, grid[i] + step
        a, b = hi - gold * (hi - lo), lo + gold * (hi - lo)
        fa, fb = f(a), f(b)
        for _ in range(80):  # one new value per step: the kept inner point is the next bracket's other one
            if fa < fb:
                hi, b, fb = b, a, fa
                a = hi - gold * (hi - lo)
                fa = f(a)
            else:
                lo, a, fa = a, b, fb
                b = lo + gold * (hi - lo)
                fb = f(b)
        v = math.remainder(0.5 * (lo + hi), 2.0 * math.pi)
        for exact in (0.0, math.pi, -math.pi, 0.5 * math.pi, -0.5 * math.pi):
            if abs(v - exact) <= 1e-7 and f(exact) <= level:
                v = exact
        if f(v) <= level:
            found.append(math.pi if v == -math.pi else float(v))
    return tuple(sorted(set(found)))
