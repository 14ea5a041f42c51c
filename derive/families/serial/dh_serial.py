"""Serial DH chains: symbolic FK, geometric Jacobian and a closed-form IK solution tree, one generic module.

A robot is a `SerialSpec`: DH rows plus IK stages (from the planner, planned.py): a list of stages, each solving one or
more joints from pose entries and the joints solved before it:

- ``trig_linear``: A cos q + B sin q + C = 0 (two branches, atan2 +/- acos),
- ``rotation2d``: (u, v) = Rot(q) (u0, v0), so q = atan2(v, u) - atan2(v0, u0) (one branch),
- ``value``: q = expression (one branch; prismatic joints, or an angle given directly),
- ``wrist``: a spherical wrist M = R(q4) R(q5) R(q6) with the sign pattern found here (two branches).

Every stage equation is checked against the chain's own FK before it is emitted, and the generated IK
verifies every candidate by FK, so poses a < 6-DOF chain cannot reach give an empty set.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np
import sympy as sp

from ...checks import jacobian_fd_error, numeric_predicate, sampler, symbolic_identity
from ...identities.dh import DHRow, chain, explicit
from ...kinematics import arm_angle
from ...kinematics.general6r import numerics
from ...kinematics.general6r import steps as elimination_steps
from ...kinematics.poe import Chain, rot
from ...model import Check, Derivation, Finding, Step
from ...serial_core.stages import POSE_SYMBOLS, Stage, stage_output_names
from .shoulder_family import shoulder_step
from .wrist_centre import centre_steps


@dataclass
class SerialSpec:
    name: str
    title: str
    seed: str
    rows: list[DHRow]
    joints: tuple[sp.Symbol, ...]
    kinds: tuple[str, ...]
    design: tuple[sp.Symbol, ...]
    design_default: tuple[float, ...]
    stages: list[Stage]
    printed: dict = field(default_factory=dict)  # seed's printed matrices: name -> (our expression, printed)
    findings: list[Finding] = field(default_factory=list)
    notes: str = ""
    convention: str = "standard"  # or "modified" (Craig): A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)
    tool: sp.Matrix | None = None  # constant end transform (e.g. the last Tx(a_n) Rx(alpha_n) of a modified table)
    base: sp.Matrix | None = None  # constant frame 0 in the world (a robot whose first axis is off the world's z)
    # (joint index, design symbol): a joint held at a run-time value (a 7-joint arm's free joint), its stage reading
    # the symbol (the last design entry: the lengths come first)
    held: tuple[int, sp.Symbol] | None = None
    # the design symbol of an S-R-S arm's arm angle, its run-time parameter (the arm_angle stage reads it), or None
    arm_angle: sp.Symbol | None = None


# ------------------------------------------------------------------------------------------- checks
def draw_design(design, defaults, rng, angles=()) -> dict:
    """A design as the derivation's checks draw one: lengths around their defaults (never zero, so no accidental
    degeneracy), the symbols in `angles` (a held joint's value, an arm angle) uniform in [-pi, pi]; one draw each,
    in the design's order."""
    return {s: rng.uniform(-math.pi, math.pi) if s in angles else v * rng.uniform(0.5, 1.5) if v != 0 else
            rng.uniform(0.0, 0.2) for s, v in zip(design, defaults, strict=True)}


def _sample_design(spec: SerialSpec, rng) -> dict:
    return draw_design(spec.design, spec.design_default, rng, (spec.held[1],) if spec.held else ())


def _design_at(spec: SerialSpec, q: dict, dsn: dict) -> dict:
    """The design the stages solve the FK of q at (dsn updated): a held joint at its value; an S-R-S arm's arm angle
    at the joints' own (read on the arm_angle stage's reader: the shoulder and wrist centres, the elbow point and the
    first axis they place, kinematics/arm_angle.angle_of)."""
    if spec.held:
        dsn[spec.held[1]] = q[spec.joints[spec.held[0]]]
    if spec.arm_angle is not None:
        st = next(s for s in spec.stages if s.kind == "arm_angle")
        dsn[spec.arm_angle] = _own_arm_angle(spec, st, q, dsn)
    return dsn


def _own_arm_angle(spec: SerialSpec, st: Stage, q: dict, dsn: dict) -> float:
    """The arm angle of joint values q (design dsn), read on the stage's reader: the shoulder and wrist centres, the
    elbow point and the first axis they place (kinematics/arm_angle.angle_of)."""
    fn = _reader(tuple(spec.joints), tuple(spec.design), tuple(st.reader))
    h1, s, e, w, _axis = np.array([float(v) for v in fn(*q.values(), *dsn.values())]).reshape(5, 3)
    return arm_angle.angle_of(h1, s, e, w)


@functools.lru_cache(maxsize=8)
def _reader(joints: tuple, design: tuple, reader: tuple):
    """An arm_angle stage's reader, lambdified once per (symbols, expressions): the samples of every check read it."""
    return sp.lambdify((*joints, *design), list(reader), "numpy")


def _draw(spec: SerialSpec, rng) -> tuple[dict, dict]:
    """Joints and the design the stages solve their FK at (a held joint's value, an arm angle: _design_at)."""
    q = _sample_joints(spec, rng)
    return q, _design_at(spec, q, _sample_design(spec, rng))


def _sample_joints(spec: SerialSpec, rng) -> dict:
    return {q: (rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-1.0, 1.0))
            for q, k in zip(spec.joints, spec.kinds, strict=True)}


def wrist_signs(m: sp.Matrix, q4, q5, q6) -> tuple[int, int, int, int]:
    """Signs e with m22 = e0 c5, (m02, m12) = e1 s5 (c4, s4), (m20, m21) = s5 (e2 c6, e3 s6)."""
    c4, s4, c5, s5, c6, s6 = sp.cos(q4), sp.sin(q4), sp.cos(q5), sp.sin(q5), sp.cos(q6), sp.sin(q6)
    ratios = (m[2, 2] / c5, m[0, 2] / (c4 * s5), m[1, 2] / (s4 * s5), m[2, 0] / (s5 * c6), m[2, 1] / (s5 * s6))
    vals = [sp.simplify(r) for r in ratios]
    if any(v not in (1, -1) for v in vals) or vals[1] != vals[2]:
        raise ValueError(f"not a spherical wrist of the supported form: ratios {vals}")
    return int(vals[0]), int(vals[1]), int(vals[3]), int(vals[4])


def derive_spec(spec: SerialSpec) -> Derivation:
    syms = {s.name: s for s in (*spec.joints, *spec.design)}
    dv = Derivation(spec.name, spec.title, spec.seed, syms)
    plain = chain(spec.rows, spec.convention, None, spec.base)  # the frames without the tool (the Jacobian's)
    ts = plain if spec.tool is None else [*plain[:-1], plain[-1] * spec.tool]  # identities/dh.chain's own product
    rule = ("standard DH: A = Rz(theta) Tz(d) Tx(a) Rx(alpha)" if spec.convention == "standard" else
            "modified (Craig) DH: A = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta) Tz(d)")
    for i, row in enumerate(spec.rows, start=1):
        A = row.transform(spec.convention)
        dv.add(Step(f"A{i}", f"Link transform A{i}", rule, (), {f"A{i}": A},
                    (symbolic_identity(A, explicit(row, spec.convention), "product form = textbook closed form"),)))
    T = ts[-1]  # the chain's compact form (identities/dh.chain): no simplify (5 s of a UR's derivation)
    fT = sampler((*spec.joints, *spec.design), T)

    def orth_err(rng):
        vals = [*_sample_joints(spec, rng).values(), *_sample_design(spec, rng).values()]
        m = np.array(fT(*vals), dtype=float)
        return float(np.max(np.abs(m[:3, :3].T @ m[:3, :3] - np.eye(3))) + abs(np.linalg.det(m[:3, :3]) - 1))
    dv.add(Step("T", f"Forward kinematics T_{len(spec.rows)}^0", "product of the link transforms",
                tuple(f"A{i}" for i in range(1, len(spec.rows) + 1)), {"T": T},
                (numeric_predicate(orth_err, "rotation block is proper orthonormal", samples=100, tol=1e-12),)))
    for name, (ours, printed) in spec.printed.items():
        ok = symbolic_identity(ours, printed, f"{name} as printed in the seed").passed
        dv.findings.append(Finding(name, "printed matrix", "derived by the chain product",
                                   "reproduced" if ok else "wrong in seed",
                                   "symbolic identity (simplify of the difference is zero)" if ok else
                                   _mismatch(ours, printed)))
    dv.findings.extend(spec.findings)
    _jacobian_step(dv, spec, plain, ts[-1])
    _ik_steps(dv, spec, fT)
    # the wrist centre's candidates: the frames' origins (a spherical wrist's is one of them)
    axes = joint_axes(spec, plain)
    centre_steps(dv, spec, axes, [_base(spec)[:3, 3]] + [f[:3, 3] for f in plain], lambda rng: _draw(spec, rng))
    shoulder_step(dv, spec, fT, axes, lambda rng: _draw(spec, rng))
    dv.exports["T"] = T
    dv.exports["frames"] = ts
    return dv


def _mismatch(ours: sp.Matrix, printed: sp.Matrix) -> str:
    """The entries where the chain product and the printed matrix differ (as evidence in the audit)."""
    bad = [(i, j) for i in range(ours.rows) for j in range(ours.cols) if sp.simplify(ours[i, j] - printed[i, j]) != 0]
    return "; ".join(f"entry [{i}, {j}]: the chain gives {sp.sstr(ours[i, j])}, the seed prints "
                     f"{sp.sstr(printed[i, j])}" for i, j in bad)


def _base(spec: SerialSpec) -> sp.Matrix:
    return sp.eye(4) if spec.base is None else spec.base


def joint_axes(spec: SerialSpec, ts) -> list[tuple[sp.Matrix, sp.Matrix]]:
    """Each joint's axis in the world, (direction z, a point o) over the frames without the tool: joint i turns about
    z of frame i - 1 (standard DH) or of frame i (modified DH)."""
    frames = [ts[i] if spec.convention == "modified" else _base(spec) if i == 0 else ts[i - 1]
              for i in range(len(spec.joints))]
    return [(f[:3, 2], f[:3, 3]) for f in frames]


def _jacobian_step(dv: Derivation, spec: SerialSpec, ts, t_end) -> None:
    """Joint i turns about z of frame i-1 (standard DH) or of frame i (modified DH): joint_axes."""
    p_end = t_end[:3, 3]
    cols = []
    for kind, (z, o) in zip(spec.kinds, joint_axes(spec, ts), strict=True):
        cols.append(sp.Matrix.vstack(z.cross(p_end - o), z) if kind == "R" else sp.Matrix.vstack(z, sp.zeros(3, 1)))
    J = sp.Matrix.hstack(*cols)
    fT = sampler((*spec.joints, *spec.design), t_end)
    fJ = sampler((*spec.joints, *spec.design), J)

    def jac_err(rng):
        q = np.array(list(_sample_joints(spec, rng).values()))
        dsn = list(_sample_design(spec, rng).values())
        return jacobian_fd_error(lambda x: fT(*x, *dsn), np.array(fJ(*q, *dsn), dtype=float), q)
    dv.add(Step("jacobian", "Geometric Jacobian", "column i: (z_{i-1} x (p - o_{i-1}), z_{i-1}) for a revolute "
                "joint, (z_{i-1}, 0) for a prismatic one; linear velocity first", ("T",), {"J": J},
                (numeric_predicate(jac_err, "columns equal central differences of FK (h = 1e-6)", samples=40,
                                   tol=1e-7),)))
    dv.exports["jacobian"] = J


def _ik_steps(dv: Derivation, spec: SerialSpec, fT) -> None:
    """Each stage checked on the FK: its expressions at the pose FK gives (fT, numbers) for random joints and
    design (the pose read as numbers, as the solver reads it: substituting T into them and printing the result took
    3 s of a UR's derivation)."""
    solved: list[int] = []
    for k, st in enumerate(spec.stages, start=1):
        fn = sp.lambdify((*POSE_SYMBOLS, *spec.joints, *spec.design), list(st.exprs), "numpy")
        wrist = sp.lambdify(st.wrist_joints, st.wrist_rotation, "numpy") if st.kind == "wrist" else None

        def at_fk(q, dsn, fn=fn):
            pose = np.array(fT(*q.values(), *dsn.values()), dtype=float)[:3].ravel()
            return [float(v) for v in fn(*pose, *q.values(), *dsn.values())]

        def err(rng, st=st, at_fk=at_fk, wrist=wrist):
            q, dsn = _draw(spec, rng)  # a held joint at its value, the arm angle at the joints': the stages solve that
            vals = at_fk(q, dsn)
            qs = [q[spec.joints[j]] for j in st.joints]
            if st.kind == "trig_linear":
                a, b, c = vals[:3]
                return abs(a * math.cos(qs[0]) + b * math.sin(qs[0]) + c)
            if st.kind == "quadratic":  # (q + B)^2 = D, relative to D's scale E
                b, d, e = vals
                return abs((qs[0] + b) ** 2 - d) / max(e, 1e-300)
            if st.kind == "rotation2d":
                u, v, u0, v0 = vals
                cq, sq = math.cos(qs[0]), math.sin(qs[0])
                return abs(u - (cq * u0 - sq * v0)) + abs(v - (sq * u0 + cq * v0))
            if st.kind == "value":
                val = vals[0]
                if spec.kinds[st.joints[0]] == "R":
                    return abs(math.remainder(val - qs[0], 2 * math.pi))
                return abs(val - qs[0])
            if st.kind == "general6r":  # the product of exponentials of the axes and points is the target
                axes, points, g = _general6r_parts(vals)
                return float(np.max(np.abs(_poe_product(axes, points, qs) - g)))
            if st.kind == "spatial3":  # the three turns carry x onto y
                v = np.array(vals, dtype=float)
                home = np.eye(4)
                home[:3, 3] = v[18:21]
                p = Chain("stage", ("a", "b", "c"), ("R",) * 3, v[:9].reshape(3, 3), v[9:18].reshape(3, 3),
                          home).fk(qs)[:3, 3]
                return float(np.max(np.abs(p - v[21:24])))
            if st.kind == "sp6":  # both invariants of the parallel group hold
                return _sp6_residual(vals, qs)
            if st.kind == "arm_angle":  # the shoulder and elbow carry the wrist centre onto its target
                return _arm_angle_residual(vals, qs)
            if st.kind == "held_elbow":  # the shoulder carries the wrist centre (the held elbow's) onto its target
                return _arm_angle_residual(vals, [*qs, 0.0])
            m = np.array(vals).reshape(3, 3)
            w = np.array(wrist(*qs), dtype=float)
            return float(np.max(np.abs(m - w)))
        claim = {"trig_linear": "A cos q + B sin q + C = 0 on the FK",
                 "rotation2d": "(u, v) = Rot(q)(u0, v0) on the FK", "value": "q = expression on the FK",
                 "wrist": "M = wrist rotation on the FK", "quadratic": "(q + B)^2 = D on the FK",
                 "general6r": "exp(S_1 q_1) ... exp(S_6 q_6) = T M^-1 from the axes and points on the FK",
                 "spatial3": "rot(h_a, q_a) rot(h_b, q_b) rot(h_c, q_c) x = y from the lines on the FK",
                 "sp6": "n . rot(h_j, -q_j) p_j - n . rot(h_k, q_k) p_k = d_j and n . rot(h_j, -q_j) g = "
                        "n . rot(h_k, q_k) h_l on the FK",
                 "arm_angle": "the shoulder's and the elbow's turns carry the wrist centre x onto its target y on "
                              "the FK",
                 "held_elbow": "the shoulder's turns carry the wrist centre x (where the held elbow puts it) onto its "
                               "target y on the FK"}[st.kind]
        checks: list[Check] = [numeric_predicate(err, claim, samples=200, tol=1e-9)]
        if st.kind == "general6r":
            checks.append(_elimination_finds(spec, st, at_fk))
        if st.kind in ("arm_angle", "held_elbow"):
            checks.append(_arm_angle_finds(spec, st, at_fk))
        if st.factored:
            def factors(rng, at_fk=at_fk):
                q, dsn = _draw(spec, rng)
                a, b, c, dm, dp, em = at_fk(q, dsn)
                # relative to (A^2 + B^2): both sides are sums of squares of metre-sized terms
                return abs(dm * dp / 4 - (a * a + b * b - c * c)) / max(a * a + b * b, 1e-300) + (em < abs(dm)) * 1.0
            checks.append(numeric_predicate(factors, "Dm Dp / 4 = A^2 + B^2 - C^2 and Em >= |Dm| on the FK",
                                            samples=200, tol=1e-9))
        result = dict(zip(stage_output_names(st), st.exprs, strict=True))
        if st.kind == "wrist":
            result["signs (e0, e1, e2, e3, k00@0, k10@0, k00@pi, k10@pi)"] = sp.Matrix(st.signs)
        dv.add(Step(f"ik_stage{k}", f"IK stage {k}: {st.title}", st.rule, ("T",) + tuple(
            f"ik_stage{j}" for j in range(1, k)), result, tuple(checks)))
        if st.elimination is not None:  # the elimination's own records: its structure, equations, solutions
            for rec in elimination_steps(*st.elimination, np.random.default_rng(12)):
                dv.add(replace(rec, depends_on=rec.depends_on or (f"ik_stage{k}",)))
        solved.extend(st.joints)
    if sorted(solved) != list(range(len(spec.joints))):
        raise ValueError(f"{spec.name}: the IK plan must solve every joint exactly once")


def _general6r_parts(vals):
    """(axes 6 x 3, points 6 x 3, target 3 x 4) of a general6r stage's outputs."""
    v = np.array(vals, dtype=float)
    return v[:18].reshape(6, 3), v[18:36].reshape(6, 3), v[36:48].reshape(3, 4)


def _poe_product(axes, points, qs) -> np.ndarray:
    """exp(S_1 q_1) ... exp(S_6 q_6) (top 3 x 4) of revolute axes (direction h, point r): the numeric product of
    exponentials of kinematics/poe.py (its own Rodrigues), home the identity."""
    return Chain("stage", tuple(f"j{i}" for i in range(6)), ("R",) * 6, axes, points, np.eye(4)).fk(qs)[:3]


def _sp6_residual(vals, qs) -> float:
    """The larger residual of subproblem 6's two equations at the stage's joints (q_j, q_k), its outputs (n, h_j,
    p_j, h_k, p_k, d_j, g, h_l) read on the FK: numpy rotation matrices (kinematics/poe.rot), not the runtime's."""
    v = np.array(vals, dtype=float)
    nv, h0, p0, h4, p4, d0, g, h5 = v[0:3], v[3:6], v[6:9], v[9:12], v[12:15], v[15], v[16:19], v[19:22]
    r0, r4 = rot(h0, -qs[0]), rot(h4, qs[1])
    return max(abs(nv @ r0 @ p0 - nv @ r4 @ p4 - d0), abs(nv @ r0 @ g - nv @ r4 @ h5))


def _arm_angle_residual(vals, qs) -> float:
    """|rot_a rot_b rot_c (about the shoulder centre s) rot_e (about the elbow's line) x - y| of an arm_angle stage's
    outputs (h_a, h_b, h_c, s, h_e, p_e, x, y, psi) at its joints (q_a, q_b, q_c, q_e): numpy rotation matrices."""
    v = np.array(vals, dtype=float)
    ha, hb, hc, s, he, pe, x, y = (v[3 * i:3 * i + 3] for i in range(8))
    turned = rot(he, qs[3]) @ (x - pe) + pe
    return float(np.max(np.abs(s + rot(ha, qs[0]) @ rot(hb, qs[1]) @ rot(hc, qs[2]) @ (turned - s) - y)))


def _arm_angle_finds(spec: SerialSpec, st: Stage, at_fk) -> Check:
    """The runtime's arm-angle core (runtime/python/arm_angle.py, as the generated solvers carry it) on the stage's
    outputs at the FK of random joints, at their own arm angle, returns those joints among its sets (to 1e-9 rad:
    closed forms, random joints far from the stretched elbow and the shoulder's family). A held elbow's stage: the core
    with the elbow held (at 0: x has its turn), the arm angle the joints' own, as previous's is at run time."""
    core = arm_angle.numerics()
    tols = (1.0, 1e-12, *core["AA_BANDS"])  # the bands the emitted stage runs it at, on a unit size
    held = st.kind == "held_elbow"

    def missed(rng):
        q = _sample_joints(spec, rng)
        dsn = _design_at(spec, q, _sample_design(spec, rng))
        v = at_fk(q, dsn)
        parts = [tuple(v[3 * i:3 * i + 3]) for i in range(8)]
        qs = np.array([q[spec.joints[j]] for j in st.joints])
        if held:
            sets = core["_arm_angle_core"](*parts, _own_arm_angle(spec, st, q, dsn), None, tols, held=0.0)
        else:
            sets = core["_arm_angle_core"](*parts, v[24], None, tols)
        return min((float(np.max(np.abs(np.remainder(np.array(c[:len(qs)]) - qs + math.pi, 2 * math.pi) - math.pi)))
                    for c, _ in sets), default=math.inf)
    return numeric_predicate(missed, "the arm-angle core on the stage's outputs, at the joints' own arm angle, returns "
                             "the generating shoulder" + ("" if held else " and elbow") +
                             (" (the elbow held: the pose on its reach)" if held else ""), samples=40, tol=1e-9)


def _elimination_finds(spec: SerialSpec, st: Stage, at_fk) -> Check:
    """The runtime's elimination (runtime/python/general6r.py, as the generated solvers carry it) on the stage's
    outputs at the FK of random joints returns those joints among its candidates (to 1e-6 rad: its Newton refine
    leaves them at rounding unless the pose is near a double root, which random joints are not)."""
    g6 = numerics()

    def missed(rng):
        q = _sample_joints(spec, rng)
        dsn = _sample_design(spec, rng)
        _design_at(spec, q, dsn)
        axes, points, g = _general6r_parts(at_fk(q, dsn))
        qs = np.array([q[spec.joints[j]] for j in st.joints])
        shift, reverse, hidden = st.labelling[0]
        cands = g6.g6_solve(g6.g6_z_frames(axes, points), np.eye(4), np.vstack([g, [0, 0, 0, 1]]), shift,
                            bool(reverse), hidden)
        return min((float(np.max(np.abs(np.remainder(np.array(c) - qs + math.pi, 2 * math.pi) - math.pi)))
                    for c in cands), default=math.inf)
    # floor: the refined candidates' rounding on 40 poses moves with the eigensolver's kernels across a decade
    # boundary (the Panda with joint1 held: < 1e-11 on this CPU's, < 1e-12 on Sandybridge's), so the audit, the same
    # bytes on every CPU, states it below 1e-10
    return numeric_predicate(missed, "the elimination on the stage's outputs returns the generating joints",
                             samples=40, tol=1e-6, floor=1e-10)


def wrist_stage(spec_rows_wrist, joints3, m_expr, title: str, rule: str, joint_idx) -> Stage:
    """Build a wrist stage: M (pose side) must equal the product of the three wrist link rotations."""
    rot = sp.eye(3)
    for row in spec_rows_wrist:
        rot = rot * row.transform()[:3, :3]  # wrist stages are written for standard-DH wrist rows
    rot = sp.simplify(rot)
    signs = wrist_signs(rot, *joints3)
    # At sin q5 = 0 only one combination of q4, q6 is defined: q4 := 0 and q6 from the top-left block.
    q4, q5, q6 = joints3
    degenerate = []
    for q5v in (0, sp.pi):
        m0 = sp.simplify(rot.subs({q4: 0, q5: q5v}))
        k00, k10 = sp.simplify(m0[0, 0] / sp.cos(q6)), sp.simplify(m0[1, 0] / sp.sin(q6))
        if k00 not in (1, -1) or k10 not in (1, -1):
            raise ValueError(f"wrist at q5 = {q5v}: unexpected block {m0}")
        degenerate += [int(k00), int(k10)]
    return Stage("wrist", tuple(joint_idx), tuple(m_expr), title,
                 rule + f"; sign pattern {signs}; at sin q5 = 0: q4 := 0, q6 = atan2(k10 m10, k00 m00) with "
                 f"(k00, k10) = {tuple(degenerate[:2])} at q5 = 0 and {tuple(degenerate[2:])} at q5 = pi",
                 signs + tuple(degenerate), rot, tuple(joints3))
