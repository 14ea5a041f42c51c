"""The serial-arm layer the serial families share (the catalogue's DH chains, derive/families/serial, and the
finite-screw chains' serial view, derive/families/screw): the pose symbols, an IK stage and its kernels
(FK, FK from cos/sin, geometric Jacobian, one kernel per stage), the stage tree's view for the templates and
the proof that the wrist mirror keeps the FK check. Not a family: families import it, never each other."""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from ..lower import distinct_nodes
from ..model import Derivation

POSE = sp.Matrix(3, 4, sp.symbols("r00 r01 r02 px r10 r11 r12 py r20 r21 r22 pz", real=True))
POSE_SYMBOLS = tuple(POSE)  # row-major [R | p]
R_POSE = POSE[:, :3]
P_POSE = POSE[:, 3]


@dataclass(frozen=True)
class Stage:
    # trig_linear | rotation2d | value | wrist | quadratic | general6r | spatial3 | sp6 | arm_angle | held_elbow
    kind: str
    joints: tuple[int, ...]
    # trig_linear (A, B, C); rotation2d (u, v, u0, v0); value (q,); wrist (3x3 M as 9 entries); quadratic (a slide
    # from a distance: (q + B)^2 = D, E the scale of D's rounding); general6r (the six axes' directions and points,
    # 18 + 18, then the product of exponentials [R | p] they must reach, 12: every joint by elimination); spatial3
    # (three axes' directions and points, 9 + 9, the point x at the joints' zero and its target y: rot rot rot x = y);
    # sp6 (subproblem 6's n, h_j, p_j, h_k, p_k, d_j, g, h_l: 3 x 5 + 1 + 3 + 3, planned._sp6_stages); arm_angle
    # (the shoulder's axes h_a, h_b, h_c, its centre s, the elbow's axis h_e and point p_e, the wrist centre x at home
    # and its target y, 8 x 3, then the arm angle psi: planned._arm_angle_stage); held_elbow (as arm_angle's without
    # psi, x where the held elbow puts the wrist centre: planned._held_elbow_stage)
    exprs: tuple
    title: str
    rule: str
    signs: tuple[int, ...] = ()  # wrist: (e0, e1, e2, e3, k00@0, k10@0, k00@pi, k10@pi)
    wrist_rotation: sp.Matrix | None = None  # wrist: R(q4) R(q5) R(q6) of the three wrist rows
    wrist_joints: tuple = ()
    # a factored stage's double-root band: "distance" (ROOT_GAP_TOL: a distance's square carries the lengths'
    # rounding) or "wrist" (the DH wrist's family bands, WRIST_FAMILY_TOL and WRIST_EXACT_TOL: the half-gap is a
    # wrist's |sin|, read from unit vectors to eps)
    gap: str = "distance"
    # a rotation2d stage whose family moves what its next stage must reach (a UR's q6 at its wrist singularity):
    # the member is the one that stage reaches (serial_stages._family_by_reach), probed on its kernel
    probe_next: bool = False
    # general6r: the elimination's readings of the loop, (shift, reverse, hidden) each (runtime/python/general6r.py):
    # the one chosen (complete on sampled poses, regular: derive/kinematics/general6r.choose_labelling), then the next
    # in that order, tried in turn when no candidate of the one before verifies (a pose where its equations degenerate)
    labelling: tuple[tuple[int, int, int], ...] = ((0, 0, 0),)
    # arm_angle, held_elbow: the arm angle of joint values (first axis h_1, shoulder centre s, elbow point e, wrist
    # centre w, the elbow axis's direction, 5 x 3, from the joints and the design), the module's arm_angle() reads it
    reader: tuple = ()
    # general6r: (the solved chain at the design's defaults, a kinematics.poe.Chain; its general6r.Labelling) for
    # the derivation's records of the elimination (kinematics/general6r.steps)
    elimination: tuple | None = field(default=None, compare=False, repr=False)

    @property
    def branches(self) -> int:
        """Sets this stage can give per prefix: two roots, one, a spatial 3R's four or the general 6R's at most 16
        (Lee and Liang)."""
        if self.kind == "general6r":
            return 16
        if self.kind == "spatial3":
            return 4  # a 3R's positions: at most four (Pieper)
        if self.kind in ("sp6", "arm_angle"):
            return 4  # a quartic's real roots; the arm angle's two elbows x two shoulders
        if self.kind == "held_elbow":
            return 2  # the shoulder's two sets
        return 2 if self.kind in ("trig_linear", "wrist", "quadratic") else 1

    @property
    def width(self) -> int:
        """Bits of the set index the stage takes (its branches rounded up to a power of two)."""
        return (self.branches - 1).bit_length()

    @property
    def factored(self) -> bool:
        """A distance stage: A, B, C and its root gap's factors Dm, Dp, Em (planned._distance_factors)."""
        return self.kind == "trig_linear" and len(self.exprs) == 6


def stage_output_names(st: Stage) -> list[str]:
    if st.factored:
        return ["A", "B", "C", "Dm", "Dp", "Em"]
    return {"trig_linear": ["A", "B", "C"], "rotation2d": ["u", "v", "u0", "v0"], "value": ["q"],
            "quadratic": ["B", "D", "E"],
            "wrist": [f"m{i}{j}" for i in range(3) for j in range(3)],
            "general6r": [f"{w}{i}{x}" for w in "hr" for i in range(1, 7) for x in "xyz"] +
            [f"g{i}{j}" for i in range(3) for j in range(4)],
            "spatial3": [f"{w}{i}{x}" for w in "hr" for i in "abc" for x in "xyz"] +
            [f"{p}{x}" for p in "xy" for x in "xyz"],
            "sp6": [f"{w}{x}" for w in ("n", "h0", "p0", "h4", "p4") for x in "xyz"] + ["d0"] +
            [f"{w}{x}" for w in ("g", "h5") for x in "xyz"],
            "arm_angle": [f"{w}{x}" for w in ("ha", "hb", "hc", "s", "he", "pe", "x", "y") for x in "xyz"] +
            ["psi"],
            "held_elbow": [f"{w}{x}" for w in ("ha", "hb", "hc", "s", "he", "pe", "x", "y") for x in "xyz"]}[st.kind]


def cs_symbols(spec):
    cs = tuple(sp.Symbol(f"c{i + 1}", real=True) for i in range(len(spec.joints)))
    ss = tuple(sp.Symbol(f"s{i + 1}", real=True) for i in range(len(spec.joints)))
    return cs, ss


def on_cs_all(exprs, spec) -> list:
    """The expressions with cos/sin of revolute joints as c_i, s_i symbols (the IK carries them algebraically, no
    trig): a kernel's outputs at once, since the entries of a matrix product share their subtrees, which one walk over
    the distinct nodes visits once (a calibrated arm's true-chain Jacobian took 9 s entry by entry, in expand_trig and
    xreplace, which walk the whole tree)."""
    cs, ss = cs_symbols(spec)
    es = [sp.sympify(e) for e in exprs]
    shifted = _shifted_trig(es, spec, cs, ss)
    if shifted is None:  # a form the angle-sum map does not cover: expand_trig, entry by entry
        rep = {}
        for i, (q, k) in enumerate(zip(spec.joints, spec.kinds, strict=True)):
            if k == "R":
                rep[sp.cos(q)] = cs[i]
                rep[sp.sin(q)] = ss[i]
        out = [sp.expand_trig(e).xreplace(rep) for e in es]
    else:
        memo: dict = {}
        out = [_replace(e, shifted, memo) for e in es]
    left = {f for f in distinct_nodes(out) if isinstance(f, (sp.cos, sp.sin)) and f.free_symbols & set(spec.joints)}
    if left:
        raise ValueError(f"{spec.name}: joint trig left after substitution: {left}")
    return out


def _replace(e, rule, memo):
    """e.xreplace(rule) over e's distinct nodes (memo: node -> its replacement, shared across expressions)."""
    hit = memo.get(e)
    if hit is not None:
        return hit
    if e in rule:
        out = rule[e]
    elif not e.args:
        out = e
    else:
        args = [_replace(a, rule, memo) for a in e.args]
        out = e.func(*args) if any(x is not y for x, y in zip(args, e.args, strict=True)) else e
    memo[e] = out
    return out


def _shifted_trig(es, spec, cs, ss):
    """{cos(+-q_i + c): its angle-sum expansion in c_i, s_i} for every joint trig of the expressions, each of one
    revolute joint with a unit coefficient (a DH or POE product's); None where some other form is there (expand_trig's
    case)."""
    index = {q: i for i, (q, k) in enumerate(zip(spec.joints, spec.kinds, strict=True)) if k == "R"}
    out = {}
    for f in distinct_nodes(es):
        if not isinstance(f, (sp.cos, sp.sin)) or f in out:
            continue
        arg = f.args[0]
        js = arg.free_symbols & set(index)
        if not js:
            continue
        if len(js) > 1:
            return None
        q = js.pop()
        c, a = arg.as_independent(q, as_Add=True)
        sign = 1 if a == q else -1 if a == -q else 0
        if not sign:
            return None
        ci, si = cs[index[q]], sign * ss[index[q]]  # cos(sign q), sin(sign q)
        cc, sc = sp.cos(c), sp.sin(c)
        out[f] = ci * cc - si * sc if isinstance(f, sp.cos) else si * cc + ci * sc
    return out


def serial_kernels(spec, dv: Derivation):
    from ..lower import Kernel

    q = ("q", spec.joints)
    dp = ("dp", spec.design)
    pose = ("pose", POSE_SYMBOLS)
    cs, ss = cs_symbols(spec)
    T = dv.exports["T"]
    T_raw = dv.exports["frames"][-1]
    J = dv.exports["jacobian"]
    ks = [Kernel("fk", "Pose [R | p] (row-major 3x4) of the end frame.", (q, dp),
                 tuple((str(s), T[i // 4, i % 4]) for i, s in enumerate(POSE_SYMBOLS))),
          Kernel("fk_cs", "The same pose from (cos, sin) of the revolute joints (used to verify IK sets).",
                 (q, ("c", cs), ("s", ss), dp),
                 tuple(zip((str(s) for s in POSE_SYMBOLS), on_cs_all([T_raw[i // 4, i % 4] for i in range(12)], spec),
                                    strict=True))),
          Kernel("jacobian", "Geometric Jacobian (6 x n, row-major; linear velocity rows first).", (q, dp),
                 tuple((f"j{r}{c}", J[r, c]) for r in range(6) for c in range(len(spec.joints))))]
    for k, st in enumerate(spec.stages, start=1):
        ks.append(Kernel(f"stage{k}", f"IK stage {k} ({st.kind}): {st.title}", (pose, q, ("c", cs), ("s", ss), dp),
                         tuple(zip(stage_output_names(st), on_cs_all(st.exprs, spec), strict=True))))
        centre = dv.exports.get("wrist_centre", {}).get(k)
        if centre is not None:  # the wrist centre's Jacobian in the prefix joints (families/serial/wrist_centre.py)
            ks.append(Kernel(f"stage{k}_centre", f"IK stage {k}'s wrist centre Jacobian in the joints solved before "
                             "it (3 x 3, row-major): its family band's amplification", (pose, q, ("c", cs), ("s", ss),
                                                                                         dp),
                             tuple(zip((f"j{r}{c}" for r in range(3) for c in range(3)),
                                       on_cs_all([centre[r, c] for r in range(3) for c in range(3)], spec),
                                       strict=True))))
        if st.reader:  # the arm angle of joint values: what the module's arm_angle() reads (serial_arm_angle.py)
            ks.append(Kernel("arm_angle_parts", "The first axis, the shoulder centre, the elbow point, the wrist "
                             "centre and the elbow axis's direction the joints place (5 x 3).", (q, dp),
                             tuple((f"{w}{x}", e) for (w, x), e in zip(
                                 ((w, x) for w in ("h1", "s", "e", "w", "axis") for x in "xyz"), st.reader,
                                 strict=True))))
    return ks


def stage_view(spec, kernel_names=frozenset()) -> list[dict]:
    """What the templates need to emit the solution tree (`kernel_names`: the kernels emitted, where a wrist stage's
    centre Jacobian is one).

    The first branching stage takes the highest bits of the set index, so consecutive sets share their
    prefix and a stage is recomputed only when its prefix (key = k >> shift) changes. A stage of more than two
    branches (the general 6R's) takes `width` bits: its candidates are computed once per prefix above them
    (k >> (shift + width)) and set k takes candidate (k >> shift) & mask.
    """
    total = sum(st.width for st in spec.stages)
    out, used = [], 0
    for k, st in enumerate(spec.stages, start=1):
        used += st.width
        shift = total - used
        view = {"index": k, "kind": st.kind, "joints": list(st.joints), "branches": st.branches,
                "bit": shift if st.branches == 2 else None, "shift": shift, "width": st.width,
                "labelling": [list(r) for r in st.labelling]}
        # the angle stages before it: their amplification of the input's rounding widens a wrist's family band and
        # a factored distance stage's double-root band (serial_stages._wrist, _trig_linear)
        view["amp_joints"] = [j for prior in spec.stages[:k - 1]
                              if prior.kind in ("trig_linear", "rotation2d", "sp6") for j in prior.joints]
        view["factored"] = st.factored
        nxt = spec.stages[k] if k < len(spec.stages) else None
        view["probe"] = k + 1 if st.probe_next and nxt is not None and nxt.kind == "trig_linear" and any(
            spec.joints[st.joints[0]] in sp.sympify(e).free_symbols for e in nxt.exprs) else None
        view["gap_tol"] = {"distance": "ROOT_GAP_TOL", "wrist": "WRIST_EXACT_TOL"}[st.gap]
        # a wrist's half-gap is one double root below the family's band only; up to gap_tol's the pose's own reading
        view["floor_tol"] = {"distance": "0.0", "wrist": "WRIST_FAMILY_TOL"}[st.gap]
        if st.kind == "wrist":
            view["signs"] = list(st.signs)
            view["centre"] = f"stage{k}_centre" in kernel_names  # its family band reads the centre's kappa
            view["joint_kinds"] = [spec.kinds[j] for j in st.joints]
        else:
            view["joint_kind"] = spec.kinds[st.joints[0]]
        out.append(view)
    return out


# stages that give several candidates at once (one computation per prefix, kept in the call's scratch)
SEVERAL_CANDIDATES = ("general6r", "spatial3", "sp6", "arm_angle", "held_elbow")


def fold_masks(spec) -> list[int]:
    """The set-index masks whose pairs (k ^ k2 within a mask) the runtime merges when the pose cannot tell them apart
    (a double root): a two-root (trig_linear) stage's bit, and the bits of a stage that gives several candidates at
    once (its candidates within MERGE_SPAN of each other are flagged merge candidates: serial_stages._ws_mark_near)."""
    out = []
    for v in stage_view(spec):
        if v["kind"] == "trig_linear":
            out.append(1 << v["bit"])
        elif v["kind"] in SEVERAL_CANDIDATES:
            out.append(((1 << v["width"]) - 1) << v["shift"])
    return out


def flip_parity(e, flipped: set, known: dict):
    """0 when e is unchanged, 1 when it is exactly negated, once the symbols in `flipped` are negated; None when
    neither holds. Exact in IEEE arithmetic term by term: a product with a negated factor, a sum of negated terms and
    an integer power of a negated base are the negated (or the same) rounded values, so parity holds for every
    sub-expression the printed code evaluates (and for a fused multiply-add of them)."""
    if e.is_Symbol:
        return known.get(e, 1 if e in flipped else 0)
    if e.is_Number:
        return 0
    if e.is_Mul or e.is_Pow:
        parts = e.args if e.is_Mul else (e.base,)
        ps = [flip_parity(a, flipped, known) for a in parts]
        if None in ps:
            return None
        if e.is_Pow:
            return (ps[0] * int(e.exp)) % 2 if e.exp.is_Integer else (None if ps[0] else 0)
        return sum(ps) % 2
    if e.is_Add:
        ps = {flip_parity(a, flipped, known) for a in e.args}
        return ps.pop() if len(ps) == 1 and None not in ps else None
    return 0 if all(flip_parity(a, flipped, known) == 0 for a in e.args) else None


def mirror_keeps_fk(spec, fk_cs_kernel) -> bool:
    """Whether the wrist's mirrored set (q4 + pi, -q5, q6 + pi: cos and sin of q4, q6 and sin q5 negated) gives
    bit for bit the FK of its base set in the generated fk_cs kernel: every CSE temporary of the kernel, as printed,
    is unchanged or exactly negated under the flip and every output unchanged. Then the base set's verification is
    the mirror's, and the C solver reuses it."""
    from ..lower import reduced

    wrist = [st for st in spec.stages if st.kind == "wrist"]
    if not wrist:
        return False
    cs, ss = cs_symbols(spec)
    j4, j5, j6 = wrist[0].joints
    flipped = {cs[j4], ss[j4], ss[j5], cs[j6], ss[j6]}
    cse = reduced(fk_cs_kernel)  # the CSE lower() prints (computed once)
    known: dict = {}
    for sym, e in cse.temps:
        p = flip_parity(sp.sympify(e), flipped, known)
        if p is None:
            return False
        known[sym] = p
    return all(flip_parity(e, flipped, known) == 0 for e in cse.reduced)
