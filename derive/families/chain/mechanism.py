"""The chain family's mechanism: a description -> the planner's decomposition -> derivation records, template
context, CasADi functions and audit numbers."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...checks import jacobian_fd_error, numeric_predicate
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
from ...kinematics.subproblems import subproblem_checks
from ...literals import c_num, floats, own_api_literals, vectors
from ...mechanism import CApi, MechanismDefaults
from ...model import Check, Derivation, Finding, NoDecomposition, NotDerivable, Step
from ...tolerances import TOLERANCES
from . import views
from .description import Description
from .kernels import chain_kernels, kernel_check
from .stages import stage

FREE_SAMPLES = (0.0, 0.7, -1.9, 2.6)  # values of a free joint the decomposition must hold at
# true axes off the ideal ones by more than this (rounding of a description's angles is ~1e-16): a calibrated robot,
# whose candidates the emitted solver compensates when their polish fails (chain_api._compensated)
CALIBRATED_DEVIATION = 1e-13
# the arm angle is read on the ideal S-R-S geometry: an arm whose axes are farther from it than this (metres and sines;
# a description's rounded angles are ~1e-12 off, pybullet's iiwa 5e-13) would see its arm angle off by as much
ARM_ANGLE_DEVIATION = 1e-9
# the held six joints' Jacobian at or below this (sigma_min / sigma_max) at every sampled configuration: a
# self-motion (rank < 6 everywhere; rounding leaves ~1e-16, a regular arm's random configurations ~1e-2)
SELF_MOTION_RATIO = 1e-9


class ChainMechanism(MechanismDefaults):
    """A serial chain from a description (DH, POE, URDF), solved by the planner's decomposition."""

    ROBOT_DESCRIPTION = True
    C_API = CApi(pose12=True, ik_near=True, jacobian=True, fk_matrix=True, frames=True)

    TEMPLATES = ("python/chain.py.jinja", "c/chain.h.jinja", "c/chain.c.jinja")
    VECTORISED_KERNELS = ()
    DERIVE_SECONDS = 3

    def __init__(self, name: str, title: str, desc: Description):
        self.NAME, self.title, self.desc = name, title, desc
        self._plan: Plan | None = None
        self._ideal: Chain | None = None
        self._labelling: general6r.Labelling | None = None
        self._degenerate: tuple[tuple[float, str], ...] | None = None
        self._samples: tuple[float, ...] | None = None  # _held_samples, computed once
        self._held_elbow: bool | None = None  # held_elbow, computed once
        self._everywhere: float | None = None  # _everywhere_ratio, computed once
        self._kernels: list | None = None  # derive's FK / Jacobian kernels, emitted as they were checked
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
        infinity there. The smallest sine of the angle between two of them, scanned on a 720-point grid and each
        local minimum below 1e-2 refined by golden section, kept when it reaches the geometry tolerance."""
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
        """No decomposition fits: a 6R chain (after the free joint is held) is solved by elimination, read the way
        that keeps it regular at every held value sampled; anything else keeps the planner's refusal."""
        if base.n != 6 or any(k != "R" for k in base.kinds):
            raise refused
        chains = [self.solver_chain(self.chain, v) for v in self._held_samples()]
        try:
            labelling = general6r.choose_labelling(chains, np.random.default_rng(11))
        except NoDecomposition as exc:
            raise NoClosedForm(f"{refused}; {exc}") from None
        self._labelling = labelling
        return Plan([general6r.op(labelling)], False, "no closed-form decomposition (no three axes meet or are "
                    "parallel where one is needed): the general 6R by elimination (Raghavan-Roth's 14 equations, "
                    f"Manocha-Canny's eigenproblem), {labelling.text(base.joint_names)}")

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
        """The robot as a DH table for `--stages derived` (kinematics/dh_table.RobotTable) on its ideal axes, with
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
        """The module's constants beyond the verbs: the interpreted module's, and the derived one's (robot_table)."""
        c = self.chain
        roles, labels = _roles(plan, self.solver_chain(c, 0.0, plan.reversed))
        deviation = self.deviation()
        return OwnRobotApi(c.lower, c.upper, labels, tuple(roles), ideal.axes, ideal.points, ideal.home,
                           plan.strategy, self.controls(), c.base, c.tool, self.scale(), self.desc.geometry_tol,
                           deviation, deviation > CALIBRATED_DEVIATION, 1e-12 * self.scale())  # the chain step's

    def scale(self) -> float:
        c = self.chain
        # same_bits: a generated constant (SCALE), the same on every CPU
        return max(1e-3, *(norm(p) for p in c.points), norm(c.home[:3, 3]))

    def deviation(self) -> float:
        _, ideal = self.plan()
        return float(max(np.max(np.abs(ideal.axes - self.chain.axes)),
                         np.max(np.abs(ideal.points - self.chain.points))))

    # ------------------------------------------------------------------------------------------ derivation
    def derive(self) -> Derivation:
        if self.held_elbow:
            raise NoClosedForm(f"holding the elbow {self.chain.joint_names[ELBOW]} leaves a self-motion, which the "
                               "derived stages solve (--stages auto or derived) and the plan interpreter does not")
        c, desc = self.chain, self.desc
        dv = Derivation(self.NAME, self.title, "user description", {})
        scale = self.scale()

        def poe_err(rng):
            q = _random_joints(c, rng)
            return float(np.max(np.abs(c.fk_full(q) - desc.fk(q))))
        dv.add(Step("chain", "Product-of-exponentials form of the description", desc.rule + "; then T(q) = base "
                    "exp(S_1 q_1) ... exp(S_n q_n) M tool with S_i the joint's axis and a point on it at q = 0", (),
                    _chain_table(c), (numeric_predicate(poe_err, "the POE form equals the description's own "
                                                        "product of transforms", samples=100, tol=1e-12 * scale),)))
        try:
            plan, ideal = self.plan()
        except NoClosedForm:
            raise
        names = self.solver_chain(c, 0.0, plan.reversed).joint_names
        rel_checks = tuple(Check("numeric", r.text(names), r.deviation <= desc.geometry_tol, r.deviation,
                                 desc.geometry_tol, 1) for r in plan.relations)
        dv.add(Step("axes", "Axis relations the decomposition relies on", "axes compared pairwise and in threes: "
                    "parallel when sin of the angle <= the geometry tolerance, meeting in one point when every axis "
                    "passes within the tolerance of the least-squares common point", ("chain",),
                    {"relations": "; ".join(r.text(names) for r in plan.relations) or "none needed",
                     "geometry tolerance": f"{desc.geometry_tol:g}",
                     "largest deviation of the true axes from the ideal ones": f"{self.deviation():.2e}"},
                    rel_checks or (Check("numeric", "no relation needed", True, 0.0, desc.geometry_tol, 1),)))
        for key, statement, check in subproblem_checks():
            dv.add(Step(f"proof_{key}", f"Subproblem formula: {key}", "proven for symbolic unit axes and vectors",
                        (), {"statement": statement}, (check,)))
        dv.add(Step("decomposition", "Decomposition found from the axes", plan.strategy, ("axes",),
                    {"ops": " -> ".join(_op_text(op, names) for op in plan.ops), "branches (max IK sets)":
                     str(plan.branches), "controls": self.controls()}, ()))
        rng_free = self.plan_samples()
        chains = {v: self.solver_chain(ideal, v, plan.reversed) for v in rng_free}
        residuals: dict = {}  # every op's check draws the same seeded samples: each replayed once

        if self._labelling is not None:  # the elimination's own records (its op's equations among them)
            for st in general6r.steps(self.solver_chain(ideal, rng_free[0]), self._labelling,
                                      np.random.default_rng(12)):
                dv.add(replace(st, depends_on=st.depends_on or ("decomposition",)))
        for k, op in enumerate(plan.ops if self._labelling is None else ()):
            def err(rng, k=k):
                v = rng_free[int(rng.integers(len(rng_free)))]
                q = _random_joints(chains[v], rng)
                key = (v, *q.tolist())
                if key not in residuals:
                    residuals[key] = replay(chains[v], replace(plan, reversed=False), q)
                return residuals[key][k]
            dv.add(Step(f"op{k + 1}", f"IK op {k + 1}: {op['op']}", _op_rule(op, names), ("decomposition",),
                        {"equation": _op_text(op, names)},
                        (numeric_predicate(err, "the op's equation holds at the true joint values of sampled "
                                                "configurations of the ideal chain", samples=200,
                                           tol=1e-9 * scale),)))

        def jac_err(rng):
            q = _random_joints(c, rng)
            return jacobian_fd_error(c.fk_full, c.jacobian(q), q)
        dv.add(Step("jacobian", "Geometric Jacobian", "column i: (w_i x (p - o_i), w_i) for a revolute joint, "
                    "(w_i, 0) for a prismatic one, with w_i, o_i the joint's axis and point moved by the joints "
                    "before it; linear velocity first", ("chain",), {"columns": f"{c.n}"},
                    (numeric_predicate(jac_err, "columns equal central differences of FK (h = 1e-6)", samples=40,
                                       tol=1e-7 * max(1.0, scale)),)))
        ks = self._kernels = chain_kernels(c)
        dv.add(Step("kernels", "The robot's FK and Jacobian as straight-line kernels",
                    "the product of exponentials and the Jacobian's columns over the joint symbols, each axis and "
                    "point substituted as numbers (exact 0 and +-1 kept exact, so the terms they zero vanish), then "
                    "CSE'd per target", ("chain", "jacobian"),
                    {"kernels": ", ".join(f"{k.name} ({k.n_out} outputs)" for k in ks)},
                    (numeric_predicate(kernel_check(c, ks), "the kernels equal the chain's product of 4 x 4 "
                                       "transforms and its Jacobian (kinematics/poe.py; base and tool left out)",
                                       samples=40, tol=1e-12 * max(1.0, scale)),)))
        checked = ("every op checked on 200 sampled configurations" if self._labelling is None else
                   "the 14 equations checked on 40 sampled configurations, the solutions against a multistart count")
        dv.findings.append(Finding("decomposition", "the description (no IK given)", plan.strategy, "clarified",
                                   f"{len(plan.relations)} axis relation(s) within {desc.geometry_tol:g}; {checked}"))
        return dv

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

    # ------------------------------------------------------------------------------------------ emission
    def kernels(self, dv):
        return self._kernels if self._kernels is not None else chain_kernels(self.chain)

    def extra_context(self, ks) -> dict:
        plan, ideal = self.plan()
        c = self.chain
        solver = self.solver_chain(c, 0.0, plan.reversed)
        api = self._own_api(plan, ideal)
        free = self.desc.free
        deviation = api.deviation
        return {"name": self.NAME, "title": self.title, "joint_names": list(c.joint_names),
                "joint_kinds": list(c.kinds), "n_joints": c.n, "max_ik": plan.branches,
                "design_names": [c.joint_names[free]] if free >= 0 else (["arm_angle"] if self.arm_angle else []),
                "design_values": ["0.0"] if free >= 0 or self.arm_angle else [],
                "arm_angle": self.arm_angle,
                **own_api_literals(api), "strategy": api.strategy, "controls": api.controls,
                "degenerate_held": repr(self.degenerate_held_reasons()),
                "tangent_tol": repr(max(float(TOLERANCES["stage_tangent"]),
                                        8.0 * deviation / min(1.0, api.scale))),
                "axes": vectors(c.axes), "points": vectors(c.points), "home": vectors(c.home),
                "base": vectors(c.base), "tool_frame": vectors(c.tool),
                "free": free, "reversed": plan.reversed, "plan": _plan_literal(plan),
                "plan_ops": plan.ops,
                "has_spatial3": any(op["op"] == "spatial3" for op in plan.ops),
                "has_sp6": any(op["op"] == "sp6" for op in plan.ops),
                "has_poly": any(op["op"] in ("spatial3", "sp6") for op in plan.ops),
                "c_plan_rows": views.c_plan_rows([stage(i, op) for i, op in enumerate(plan.ops)], solver.joint_names),
                "c_runtime_files": views.c_runtime_files(plan.ops),
                "c_flags": views.c_flags(plan.ops, free, plan.reversed, api.calibrated, self.degenerate_held(),
                                         self.desc.geometry_tol),
                **views.stage_tolerances(plan.ops),
                "py_runtime_files": views.py_runtime_files(plan.ops),
                "c_includes": views.c_includes(plan.ops),
                # the same data as plain numbers, for the C template
                "c_data": {"axes": floats(c.axes), "points": floats(c.points), "home": floats(c.home),
                           "ideal_axes": floats(ideal.axes), "ideal_points": floats(ideal.points),
                           "ideal_home": floats(ideal.home), "base": floats(c.base), "tool": floats(c.tool),
                           "lower": [c_num(v) for v in c.lower], "upper": [c_num(v) for v in c.upper]}}

    def c_shared_files(self) -> list[str]:
        """Runtime sources (runtime/c/...) written beside the robot's C: the general 6R's, when it is one."""
        return views.c_shared_files(self.plan()[0].ops)

    def casadi_functions(self, dv, kernels) -> dict:
        from .chain_casadi import chain_functions
        return chain_functions(self.NAME, self.chain)

    CASADI_DESIGN_NAMES = ("none",)

    def audit_numbers(self, dv, solver, audit_dir) -> dict:
        """Seeded round trips through the generated solver, and the ideal geometry's effect (counts and
        bucketed errors only: byte-stable across machines)."""
        from ...report_numbers import error_bucket

        c = self.chain
        rng = np.random.default_rng(2024)
        counts: dict[int, int] = {}
        contains, worst, n = 0, 0.0, 100
        free = self.desc.free
        for _ in range(n):
            q = _random_joints(c, rng)
            design = [q[free]] if free >= 0 else ([solver.arm_angle(q)] if self.arm_angle else None)
            sol = solver.ik(solver.fk_matrix(q), design)
            counts[sol.count] = counts.get(sol.count, 0) + 1
            for v in sol:
                worst = max(worst, float(np.max(np.abs(solver.fk_matrix(v) - solver.fk_matrix(q)))))
            contains += any(_joint_gap(v, q, c.kinds) < 1e-6 for v in sol)
        _, ideal = self.plan()
        gap = 0.0
        for _ in range(100):
            q = _random_joints(c, rng)
            gap = max(gap, float(np.max(np.abs(ideal.fk(q) - c.fk(q)))))
        return {
            "summary": [("joints", ", ".join(f"{nm} ({'revolute' if k == 'R' else 'prismatic'})"
                                             for nm, k in zip(c.joint_names, c.kinds, strict=True))),
                        ("description", c.source_format), ("decomposition", self.plan()[0].strategy),
                        ("controls", self.controls()),
                        ("run-time parameter", f"the free joint {c.joint_names[free]}" if free >= 0 else
                         ("the arm angle psi (derive/kinematics/arm_angle.py)" if self.arm_angle else "none")),
                        ("IK solution sets per pose (max)", str(solver.MAX_IK))],
            "sections": [{"title": "Round trips through the generated solver",
                          "body": f"{n} seeded random joint vectors (revolute in (-pi, pi], prismatic in (-0.5, 0.5) m"
                                  f"{', the free joint drawn too' if free >= 0 else ''}"
                                  f"{'; IK at the arm angle of the drawn joints' if self.arm_angle else ''}): IK "
                                  "solution counts "
                                  f"{dict(sorted(counts.items()))}; the generating joints were among the solutions "
                                  f"{contains} of {n} times; largest pose error of a returned solution "
                                  f"{error_bucket(worst)} (tolerance 1e-9). The comparison with an independent "
                                  f"numeric multistart reference is in tests/"
                                  f"{'test_arm_angle.py' if self.arm_angle else 'test_chain_robots.py'}."},
                         {"title": "Ideal versus true geometry",
                          "body": f"The decomposition runs on the chain with its relations made exact (largest change "
                                  f"of an axis or point {error_bucket(self.deviation())}); at the same joint values "
                                  f"the ideal chain's pose differs from the true one's by at most {error_bucket(gap)} "
                                  "over 100 samples. Every solution is verified on the true chain and, when needed, "
                                  "polished there by Gauss-Newton steps to 1e-9."}],
        }


# ---------------------------------------------------------------------------------------------- helpers
def _random_joints(c: Chain, rng) -> np.ndarray:
    return np.array([rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in c.kinds])


def _joint_gap(a, b, kinds) -> float:
    return max((abs(math.remainder(x - y, 2 * math.pi)) if k == "R" else abs(x - y))
               for x, y, k in zip(a, b, kinds, strict=True))




def _spec_literal(s) -> str:
    return "(" + ", ".join(repr(x) for x in s) + ("," if len(s) == 1 else "") + ")"


def _plan_literal(plan: Plan) -> str:
    rows = []
    for op in plan.ops:
        k = op["op"]
        if k == "begin":
            rows.append(f'("begin", {_spec_literal(op["x"])}, {op["lo"]}, {op["hi"]})')
        elif k in ("first_plane", "last_plane"):
            rows.append(f'("{k}", {op["j"]}, "{op["kind"]}", {_spec_literal(op["n"])})')
        elif k in ("first_dist", "last_dist"):
            rows.append(f'("{k}", {op["j"]}, "{op["kind"]}", {_spec_literal(op["s"])}, {bool(op.get("planar"))})')
        elif k == "pair":
            rows.append(f'("pair", {op["j"]}, {op["k"]}, {_spec_literal(op["s"])})')
        elif k == "single":
            rows.append(f'("single", {op["j"]}, "{op["kind"]}")')
        elif k == "linear":
            rows.append(f'("linear", {_spec_literal(op["js"])})')
        elif k == "spatial3":
            rows.append(f'("spatial3", {op["js"][0]}, {op["js"][1]}, {op["js"][2]})')
        elif k == "sp6":
            rows.append(f'("sp6", {op["j"]}, {op["k"]}, {op["l"]}, {_spec_literal(op["n"])})')
        elif k == "orient":
            units = ("(" + ", ".join(_spec_literal(u) for u in op["units"]) + ("," if len(op["units"]) == 1 else "")
                     + ")")
            rows.append(f'("orient", {units}, {op["lo"]}, {op["hi"]})')
        elif k == "group_rest":
            rows.append(f'("group_rest", {op["j"]}, {_spec_literal(op["group"])})')
        elif k == "general6r":
            rows.append(f'("general6r", {op["shift"]}, {op["reverse"]}, {op["hidden"]})')
        elif k == "arm_angle":
            rows.append(f'("arm_angle", {_spec_literal(op["shoulder"])}, {op["elbow"]}, {_spec_literal(op["s"])})')
    return "(\n    " + ",\n    ".join(rows) + ",\n)"


def _chain_table(c: Chain) -> dict:
    out = {}
    for nm, k, a, p in zip(c.joint_names, c.kinds, c.axes, c.points, strict=True):
        out[nm] = (f"{'revolute' if k == 'R' else 'prismatic'} axis ({', '.join(f'{x:.6g}' for x in a)})"
                   + (f" through ({', '.join(f'{x:.6g}' for x in p)})" if k == "R" else ""))
    out["home M"] = "position (" + ", ".join(f"{x:.6g}" for x in c.home[:3, 3]) + ")"
    return out


def _x_words(spec, names) -> str:
    if spec[0] == "meet":
        return "the point where axes " + ", ".join(names[j] for j in spec[1:]) + " meet"
    if spec[0] == "on":
        return f"a point on axis {names[spec[1]]}"
    return "the end frame's origin"


def _op_text(op, names) -> str:
    k = op["op"]

    def nm(j):
        return names[j]
    if k == "begin":
        return f"place {_x_words(op['x'], names)}: y = G' x"
    if k == "first_plane":
        return f"{nm(op['j'])} from n . e_{nm(op['j'])}^-1 y = n . x (n = {_dir_words(op['n'], names)})"
    if k == "last_plane":
        return f"{nm(op['j'])} from n . e_{nm(op['j'])} x = n . y (n = {_dir_words(op['n'], names)})"
    if k == "first_dist":
        return f"{nm(op['j'])} from |e_{nm(op['j'])}^-1 y - s| = |x - s| (s = {_x_words(op['s'], names)})"
    if k == "last_dist":
        return f"{nm(op['j'])} from |e_{nm(op['j'])} x - s| = |y - s| (s = {_x_words(op['s'], names)})"
    if k == "pair":
        return f"{nm(op['j'])}, {nm(op['k'])} from R_{nm(op['j'])} R_{nm(op['k'])} (x - s) = y - s"
    if k == "single":
        return f"{nm(op['j'])} from e_{nm(op['j'])} x = y"
    if k == "linear":
        return ", ".join(nm(j) for j in op["js"]) + " from the slides: x + sum q_i h_i = y"
    if k == "sp6":
        return (f"{nm(op['j'])}, {nm(op['k'])} from n . e_{nm(op['j'])}^-1 y = n . e_{nm(op['k'])} x and "
                f"n . R_{nm(op['j'])}^T R h = n . R_{nm(op['k'])} h (n = {_dir_words(op['n'], names)}, h = axis "
                f"{nm(op['l'])}, R = the target's rotation), then {nm(op['l'])} from rot(h, -q) R_{nm(op['k'])}^T n = "
                f"(R_{nm(op['j'])}^T R)^T n; where h lines up with n (the wrist singularity) {nm(op['l'])} is the "
                f"family's free angle (from previous, else the first of FAMILY_ANGLES with a verified set)")
    if k == "spatial3":
        return (", ".join(nm(j) for j in op["js"]) + " from e x = y: the distance to the first axis's point and the "
                "component along it, a degree-8 polynomial in tan(q/2) of the middle joint")
    if k == "orient":
        units = " ".join("R(" + "+".join(nm(j) for j in u) + ")" for u in op["units"])
        return f"{units} = R_d"
    if k == "general6r":
        return "all six joints from the loop's 14 equations: the real eigenvalues of a 24 x 24 companion matrix"
    if k == "arm_angle":
        return (f"{nm(op['elbow'])} from |e_{nm(op['elbow'])} x - s| = |y - s| (s = {_x_words(op['s'], names)}); "
                f"{', '.join(nm(j) for j in op['shoulder'])} from the rotation about s taking the home side's "
                "directions (s -> the turned wrist centre, that line -> the elbow point) to the target's (s -> y, "
                "E(psi)): E(psi) = s + d_se (cos a u + sin a (cos psi n1 + sin psi n2)), u = (y - s) / |y - s|, n1 the "
                f"axis of {nm(op['shoulder'][0])} normal to u, n2 = u x n1")
    return f"{nm(op['j'])} = the parallel group's sum minus the others"


def _dir_words(spec, names) -> str:
    return f"axis {names[spec[1]]}" if spec[0] == "dir" else f"{names[spec[1]]} x {names[spec[2]]}"


def _op_rule(op, names) -> str:
    return {"begin": "the point x is fixed by every joint after the placing ones, so their product maps it to "
                     "y = G' x (G' = the target with the solved joints removed)",
            "first_plane": "subproblem 4 (linear for a slide): the joints after it keep the component along n",
            "last_plane": "subproblem 4 (linear for a slide): the joints before it keep the component along n",
            "first_dist": "subproblem 3 (a quadratic for a slide): the joints after it keep the distance to s",
            "last_dist": "subproblem 3 (a quadratic for a slide): the joints before it keep the distance to s",
            "pair": "subproblem 2: two rotations about axes through s",
            "single": "subproblem 1 (the slide's component for a prismatic joint)",
            "linear": "linear least squares over the slides",
            "sp6": "subproblem 6: the parallel group keeps the component along its direction n of a point and "
                   "of a direction, two equations each linear in the cosines and sines of both joints; Cramer's "
                   "rule and cos^2 + sin^2 = 1 give a quartic in tan(q/2), every real root (the wrist singularity, "
                   "a double root, tried directly)",
            "spatial3": "three revolute axes in general position (subproblem 5 in effect): two invariants of the "
                        "first joint, bilinear in the other two; every real root of the resulting polynomial",
            "orient": "subproblem 2 on the last unit's axis, then subproblem 1 about it (fewer units: subproblem 1)",
            "group_rest": "rotations about parallel axes add: the last one is the sum minus the others",
            "general6r": "Raghavan-Roth elimination, Manocha-Canny eigenproblem (derive/kinematics/general6r.py)",
            "arm_angle": "the arm angle psi places the elbow on its circle about the shoulder-wrist line "
                         "(derive/kinematics/arm_angle.py); subproblem 3 for the elbow, the rotation of two "
                         "directions and subproblems 2 and 1 for the shoulder"}[
        op["op"]]


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
    """The values v in (-pi, pi] at which f(v) >= 0 reaches `level`: f scanned on a 720-point grid (cyclic), each
    local minimum below 1e-2 refined by golden section (the bracket shrinks to ~1e-17), snapped to 0, +-pi/2 or pi
    when within 1e-7 of one where f reaches the level too (the value a description's zero convention gives)."""
    grid = np.linspace(-math.pi, math.pi, 720, endpoint=False)
    vals = [f(v) for v in grid]
    found = []
    step = grid[1] - grid[0]
    gold = (math.sqrt(5.0) - 1.0) / 2.0
    for i in range(len(grid)):  # cyclic: -pi is pi
        before, after = vals[i - 1], vals[(i + 1) % len(grid)]
        if not (vals[i] <= before and vals[i] < after and vals[i] < 1e-2):
            continue
        lo, hi = grid[i] - step, grid[i] + step
        for _ in range(80):
            a, b = hi - gold * (hi - lo), lo + gold * (hi - lo)
            if f(a) < f(b):
                hi = b
            else:
                lo = a
        v = math.remainder(0.5 * (lo + hi), 2.0 * math.pi)
        for exact in (0.0, math.pi, -math.pi, 0.5 * math.pi, -0.5 * math.pi):
            if abs(v - exact) <= 1e-7 and f(exact) <= level:
                v = exact
        if f(v) <= level:
            found.append(math.pi if v == -math.pi else float(v))
    return tuple(sorted(set(found)))
