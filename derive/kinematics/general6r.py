"""The general 6R arm's inverse kinematics by elimination (Raghavan and Roth 1993; the linear algebra of Manocha
and Canny 1994), derived per robot with SymPy from its DH parameters (dh_frames.py).

With F = base_dh^-1 T end_dh^-1 = A1 ... A6, the last joint's line in frame 0 has direction l = F e_z and point
p = F o (A6 = Rz(theta6) turns about it), so

    A3 A4 A5 (e_z, o) = A2^-1 A1^-1 (l, p)                                     (3 + 3 equations)

and, from these two vectors on each side, p.p, p.l, p x l and (p.p) l - 2 (p.l) p (1 + 1 + 3 + 3 more): 14
equations. On the left each is linear in X = (s4 s5, s4 c5, c4 s5, c4 c5, s4, c4, s5, c5, 1) with coefficients
linear in (c3, s3, 1) and free of the pose; on the right linear in Y = (s1 s2, s1 c2, c1 s2, c1 c2, s1, c1, s2, c2)
plus a constant, with coefficients polynomial in (l, p). Both facts are what the derivation proves for the robot
(after reducing c^2 + s^2 = 1, no other monomial is left):

    (P0 + P1 c3 + P2 s3) X = Q(l, p) Y + r(l, p)                              (14 x 9, 14 x 8, 14)

At run time Y is eliminated by the 6 x 14 left null space N of Q (N Q = 0), leaving N (P(theta3) X - r) = 0: six
equations in theta3, theta4, theta5. The half-angle tangents x3 (of theta3 - phi, phi chosen per pose), x4, x5
turn them into a 12 x 12 matrix polynomial (A x3^2 + B x3 + C) m = 0 over the monomials m = x4^i x5^j (i <= 3,
j <= 2) (the six equations and their x4 multiples); its real eigenvalues give theta3, the null vector of
M(x3) gives theta4 and theta5, Y (least squares on the 14 equations) theta1 and theta2, and the remaining
rotation theta6. runtime/python/general6r.py does that numerically; this module derives P0, P1, P2, Q and r.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import sympy as sp
from sympy import QQ, lex, ring

from .. import runtime_files
from ..model import Check, NoDecomposition, Step
from .dh_frames import DHChain, dh_from_chain
from .poe import Chain

EQUATION_NAMES = ("l_x", "l_y", "l_z", "p_x", "p_y", "p_z", "p.p", "p.l", "(p x l)_x", "(p x l)_y", "(p x l)_z",
                  "((p.p) l - 2 (p.l) p)_x", "((p.p) l - 2 (p.l) p)_y", "((p.p) l - 2 (p.l) p)_z")
POSE_LP = sp.symbols("lx ly lz px py pz", real=True)
EXACT_ZERO = 1e-15  # a DH constant this close to 0, 1 or -1 is the geometry's exact value (meeting, right angle)

# exponents of X = (s4 s5, s4 c5, c4 s5, c4 c5, s4, c4, s5, c5, 1) in (c4, s4, c5, s5) and of
# Y = (s1 s2, s1 c2, c1 s2, c1 c2, s1, c1, s2, c2) in (c1, s1, c2, s2)
_X_EXP = ((0, 1, 0, 1), (0, 1, 1, 0), (1, 0, 0, 1), (1, 0, 1, 0), (0, 1, 0, 0), (1, 0, 0, 0), (0, 0, 0, 1),
          (0, 0, 1, 0), (0, 0, 0, 0))
_Y_EXP = ((0, 1, 0, 1), (0, 1, 1, 0), (1, 0, 0, 1), (1, 0, 1, 0), (0, 1, 0, 0), (1, 0, 0, 0), (0, 0, 0, 1),
          (0, 0, 1, 0))
_NAMES = ([f"s{i}" for i in range(1, 6)] + [f"sa{i}" for i in range(1, 6)] + [f"c{i}" for i in range(1, 6)] +
          [f"ca{i}" for i in range(1, 6)] + [f"d{i}" for i in range(1, 6)] + [f"a{i}" for i in range(1, 6)] +
          ["lx", "ly", "lz", "px", "py", "pz"])


@dataclass(frozen=True)
class Elimination:
    P: np.ndarray  # (3, 14, 9): P0, P1 (times c3), P2 (times s3); free of the pose
    Q: sp.Matrix  # 14 x 8, polynomial in l, p
    r: sp.Matrix  # 14 x 1, polynomial in l, p


@dataclass(frozen=True)
class GeneralEquations:
    """The 14 equations for symbolic DH constants, reduced to normal form modulo c^2 + s^2 = 1 for every joint
    angle and twist (lex order with the sines first: these binomials are a Groebner basis, so the remainder is
    unique and zero exactly when the expression vanishes on the circles)."""

    ring: object
    gens: dict
    left: tuple  # 14 polynomials in c3..s5, DH constants of links 3-5
    right: tuple  # 14 polynomials in c1..s2, DH constants of links 1-2, l, p


@lru_cache(maxsize=1)
def general_equations() -> GeneralEquations:
    R, *g = ring(",".join(_NAMES), QQ, lex)
    G = dict(zip(_NAMES, g, strict=True))
    c = [G[f"c{i}"] for i in range(1, 6)]
    s = [G[f"s{i}"] for i in range(1, 6)]
    ideal = [s[i] ** 2 + c[i] ** 2 - 1 for i in range(5)] + [G[f"sa{i}"] ** 2 + G[f"ca{i}"] ** 2 - 1
                                                            for i in range(1, 6)]

    def link(i):
        ca, sa, d, a = G[f"ca{i + 1}"], G[f"sa{i + 1}"], G[f"d{i + 1}"], G[f"a{i + 1}"]
        z, o = R.zero, R.one
        return [[c[i], -s[i] * ca, s[i] * sa, a * c[i]], [s[i], c[i] * ca, -c[i] * sa, a * s[i]], [z, sa, ca, d],
                [z, z, z, o]]

    def inverse(t):
        rt = [[t[j][i] for j in range(3)] for i in range(3)]
        return [[*rt[i], -(rt[i][0] * t[0][3] + rt[i][1] * t[1][3] + rt[i][2] * t[2][3])] for i in range(3)] + [
            [R.zero, R.zero, R.zero, R.one]]

    def mul(a, b):
        return [[sum((a[i][k] * b[k][j] for k in range(4)), R.zero) for j in range(4)] for i in range(4)]

    def dot(u, v):
        return sum((x * y for x, y in zip(u, v, strict=True)), R.zero)

    def fourteen(p, d):  # of a line with point p and direction d
        pp, pd = dot(p, p), dot(p, d)
        cross = [p[1] * d[2] - p[2] * d[1], p[2] * d[0] - p[0] * d[2], p[0] * d[1] - p[1] * d[0]]
        return [*d, *p, pp, pd, *cross, *(pp * d[i] - 2 * pd * p[i] for i in range(3))]

    left = mul(mul(link(2), link(3)), link(4))
    right = mul(inverse(link(1)), inverse(link(0)))
    lv, pv = [G["lx"], G["ly"], G["lz"]], [G["px"], G["py"], G["pz"]]
    lhs = fourteen([left[i][3] for i in range(3)], [left[i][2] for i in range(3)])
    rhs = fourteen([dot(right[i][:3], pv) + right[i][3] for i in range(3)], [dot(right[i][:3], lv) for i in range(3)])
    return GeneralEquations(R, G, tuple(e.rem(ideal) for e in lhs), tuple(e.rem(ideal) for e in rhs))


def structure_violations() -> list[str]:
    """Monomials outside (c3, s3, 1) x X on the left or Y + 1 on the right, for every 6R: the claim the
    elimination rests on (empty when it holds)."""
    eq = general_equations()
    idx = {n: i for i, n in enumerate(_NAMES)}
    bad = []
    for row, e in enumerate(eq.left):
        for mono in e.monoms():
            t3 = (mono[idx["c3"]], mono[idx["s3"]])
            x = (mono[idx["c4"]], mono[idx["s4"]], mono[idx["c5"]], mono[idx["s5"]])
            if t3 not in ((0, 0), (1, 0), (0, 1)) or x not in _X_EXP:
                bad.append(f"left {EQUATION_NAMES[row]}: c3^{t3[0]} s3^{t3[1]} X-part {x}")
    for row, e in enumerate(eq.right):
        for mono in e.monoms():
            y = (mono[idx["c1"]], mono[idx["s1"]], mono[idx["c2"]], mono[idx["s2"]])
            if y not in _Y_EXP and y != (0, 0, 0, 0):
                bad.append(f"right {EQUATION_NAMES[row]}: Y-part {y}")
    return bad


def _exact(v: float):
    for exact in (0.0, 1.0, -1.0):
        if abs(v - exact) <= EXACT_ZERO:
            return sp.Integer(int(exact))
    return sp.Float(v, 17)


def dh_values(dh: DHChain) -> dict:
    """The robot's DH constants of links 1-5 by name (exact 0 and +-1 where the geometry makes them so)."""
    out = {}
    for i in range(5):
        out[f"ca{i + 1}"] = _exact(float(np.cos(dh.alpha[i])))
        out[f"sa{i + 1}"] = _exact(float(np.sin(dh.alpha[i])))
        out[f"d{i + 1}"] = _exact(float(dh.d[i]))
        out[f"a{i + 1}"] = _exact(float(dh.a[i]))
    return out


def derive_elimination(dh: DHChain) -> Elimination:
    """P0, P1, P2, Q and r for this robot: the general equations with its DH constants substituted."""
    eq = general_equations()
    idx = {n: i for i, n in enumerate(_NAMES)}
    vals = dh_values(dh)
    pose = dict(zip(("lx", "ly", "lz", "px", "py", "pz"), POSE_LP, strict=True))
    P = np.zeros((3, 14, 9))
    for row, e in enumerate(eq.left):
        for mono, coef in e.terms():
            t3 = {(0, 0): 0, (1, 0): 1, (0, 1): 2}[(mono[idx["c3"]], mono[idx["s3"]])]
            col = _X_EXP.index((mono[idx["c4"]], mono[idx["s4"]], mono[idx["c5"]], mono[idx["s5"]]))
            value = sp.Rational(coef)
            for name, k in idx.items():
                if mono[k] and name not in ("c3", "s3", "c4", "s4", "c5", "s5"):
                    value *= vals[name] ** mono[k]
            P[t3, row, col] += float(value)
    Q, r = sp.zeros(14, 8), sp.zeros(14, 1)
    for row, e in enumerate(eq.right):
        for mono, coef in e.terms():
            y = (mono[idx["c1"]], mono[idx["s1"]], mono[idx["c2"]], mono[idx["s2"]])
            term = sp.Rational(coef)
            for name, k in idx.items():
                if mono[k] and name not in ("c1", "s1", "c2", "s2"):
                    term *= (pose[name] if name in pose else vals[name]) ** mono[k]
            if y == (0, 0, 0, 0):
                r[row] += term
            else:
                Q[row, _Y_EXP.index(y)] += term
    return Elimination(P, Q.applyfunc(sp.expand), r.applyfunc(sp.expand))


# ------------------------------------------------------------------------------------------------ per robot
REGULARITY_MIN = 1e-8  # sigma_min / sigma_max of Q or of M(x) below this: the labelling's equations are dependent
HIDDEN_T3_PREFERENCE = 100.0  # a hidden-t3 labelling wins while its regularity is within this factor of the best
OPTIONS = tuple((shift, rev, hidden) for rev in (False, True) for shift in range(6) for hidden in range(3))


def numerics():
    """The run-time numerics (runtime/python/general6r.py), as the generated solvers carry them."""
    return runtime_files.load_python("python/general6r.py")


@dataclass(frozen=True)
class Labelling:
    shift: int  # the loop read from this joint (0-based)
    reverse: bool  # ... backwards
    hidden: int  # the eigenvalue's variable: 0, 1, 2 for the third, fourth, fifth joint of the labelled loop
    regularity: float  # its worst regularity over the sampled poses
    scores: tuple  # (shift, reverse, hidden, regularity) of every option, in OPTIONS order
    # (shift, reverse, hidden) of the regular options in the order chosen: fewest misses on the sampled poses, then
    # within WORK_SLACK of the least work per root, then the regularity rule (choose_labelling); readings() picks the
    # runtime's fallbacks from it
    ranked: tuple = ()
    sampled: int = 0  # the sampled poses the choice was tried on (random and near singular), and how many of them
    near_singular: int = 0  # were moved off a singular configuration
    misses: int = 0  # those whose generating joints this labelling's candidates missed

    def readings(self, n: int) -> tuple:
        """The first n readings the runtime tries in turn: the chosen one; then the first in rank order that hides
        another joint and runs the same eigenproblem (the runtime's second try where the sets' count is odd: as
        cheap as the first); then the first that hides a third joint and runs the other eigenproblem (the deflated
        16 x 16 of a hidden t3, the 24 x 24 companion otherwise); then the rest in rank order. A pose where one
        reading degenerates tends to degenerate every reading alike: the Panda with joint1 held at a family pose
        fails in C on every deflated reading tried, and the companion hiding joint 1 solves it."""
        if not self.ranked:
            return ()
        first = self.ranked[0]
        out = [first]
        for same_path in (True, False):
            hidden = {hidden_joint(o) for o in out}
            fits = [o for o in self.ranked if hidden_joint(o) not in hidden and ((o[2] == 0) == (first[2] == 0)) ==
                    same_path]
            if fits:
                out.append(fits[0])
        out += [o for o in self.ranked if o not in out]
        return tuple(out[:n])

    def text(self, names) -> str:
        order = [names[j] for j in (list(range(6))[::-1] if self.reverse else list(range(6)))]
        k = self.shift % 6
        order = order[k:] + order[:k]
        return (f"the loop read {' -> '.join(order)}{' (reversed)' if self.reverse else ''}: {order[0]}, "
                f"{order[1]} eliminated, {order[2 + self.hidden]} the eigenvalue's variable, {order[5]} last")


def hidden_joint(option) -> int:
    """The joint (0-based) whose angle a reading (shift, reverse, hidden) takes as the eigenvalue's."""
    shift, reverse, hidden = option
    order = list(range(6))[::-1] if reverse else list(range(6))
    return order[(shift + 2 + hidden) % 6]


# The sampled poses a labelling must solve completely: random joints, and joints moved SINGULAR_OFFSET off a singular
# configuration (det J = 0 along one joint). A hidden angle that two solutions share, or nearly (a wrist 1e-5 from
# spherical: its flips share the arm's angles to 1e-5, and q5 = +-delta near its singularity), merges eigenvalues
# into a cluster whose members the eigenproblem resolves only to its k-th root of eps: the candidates then miss
# (a KR 6 calibrated 1e-5 off, read with an arm joint hidden: 9 of 80 such poses). Reading another joint as the
# hidden one keeps them apart, and the sample is what tells which.
RANDOM_SAMPLES = 6
SINGULAR_SAMPLES = 6
# The ranking's few samples can leave readings near a tie of which one misses rare random poses: the near-special
# KR 6 (tests/chain_specs.kr6_near_special) had two readings complete on its 9 + 3 sampled poses, a last-bit change
# of its chain's constants swapped their rank, and the one first then missed 1 of the audit's 40 random poses. So the
# ranked readings are tried in order on this many more random poses, at most VALIDATED of them, and the first that
# misses none is chosen.
VALIDATION_SAMPLES = 40
VALIDATED = 4
SINGULAR_OFFSET = 1e-3  # rad: near enough that a near-singular cluster shows, far enough that the pose fixes the
# joints to ~1e-13 (the 1e-6 below holds with room)
SAMPLE_TOL = 1e-6  # rad: a candidate this close (wrapped, every joint) returns the generating joints
SINGULAR_GRID = 48  # points of the det J scan along a joint
# A reading's work per root (_work): a near-special arm (a KR 6 calibrated 1e-4 off) read with its nearly spherical
# wrist's q5 hidden has spurious real eigenvalues and a cluster sharing q5 = 0 (4-5 of 13 real roots, 600 us per IK
# in C against 110 us read otherwise). Readings within WORK_SLACK of the cheapest complete one count as equal.
SHARED_ROOT_WORK = 10
WORK_SLACK = 1.25


def _near_singular(chain: Chain, joint: int, rng: np.random.Generator):
    """Random joints with `joint` moved SINGULAR_OFFSET off a zero of det J along it (bisected from a sign change
    of the scan), or None where det J keeps its sign along that joint."""
    q = rng.uniform(-np.pi, np.pi, chain.n)

    def det(v):
        qq = q.copy()
        qq[joint] = v
        return float(np.linalg.det(chain.jacobian(qq)))

    grid = np.linspace(-np.pi, np.pi, SINGULAR_GRID + 1)
    vals = [det(v) for v in grid]
    crossings = [k for k in range(SINGULAR_GRID) if vals[k] == 0.0 or vals[k] * vals[k + 1] < 0.0]
    if not crossings:
        return None
    k = crossings[int(rng.integers(len(crossings)))]
    lo, hi, flo = grid[k], grid[k + 1], vals[k]
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        fm = det(mid)
        if (fm < 0.0) == (flo < 0.0) and fm != 0.0:
            lo, flo = mid, fm
        else:
            hi = mid
    q[joint] = 0.5 * (lo + hi) + (SINGULAR_OFFSET if rng.random() < 0.5 else -SINGULAR_OFFSET)
    return q


def _samples(chains, rng: np.random.Generator) -> tuple[list, int]:
    """(frames, home, joints, pose) of the sampled poses over the chains in turn, and how many are near singular."""
    g6 = numerics()
    out, near = [], 0
    for i in range(RANDOM_SAMPLES + SINGULAR_SAMPLES):
        chain = chains[i % len(chains)]
        q = rng.uniform(-np.pi, np.pi, 6) if i < RANDOM_SAMPLES else _near_singular(chain, (i - RANDOM_SAMPLES) % 6,
                                                                                      rng)
        if q is None:
            continue
        near += i >= RANDOM_SAMPLES
        out.append(_sample(g6, chain, q))
    return out, near


def _sample(g6, chain: Chain, q) -> tuple:
    """(frames, home, joints, pose) of one sampled pose, as _misses and _work read it (g6: the runtime's numerics,
    loaded once by the caller)."""
    return g6.g6_z_frames(chain.axes, chain.points), chain.home, q, chain.fk(q)


def _misses(option, samples) -> int:
    """The sampled poses whose generating joints the option's candidates do not return."""
    g6 = numerics()
    shift, rev, hidden = option
    return sum(all(np.max(np.abs(_wrapped(np.array(c) - q))) > SAMPLE_TOL
                   for c in g6.g6_solve(frames, home, pose, shift, rev, hidden))
               for frames, home, q, pose in samples)


def _work(option, samples) -> float:
    """The option's per-root work on the sampled poses, averaged: its real eigenvalues (each back-substituted,
    refined and verified), each shared one (M(x) with a null space of dimension > 1: the shift pencil, in C an SVD
    ~20x an LU) counted SHARED_ROOT_WORK times more. The runtime's own roots (its _g6_real_roots, which g6_candidates
    reads), so the count is the emitted solver's."""
    g6 = numerics()
    shift, rev, hidden = option
    total = 0
    for frames, home, _, pose in samples:
        svs = g6._g6_real_roots(g6.g6_labelled(g6.g6_loop_links(frames, home, pose), shift, rev)[0], hidden)[5]
        total += len(svs) + SHARED_ROOT_WORK * sum(int(np.sum(sv <= g6.G6_NULL_TOL * sv[0]) > 1) for sv in svs)
    return total / max(len(samples), 1)


def regularity_preference(score) -> float:
    """The regularity rule's sort value of a score (shift, reverse, hidden, regularity), larger first: the regularity,
    a hidden t3 (0) counted HIDDEN_T3_PREFERENCE times (it deflates the determinant's (1 + x^2)^4 and runs a 16 x 16
    eigenproblem instead of 24 x 24, ~3x cheaper: preferred while it costs at most two digits of regularity; the
    candidates are refined on the chain, the regularity only has to keep roots apart)."""
    return score[3] * (HIDDEN_T3_PREFERENCE if score[2] == 0 else 1.0)


# the decomposition in words, before the reading the stage runs (the planner says this much; the stage adds its
# reading, which it chooses on the chain it solves)
STRATEGY = ("no closed-form decomposition (no three axes meet or are parallel where one is needed): the general 6R "
            "by elimination (Raghavan-Roth's 14 equations, Manocha-Canny's eigenproblem)")


def _regularity_scores(chains, rng: np.random.Generator, poses: int):
    """(shift, reverse, hidden, worst regularity) of every reading over `poses` random poses of each chain, and the
    regular ones, most preferred first; NoDecomposition when none is regular."""
    for chain in chains:
        if chain.n != 6 or any(k != "R" for k in chain.kinds):
            raise NoDecomposition(f"the general 6R elimination needs 6 revolute joints ({chain.n} joints, kinds "
                                  f"{''.join(chain.kinds)})")
    g6 = numerics()
    cases = []
    for chain in chains:
        frames = g6.g6_z_frames(chain.axes, chain.points)
        cases += [(frames, chain.home, chain.fk(rng.uniform(-np.pi, np.pi, 6))) for _ in range(poses)]
    scores = []
    for shift, rev, hidden in OPTIONS:
        worst = min(g6.g6_regularity(g6.g6_labelled(g6.g6_loop_links(f, h, t), shift, rev)[0], hidden)
                    for f, h, t in cases)
        scores.append((shift, rev, hidden, worst))
    regular = sorted((s for s in scores if s[3] >= REGULARITY_MIN), key=lambda s: -regularity_preference(s))
    if not regular:
        best = max(s[3] for s in scores)
        raise NoDecomposition(f"the general 6R elimination is degenerate for every labelling of the loop (best "
                              f"regularity {best:.1e} < {REGULARITY_MIN:g}): the 14 equations are dependent for "
                              "this geometry")
    return scores, regular


def check_regular(chains, rng: np.random.Generator, poses: int = 4) -> None:
    """NoDecomposition where no reading of the loop is regular at the chains' random poses (the 14 equations
    dependent for this geometry): the planner's check, without choose_labelling's sampled solves."""
    _regularity_scores([chains] if isinstance(chains, Chain) else list(chains), rng, poses)


def choose_labelling(chains, rng: np.random.Generator, poses: int = 4) -> Labelling:
    """The labelling that returns the generating joints at every sampled pose (random and near singular) of every
    chain given (a free joint's held values give several; where none does, the fewest misses), among those the ones
    within WORK_SLACK of the least work per root, and among those the best worst regularity, a hidden t3 preferred
    within HIDDEN_T3_PREFERENCE of it. Every regular option is ranked so (the runtime falls back along the order).
    NoDecomposition when every one is degenerate."""
    chains = [chains] if isinstance(chains, Chain) else list(chains)
    scores, regular = _regularity_scores(chains, rng, poses)
    g6 = numerics()
    samples, near = _samples(chains, rng)
    misses = {sc[:3]: _misses(sc[:3], samples) for sc in regular}
    fewest = min(misses.values())
    work = {o: _work(o, samples) for o, m in misses.items() if m == fewest}  # only where it decides
    cheapest = min(work.values())

    def rank(sc):  # complete first; then cheap (a near-special arm's spurious and shared roots); then regular
        o = sc[:3]
        return misses[o], o not in work or work[o] > WORK_SLACK * cheapest, regular.index(sc)
    order = sorted(regular, key=rank)
    extra = [_sample(g6, chains[i % len(chains)], rng.uniform(-np.pi, np.pi, 6)) for i in range(VALIDATION_SAMPLES)]
    valid = next((sc for sc in order[:VALIDATED] if misses[sc[:3]] == fewest and _misses(sc[:3], extra) == 0),
                 order[0])
    order.remove(valid)
    order.insert(0, valid)
    best = order[0]
    return Labelling(best[0], best[1], best[2], best[3], tuple(scores), tuple(s[:3] for s in order), len(samples),
                     near, misses[best[:3]])

def op(labelling: Labelling) -> dict:
    """The reading as a planner op's fields (one op solving all six joints), as equation_residual reads them."""
    return {"op": "general6r", "shift": labelling.shift, "reverse": labelling.reverse, "hidden": labelling.hidden}


def equation_residual(chain: Chain, op_: dict, q) -> float:
    """The op's equations at the true joints q: max |(P X - r) - Q Y| of the labelled loop (0 up to rounding)."""
    g6 = numerics()
    frames = g6.g6_z_frames(chain.axes, chain.points)
    links, joints, sign = g6.g6_labelled(g6.g6_loop_links(frames, chain.home, chain.fk(q)), op_["shift"],
                                          op_["reverse"])
    t = [sign * q[j] for j in joints]
    P, Q, r = g6.g6_equations(links)
    f = [np.array([1.0, np.cos(v), np.sin(v)]) for v in t]
    lhs = np.einsum("eabc,a,b,c->e", P, f[2], f[3], f[4]) - r
    y = np.array([f[0][2] * f[1][2], f[0][2] * f[1][1], f[0][1] * f[1][2], f[0][1] * f[1][1], f[0][2], f[0][1],
                  f[1][2], f[1][1]])
    return float(np.max(np.abs(lhs - Q @ y)))


def _wrapped(q) -> np.ndarray:
    return np.remainder(np.asarray(q, dtype=float) + np.pi, 2 * np.pi) - np.pi


def _new(q, found, tol=1e-6) -> bool:
    return all(np.max(np.abs(_wrapped(q - s))) > tol for s in found)


def solve(chain: Chain, labelling: Labelling, pose: np.ndarray, tol: float = 1e-9) -> list[np.ndarray]:
    """Every solution the generated solvers return for the pose of chain.fk (the same numerics: candidates refined
    on the chain), verified to `tol`, merged within 1e-6."""
    g6 = numerics()
    frames = g6.g6_z_frames(chain.axes, chain.points)
    out: list[np.ndarray] = []
    for q in g6.g6_solve(frames, chain.home, pose, labelling.shift, labelling.reverse, labelling.hidden):
        q = _wrapped(q)
        if np.max(np.abs(chain.fk(q) - pose)) <= tol and _new(q, out):
            out.append(q)
    return out


def multistart(chain: Chain, pose: np.ndarray, rng: np.random.Generator, starts: int = 60, tol: float = 1e-10):
    """An independent count: Newton steps on the chain's pose error from random starts (no elimination)."""
    g6 = numerics()
    frames = g6.g6_z_frames(chain.axes, chain.points)
    found: list[np.ndarray] = []
    for _ in range(starts):
        q = _wrapped(g6.g6_refine(frames, chain.home, pose, rng.uniform(-np.pi, np.pi, chain.n), steps=40))
        if np.max(np.abs(chain.fk(q) - pose)) <= tol and _new(q, found):
            found.append(q)
    return found


def symbolic_mismatch(chain: Chain, rng: np.random.Generator, poses: int = 3) -> float:
    """The largest difference, relative to max |P|, between the coefficients the solvers interpolate at run time
    (three angles per joint, runtime/python/general6r.py) and the general symbolic equations specialised to the
    robot's DH constants, on the loop read in DH frames at sampled poses: the derivation checking the numerics."""
    g6 = numerics()
    dh = dh_from_chain(chain)
    el = derive_elimination(dh)
    fq, fr = sp.lambdify(POSE_LP, el.Q, "numpy"), sp.lambdify(POSE_LP, el.r, "numpy")
    # X's monomials as (1, c, s) indices of theta4 and theta5, from their exponents (c4, s4, c5, s5)
    x_index = [(1 if c4 else 2 if s4 else 0, 1 if c5 else 2 if s5 else 0) for c4, s4, c5, s5 in _X_EXP]
    worst = 0.0
    for _ in range(poses):
        f = np.linalg.inv(dh.base) @ chain.fk(rng.uniform(-np.pi, np.pi, 6)) @ np.linalg.inv(dh.end)
        P, Q, r = g6.g6_equations([dh.constant_link(i) for i in range(5)] + [np.linalg.inv(f)])
        lp = (*f[:3, 2], *f[:3, 3])
        scale = 1.0 + float(np.max(np.abs(P)))
        worst = max(worst, float(np.max(np.abs(Q - np.array(fq(*lp), float)))) / scale,
                    float(np.max(np.abs(r - np.array(fr(*lp), float).ravel()))) / scale)
        for k3 in range(3):
            for col, (a, b) in enumerate(x_index):
                worst = max(worst, float(np.max(np.abs(P[:, k3, a, b] - el.P[k3, :, col]))) / scale)
    return worst


def steps(chain: Chain, labelling: Labelling, rng: np.random.Generator, poses: int = 16) -> list[Step]:
    """The derivation's records: the structure (proven for every 6R), the robot's equations on its FK, the
    labelling chosen and why, and sampled poses against a multistart count."""
    viol = structure_violations()
    out = [Step("g6_structure", "The 14 equations of the general 6R", "Raghavan-Roth: the line of the last joint "
                "seen from both sides of the loop, its direction l and point p, p.p, p.l, p x l, (p.p) l - 2 (p.l) p; "
                "reduced modulo c^2 + s^2 = 1 of every joint angle and twist (a Groebner basis in lex order)",
                (), {"left": "linear in (1, c, s) of each of theta3, theta4, theta5",
                     "right": "linear in (1, c, s) of each of theta1, theta2"},
                (Check("symbolic", "no other monomial left, for symbolic DH constants (any rigid link is a DH link "
                       "up to turns about the joint axes, which shift angles and keep the span)", not viol),))]

    def eq_err(r):
        q = r.uniform(-np.pi, np.pi, 6)
        return equation_residual(chain, op(labelling), q) / (1.0 + float(np.max(np.abs(chain.points))) ** 3)

    from ..checks import numeric_predicate

    out.append(Step("g6_equations", "The robot's 14 equations", "each side's coefficients from its values at three "
                    "angles per joint (0, 2 pi / 3, 4 pi / 3: exact, the sides lie in the span), at run time",
                    ("g6_structure",), {"labelling": labelling.text(chain.joint_names)},
                    (numeric_predicate(eq_err, "(P X - r) = Q Y at the joints of the chain's own FK, relative to "
                                       "(1 + the chain's size)^3 (the equations are cubic in lengths)", samples=40,
                                       tol=1e-12),),
                    note=f"chosen of {len(OPTIONS)} labellings: the generating joints returned at "
                         f"{labelling.sampled - labelling.misses} of {labelling.sampled} sampled poses "
                         f"({labelling.near_singular} of them {SINGULAR_OFFSET:g} rad off a singular configuration), "
                         f"work per root within {WORK_SLACK:g}x the least, then regularity (sigma_min / sigma_max of Q "
                         f"and of M(0.3), worst of 4 poses) {labelling.regularity:.1e} >= {REGULARITY_MIN:g}; the "
                         f"first of the {VALIDATED} best so ranked that misses none of {VALIDATION_SAMPLES} more "
                         "random poses"))
    mismatch = symbolic_mismatch(chain, rng)
    out.append(Step("g6_symbolic", "The run-time coefficients are the symbolic ones", "the general equations of "
                    "g6_structure with the robot's DH constants substituted (exact 0 and +-1 kept), against the "
                    "interpolated P, Q, r of the same loop read in DH frames", ("g6_structure", "g6_equations"),
                    {"DH frames": "dh_frames.dh_from_chain (common normals of neighbouring axes)"},
                    (Check("numeric", "max |interpolated - symbolic| over P, Q, r at 3 sampled poses, relative to "
                           "1 + max |P|", mismatch <= 1e-12, mismatch, 1e-12, 3),)))
    counts, missed = [], 0
    for _ in range(poses):
        q = rng.uniform(-np.pi, np.pi, 6)
        pose = chain.fk(q)
        sols = solve(chain, labelling, pose)
        ref = multistart(chain, pose, rng)
        missed += sum(1 for x in ref if _new(x, sols, 1e-5))
        counts.append((len(sols), len(ref)))
    out.append(Step("g6_solutions", "Every real solution", "the real eigenvalues of the 24 x 24 companion matrix of "
                    "(A x^2 + B x + C) (det: degree 24, of which 16 at most are the arm's, the rest at x = +-i), each "
                    "refined by Newton steps on the chain and verified", ("g6_equations",),
                    {"solutions per pose (elimination, multistart)": str(counts)},
                    (Check("numeric", f"no pose of {poses} where Newton steps from 60 random starts find a solution "
                           "the elimination lacks", missed == 0, float(missed), 0.0, poses),)))
    return out
