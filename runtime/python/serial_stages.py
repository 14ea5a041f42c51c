"""A serial arm's IK stage solvers: each solves its joints and their (cos, sin) algebraically from the stage
kernel's coefficients, so no stage after the first needs trigonometry, and the FK check (fk_cs) needs none
either. The generated module's _solve_stage<k> call them with the stage's joints and branch bit.

A wristkin runtime source: every serial arm's generated module (the catalogue's DH chains, the finite-screw chains'
serial view) inlines it from the marker line on (derive/runtime_files.py), after its constants, derived kernels
and stage functions; above the marker, what it reads from them and from the other sources (serial_stand_in.py:
the PUMA-560), so that it is linted and tested as it is (tests/test_serial_runtime.py)."""

from __future__ import annotations

import math

import _runtime
from serial_stand_in import (
    _FK_IDEAL,
    DEGENERATE_EPS,
    DOUBLE_ROOT_TOL,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_INVERSE,
    N_JOINTS,
    N_LENGTHS,
    ON_AXIS_TOL,
    ROOT_GAP_TOL,
    SINGULAR_EPS,
    STAGE_NOISE,
    TANGENT_CALIBRATED,
    TANGENT_MAX,
    TANGENT_TOL,
    WRIST_EXACT_TOL,
    WRIST_FAMILY_TOL,
    _k_fk,
    _wrap,
)

# wristkin: inlined from here
_EPS = 2.220446049250313e-16
# internal, never returned: a wrist within rounding of its family whose member the pose's own entries placed (between
# WRIST_FAMILY_TOL and WRIST_EXACT_TOL); `previous` moves only a family's representative, never such a set
FLAG_READ_MEMBER = _runtime.FLAG_READ_MEMBER


def _sign(k, bit):
    """The root a two-root stage takes in set k: +1 when bit `bit` of k is 0 (the +acos root, the first wrist
    branch), else -1."""
    return 1.0 if (k >> bit) & 1 == 0 else -1.0


def _family_member(j, q, c, s, prev):
    """A stage whose equation vanishes (a one-parameter family in joint j): its representative, previous's value
    when `previous` is given (the member nearest it), else 0."""
    v = 0.0 if prev is None else prev[j]
    q[j], c[j], s[j] = (v, 1.0, 0.0) if v == 0.0 else (v, math.cos(v), math.sin(v))


def _ws_take(ws, parent, compute, idx, joints, q, c, s):
    """Candidate idx of the stage that computes several at once (the general 6R's, the spatial 3R's, subproblem 6's,
    the arm angle's or the held elbow's: one per chain), its candidates compute()d once per `parent`, the set
    index's prefix above its bits, and kept in the call's scratch ws: its joints into q, c, s (wrapped: Newton's
    steps and band splits reach past pi). Returns the candidate (values, flags[, amplification]), None when there is
    no such candidate."""
    if ws.get("key") != parent:
        ws["key"], ws["cands"] = parent, _ws_mark_near(compute())
    if idx >= len(ws["cands"]):
        return None
    cand = ws["cands"][idx]
    for j, v in zip(joints, cand[0], strict=True):
        v = _wrap(v)
        q[j], c[j], s[j] = v, math.cos(v), math.sin(v)
    return cand


def _ws_mark_near(cands):
    """FLAG_MERGE_CANDIDATE on each of a stage's candidates within MERGE_SPAN in every joint of another (its joints
    revolute: the general 6R's, a spatial 3R's, subproblem 6's, the arm angle's): near a double root of the stage the
    two may be one solution, which the runtime's merge_indistinct decides on the whole set (the stage's bits are one
    of its masks). A new list of (values, flags, ...) tuples; the C runtime's sr_ws_mark_near."""
    out = list(cands)
    for i in range(len(out)):
        for j in range(i + 1, len(out)):
            if all(abs(_wrap(float(v - u))) <= _runtime.MERGE_SPAN for u, v in zip(out[i][0], out[j][0], strict=True)):
                out[i] = (out[i][0], int(out[i][1]) | _runtime.FLAG_MERGE_CANDIDATE, *out[i][2:])
                out[j] = (out[j][0], int(out[j][1]) | _runtime.FLAG_MERGE_CANDIDATE, *out[j][2:])
    return out


def _design_size(dp):
    """The design's size: its largest length, at least 1 (a stage's coefficients carry rounding of that order)."""
    return max(1.0, max(map(abs, dp[:N_LENGTHS]), default=0.0))


def _trig_linear(out, j, sgn, q, c, s, prev, amp, amp_before=1.0, gap_tol=ROOT_GAP_TOL, size=1.0, floor_tol=0.0):
    """Joint j from A cos q + B sin q + C = 0 (out = (A, B, C), a factored stage's also (Dm, Dp, Em)): q = atan2(B, A)
    + sgn acos(-C / sqrt(A^2 + B^2)), its cos and sin from (A, B, u) without trigonometry; amp[j]: how much its roots
    amplify the input's rounding; amp_before: the angle stages' before it; gap_tol: a factored stage's band
    (_root_gap); size: the design's (_design_size), the scale of (A, B)'s rounding; floor_tol: a wrist's half-gap
    (a UR's q5) is one double root only below this band (WRIST_FAMILY_TOL, the rounding measured at exact
    singularities with a margin); between it and gap_tol's the two roots are the pose's own reading, flagged
    indeterminate (the pose is within rounding of its family). Returns (ok, flags)."""
    a, b, cc = out[0], out[1], out[2]
    r = math.hypot(a, b)
    # (A, B) at the rounding of the design's lengths: a family (a KR 6's wrist centre 1e-12 m off its shoulder axis,
    # DEGENERATE_EPS, came back as the family's member 2 rad off; the pose fixes the joint to eps / r)
    family = r <= ON_AXIS_TOL * size
    if not family:
        u = -cc / r
        # the band grows with the rounding the stages before amplified into u (TANGENT_MAX says why it may), and with a
        # calibrated robot's geometry (TANGENT_CALIBRATED)
        if not abs(u) <= 1.0 + max(TANGENT_TOL, min(TANGENT_MAX, STAGE_NOISE * amp_before), TANGENT_CALIBRATED):
            # a calibrated robot's (A, B) within its geometry's deviation: its ideal table's 3.5e-9 m lateral offset
            # kept the wrist centre from axis 1, where the true robot's was 1.4e-9 m off it (u - 1 = 1.5, test seed
            # 7): the family's representative, which the polish and the near-null search take to the true chain's set
            if not r <= TANGENT_CALIBRATED * size:
                return False, 0
            family = True
    if family:
        # |C| within sqrt(DOUBLE_ROOT_TOL): a double root upstream (resolved to sqrt(eps)) can leave this stage a
        # residue of that size where it is really a family (PUMA with a3 = 0, a2 = d4, the arm folded onto the
        # shoulder); the representative is kept only if the set then passes the FK check
        if abs(cc) > math.sqrt(DOUBLE_ROOT_TOL) or sgn < 0.0:
            return False, 0
        _family_member(j, q, c, s, prev)  # one-parameter family: its representative
        amp[j] = 1.0
        return True, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
    u = max(-1.0, min(1.0, u))
    sg, scale = _root_gap(out, r, u, amp_before)
    band = math.sqrt((floor_tol or gap_tol) * scale) if len(out) > 3 else math.sqrt(ROOT_GAP_TOL)
    f = FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE if sg <= band else 0
    if f and sgn < 0.0:
        return False, 0  # a double root is one solution: reported once, by the + branch
    if f:
        # at its centre phi: within the band sin w is rounding (Dm's noise reads as sqrt(noise), 6e-9 for a PUMA
        # elbow folded onto its shoulder), and a stage after it would take that for geometry
        sg = 0.0
    elif floor_tol and len(out) > 3 and sg * sg <= gap_tol * scale:
        # above the rounding measured at exact singularities, within WRIST_EXACT_TOL: q5 = +-1e-12 on a UR5e read
        # as its double root gave the family's member 2 rad from the generating joints (12 of 400 poses)
        f = FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
    elif sg * sg <= (gap_tol if len(out) > 3 else ROOT_GAP_TOL) * amp_before:
        # within the stages' noise of a double root (sin^2 of the half-gap at most its band times the angle stages'
        # amplification: an exact double root split by that noise): merge_indistinct decides whether the pose tells
        # the pair apart; a pair farther apart is two roots and costs no refit (4 refits a call made the IRB 120's
        # slowest 1 % near its elbow 4x its median)
        f = _runtime.FLAG_MERGE_CANDIDATE
    # the roots phi +- w amplify the input's rounding by 1 / sin w (a double root: 1 / band): a wrist after them reads
    # its rotation with that much more rounding (seed 627229: a PUMA shoulder 0.0022 from its double root left
    # |sin theta5| = 1.3e-13 at an exact wrist singularity, which came back as 8 "regular" sets)
    amp[j] = 1.0 / (band if f & FLAG_DOUBLE_ROOT else sg)
    ca, sa = a / r, b / r  # q = atan2(B, A) + sgn acos(u)
    c[j], s[j] = ca * u - sgn * sa * sg, sa * u + sgn * ca * sg
    q[j] = math.atan2(s[j], c[j])
    return True, f


def _root_gap(out, r, u, amp_before):
    """(sin w, scale): the half-gap w of the roots phi +- w, and the scale of its rounding: sin w is one double root
    below sqrt(tol x scale) (the caller's tol).

    From u alone 1 - u^2 carries a few eps of rounding: scale 1, tol ROOT_GAP_TOL. A factored stage gives the
    factors (Dm, Dp) of 4 R^2 (1 - u^2), each to its own precision, and Em, the scale of Dm's rounding: when Dm is the
    small factor its rounding is Em / (2 R) of what 1 - u^2 carries (times the angle stages' amplification before
    it), and the band narrows by its square root (a SCARA with a1 = a2 folded to 1e-8 keeps both elbows). Its tol: a
    distance stage's ROOT_GAP_TOL; a wrist's half-gap (Dm = 2 |n x w|^2, Em = 4 |n x w|: the band is 2 tol amp_before
    on |n x w|) takes the DH wrist's family bands on |sin theta5| (WRIST_FAMILY_TOL, WRIST_EXACT_TOL)."""
    if len(out) == 3:
        return math.sqrt(1.0 - u * u), 1.0
    dm, dp, em = out[3], out[4], out[5]
    # the product and |Dm| <= |Dp|: a length derived as positive and given negative swaps the factors and their signs
    sg = math.sqrt(max(dm * dp, 0.0)) / (2.0 * r)
    # Dm's rounding is never below eps of the stage's size r: Em = 0 exactly (a UR wrist at q5 = 0, |n x w| = 0) gave
    # a band of 0 and an amplification 1 / 0 (numpy raised, C went on with inf)
    scale = min(1.0, max(em, _EPS * r) * amp_before / (2.0 * r)) if abs(dm) <= abs(dp) else 1.0
    return sg, scale


def _rotation2d(out, j, q, c, s, prev, amp, probe=None, pose=None, dp=None):
    """Joint j as the angle from (u0, v0) to (u, v) (out = (u, v, u0, v0)); a family where either vanishes at the
    rounding of the design's lengths, ON_AXIS_TOL of its size (its member by _family_by_reach when the stage has a
    `probe`, the next stage's kernel, read at pose and dp). Above that the pose fixes the angle to eps over the
    shorter length: a SCARA with equal links folded 1e-12 rad from straight puts its flange 3e-13 m off axis 1, which
    fixes joint 1 to 1e-3 rad (a 1e-12 m band made it a family, its member pi off). amp[j]: the angle carries the
    vectors' rounding (a few eps of the metre-sized terms) over the shorter one's length."""
    u, v, u0, v0 = out
    nu, n0 = math.hypot(u, v), math.hypot(u0, v0)
    tol = ON_AXIS_TOL * (1.0 if dp is None else _design_size(dp))
    if n0 <= tol or nu <= tol:
        if probe is None:
            _family_member(j, q, c, s, prev)
        else:
            _family_by_reach(j, q, c, s, prev, probe, pose, dp)
        amp[j] = 1.0
        return True, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
    # a wrist after it reads its rotation with that much more rounding (seed 507497: a PUMA's wrist centre near the
    # shoulder axis left |sin theta5| = 5e-12 at an exact wrist singularity, returned as two "regular" sets)
    amp[j] = max(1.0, 1.0 / min(nu, n0))
    cu, su, c0, s0 = u / nu, v / nu, u0 / n0, v0 / n0
    c[j], s[j] = cu * c0 + su * s0, su * c0 - cu * s0
    q[j] = math.atan2(s[j], c[j])
    if probe is not None and STAGE_NOISE * amp[j] > TANGENT_MAX and _near_family_by_reach(
            j, q, c, s, probe, pose, dp, tol / min(nu, n0)):
        return True, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
    return True, 0


def _reach_terms(j, q, c, s, probe, pose, dp):
    """(C0, C1, C2): the next stage's C = C0 + C1 cos t + C2 sin t over joint j's value t (a distance squared to a
    point on a circle), from its kernel `probe` at t = 0, pi and pi / 2 (q, c, s[j] left at the last)."""
    out = []
    for t, ct, st in ((0.0, 1.0, 0.0), (math.pi, -1.0, 0.0), (0.5 * math.pi, 0.0, 1.0)):
        q[j], c[j], s[j] = t, ct, st
        out.append(probe(pose, q, c, s, dp)[2])
    c0 = 0.5 * (out[0] + out[1])
    return c0, 0.5 * (out[0] - out[1]), out[2] - c0


def _near_family_by_reach(j, q, c, s, probe, pose, dp, window):
    """Near the family (a UR's q5 within ~1e-9 of its wrist singularity) joint j is read from vectors so short that
    its rounding moves the next stage's target past the band that stage allows (STAGE_NOISE times the amplification
    reaches TANGENT_MAX): q6 to eps / 1e-12 = 2e-4 rad put a nearly straight elbow's u 4e-5 past 1, and the generating
    branch was lost. Where the next stage does not reach at the joint as read, the joint moves to the nearest member
    where it does (its reach's edge, C = +-sqrt(A^2 + B^2), from the three probes _family_by_reach takes: C = C0 + C1
    cos t + C2 sin t), if that is within `window`, the angle the vectors' rounding allows (the family's band over the
    shorter vector: continuous with the family, where every member is allowed). Moving along the near family changes
    the pose by |sin q5| times the move (rounding): the sets verify. Returns whether it moved (else q, c, s as read)."""
    o = probe(pose, q, c, s, dp)
    r = math.hypot(o[0], o[1])
    if abs(o[2]) <= r:
        return False
    read = (q[j], c[j], s[j])
    c0, c1, c2 = _reach_terms(j, q, c, s, probe, pose, dp)
    g = math.hypot(c1, c2)
    x = (math.copysign(r, o[2]) - c0) / g if g > DEGENERATE_EPS else 2.0
    if abs(x) <= 1.0:
        phi, w = math.atan2(c2, c1), math.acos(x)
        t = min((phi + w, phi - w), key=lambda v: abs(math.remainder(v - read[0], 2.0 * math.pi)))
        if abs(math.remainder(t - read[0], 2.0 * math.pi)) <= window:
            q[j], c[j], s[j] = _wrap(t), math.cos(t), math.sin(t)
            return True
    q[j], c[j], s[j] = read
    return False


def _family_by_reach(j, q, c, s, prev, probe, pose, dp):
    """The member of a family in joint j whose next stage, A cos q' + B sin q' + C = 0, reaches: at a UR's wrist
    singularity q6 trades with the parallel group along a self-motion that carries the planar pair's target round a
    circle, so the next stage's C is C0 + C1 cos t + C2 sin t in the member t (a distance squared to a point on a
    circle), read from three probes of its kernel. previous's member where it reaches (|C| <= sqrt(A^2 + B^2));
    else the member with C = 0, the middle of that stage's reach, or the one nearest it (if any member reaches,
    that one does). A fixed three or four kernel calls: no search over the family."""
    if prev is not None:
        q[j], c[j], s[j] = prev[j], math.cos(prev[j]), math.sin(prev[j])
        o = probe(pose, q, c, s, dp)
        if abs(o[2]) <= math.hypot(o[0], o[1]) * (1.0 + TANGENT_TOL):
            return
    c0, c1, c2 = _reach_terms(j, q, c, s, probe, pose, dp)
    g = math.hypot(c1, c2)
    if g <= DEGENERATE_EPS:  # the next stage does not see the family: its usual representative
        _family_member(j, q, c, s, prev)
        return
    t = math.atan2(c2, c1) + math.acos(max(-1.0, min(1.0, -c0 / g)))
    c[j], s[j] = math.cos(t), math.sin(t)
    q[j] = math.atan2(s[j], c[j])


def _revolute_value(out, j, q, c, s):
    """A revolute joint j given directly (out = (q_j,)), wrapped."""
    q[j] = _wrap(out[0])
    c[j], s[j] = math.cos(q[j]), math.sin(q[j])
    return True, 0


def _prismatic_value(out, j, q):
    """A prismatic joint j given directly (out = (q_j,))."""
    q[j] = out[0]
    return True, 0


def _slide_quadratic(out, j, sgn, q):
    """A slide from a distance (out = (B, D, E): (q + B)^2 = D, E the scale of D's rounding): q = -B + sgn sqrt(D).
    D within ROOT_GAP_TOL of E is one double root (reported once, by the + branch: the moving point's line touches
    the target's sphere), below that no real root."""
    b, d, e = out
    band = ROOT_GAP_TOL * e
    if not d >= -band:
        return False, 0
    if d <= band:
        if sgn < 0.0:
            return False, 0
        q[j] = -b
        return True, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE
    q[j] = -b + sgn * math.sqrt(d)
    return True, 0


def _wrist_sigma(up, dp, joints):
    """+1 when turning q4 by a moves the end frame as turning q6 by a does at theta5 = 0 (up) or pi (down),
    else -1: the two axes coincide there, so q6 + sigma q4 is what the pose defines. Probed on the chain's
    own FK (a structural sign: the DH twists fix it; a calibrated robot's ideal table's, whose axes coincide)."""
    j4, j5, j6 = joints
    q = [0.0] * N_JOINTS
    q[j5] = 0.0 if up else math.pi
    qa, qb = list(q), list(q)
    qa[j4], qb[j6] = 0.5, 0.5
    if _FK_IDEAL is None:
        ta, tb = _k_fk(qa, dp), _k_fk(qb, dp)
    else:
        ta, tb = (_FK_IDEAL(x, [math.cos(v) for v in x], [math.sin(v) for v in x], dp) for x in (qa, qb))
    same = max(abs(x - y) for x, y in zip(ta, tb, strict=True))
    return 1.0 if same <= 1e-9 * (1.0 + max((abs(v) for v in dp[:N_LENGTHS]), default=0.0)) else -1.0


# The factor the wrist's family bands scale by (_wrist_amp) takes these shares of its two readings: at exact wrist
# singularities the computed |sin theta5| stayed below 0.96 eps kappa and below 130 eps amp_before (bench/wrist_band.py:
# 6,000 poses of four arms), so the family band WRIST_FAMILY_TOL (64 eps) times 0.25 kappa, or times 16 amp_before
# where that is smaller, keeps a margin of 8 or more over that rounding
WRIST_KAPPA_SHARE = 0.25
WRIST_AMP_SHARE = 16.0


def _wrist_amp(s5, amp_before, centre, pose, q, c, s, dp):
    """The factor the wrist's family bands scale by: how much the stages before the wrist amplify the pose's rounding
    into the wrist's rotation. Where the stage has its wrist centre's Jacobian J_c in the prefix joints (`centre`, its
    kernel: derive/families/serial/wrist_centre.py), WRIST_KAPPA_SHARE kappa, kappa = size ||adj J_c||_F / |det J_c|
    >= size / sigma_min(J_c), capped at WRIST_AMP_SHARE amp_before: the product of the angle stages' own
    amplifications, loose on most poses (up to 100x kappa), the bound where a prefix stage sits at its double root
    (kappa unbounded, that stage's error held to its band). Without the kernel, amp_before. Read only where
    |sin theta5| is within twice the widest band's reach (a regular pose never evaluates the kernel; the margin lets
    the mirror, which reads its base's normalised sine, take the same factor)."""
    if centre is None:
        return amp_before
    cap = WRIST_AMP_SHARE * amp_before
    if not abs(s5) <= 2.0 * WRIST_EXACT_TOL * cap:
        return amp_before
    m = centre(pose, q, c, s, dp)
    a0, a1, a2 = m[4] * m[8] - m[5] * m[7], m[5] * m[6] - m[3] * m[8], m[3] * m[7] - m[4] * m[6]
    a3, a4, a5 = m[2] * m[7] - m[1] * m[8], m[0] * m[8] - m[2] * m[6], m[1] * m[6] - m[0] * m[7]
    a6, a7, a8 = m[1] * m[5] - m[2] * m[4], m[2] * m[3] - m[0] * m[5], m[0] * m[4] - m[1] * m[3]
    det = abs(m[0] * a0 + m[1] * a1 + m[2] * a2)
    adj = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3 + a4 * a4 + a5 * a5 + a6 * a6 + a7 * a7 + a8 * a8)
    share = WRIST_KAPPA_SHARE * max(1.0, abs(pose[3]), abs(pose[7]), abs(pose[11])) * adj
    return share / det if share < cap * det else cap


def _wrist_mirror(joints, q, c, s, amp_before, centre=None, pose=None, dp=None):
    """The second wrist branch mirrors the first, computed for the same prefix at set k - 1 (the wrist is the last
    branching stage): q5 -> -q5, q4 -> q4 + pi, q6 -> q6 + pi. At the singularity the first branch already holds
    the whole family (its sin theta5 exactly 0), so this one is a duplicate; within WRIST_EXACT_TOL of it (times the
    factor _wrist_amp reads, as the first branch did) both are the pose's own reading of a near family (_wrist)."""
    j4, j5, j6 = joints
    if abs(s[j5]) <= WRIST_FAMILY_TOL:
        return False, 0
    amp_before = _wrist_amp(s[j5], amp_before, centre, pose, q, c, s, dp)
    q[j5], s[j5] = -q[j5], -s[j5]
    for j in (j4, j6):
        q[j], c[j], s[j] = q[j] - math.pi if q[j] > 0.0 else q[j] + math.pi, -c[j], -s[j]
    if abs(s[j5]) <= WRIST_EXACT_TOL * amp_before:
        return True, FLAG_SINGULAR_INVERSE | FLAG_INDETERMINATE | FLAG_READ_MEMBER
    return True, FLAG_SINGULAR_INVERSE if abs(s[j5]) <= SINGULAR_EPS else 0


def _wrist(out, sgn, signs, joints, q, c, s, dp, amp_before, centre=None, pose=None):
    """The spherical wrist (q4, q5, q6) from the entries of its rotation (out, 9), branch sgn; `signs`: the DH
    twists' signs of those entries (e0..e3) and of the singular family's (k00, k10 with theta5 = 0, then pi);
    `amp_before`: how much the angle stages before it amplified the input's rounding (the product of their amp: each
    reads the joints the ones before it solved), by which its family bands grow: |sin theta5| within
    WRIST_FAMILY_TOL amp_before is the family (one representative), within WRIST_EXACT_TOL amp_before the pose is
    within rounding of it and both branches are its own reading, flagged indeterminate; where the stage has its wrist
    centre's kernel (`centre`, read at `pose`) the bands take _wrist_amp's factor instead (the centre's kappa share,
    capped at WRIST_AMP_SHARE amp_before)."""
    e0, e1, e2, e3, k00a, k10a, k00b, k10b = signs
    j4, j5, j6 = joints
    s5 = sgn * math.hypot(out[2], out[5])
    c5 = e0 * out[8]
    amp_before = _wrist_amp(s5, amp_before, centre, pose, q, c, s, dp)
    f = FLAG_SINGULAR_INVERSE if abs(s5) <= SINGULAR_EPS else 0
    if abs(s5) <= WRIST_EXACT_TOL * amp_before:
        # the sine 1e-12 on a KR 6 read as the family gave q4 := 0, 2 rad from the generating joints (62 of 400
        # poses): above the rounding measured at exact singularities (38 eps x amp_before at most, 5,000 poses of
        # five arms) the entries place the member
        f |= FLAG_INDETERMINATE | FLAG_READ_MEMBER
    if abs(s5) <= WRIST_FAMILY_TOL * amp_before:
        # wrist singularity: only q4 +/- q6 is defined; q4 := 0 (documented representative, moved to the member
        # nearest `previous` by ik)
        if sgn < 0.0:
            return False, 0
        up = c5 >= 0.0
        q[j4], c[j4], s[j4] = 0.0, 1.0, 0.0
        q[j5], c[j5], s[j5] = (0.0, 1.0, 0.0) if up else (math.pi, -1.0, 0.0)
        k00, k10 = (k00a, k10a) if up else (k00b, k10b)
        x, y = k00 * out[0], k10 * out[3]
        f = FLAG_SINGULAR_INVERSE | FLAG_INDETERMINATE
    elif abs(s5) <= SINGULAR_EPS:
        # near the singularity q4 (and q6 on its own) carry errors ~ eps / sin(theta5), but the angle
        # phi = q6 + sigma q4 read from the well-conditioned entries (as at the singularity) is exact up to
        # O(sin^2 theta5) <= SINGULAR_EPS^2: q6 = phi - sigma q4 keeps the pose to rounding.
        up = c5 >= 0.0
        n = math.hypot(s5, c5)
        q[j5], c[j5], s[j5] = math.atan2(s5, c5), c5 / n, s5 / n
        x, y = e1 * sgn * out[2], e1 * sgn * out[5]
        n = math.hypot(x, y)
        q[j4], c[j4], s[j4] = math.atan2(y, x), x / n, y / n
        k00, k10 = (k00a, k10a) if up else (k00b, k10b)
        q[j6] = _wrap(math.atan2(k10 * out[3], k00 * out[0]) - _wrist_sigma(up, dp, joints) * q[j4])
        c[j6], s[j6] = math.cos(q[j6]), math.sin(q[j6])
        return True, f
    else:
        n = math.hypot(s5, c5)
        q[j5], c[j5], s[j5] = math.atan2(s5, c5), c5 / n, s5 / n
        x, y = e1 * sgn * out[2], e1 * sgn * out[5]
        n = math.hypot(x, y)
        q[j4], c[j4], s[j4] = math.atan2(y, x), x / n, y / n
        x, y = e2 * sgn * out[6], e3 * sgn * out[7]
    n = math.hypot(x, y)
    if n <= DEGENERATE_EPS:
        return False, 0
    q[j6], c[j6], s[j6] = math.atan2(y, x), x / n, y / n
    return True, f
