"""`wristkin derive`: a user's robot, as its family reads it (a RobotTable: its ideal axes as a
standard DH table, kinematics/dh_table.py), derived as this family's straight-line stages and emitted as the
PUMA-560's are. The table's lengths stay design parameters (defaults: the
robot's), its angles are made exact, and a derivation step proves the table is the user's robot.

The robot's family refuses what the table cannot hold (more than six solved joints, the arm angle standing for a
seventh); here the planner's decomposition must fit the stage kinds planned.py emits, else the robot is refused with
the reason. A 7-joint arm's held joint stays a
joint of the table, its value the design (the lengths folded); its stage
reads it, and the others are planned with it held. A slide's row adds q to d (its DH frame on the previous
frame's origin: kinematics/dh_table.py)."""

from __future__ import annotations

import keyword
import math
import re
from dataclasses import replace

import numpy as np
import sympy as sp

from ...checks import jacobian_fd_error, numeric_predicate, sampler
from ...identities.dh import DHRow
from ...kinematics.dh_table import OwnRobotApi, RobotTable
from ...kinematics.poe_symbolic import number, symbolic_chain
from ...literals import c_num, own_api_literals, text_literal
from ...model import NotDerivable, Step
from ...serial_core.stages import POSE_SYMBOLS, cs_symbols, fold_masks, on_cs_all
from .dh_serial import SerialSpec
from .mechanism import SerialMechanism
from .planned import SUPPORTED, PlanError
from .planned import stages as planned_stages

# an angle of the table (twist, offset) within this of a multiple of pi / 36 (5 degrees) is that multiple: the
# decomposition's structure (parallel, perpendicular axes) must be exact for the stages, and exact offsets keep the
# derivation symbolic (floating-point offsets made a UR's take 50 s instead of 12). An angle off the grid stays a
# number: no structure rests on it (the planner's relations are parallel axes, a twist of 0 or pi, and meeting axes,
# which the lengths make; a KR 6 or a UR5e with a twist of 0.3 or 1.2 rad derives in 4-5 s, its sets a
# multistart reference's). A description's rounded angles (8 decimals: 5e-9) move the end frame
# by at most their sum times the robot's size, which the description step's tolerance states and checks.
ANGLE_SNAP = 1e-8
ANGLE_GRID = 36
# the description's axes off the ideal ones by at most this (metres and sines): its numbers' rounding (an 8-decimal
# URDF, the PUMA 560 of ROS-Industrial at 5e-11), derived on the ideal geometry, the end frame's difference stated and
# checked as for the angles; farther off, a calibrated robot (its FK the true chain, every set polished on it)
ROUNDING_DEVIATION = 1e-8
# a length below this (relative to the robot's size) is zero: two axes that meet, a wrist without offset
LENGTH_ZERO = 1e-12
# a calibrated robot's angles within this many geometry tolerances of the grid (and lengths as close to 0) are ideal:
# the planner's own slack (it reads a point on an axis within 10 tolerances), and a 4-decimal description's grid
# angles (1.5708, 0.7854, 3.1416: within 7.3e-6) at the default tolerance
CALIBRATED_SNAP = 10.0
# a DH table's rows carry a few eps of the size each, divided by |sin alpha| of a twist near 0 or pi (below)
DH_ROUNDING = 8 * 2.0**-52
# entries of a constant rotation (the base's, the tool's) within this of 0, +-1/2, +-sqrt(2)/2, +-sqrt(3)/2, +-1 are
# those numbers; others stay floating point
ENTRY_SNAP = 1e-12
_ENTRIES = (sp.Integer(0), sp.Integer(1), sp.Rational(1, 2), sp.sqrt(2) / 2, sp.sqrt(3) / 2)


def _angle(v: float, snap: float = ANGLE_SNAP) -> sp.Expr | None:
    k = round(v * ANGLE_GRID / math.pi)
    return sp.pi * sp.Rational(k, ANGLE_GRID) if abs(v - k * math.pi / ANGLE_GRID) <= snap else None


def _entry(v: float) -> sp.Expr:
    for e in _ENTRIES:
        if abs(abs(v) - float(e)) <= ENTRY_SNAP:
            return e if v >= 0 else -e
    return sp.Float(v)


def _constant(m: np.ndarray) -> sp.Matrix | None:
    """A constant 4x4 as an exact rotation block where its entries are special values; None for the identity."""
    if np.max(np.abs(m - np.eye(4))) <= ENTRY_SNAP:
        return None
    out = sp.eye(4)
    for i in range(3):
        for j in range(3):
            out[i, j] = _entry(float(m[i, j]))
        out[i, 3] = sp.Integer(0) if abs(m[i, 3]) <= ENTRY_SNAP else sp.Float(float(m[i, 3]))
    return out


# names the emitted kernels use for their own (serial_core.stages, lower.py) or the targets reserve: a joint named
# "c", "t3" or "for" would shadow the cosines' array, a CSE temporary or a keyword
_RESERVED = frozenset({"q", "c", "s", "dp", "pose", "out", "math", "np", "t", *map(str, POSE_SYMBOLS),
                       *keyword.kwlist, "auto", "break", "case", "char", "const", "continue", "default", "do", "double",
                       "enum", "extern", "float", "goto", "inline", "int", "long", "register", "restrict", "short",
                       "signed", "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void",
                       "volatile", "main", "NAN", "INFINITY"})
_GENERATED = re.compile(r"[cst]\d+|j\d\d")  # cos / sin of joint i, CSE temporaries, Jacobian entries


def _identifier(name: str, taken: set[str]) -> str:
    s = "".join(c if c.isalnum() else "_" for c in name).strip("_") or "q"
    s = s if s[0].isalpha() else "q_" + s
    while s in taken or s in _RESERVED or _GENERATED.fullmatch(s):
        s += "_"
    taken.add(s)
    return s


def from_table(robot: RobotTable) -> SerialMechanism:
    """The robot as a serial-family mechanism with derived stages, or NotDerivable with the reason. A calibrated
    robot too: the stages solve its ideal table and every set is polished on its true chain (searched along the
    near-null direction near its singularities: bench/near_singular.py)."""
    name, table = robot.name, robot.table
    # a calibrated robot (axes off the ideal ones beyond rounding): the stages solve the ideal table, the emitted FK is
    # the description's true chain, and every candidate is polished on it (the serial runtime's Gauss-Newton)
    calibrated = robot.deviation > ROUNDING_DEVIATION
    # its twists and offsets within CALIBRATED_SNAP geometry tolerances of the grid are the grid's, its lengths as
    # close to 0 are 0 (its ideal geometry: the polish on the true chain takes the difference). Off the grid they stay
    # numbers that every stage expression carries: a shipped xArm7's twists 1.5708 (3.7e-6 from pi / 2, beyond the
    # default tolerance) grew its stages to 1.5e5 operations and its derivation to 78 s
    snap = max(ANGLE_SNAP, CALIBRATED_SNAP * robot.api.geometry_tol) if calibrated else ANGLE_SNAP
    length_zero = max(LENGTH_ZERO * robot.size, snap) if calibrated else LENGTH_ZERO * robot.size
    n = len(robot.joint_names)
    kinds = table.kinds or ("R",) * n
    general = "general6r" in robot.ops  # the planner's: the general 6R by elimination
    taken: set[str] = set()
    joints = [sp.Symbol(_identifier(j, taken), real=True) for j in robot.joint_names]
    design, defaults, rows = [], [], []
    snapped = 0.0  # the angles' changes when made exact, summed
    for k, ((a, alpha, d, theta), q) in enumerate(zip(table.rows, joints, strict=True), start=1):
        angles = [_angle(alpha, snap), _angle(theta, snap)]
        if angles[0] is None:  # a twist off the grid stays a number: no structure rests on it
            angles[0] = sp.Float(alpha)
        if angles[1] is None:  # an offset off the grid (the Z1's 2.886 rad) stays a number: no structure rests on it
            angles[1] = sp.Float(theta)
        snapped += abs(alpha - float(angles[0])) + abs(theta - float(angles[1]))
        lengths = []
        for label, v in (("a", a), ("d", d)):
            if abs(v) <= length_zero:
                lengths.append(sp.Integer(0))
                continue
            # the design: a held joint's value alone; a calibrated robot's FK is its true
            # chain, which no length moves; a general 6R's lengths carry no structure (a shipped xArm6's 1e-6 m
            # offsets, below LENGTH_MIN as a design's lengths)
            if robot.held >= 0 or robot.arm_angle or calibrated or general:
                lengths.append(sp.Float(v))
                continue
            sym = sp.Symbol(_identifier(f"{label}{k}", taken), real=True)
            design.append(sym)
            defaults.append(float(v))
            lengths.append(sym)
        if kinds[k - 1] == "P":  # a slide: q adds to d (its constant part the table's d, a length as any other)
            rows.append(DHRow(lengths[0], angles[0], lengths[1] + q, angles[1], q, "P"))
        else:
            rows.append(DHRow(lengths[0], angles[0], lengths[1], q + angles[1], q, "R"))
    held = None
    if robot.held >= 0:  # the held joint's value: the design (the lengths folded), 0 by default
        held = (robot.held, sp.Symbol(_identifier(f"held_{robot.joint_names[robot.held]}", taken), real=True))
        design.append(held[1])
        defaults.append(0.0)
    psi = None
    if robot.arm_angle:  # the arm angle: the design (the lengths folded), 0 by default
        psi = sp.Symbol(_identifier("arm_angle", taken), real=True)
        design.append(psi)
        defaults.append(0.0)
    base, tool = _constant(robot.base), _constant(table.tool)
    spec = SerialSpec(name, robot.title, robot.source, rows, tuple(joints), tuple(kinds), tuple(design),
                      tuple(defaults), [], notes=f"standard DH table read from the description ({robot.rule})",
                      tool=tool, base=base, held=held, arm_angle=psi)
    try:
        stage_list, planned = planned_stages(rows, tuple(joints), spec.kinds, tuple(design), tuple(defaults),
                                             "standard", [str(q) for q in joints], base, tool, held, general, psi,
                                             "held_elbow" in robot.ops)
    except (PlanError, ValueError) as exc:
        missing = sorted(robot.ops - SUPPORTED - {"general6r"})
        if missing:  # say what the planner's decomposition needs, not the search's refusal
            why = (f"its decomposition, {robot.api.strategy.split(':')[0]}, needs the ops {', '.join(missing)}, which "
                   "the derived stages do not have yet")
            raise NotDerivable.because(name, why) from None
        raise NotDerivable.because(name, f"no decomposition in the derived stage kinds: {exc}",
                                   f"its decomposition, {robot.api.strategy.split(':')[0]}, is none the derived "
                                   "stages express") from None
    # each angle's change turns the links after it, at most the robot's size away (and the frame's axes by as
    # much), and each axis's deviation (direction and point) moves the end frame by at most twice its size: the end
    # frame moves by at most their sum times the size, on top of the products' rounding
    # (a calibrated robot's FK is its true chain: the description's product to rounding)
    # A twist alpha near 0 or pi (axes 1e-5 from parallel) places its row's common normal, and with it d, only to
    # eps / |sin alpha| of the size: the table's own rounding (a KR 6 calibrated 1e-5 off: 5.8e-12 at size 1.1)
    tilts = [abs(math.sin(float(r.alpha))) for r in rows if float(r.alpha) % math.pi != 0.0]
    conditioning = DH_ROUNDING / min(tilts, default=1.0)
    tol = 1e-12 * max(robot.size, 1.0) if calibrated else \
        1e-12 + (snapped + 2 * n * robot.deviation + conditioning) * max(robot.size, 1.0)
    # an elimination's words name the reading its stage runs, chosen on the table (the planner only checked that one
    # is regular); the free-joint note is the api's own field
    strategy = planned if general else robot.api.strategy
    mech = _DerivedRobot(name, lambda: replace(spec, stages=stage_list), robot.description_fk, tol,
                         replace(robot.api, description_tol=tol, strategy=strategy), robot.joint_names,
                         robot.degenerate_held,
                         robot.chain if calibrated else None)
    mech.DERIVE_SECONDS = 0.2 * 2 ** n
    return mech


class _DerivedRobot(SerialMechanism):
    """The serial family's derivation plus the step that proves the DH table is the user's robot (its description's
    own FK, to `description_tol`)."""

    def __init__(self, name: str, build, description_fk, description_tol: float, api: OwnRobotApi,
                 joint_names=(), degenerate_held=(), true_chain=None):
        super().__init__(name, build)
        self.description_fk, self.description_tol, self.api = description_fk, description_tol, api
        self.joint_names, self.degenerate_held = tuple(joint_names), tuple(degenerate_held)
        self.true_chain = true_chain  # a calibrated robot's: its FK, Jacobian and polish (the stages: the ideal)
        self._shoulder_family = None  # the joint of the derivation's shoulder_family step, once derived

    def _held_checks(self) -> list:
        """(what, expression, value) per held value the IK refuses: 2 sin((v_held - v) / 2), |.| = the angle's distance
        to v (0 only there, mod 2 pi), refused within the geometry tolerance."""
        held = self.spec.held
        if not held:
            return []
        name = self.joint_names[held[0]]
        return [(f"{name} (held) not within GEOMETRY_TOL of {v!r}, where {why}", 2 * sp.sin((held[1] - v) / 2), v)
                for v, why in self.degenerate_held]

    def kernels(self, dv):
        from ...lower import Kernel

        ks = super().kernels(dv)
        if self.true_chain is not None:  # the ideal table's FK: the pose its stages solve (serial_ik._compensated)
            spec = self.spec
            cs, ss = cs_symbols(spec)
            t = self._ideal_t
            ks.append(Kernel("fk_ideal", "The ideal table's pose [R | p] (row-major 3x4) from (cos, sin) of the "
                             "joints: the geometry the stages solve.", (("q", spec.joints), ("c", cs), ("s", ss),
                                                                ("dp", spec.design)),
                             tuple(zip((str(s) for s in POSE_SYMBOLS),
                                       on_cs_all([t[i // 4, i % 4] for i in range(12)], spec), strict=True))))
            # the true chain's Jacobian from the (cos, sin) a set carries: the polish's first step on every set
            # (sr_polish_cs) then calls no trigonometry (12 of its calls per set, a tenth of a calibrated IK)
            jac = dv.exports["jacobian"]
            ks.append(Kernel("jacobian_cs", "The geometric Jacobian (6 x n) from (cos, sin) of the joints.",
                             (("q", spec.joints), ("c", cs), ("s", ss), ("dp", spec.design)),
                             tuple(zip((f"j{r}{c}" for r in range(6) for c in range(len(spec.joints))),
                                       on_cs_all([jac[r, c] for r in range(6) for c in range(len(spec.joints))], spec),
                                       strict=True)), python=False))
        checks = self._held_checks()
        if checks:
            ks.append(Kernel("design_check", "Design conditions (see DESIGN_CHECKS): the held values refused.",
                             (("dp", self.spec.design),), tuple((f"d{i}", e) for i, (_, e, _) in enumerate(checks))))
        return ks

    def own_context(self) -> dict:
        """A user robot's limits, named branches and command line (runtime/python/own_api.py), read on its ideal
        chain."""
        api = self.api
        lit = own_api_literals(api)
        n = len(api.lower)
        held = self.spec.held
        # the description's joint names (the kernels' identifiers may differ: "c" or "shoulder-lift" are renamed there)
        extra = {"calibrated": self.true_chain is not None, "joint_names": list(self.joint_names),
                 # what the ideal stages' u may lie past 1 by on the true robot's pose (serial.py.jinja says why)
                 "tangent_calibrated": 16.0 * api.deviation if self.true_chain is not None else 0.0}
        if self.true_chain is not None:
            # every bit of the set index is a pair the merge compares: near a singularity of the ideal geometry two
            # sets (a wrist's mirror, an elbow's or a shoulder's pair) are polished or searched onto one solution of
            # the true chain, apart along its near-null direction by what the pose cannot resolve (and a
            # several-candidate stage's bits, as every robot's)
            bits = sum(st.width for st in self.spec.stages)
            extra["fold_masks"] = [1 << b for b in range(bits)] + [m for m in fold_masks(self.spec) if m & (m - 1)]
            if self.spec.stages and self.spec.stages[-1].kind == "wrist":
                # near theta5 = 0 or pi the calibration breaks the ideal wrist's self-motion into up to four solutions:
                # each family (a mirror pair, sets 2P and 2P + 1) is scanned, after the merge, into its free slots and
                # two more of its own after the stages' sets (serial_ik._scan_families)
                extra.update(family_scan=True, stage_sets=2 ** bits, max_ik=2 ** (bits + 1))
                if self._shoulder_family is not None:
                    # q1 read from the wrist centre's (x, y) (C = 0: the derivation's shoulder_family step, its checks
                    # passed): the centre on axis 1 is a self-motion of the ideal geometry, broken by the calibration
                    # as the wrist's: scanned along q1 too
                    extra["shoulder_family"] = self._shoulder_family
        if held:  # the held joint's value: the design, named as the joint
            extra.update(held=held[0], n_lengths=0, design_names=[self.joint_names[held[0]]])
            checks = self._held_checks()
            if checks:
                extra["design_checks"] = [{"kind": "held", "tol": repr(api.geometry_tol), "what": what}
                                          for what, _, _ in checks]
        if self.spec.arm_angle is not None:  # the arm angle: the design
            extra.update(n_lengths=0, design_names=["arm_angle"])
        return {**extra, **{k: lit[k] for k in ("limits_lower", "limits_upper", "strategy_literal",
                                                "controls_literal", "branch_names", "description_tol")},
                "unreachable_note": text_literal(f"this chain controls {api.controls} only") if n - bool(held) < 6
                else "None",
                "own_api": {**{k: lit[k] for k in ("ideal_axes", "ideal_points", "ideal_home", "roles", "scale",
                                                   "geometry_tol", "geometry_deviation")},
                            "c_lower": [c_num(v) for v in api.lower], "c_upper": [c_num(v) for v in api.upper],
                            "degenerate_held": repr(tuple(self.degenerate_held)),
                            "base0": [repr(float(v)) for v in api.base[:3].ravel()],
                            "tool0": [repr(float(v)) for v in api.tool[:3].ravel()]}}

    def round_trips(self) -> int:
        """A calibrated robot polishes every set on its true chain (~10 ms a pose on numpy): 100, as an
        elimination."""
        return 100 if self.true_chain is not None else super().round_trips()

    def audit_numbers(self, dv, solver, audit_dir) -> dict:
        """The serial family's round trips, after what the report of a user's robot should say first: the
        decomposition its stages follow and how far its description is from the exact geometry they solve."""
        out = super().audit_numbers(dv, solver, audit_dir)
        api = self.api
        out["summary"] = [("decomposition (derived straight-line stages)", api.decomposition),
                          ("what the joints control", api.controls),
                          ("the description's axes off the exact geometry", f"{api.deviation:.2g} (geometry "
                           f"tolerance {api.geometry_tol:g}; the end frame's difference is checked in the last "
                           "step)"),
                          *out["summary"]]
        return out

    def derive(self):
        dv = super().derive()
        spec = self.spec
        self._shoulder_family = dv.exports.get("shoulder_family")  # recorded only where its step was derived
        if self.true_chain is not None:
            self._true_chain_step(dv)
        at = {d: sp.sympify(v) for d, v in zip(spec.design, spec.design_default, strict=True)}
        # xreplace: the lengths are plain symbols (subs walked a calibrated robot's true chain for 1 s)
        table_fk = sampler(spec.joints, dv.exports["T"].xreplace(at))
        n = len(spec.joints)

        def err(rng):
            q = rng.uniform(-math.pi, math.pi, n)
            return float(np.max(np.abs(np.array(table_fk(*q), dtype=float) - self.description_fk(q))))
        if self.true_chain is not None:
            title, rule = ("The emitted FK is the description's robot", "the true chain's product equals the "
                           "description's own product (its URDF transforms, DH matrices or exponentials, base and tool "
                           "included) to 1e-12 times the robot's size")
        else:
            title, rule = ("The DH table is the description's robot", "the table's product at the design defaults "
                           "equals the description's own product (its URDF transforms, DH matrices or exponentials, "
                           "base and tool included); tolerance 1e-12 plus the angles' changes when made exact and "
                           "twice the axes' deviation per joint, summed, times the robot's size")
        dv.add(Step("description", title, rule, ("T",), {},
                    (numeric_predicate(err, "same end frame at random joints", samples=200,
                                       tol=self.description_tol),)))
        return dv

    def _true_chain_step(self, dv) -> None:
        """A calibrated robot: the FK and Jacobian the module emits (and polishes every candidate on) become the
        description's true chain, base and tool folded in; the stages stay those of the ideal table, proven above."""
        chain, spec = self.true_chain, self.spec
        rot, end, cols = symbolic_chain(chain, spec.joints)
        base, tool = (sp.Matrix(4, 4, [number(x) for x in np.asarray(m, dtype=float).ravel()])
                      for m in (chain.base, chain.tool))
        t = sp.eye(4)
        t[:3, :3], t[:3, 3] = rot, end
        full = base * t * tool
        lever = rot * tool[:3, 3]  # the tool point's offset from the chain's end frame origin
        jac = sp.zeros(6, chain.n)
        for k, col in enumerate(cols):
            w, lin = sp.Matrix(col[3:]), sp.Matrix(col[:3])
            jac[:3, k] = base[:3, :3] * (lin + w.cross(lever))
            jac[3:, k] = base[:3, :3] * w
        f_t, f_j = sampler(spec.joints, full), sampler(spec.joints, jac)
        scale = max(self.api.scale, 1.0)

        def fk_err(rng):
            q = rng.uniform(-math.pi, math.pi, chain.n)
            return float(np.max(np.abs(np.array(f_t(*q), dtype=float) - chain.fk_full(q))))

        def jac_err(rng):
            q = rng.uniform(-math.pi, math.pi, chain.n)
            return jacobian_fd_error(lambda x: f_t(*x), np.array(f_j(*q), dtype=float), q)
        dv.add(Step("true_chain", "The FK, Jacobian and polish of a calibrated robot: its true chain",
                    f"the stages solve the ideal table (axes {self.api.deviation:.2g} off the description's); the "
                    "module's FK and Jacobian are the description's product of exponentials exp(S_1 q_1) ... "
                    "exp(S_n q_n) M with base and tool, every candidate verified and polished (Gauss-Newton) on it",
                    ("T",), {"T_true": full},
                    (numeric_predicate(fk_err, "the true chain's POE form equals its 4 x 4 product", samples=100,
                                       tol=1e-12 * scale),
                     numeric_predicate(jac_err, "Jacobian columns equal central differences of the true FK "
                                       "(h = 1e-6)", samples=20, tol=1e-7 * scale))))
        self._ideal_t = dv.exports["frames"][-1]  # the table's (the stages' geometry): the compensated re-solve's
        dv.exports["T"], dv.exports["jacobian"] = full, jac
        dv.exports["frames"] = [*dv.exports["frames"][:-1], full]
