"""Serial chains of R and P joints as finite-screw displacement models (seed 003), one generic module.

A robot is a `ScrewSpec`: each joint's kind, axis direction s_k and point r_k at the initial pose (symbols of the
design, so one derivation covers every robot of the structure, random ones included), plus an IK plan in the
stage language of `dh_serial` (trig_linear / rotation2d / value). The derivation

1. takes over the finite-screw algebra of `identities.screws` (conversions, triangle product, group laws),
2. builds S = S_1 triangle ... triangle S_n symbolically and checks T(S) against the product of exponentials,
3. emits FK as that product in (cos q, sin q): the same displacement, but defined at half turns where S is not,
4. checks the geometric Jacobian, the IK stages and the image condition of a < 6-DOF chain against the FK.

The pose is the displacement of the end frame from the initial pose (the end frame coincides with the base frame
at q = 0), as a 4x4 matrix, the convention of the seed ("measured from a preset initial pose").
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from ...checks import jacobian_fd_error, numeric_predicate, sampler
from ...identities import screws
from ...identities.frames import skew
from ...lower import Kernel
from ...model import Check, Derivation, Finding, Step
from ...serial_core import stages, views
from ...serial_core.stages import POSE_SYMBOLS, Stage

DESIGN_NONZERO_TOL = 1e-9  # a squared norm / determinant of the design at or below this is degenerate
DESIGN_UNIT_TOL = 1e-9  # | |s|^2 - 1 | above this: a direction is not a unit vector


@dataclass(frozen=True)
class DesignCheck:
    """A design condition: `expr` (in the design symbols) must be zero ('zero') or away from zero ('nonzero')."""

    what: str
    expr: sp.Expr
    kind: str
    tol: float


@dataclass
class ScrewSpec:
    name: str
    title: str
    seed: str
    axes: tuple[screws.JointAxis, ...]  # symbolic s, r per joint, at the initial pose
    joints: tuple[sp.Symbol, ...]
    design: tuple[sp.Symbol, ...]
    design_default: tuple[float, ...]
    directions: tuple[tuple[sp.Symbol, ...], ...]  # design triples that are unit vectors (sampled on the sphere)
    stages: list[Stage]
    design_checks: tuple[DesignCheck, ...]
    image_checks: tuple[tuple[str, sp.Expr], ...]  # residuals in (pose, design) that vanish exactly on the image
    findings: list[Finding] = field(default_factory=list)
    extra_steps: Callable | None = None  # (dv, spec) -> None: robot-specific derivations (the seed's routes)
    notes: str = ""
    structure: str = ""  # the seed's name of the joint structure (e.g. P1P2P3RaRb): what the plan was built for

    @property
    def kinds(self) -> tuple[str, ...]:
        return tuple(a.kind for a in self.axes)


# ------------------------------------------------------------------------------------------ sampling
def sample_design(spec: ScrewSpec, rng: np.random.Generator, margin: float = 1e-2) -> dict:
    """Random robot of the structure: unit directions on the sphere, points in [-1, 1]^3, away from degeneracy."""
    dirs = {s for d in spec.directions for s in d}
    checks = _nonzero_checks(spec)
    while True:
        vals: dict = {}
        for d in spec.directions:
            v = screws.random_unit(rng)
            vals.update(zip(d, v, strict=True))
        for s in spec.design:
            if s not in dirs:
                vals[s] = rng.uniform(-1.0, 1.0)
        args = [vals[s] for s in spec.design]
        if all(abs(v) > margin for v in checks(*args)):
            return {s: vals[s] for s in spec.design}  # in design order: callers splat .values()


@functools.lru_cache(maxsize=8)
def _nonzero_checks_cached(name: str, design: tuple, exprs: tuple):
    return sp.lambdify(design, list(exprs), "math")


def _nonzero_checks(spec: ScrewSpec):
    return _nonzero_checks_cached(spec.name, spec.design,
                                  tuple(c.expr for c in spec.design_checks if c.kind == "nonzero"))


def sample_joints(spec: ScrewSpec, rng: np.random.Generator, angle: float = math.pi) -> dict:
    return {q: rng.uniform(-angle, angle) if k == "R" else rng.uniform(-1.0, 1.0)
            for q, k in zip(spec.joints, spec.kinds, strict=True)}


def numeric_axes(spec: ScrewSpec, dsn: dict) -> list[screws.JointAxis]:
    def ev(v):
        return tuple(float(dsn[x]) if isinstance(x, sp.Symbol) else float(x) for x in v)
    return [screws.JointAxis(a.kind, ev(a.s), ev(a.r)) for a in spec.axes]


# ------------------------------------------------------------------------------------------ symbolic chain
def twist_exp(axis: screws.JointAxis, q) -> sp.Matrix:
    """exp([xi] q) for a unit direction s: Rodrigues R = I + sin q [s] + (1 - cos q) [s]^2, p = (I - R) r."""
    s, r = sp.Matrix(axis.s), sp.Matrix(axis.r)
    T = sp.eye(4)
    if axis.kind == "P":
        T[:3, 3] = q * s
        return T
    K = skew(s)
    R = sp.eye(3) + sp.sin(q) * K + (1 - sp.cos(q)) * K * K
    T[:3, :3] = R
    T[:3, 3] = (sp.eye(3) - R) * r
    return T


def poe_frames(spec: ScrewSpec) -> list[sp.Matrix]:
    """Partial products exp(xi_1 q_1) ... exp(xi_k q_k), k = 1..n (not simplified: CSE handles the sharing)."""
    out, T = [], sp.eye(4)
    for a, q in zip(spec.axes, spec.joints, strict=True):
        T = T * twist_exp(a, q)
        out.append(T)
    return out


def geometric_jacobian(spec: ScrewSpec, frames: list[sp.Matrix]) -> sp.Matrix:
    """Column k from joint k's current axis (s', r') = (R_{<k} s_k, T_{<k} r_k): (s' x (p - r'), s') for R,
    (s', 0) for P."""
    p = frames[-1][:3, 3]
    cols = []
    for k, a in enumerate(spec.axes):
        prev = sp.eye(4) if k == 0 else frames[k - 1]
        s = prev[:3, :3] * sp.Matrix(a.s)
        r = prev[:3, :3] * sp.Matrix(a.r) + prev[:3, 3]
        cols.append(sp.Matrix.vstack(s.cross(p - r), s) if a.kind == "R" else sp.Matrix.vstack(s, sp.zeros(3, 1)))
    return sp.Matrix.hstack(*cols)


@functools.lru_cache(maxsize=1)
def _algebra() -> Derivation:
    return screws.derive_screw_algebra()


def _take_algebra(dv: Derivation) -> None:
    """The shared finite-screw algebra (proofs of the conversions and of the triangle product) opens every report."""
    alg = _algebra()
    for st in alg.steps:
        dv.add(dataclasses.replace(st, name=f"screw_{st.name}", depends_on=tuple(f"screw_{d}" for d in st.depends_on)))
    dv.findings.extend(alg.findings)
    dv.decisions.extend(alg.decisions)


# ------------------------------------------------------------------------------------------ derivation
def derive_spec(spec: ScrewSpec) -> Derivation:
    syms = {s.name: s for s in (*spec.joints, *spec.design)}
    dv = Derivation(spec.name, spec.title, spec.seed, syms)
    _take_algebra(dv)
    args = (*spec.joints, *spec.design)
    n = len(spec.joints)

    # joint screws and their transforms
    Sj = [screws.joint_screw(a, q) for a, q in zip(spec.axes, spec.joints, strict=True)]
    f_sj = sampler(args, Sj)

    def joint_err(rng):
        dsn, q = sample_design(spec, rng), sample_joints(spec, rng, 3.0)
        axes = numeric_axes(spec, dsn)
        S = f_sj(*q.values(), *dsn.values())
        return max(float(np.max(np.abs(screws.np_screw_to_transform(np.asarray(s, float).ravel())
                                       - screws.np_twist_exp(a.kind, a.s, a.r, qv))))
                   for s, a, qv in zip(S, axes, q.values(), strict=True))
    dv.add(Step("joint_screws", "Finite screw of each joint from its initial axis",
                "R joint: S_k = 2 tan(q_k/2) (s_k; r_k x s_k); P joint: S_k = q_k (0; s_k) (seed eq. 5)",
                ("screw_finite_screw",), {f"S{k + 1}": S for k, S in enumerate(Sj)},
                (numeric_predicate(joint_err, "T(S_k) = exp([xi_k] q_k) (Rodrigues), random robots of the "
                                   "structure, |q| <= 3", samples=60, tol=1e-12),)))

    # the displacement model S = S_1 triangle ... triangle S_n
    S = screws.triangle_all(Sj)
    f_s = sampler(args, S)
    rot_idx = [k for k, a in enumerate(spec.axes) if a.kind == "R"]
    g_rot = screws.triangle_all([Sj[k] for k in rot_idx])[:3, 0] if rot_idx else sp.zeros(3, 1)
    f_g = sampler(args, g_rot)

    def chain_err(rng):
        dsn = sample_design(spec, rng)
        while True:
            q = sample_joints(spec, rng, 2.5)
            poe = screws.np_poe(numeric_axes(spec, dsn), list(q.values()))
            if 1 + np.trace(poe[:3, :3]) > 1e-2:  # the finite screw exists only off the half turns
                break
        Sv = np.asarray(f_s(*q.values(), *dsn.values()), float).ravel()
        return float(np.max(np.abs(screws.np_screw_to_transform(Sv) - poe)))

    def orient_err(rng):
        dsn, q = sample_design(spec, rng), sample_joints(spec, rng, 1.0)
        Sv = np.asarray(f_s(*q.values(), *dsn.values()), float).ravel()
        g = np.asarray(f_g(*q.values(), *dsn.values()), float).ravel()
        return float(np.max(np.abs(Sv[:3] - g)) / max(1.0, np.abs(g).max()))
    dv.add(Step("displacement_model", "Displacement model S = S_1 triangle S_2 triangle ... triangle S_n",
                "screw triangle product of the joint screws, joint n acting first (seed eq. 4); symbolic in the "
                "joints and in every axis direction and position. T(S) = product of exponentials follows by "
                "induction from T(S_a triangle S_b) = T(S_a) T(S_b) (symbolic, screw_triangle_product) and "
                "T(S_k) = exp([xi_k] q_k) (symbolic, screw_cayley_rotation and screw_translation_map); the "
                "numeric check confirms it on this structure", ("joint_screws", "screw_triangle_product",
                                                                    "screw_chain_displacement"),
                {"S": f"({int(sp.count_ops(S[0]))} operations in its first entry; evaluated, not printed)",
                 "orientation mapping": "g(S) = triangle product of the revolute joints' screws only"},
                (numeric_predicate(chain_err, "T(S_1 triangle ... triangle S_n) = product of exponentials, random "
                                   "robots and joints (composite rotation kept 1e-2 in 1 + tr R off a half turn)",
                                   samples=60, tol=1e-10),
                 numeric_predicate(orient_err, "the rotational part g of S equals the triangle product of the "
                                   "revolute joints' screws alone: prismatic joints do not enter the orientation "
                                   "mapping (seed eqs. 9-10)", samples=60, tol=1e-12)),
                source="seed 003, eqs. (4), (6)-(11)",
                note="S does not exist where the total rotation is a half turn; the emitted FK is the transform of "
                     "S in (cos q, sin q), which is the same map and also defined there."))

    # FK: the product of exponentials (= T(S) where S exists)
    frames = poe_frames(spec)
    T = frames[-1]
    f_t = sampler(args, T)

    def fk_err(rng):
        dsn = sample_design(spec, rng)
        q = sample_joints(spec, rng, 2.5)
        t = np.asarray(f_t(*q.values(), *dsn.values()), float)
        ref = screws.np_poe(numeric_axes(spec, dsn), list(q.values()))
        return float(np.max(np.abs(t - ref)) + np.max(np.abs(t[:3, :3].T @ t[:3, :3] - np.eye(3))))

    def half_turn_err(rng):
        dsn, q = sample_design(spec, rng), sample_joints(spec, rng)
        k = int(rng.integers(n))
        worst = 0.0
        for side in (math.pi, -math.pi):
            qa, qb = dict(q), dict(q)
            if spec.kinds[k] == "R":
                qa[spec.joints[k]], qb[spec.joints[k]] = side, side - math.copysign(1e-7, side)
            ta = np.asarray(f_t(*qa.values(), *dsn.values()), float)
            tb = np.asarray(f_t(*qb.values(), *dsn.values()), float)
            if not np.all(np.isfinite(ta)):
                return math.inf
            worst = max(worst, float(np.max(np.abs(ta - tb))))
        return worst
    dv.add(Step("fk", "Forward kinematics T(q) = T(S(q))",
                "screw_to_transform of the displacement model, written as the product of exponentials "
                "exp([xi_1] q_1) ... exp([xi_n] q_n) in (cos q_k, sin q_k)", ("displacement_model",), {"T": T},
                (numeric_predicate(fk_err, "emitted T equals the numeric product of 4x4 exponentials and is a proper "
                                   "rigid transform", samples=60, tol=1e-12),
                 numeric_predicate(half_turn_err, "at q_k = +/-pi (no finite screw) T is finite and continuous: "
                                   "max |T(+/-pi) - T(+/-(pi - 1e-7))|", samples=40, tol=1e-6)),
                note="Half turns: FK is emitted in this form so that it never divides by cos(q/2); the finite screw "
                     "of a pose is never needed by the generated FK or IK."))

    J = geometric_jacobian(spec, frames)
    f_j = sampler(args, J)

    def jac_err(rng):
        dsn, q = sample_design(spec, rng), np.array(list(sample_joints(spec, rng).values()))
        d = list(dsn.values())
        return jacobian_fd_error(lambda x: f_t(*x, *d), np.asarray(f_j(*q, *d), float), q)
    dv.add(Step("jacobian", "Geometric Jacobian (end point velocity, angular velocity)",
                "column k from joint k's current twist axis: (s' x (p - r'), s') for R, (s', 0) for P, with "
                "(s', r') = (R_{<k} s_k, T_{<k} r_k); the twist is the first-order term of the joint's finite screw",
                ("fk", "screw_first_order"), {"J": f"6 x {n}, emitted as a kernel"},
                (numeric_predicate(jac_err, "columns equal central differences of FK (h = 1e-6)", samples=30,
                                   tol=1e-7),)))

    _design_step(dv, spec)
    _image_step(dv, spec, f_t)
    _ik_steps(dv, spec, f_t)
    if spec.extra_steps is not None:
        spec.extra_steps(dv, spec)
    dv.findings.extend(spec.findings)
    dv.exports.update({"T": T, "frames": [T], "jacobian": J, "S": S})
    return dv


def _design_step(dv: Derivation, spec: ScrewSpec) -> None:
    f = sp.lambdify(spec.design, [c.expr for c in spec.design_checks], "math")
    default_ok = all((abs(v) <= c.tol) if c.kind == "zero" else (abs(v) > c.tol)
                     for v, c in zip(f(*spec.design_default), spec.design_checks, strict=True))
    dv.add(Step("design_conditions", "Admissible designs",
                "unit directions; the IK plan divides by the quantities listed as nonzero (a zero one is a design "
                "with a redundant or missing freedom, rejected as InvalidDesign)", (),
                {c.what: c.expr for c in spec.design_checks},
                (Check("numeric", "the default design satisfies every condition", default_ok, 0.0, 0.0, 1),)))


def _image_step(dv: Derivation, spec: ScrewSpec, f_t) -> None:
    if not spec.image_checks:
        return
    exprs = [e for _, e in spec.image_checks]
    f = sp.lambdify((*POSE_SYMBOLS, *spec.design), exprs, "numpy")

    def on_image(rng):
        dsn, q = sample_design(spec, rng), sample_joints(spec, rng)
        t = np.asarray(f_t(*q.values(), *dsn.values()), float)
        return max(abs(float(v)) for v in f(*t[:3].ravel(), *dsn.values()))

    def off_image(rng):  # a random rotation is off the image: the residual must see it
        dsn = sample_design(spec, rng)
        R = screws.np_screw_to_transform(screws.random_screw(rng))[:3, :3]
        t = np.eye(4)
        t[:3, :3] = R
        return 1.0 if max(abs(float(v)) for v in f(*t[:3].ravel(), *dsn.values())) < 1e-6 else 0.0
    dv.add(Step("image", f"Image of the {len(spec.joints)}-DOF chain in SE(3)",
                "a pose is reachable only if these residuals vanish (checked before the IK stages; "
                "tolerance IK_VERIFY_TOL)", ("fk",), {w: e for w, e in spec.image_checks},
                (numeric_predicate(on_image, "residuals vanish on FK poses", samples=100, tol=1e-12),
                 numeric_predicate(off_image, "residuals exceed 1e-6 at random rotations (1 = a miss)", samples=50,
                                   tol=0.0))))


def _ik_steps(dv: Derivation, spec: ScrewSpec, f_t) -> None:
    """Each stage's expressions evaluated at the pose the FK `f_t(joints, design)` gives (the pose as numbers,
    not the FK substituted symbolically: the same check at a fraction of the compile time)."""
    args = (*POSE_SYMBOLS, *spec.joints, *spec.design)
    solved: list[int] = []
    for k, st in enumerate(spec.stages, start=1):
        fn = sampler(args, [sp.sympify(e) for e in st.exprs])

        def err(rng, st=st, fn=fn):
            q, dsn = sample_joints(spec, rng), sample_design(spec, rng)
            pose = np.asarray(f_t(*q.values(), *dsn.values()), float)[:3].ravel()
            vals = [float(v) for v in fn(*pose, *q.values(), *dsn.values())]
            qv = q[spec.joints[st.joints[0]]]
            if st.kind == "trig_linear":
                return abs(vals[0] * math.cos(qv) + vals[1] * math.sin(qv) + vals[2])
            if st.kind == "rotation2d":
                u, v, u0, v0 = vals
                return abs(u - (math.cos(qv) * u0 - math.sin(qv) * v0)) + abs(v - (math.sin(qv) * u0
                                                                                   + math.cos(qv) * v0))
            if spec.kinds[st.joints[0]] == "R":
                return abs(math.remainder(vals[0] - qv, 2 * math.pi))
            return abs(vals[0] - qv)
        claim = {"trig_linear": "A cos q + B sin q + C = 0 on the FK", "rotation2d": "(u, v) = Rot(q)(u0, v0) on "
                 "the FK", "value": "q = expression on the FK"}[st.kind]
        result = dict(zip(stages.stage_output_names(st), st.exprs, strict=True))
        dv.add(Step(f"ik_stage{k}", f"IK stage {k}: {st.title}", st.rule,
                    ("fk",) + tuple(f"ik_stage{j}" for j in range(1, k)), result,
                    (numeric_predicate(err, claim + " (random robots and joints)", samples=200, tol=1e-9),)))
        solved.extend(st.joints)
    if sorted(solved) != list(range(len(spec.joints))):
        raise ValueError(f"{spec.name}: the IK plan must solve every joint exactly once")


# ------------------------------------------------------------------------------------------ kernels
def kernels_spec(spec: ScrewSpec, dv: Derivation) -> list[Kernel]:
    ks = stages.serial_kernels(spec, dv)  # fk, fk_cs, jacobian, stage<k>: the serial templates' kernel set
    dp = ("dp", spec.design)
    ks.append(Kernel("design_check", "Design conditions (see DESIGN_CHECKS).", (dp,),
                     tuple((f"d{i}", c.expr) for i, c in enumerate(spec.design_checks))))
    if spec.image_checks:
        ks.append(Kernel("image_check", "Residuals that vanish exactly on the chain's image.",
                         (("pose", POSE_SYMBOLS), dp), tuple((f"e{i}", e) for i, (_, e) in
                                                             enumerate(spec.image_checks))))
    return ks


def context_spec(spec: ScrewSpec) -> dict:
    return views.serial_views({"name": spec.name, "title": spec.title, "joint_names": [str(q) for q in spec.joints],
            "joint_kinds": list(spec.kinds), "design_names": [str(d) for d in spec.design],
            "design_values": [repr(float(v)) for v in spec.design_default], "n_joints": len(spec.joints),
            "max_ik": 2 ** sum(st.width for st in spec.stages), "stages": stages.stage_view(spec),
            "fold_masks": stages.fold_masks(spec),
            "upper": spec.name.upper(), "design_default": [repr(float(v)) for v in spec.design_default],
            "design_checks": [{"kind": c.kind, "tol": repr(c.tol), "what": c.what} for c in spec.design_checks],
            "image_checks": [w for w, _ in spec.image_checks]})
