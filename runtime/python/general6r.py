"""The general 6R arm's inverse kinematics by elimination (numpy only): every real solution of an arm whose axes
fit no closed-form decomposition. derive/kinematics/general6r.py proves the structure this rests on and chooses,
per robot, the labelling of the loop and the hidden variable that keep the elimination regular.

The arm and the pose close a loop of six revolute joints, each a turn Rz(theta) in a frame whose z axis is the
joint's line, joined by constant rigid links (one of them holds the pose):

    Rz(t1) K1 Rz(t2) K2 Rz(t3) K3 Rz(t4) K4 Rz(t5) K5 Rz(t6) K6 = I.

Any joint may be called the first and the loop read either way (a labelling). Then (Raghavan and Roth 1993)

    Rz(t3) K3 Rz(t4) K4 Rz(t5) K5 (e_z, o) = K2^-1 Rz(-t2) K1^-1 Rz(-t1) K6^-1 (e_z, o)

(the line of joint 6 seen from both sides) and, from the two vectors (l, p) on each side, p.p, p.l, p x l and
(p.p) l - 2 (p.l) p: 14 equations. The left side is linear in (1, c, s) of each of t3, t4, t5 (27 coefficients),
the right side in (1, c, s) of each of t1, t2 (9). Because each side lies exactly in that span, its coefficients
follow from its values at three angles per joint (0, 2 pi / 3, 4 pi / 3: the interpolation is a 3-point DFT,
perfectly conditioned): P (14 x 27) and, on the right, Q (14 x 8, the terms in t1 and t2) and r (14, constant).

With N the 6 x 14 left null space of Q, N (P X - r) = 0 eliminates t1 and t2. One of t3, t4, t5 (the hidden one)
is written phi + 2 atan(x); the other two by their half-angle tangents u, v. Each (1, c, s) times (1 + u^2) is a
polynomial of degree 2 in u, so the six equations and their u multiples are (A x^2 + B x + C) m = 0 over the 12
monomials m = u^i v^j (i <= 3, j <= 2). The real eigenvalues x give the hidden angle, the null vector of
M(x) the other two, the least-squares Y the angles t1, t2 (its entries include (c1, s1) and (c2, s2)), and the
loop what turns t6. Each candidate is refined by Newton steps on the chain (g6_refine) and verified by the
caller.

When the hidden angle is t3 (the one next to the eliminated pair), det(A x^2 + B x + C) has degree 24 but only 16
roots are solutions: it has the factor (1 + x^2)^4, which is deflated before the eigenproblem (a 16 x 16 one
instead of 24 x 24, ~3x cheaper). Why: t3 enters the left side only as Rz(t3) applied to vectors of t4, t5 (and
not at all in the scalars p.p, p.l), and with z = e^(i t3), c3 = (z + 1/z) / 2 and s3 = (z - 1/z) / (2i), the
1/z part of Rz(t3) is (1/2) w conj(w)^T with w = (1, i, 0). So the 1/z part of the 14 equations lies in the span of
the four columns W4 (w placed in the rows of l, p, p x l and (p.p) l - 2 (p.l) p), and after elimination the six
equations' 1/z part, N W4 alpha(t4, t5), has rank 4: two complex combinations mu (mu^T N W4 = 0) of the six
equations have no 1/z part, mu^T G = mu0 + kappa z. As z = (1 + i x) / (1 - i x), (1 - i x) mu^T G =
(1 - i x) mu0 + (1 + i x) kappa =: L is LINEAR in x, and for real x, with mu = a + i b,
(1 + x^2) (a^T G, b^T G) = [[1, -x], [x, 1]] (Re L, Im L): each of the two mu (and each again for the u
multiples) trades a quadratic pair of rows for a linear pair, dropping one factor (1 + x^2) of the determinant.
The eight linear rows (Re L of the four real vectors (a; b) of the left null space of [[X, Y], [-Y, X]],
X + i Y = N W4) and the four quadratic rows of the two equations orthogonal to every a and b give a 12 x 12
polynomial of determinant degree 16, linearised with s = x A4 m (A4 the quadratic rows' x^2 coefficient):
x [m; s] = S [m; s], S 16 x 16 (_g6_deflated_matrix). When a mu is real up to a factor (d0 = 1 or 2 real
combinations r of the six equations free of t3 altogether, as for the UR5e with a tilted wrist or the xArm6: parallel
axes elsewhere in the loop), its pair degenerates (Re L = r g0, Im L = -x r g0); the row r g0 = 0 (degree 0 in x)
then restricts m to a (12 - 2 d0)-dimensional basis m0, the other mu give 4 - 2 d0 linear rows and the 2 + d0
complementary equations quadratic ones: again 16 x 16. tests/test_general6r.py checks that its eigenvalues are the
24 x 24 companion's other than +-i (random arms, d0 = 0; the tilted UR5e, d0 = 1). Where the structure is not met
to rounding (N W4 of rank < 4, or d0 > 2) and for hidden t4 or t5, the 24 x 24 companion is used.

The source generated Python modules inline (from the marker line on; derive/runtime_files.py), linted and tested
here as it is (tests/test_general6r.py).
"""

from __future__ import annotations

import math

import numpy as np

# wristkin: inlined from here

_G6_GRID = (0.0, 2.0 * math.pi / 3.0, 4.0 * math.pi / 3.0)
# B[k, m] = (1, cos g_k, sin g_k)[m]: values at the grid from coefficients; its inverse interpolates
_G6_B = np.array([[1.0, math.cos(g), math.sin(g)] for g in _G6_GRID])
_G6_BINV = np.linalg.inv(_G6_B)
# (1 + u^2) times 1, c, s (c = (1 - u^2) / (1 + u^2), s = 2u / (1 + u^2)) as coefficients of u^0, u^1, u^2
_G6_HALF = np.array([[1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [0.0, 2.0, 0.0]])
G6_REFINE_STEPS = 8  # Newton steps per candidate at most (a simple root: 1-2 to rounding; a double root: linear)
G6_REFINE_NEAR = 1e-10  # below this pose error (relative to 1 + |p|_1) a step may raise it while the steps contract
G6_REFINE_DONE = 2.0**-50  # ~4 eps: the pose error at rounding (relative to 1 + |p|_1), where refinement stops
G6_NULL_TOL = 1e-8  # singular values of M(x) up to this x the largest span its null space
# |Im x| / (1 + |x|) up to this: a real root moved off the axis by rounding (verification decides). A real double
# root (two solutions meeting) perturbed by the eigenproblem's backward error delta ~ c n eps / rcond(K) splits by
# ~sqrt(delta) into a complex pair: 6.6e-6 seen at rcond ~1e-4 (test_at_a_double_root_...); 1e-4 keeps such pairs
# down to rcond ~1e-6. A genuinely complex pair that close gives a candidate the verification rejects.
G6_REAL_TOL = 1e-4
G6_SHIFT_REAL_TOL = 1e-6  # the same for the k x k shift pencil's eigenvalues u (k solutions sharing the hidden angle)
# sigma_2 / sigma_max of M(x) up to this (above G6_NULL_TOL): x is one of a cluster of nearly equal roots. Where k
# solutions share a hidden angle only nearly (a near-special arm: the KR 6 1e-5 from a spherical wrist hides a joint
# whose four solutions agree to ~1e-5, more so near its wrist singularity), the cluster's eigenvalues are nearly
# defective and resolve to eps^(1/k) at best: 0.13 rad apart where the solutions are 1e-5, and C's and LAPACK's
# eigensolvers then find different members, some as complex pairs. Their invariant subspace is well determined: the
# k <= G6_MAXK singular vectors of M(x) below this give the k solutions' monomial vectors through the shift pencil,
# as for an exact multiple root, from any member near the cluster; offered besides the root's own null vector.
G6_CLUSTER_TOL = 1e-4
G6_CLUSTER_REAL_TOL = 1e-3  # the shift pencil's |Im u| / (1 + |u|) up to this on a cluster's approximate subspace
# |Im x| / (1 + |x|) of an eigenvalue pair up to this (beyond G6_REAL_TOL): a nearly defective cluster's members can
# come out this far off the axis (5e-3 seen), all of them in one eigensolver and none in another; such a pair makes the
# caller solve every reading with clusters, which reads it as a root
G6_CLUSTER_IM_TOL = 1e-2
G6_MAXK = 4  # the most solutions a cluster's subspace gives (the C runtime's fixed arrays)
# a root whose null vector lies within this of a cluster subspace already read (|v - B B^T v|) is that cluster's member:
# its solutions were offered with the subspace (the C runtime then saves an SVD)
G6_CLUSTER_COVER = 1e-2
_G6_PHIS = (0.0, 2.0 * math.pi / 3.0, -2.0 * math.pi / 3.0, math.pi / 2.0)
_G6_BLOCKS = (0, 3, 8, 11)  # the x rows of the 14's vectors l, p, p x l, (p.p) l - 2 (p.l) p (y follows)
G6_RCOND_GOOD = 1e-4  # the deflated K this well conditioned (equilibrated rows): no further origin phi tried
G6_DEFLATE_TOL = 1e-8  # sigma_min / sigma_max of [[X, Y], [-Y, X]] below this: N W4 rank < 4, no deflation


def g6_rz(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    out = np.eye(4)
    out[0, 0], out[0, 1], out[1, 0], out[1, 1] = c, -s, s, c
    return out


def g6_inverse(t: np.ndarray) -> np.ndarray:
    out = np.eye(4)
    out[:3, :3] = t[:3, :3].T
    out[:3, 3] = -t[:3, :3].T @ t[:3, 3]
    return out


def g6_fourteen(d: np.ndarray, p: np.ndarray) -> np.ndarray:
    """The 14 functions of lines (directions d, points p: (..., 3)): d, p, p.p, p.d, p x d, (p.p) d - 2 (p.d) p."""
    pp, pd = np.sum(p * p, axis=-1)[..., None], np.sum(p * d, axis=-1)[..., None]
    return np.concatenate([d, p, pp, pd, np.cross(p, d), pp * d - 2.0 * pd * p], axis=-1)


_G6_BINV2 = np.kron(_G6_BINV, _G6_BINV)  # the interpolation over two (three) joints' grids at once
_G6_BINV3 = np.kron(_G6_BINV2, _G6_BINV)
_G6_GRID_RZ = np.stack([g6_rz(g) for g in _G6_GRID])  # (3, 4, 4): Rz at the grid; transposed, Rz(-g)


def g6_equations(links):
    """(P, Q, r) of the loop with links K1..K6 (4x4 each): P[e, a, b, c] the coefficient of the product of the
    a-th, b-th, c-th of (1, c, s) of t3, t4, t5 in equation e of the left side; the right side as Q Y + r, Y =
    (s1 s2, s1 c2, c1 s2, c1 c2, s1, c1, s2, c2). The 27 (9) grid transforms at once (numpy broadcasting)."""
    k1, k2, k3, k4, k5, k6 = links
    rz, rzt = _G6_GRID_RZ, _G6_GRID_RZ.transpose(0, 2, 1)
    ta = rz @ k3  # (a)
    tb = (ta[:, None] @ rz[None]) @ k4  # (a, b)
    t = (tb[:, :, None] @ rz[None, None]) @ k5  # (a, b, c)
    vals = g6_fourteen(t[..., :3, 2], t[..., :3, 3])
    P = (_G6_BINV3 @ vals.reshape(27, 14)).T.reshape(14, 3, 3, 3)
    k2i, k1i, k6i = g6_inverse(k2), g6_inverse(k1), g6_inverse(k6)
    t = ((k2i @ rzt) @ k1i)[None] @ (rzt @ k6i)[:, None]  # [a, b] = K2^-1 Rz(-b) K1^-1 Rz(-a) K6^-1
    rvals = g6_fourteen(t[..., :3, 2], t[..., :3, 3])
    R = (_G6_BINV2 @ rvals.reshape(9, 14)).T.reshape(14, 3, 3)  # R[e, m1, m2] over (1, c, s) of t1 and of t2
    # Y = (s1 s2, s1 c2, c1 s2, c1 c2, s1, c1, s2, c2) in those indices (1 = 0, c = 1, s = 2)
    y_index = ((2, 2), (2, 1), (1, 2), (1, 1), (2, 0), (1, 0), (0, 2), (0, 1))
    Q = np.stack([R[:, i, j] for i, j in y_index], axis=1)
    return P, Q, R[:, 0, 0]


def _g6_matrix_polynomial(t6, hidden, phi):
    """(A, B, C), 12 x 12, for the hidden joint (0, 1, 2 of t3, t4, t5) = phi + 2 atan x."""
    e = np.moveaxis(t6, 1 + hidden, 1)  # (eq, hidden, u, v)
    c, s = math.cos(phi), math.sin(phi)
    # hidden's (1, c, s) with c_h = c c' - s s', s_h = s c' + c s' (c', s' of 2 atan x), times (1 + x^2)
    one, ch, sh = e[:, 0], e[:, 1], e[:, 2]
    k1, kc, ks = one, ch * c + sh * s, sh * c - ch * s
    # (x power, eq, u basis, v basis): (1 + x^2) k1 + (1 - x^2) kc + 2 x ks
    coeffs = (np.einsum("k,eab->keab", _G6_HALF[0], k1) + np.einsum("k,eab->keab", _G6_HALF[1], kc) +
              np.einsum("k,eab->keab", _G6_HALF[2], ks))
    out = []
    for power in range(3):
        g = np.einsum("ai,bj,eab->eij", _G6_HALF, _G6_HALF, coeffs[power])  # over u^i v^j, i, j <= 2
        m = np.zeros((12, 12))
        m[:6, :9] = g.reshape(6, 9)
        m[6:, 3:] = g.reshape(6, 9)
        out.append(m)
    return out[2], out[1], out[0]


def _g6_half_angle(v, axis):
    """The angle 2 atan(x) of u (axis 0) or v (axis 1) from the monomial vector (4 x 3 grid of u^i v^j): x is
    num / den of neighbours along that axis where (den, num) is largest, taken as 2 atan2(num, den) (the same for
    -vector, and pi where den vanishes)."""
    g = v.reshape(4, 3)
    pairs = ([(g[i, j], g[i + 1, j]) for i in range(3) for j in range(3)] if axis == 0 else
             [(g[i, j], g[i, j + 1]) for i in range(4) for j in range(2)])
    den, num = max(pairs, key=lambda dn: math.hypot(*dn))
    return 2.0 * math.atan2(num, den)


def g6_regularity(links, hidden) -> float:
    """How far the elimination is from degenerate for these links: sigma_min / sigma_max of Q's 8th singular value
    and of M(x) at x = 0.3 (a geometry whose six equations are dependent makes M singular for every x)."""
    P, Q, r = g6_equations(links)
    sq = np.linalg.svd(Q, compute_uv=False)
    u = np.linalg.svd(Q)[0]
    t6 = np.einsum("fe,eabc->fabc", u[:, 8:].T, _g6_with_constant(P, r))
    a, b, c = _g6_matrix_polynomial(t6, hidden, 0.7)
    sm = np.linalg.svd(a * 0.09 + b * 0.3 + c, compute_uv=False)
    return float(min(sq[-1] / sq[0], sm[-1] / sm[0]))


def _g6_with_constant(P, r):
    out = P.copy()
    out[:, 0, 0, 0] -= r
    return out


def _g6_trig_rows_many(f):
    """Trig polynomials f (k x 3 x 3 over (1, c, s) of the two non-hidden angles) times (1 + u^2)(1 + v^2), as rows
    over the 12 monomials u^i v^j: the k rows, then their u multiples (2k x 12)."""
    g = np.einsum("ai,bj,kab->kij", _G6_HALF, _G6_HALF, f).reshape(-1, 9)
    out = np.zeros((2 * len(f), 12))
    out[: len(f), :9], out[len(f):, 3:] = g, g
    return out


def g6_deflation_basis(n):
    """(r0, ab, comp) for the six equations' rows n (6 x 14, the left null space of Q): r0 (6 x d0) the real
    combinations free of t3 altogether (r^T n W4 = 0; d0 = 0 for a generic arm, 1 for a UR-like one), ab
    (12 x (4 - 2 d0)) the other real vectors (a; b) with (a + i b)^T n W4 = 0, comp (6 x (2 + d0)) the equations
    orthogonal to all of them; None where n W4 has rank < 4 or the spans do not add up (see the module docstring)."""
    x, y = n[:, _G6_BLOCKS], n[:, [b + 1 for b in _G6_BLOCKS]]
    u, sv, _ = np.linalg.svd(np.block([[x, y], [-y, x]]))
    if not sv[-1] > G6_DEFLATE_TOL * sv[0]:
        return None
    ur, sr, _ = np.linalg.svd(np.hstack([x, y]))  # 6 x 8: its left null space, the real mu
    d0 = 6 - int(np.sum(sr > G6_DEFLATE_TOL * sr[0]))
    if d0 > 2:
        return None
    r0 = ur[:, 6 - d0:]
    ab = u[:, 8:]
    if d0:  # the (r; 0), (0; r) directions out of the null space of [[X, Y], [-Y, X]]
        real = np.zeros((12, 2 * d0))
        real[:6, :d0], real[6:, d0:] = r0, r0
        ua, sa, _ = np.linalg.svd(ab - real @ (real.T @ ab))
        if d0 < 2 and not sa[3 - 2 * d0] > G6_DEFLATE_TOL * sa[0]:
            return None
        ab = ua[:, : 4 - 2 * d0]
    k = 4 - d0  # the real span of r0, the a's and the b's
    ua, sa, _ = np.linalg.svd(np.hstack([r0, ab[:6], ab[6:]]))
    if not (sa[k - 1] > G6_DEFLATE_TOL * sa[0] and (len(sa) <= k or sa[k] <= G6_DEFLATE_TOL * sa[0])):
        return None
    return r0, ab, ua[:, k:]


def _g6_deflated_parts(t6, basis):
    """The deflated pencil's rows split by the hidden angle's origin phi (each is linear in cos phi, sin phi): the
    linear rows L0 + x K = (a0 + c pr + s qr) + x (b0 + c qr - s pr) (Re L = (a g0 + kr) + x (b g0 - ki) with
    2 kappa = mu (gc - i gs) at phi; 2 pr = a gc + b gs, 2 qr = a gs - b gc), the complementary equations'
    (1, c, s) parts k1, kc, ks in the hidden angle (rows and u multiples each), all times m0 (12 x (12 - 2 d0)):
    an orthonormal basis of the monomial vectors m that the rows free of t3 (r0 g0 m = 0) leave."""
    r0, ab, comp = basis
    g0, gc, gs = t6[:, 0], t6[:, 1], t6[:, 2]
    a, b = ab[:6], ab[6:]  # (6, j) each: column j one (a; b)
    nl, nq = ab.shape[1], comp.shape[1]
    ag0, bg0, agc, ags, bgc, bgs = (np.einsum("ej,euv->juv", v, w) for v, w in
                                    ((a, g0), (b, g0), (a, gc), (a, gs), (b, gc), (b, gs)))
    lin = _g6_trig_rows_many(np.stack([ag0, bg0, 0.5 * (agc + bgs), 0.5 * (ags - bgc)]).reshape(4 * nl, 3, 3))
    lin = lin.reshape(2, 4, nl, 12).transpose(1, 0, 2, 3).reshape(4, 2 * nl, 12)  # a0, b0, pr, qr (+ u multiples)
    quad = _g6_trig_rows_many(np.einsum("ek,ehab->hkab", comp, t6).reshape(3 * nq, 3, 3))
    quad = quad.reshape(2, 3, nq, 12).transpose(1, 0, 2, 3).reshape(3, 2 * nq, 12)  # k1, kc, ks (+ u multiples)
    m0 = np.eye(12)
    if r0.shape[1]:
        rows = _g6_trig_rows_many(np.einsum("ek,euv->kuv", r0, g0))
        m0 = np.linalg.svd(rows)[2][len(rows):].T
    return lin @ m0, quad @ m0


def _g6_deflated_at(parts, phi):
    """(S, rcond of K): the 16 x 16 matrix whose eigenvalues are the roots x of hidden = t3 = phi + 2 atan x other
    than +-i (the module docstring), and the reciprocal condition of its leading coefficient K."""
    (a0, b0, pr, qr), (k1, kc, ks) = parts
    nm, nl2, nq2 = a0.shape[1], len(a0), len(k1)  # m's dimension (12 - 2 d0), linear and quadratic rows
    c, s = math.cos(phi), math.sin(phi)
    l0, l1 = a0 + c * pr + s * qr, b0 + c * qr - s * pr
    kc, ks = c * kc + s * ks, c * ks - s * kc
    a2, b2, c2 = k1 - kc, 2.0 * ks, k1 + kc  # (1 + x^2) k1 + (1 - x^2) kc + 2 x ks
    k = np.vstack([l1, a2])
    # each row with its partners equilibrated by a power of two (the C's g6_deflated_at): K's conditioning then
    # measures the problem, not the rows' scales
    lin = np.maximum(np.max(np.abs(l0), axis=1, initial=0.0), np.max(np.abs(l1), axis=1, initial=0.0))
    quad = np.max(np.abs(np.hstack([a2, b2, c2])), axis=1)
    big = np.concatenate([lin, quad])
    scale = np.exp2(-np.frexp(np.where(big > 0.0, big, 1.0))[1])
    l0, k = l0 * scale[:nl2, None], k * scale[:, None]
    b2, c2 = b2 * scale[nl2:, None], c2 * scale[nl2:, None]
    sv = np.linalg.svd(k, compute_uv=False)
    rc = sv[-1] / sv[0] if sv[0] > 0.0 else 0.0
    if not rc > 0.0:
        return None, 0.0
    rhs = np.zeros((nm, nm + nq2))
    rhs[:nl2, :nm] = -l0
    rhs[nl2:, nm:] = np.eye(nq2)
    try:
        d = np.linalg.solve(k, rhs)  # x m = K^-1 [-L0 m; s]
    except np.linalg.LinAlgError:  # K exactly singular at this phi (LU's pivot 0): the next phi, or the 24 x 24
        return None, 0.0
    return np.vstack([d, np.hstack([-c2, np.zeros((nq2, nq2))]) - b2 @ d]), rc  # x s = -C4 m - B4 x m


def _g6_deflated_matrix(t6, basis, phi):
    """_g6_deflated_at for one phi."""
    return _g6_deflated_at(_g6_deflated_parts(t6, basis), phi)


def _g6_roots(t6, n, hidden):
    """(eigenvalues x, phi, A, B, C): the roots of det(A x^2 + B x + C) for hidden = phi + 2 atan x, phi chosen so
    that the leading coefficient is well conditioned (x = infinity, phi + pi, far from a root); deflated to 16
    for hidden t3."""
    basis = g6_deflation_basis(n) if hidden == 0 else None
    parts = _g6_deflated_parts(t6, basis) if basis is not None else None
    best = None
    for phi in _G6_PHIS:
        if parts is not None:
            mat, rc = _g6_deflated_at(parts, phi)
        else:
            a = _g6_matrix_polynomial(t6, hidden, phi)[0]
            sv = np.linalg.svd(a, compute_uv=False)
            rc, mat = (sv[-1] / sv[0] if sv[0] > 0.0 else 0.0), None
        if best is None or rc > best[0]:
            best = (rc, phi, mat)
        if rc > (G6_RCOND_GOOD if basis is not None else 1e-3):  # the leading coefficient well conditioned
            break
    _, phi, mat = best
    a, b, c = _g6_matrix_polynomial(t6, hidden, phi)
    if mat is None:
        try:
            ainv = np.linalg.inv(a)
        except np.linalg.LinAlgError:  # singular at every phi tried: no candidate from this reading (never a crash)
            return np.zeros(0, dtype=complex), phi, a, b, c
        mat = np.zeros((24, 24))
        mat[:12, 12:] = np.eye(12)
        mat[12:, :12] = -ainv @ c
        mat[12:, 12:] = -ainv @ b
    return np.linalg.eigvals(mat), phi, a, b, c


def _g6_real_roots(links, hidden, wide=False):
    """(P with its constant, the pseudo-inverse of Q, phi, the real eigenvalues x, M(x) of each, their singular values
    and right singular vectors, whether a pair lies off the real axis by more than G6_REAL_TOL but within
    G6_CLUSTER_IM_TOL) of the loop's links read with `hidden` the eigenvalue's angle; `wide`: such pairs are taken
    as real roots too (at their real part)."""
    P, Q, r = g6_equations(links)
    u, sq, vt = np.linalg.svd(Q)
    n, pc = u[:, 8:].T, _g6_with_constant(P, r)
    t6 = np.einsum("fe,eabc->fabc", n, pc)
    qpinv = (vt.T / sq) @ u[:, :8].T
    roots, phi, a, b, c = _g6_roots(t6, n, hidden)
    off = [abs(x.imag) / (1.0 + abs(x)) for x in roots]
    tol = G6_CLUSTER_IM_TOL if wide else G6_REAL_TOL
    xs = np.array([x.real for x, o in zip(roots, off, strict=True)  # a near-real pair once, at its real part
                   if x.imag >= 0.0 and o <= tol])
    near_pair = any(G6_REAL_TOL < o <= G6_CLUSTER_IM_TOL for o in off)
    ms = (a * xs[:, None, None] + b) * xs[:, None, None] + c  # M(x) of every real root at once
    svs, vts = np.linalg.svd(ms)[1:] if len(xs) else (np.zeros((0, 12)), np.zeros((0, 12, 12)))
    return pc, qpinv, phi, xs, ms, svs, vts, near_pair


def g6_candidates(links, hidden=0, clusters=False):
    """Loop angles (t1..t6) of every real root of the eliminated system for the loop's links (without `clusters`,
    a root in a cluster of nearly equal roots gives only its own null vector: _g6_monomial_vectors; with them, a
    pair within G6_CLUSTER_IM_TOL of the real axis is read as a root too), and whether such a pair was seen."""
    pc, qpinv, phi, xs, _, svs, vts, near_pair = _g6_real_roots(links, hidden, clusters)
    others = [k for k in range(3) if k != hidden]
    if len(xs) == 0:
        return [], near_pair
    angles, read = [], [] if clusters else None
    for x, sv, vt in zip(xs, svs, vts, strict=True):
        vs = _g6_monomial_vectors(sv, vt, read)
        for v in vs:
            row = [0.0, 0.0, 0.0]
            row[hidden] = phi + 2.0 * math.atan(x)
            row[others[0]], row[others[1]] = _g6_half_angle(v, 0), _g6_half_angle(v, 1)
            angles.append(row)
    return (_g6_complete_many(np.array(angles), links, pc, qpinv) if angles else []), near_pair


def _g6_monomial_vectors(sv, vt, clusters):
    """The monomial vectors u^i v^j in the null space of M(x) (its singular values sv, descending, and right singular
    vectors vt): its null vector; where several solutions share the hidden angle (a null space of dimension k > 1,
    e.g. a wrist's two flips) the k vectors of that space with the shift structure (_g6_shift_vectors) instead; and
    where they share it only nearly (G6_CLUSTER_TOL), the null vector and, unless an earlier member of the cluster
    gave them (its subspace in `clusters`, appended to here; None: clusters are not read), the cluster subspace's
    vectors."""
    k = int(np.sum(sv <= G6_NULL_TOL * sv[0]))
    if k > 1:
        return _g6_shift_vectors(vt[-min(k, G6_MAXK):].T, G6_SHIFT_REAL_TOL)
    k = min(G6_MAXK, int(np.sum(sv <= G6_CLUSTER_TOL * sv[0])))
    if clusters is None or k < 2 or any(np.linalg.norm(vt[-1] - b @ (b.T @ vt[-1])) <= G6_CLUSTER_COVER
                                        for b in clusters):
        return [vt[-1]]
    clusters.append(vt[-k:].T)
    return [vt[-1]] + _g6_shift_vectors(vt[-k:].T, G6_CLUSTER_REAL_TOL)


def _g6_shift_vectors(basis, real_tol):
    """The vectors of span(basis) (12 x k) with the shift structure u^(i+1) v^j = u u^i v^j: eigenvectors of the
    k x k pencil it gives, those with a real u (|Im u| <= real_tol (1 + |u|))."""
    k = basis.shape[1]
    grid = basis.reshape(4, 3, k)
    down, up = grid[:3].reshape(9, k), grid[1:].reshape(9, k)
    swap = np.linalg.norm(down) < np.linalg.norm(up)  # u large: the shift read the other way (1/u), better scaled
    lhs, rhs = (up, down) if swap else (down, up)
    vals, vecs = np.linalg.eig(np.linalg.lstsq(lhs, rhs, rcond=None)[0])
    return [np.real(basis @ vecs[:, i]) for i in range(k) if abs(vals[i].imag) <= real_tol * (1.0 + abs(vals[i]))]


def _g6_complete_many(angles, links, P, Q):
    """_g6_complete for every row of angles (k x 3: theta3..5) at once: the k x 6 loop angles."""
    k1, k2, k3, k4, k5, k6 = links
    cs = np.stack([np.ones_like(angles), np.cos(angles), np.sin(angles)], axis=2)  # (k, 3 angles, (1, c, s))
    outer = (cs[:, 0, :, None, None] * cs[:, 1, None, :, None] * cs[:, 2, None, None, :]).reshape(-1, 27)
    y = outer @ (P.reshape(14, 27).T @ Q.T)  # Q: the pseudo-inverse (least squares)
    t1, t2 = np.arctan2(y[:, 4], y[:, 5]), np.arctan2(y[:, 6], y[:, 7])
    # Rz(t6) = (Rz(t1) K1 ... Rz(t5) K5)^-1 K6^-1
    f = _g6_rz_many(t1) @ k1
    for t, k in ((t2, k2), (angles[:, 0], k3), (angles[:, 1], k4), (angles[:, 2], k5)):
        f = (f @ _g6_rz_many(t)) @ k
    r6 = np.swapaxes(f[:, :3, :3], 1, 2) @ k6[:3, :3].T  # rotation of f^-1 K6^-1
    return np.column_stack([t1, t2, angles, np.arctan2(r6[:, 1, 0], r6[:, 0, 0])]).tolist()


def _g6_rz_many(t):
    out = np.zeros((len(t), 4, 4))
    c, s = np.cos(t), np.sin(t)
    out[:, 0, 0], out[:, 0, 1], out[:, 1, 0], out[:, 1, 1], out[:, 2, 2], out[:, 3, 3] = c, -s, s, c, 1.0, 1.0
    return out


def g6_z_frames(axes, points) -> list[np.ndarray]:
    """A frame per joint with its z axis on the joint's line (x any normal): exp(S_i q) = Z_i Rz(q) Z_i^-1."""
    out = []
    for a, p in zip(axes, points, strict=True):
        z = np.asarray(a, dtype=float) / np.linalg.norm(a)
        e = np.eye(3)[int(np.argmin(np.abs(z)))]
        x = np.cross(z, e)
        x /= np.linalg.norm(x)
        f = np.eye(4)
        f[:3, 0], f[:3, 1], f[:3, 2], f[:3, 3] = x, np.cross(z, x), z, p
        out.append(f)
    return out


def g6_frames_of(axes, points) -> list[np.ndarray]:
    """g6_z_frames of the last axes and points asked for, kept: a chain's frames move only with its design (a held
    joint's value), so the stage computes them once per design, not per call."""
    global _G6_FRAMES
    key, cached = (tuple(np.ravel(axes).tolist()), tuple(np.ravel(points).tolist())), _G6_FRAMES
    if cached[0] != key:  # read once above: another thread may replace the pair meanwhile, never half of it
        cached = _G6_FRAMES = (key, g6_z_frames(axes, points))
    return cached[1]


_G6_FRAMES = (None, None)  # (axes and points, their frames): one assignment, a thread reads the old pair or the new


def g6_loop_links(frames, home, pose):
    """K1..K6 of the loop Rz(q1) K1 ... Rz(q6) K6 = I for the chain pose(q) = prod Z_i Rz(q_i) Z_i^-1 home."""
    links = [g6_inverse(frames[i]) @ frames[i + 1] for i in range(5)]
    links.append(g6_inverse(frames[5]) @ home @ g6_inverse(pose) @ frames[0])
    return links


def g6_labelled(links, shift: int, reverse: bool):
    """(links, joints, sign) of the same loop read from joint `shift` (0-based), backwards when `reverse`: the
    loop Rz(sign q[joints[0]]) links[0] ... Rz(sign q[joints[5]]) links[5] = I."""
    if reverse:  # K6^-1 Rz(-q6) K5^-1 ... K1^-1 Rz(-q1) = I, read from Rz(-q6)
        links = [g6_inverse(links[i]) for i in (4, 3, 2, 1, 0, 5)]
        joints = [5, 4, 3, 2, 1, 0]
    else:
        joints = [0, 1, 2, 3, 4, 5]
    k = shift % 6
    return links[k:] + links[:k], joints[k:] + joints[:k], -1.0 if reverse else 1.0


def g6_fk_many(frames, home, qs):
    """prod Z_i Rz(q_i) Z_i^-1 . home for each row of qs (n x 6), and the geometric Jacobians (n x 6 x 6, linear
    velocity of the end origin first). Each Z Rz(q) Z^-1 is the turn about the line (axis a, point p) of Z:
    R = c I + s [a]x + (1 - c) a a^T, translation p - R p (Rodrigues, all rows at once)."""
    qs = np.asarray(qs, dtype=float).reshape(-1, 6)
    n = len(qs)
    a = np.array([z[:3, 2] for z in frames])  # (6, 3) axes
    p = np.array([z[:3, 3] for z in frames])  # (6, 3) points
    skew = np.zeros((6, 3, 3))
    skew[:, 0, 1], skew[:, 0, 2], skew[:, 1, 2] = -a[:, 2], a[:, 1], -a[:, 0]
    skew = skew - skew.transpose(0, 2, 1)
    c, s = np.cos(qs)[..., None, None], np.sin(qs)[..., None, None]  # (n, 6, 1, 1)
    e = c * np.eye(3) + s * skew + (1.0 - c) * (a[:, :, None] * a[:, None, :])  # (n, 6, 3, 3)
    et = p - np.einsum("nkij,kj->nki", e, p)  # (n, 6, 3)
    rot, tr = np.broadcast_to(np.eye(3), (n, 3, 3)), np.zeros((n, 3))
    axes, points = [], []
    for k in range(6):
        axes.append(rot @ a[k])
        points.append(rot @ p[k] + tr)
        tr = tr + np.einsum("nij,nj->ni", rot, et[:, k])
        rot = rot @ e[:, k]
    t = np.zeros((n, 4, 4))
    t[:, :3, :3], t[:, :3, 3], t[:, 3, 3] = rot, tr, 1.0
    t = t @ home
    ax, pt = np.stack(axes, axis=1), np.stack(points, axis=1)  # (n, 6, 3)
    lin = np.cross(ax, t[:, None, :3, 3] - pt)
    return t, np.concatenate([lin, ax], axis=2).transpose(0, 2, 1)


def g6_fk(frames, home, q):
    """prod Z_i Rz(q_i) Z_i^-1 . home, and the geometric Jacobian (linear velocity of the end origin first)."""
    t, jac = g6_fk_many(frames, home, np.asarray(q, dtype=float)[None])
    return t[0], jac[0]


def _g6_pose_error(t, pose):
    return np.max(np.abs(t[:, :3] - pose[:3]), axis=(1, 2))


def g6_refine_many(frames, home, pose, qs, steps=G6_REFINE_STEPS):
    """Newton steps on the chain's pose error for each row of qs (n x 6; all rows at once): the eigenproblem leaves
    a root ~1e-9 off where roots are close, a few steps bring it to rounding, so that every caller (C, numpy)
    starts its verification from the same set. A row stops at rounding, when a step neither lowers its error nor
    (below G6_REFINE_NEAR) contracts, or when its Jacobian is singular; it keeps its smallest-error iterate. At a
    double root (two solutions meeting, J singular there) Newton converges only linearly, halving the distance per
    step while the pose error, already near rounding, goes up and down: hence the contraction rule."""
    q = np.array(qs, dtype=float).reshape(-1, 6)
    t, jac = g6_fk_many(frames, home, q)
    err = _g6_pose_error(t, pose)
    scale = 1.0 + float(np.sum(np.abs(pose[:3, 3])))
    done, near = G6_REFINE_DONE * scale, G6_REFINE_NEAR * scale
    best, best_err, last = q.copy(), err.copy(), np.full(len(q), np.inf)
    active = err > done
    for _ in range(steps):
        idx = np.flatnonzero(active)
        if len(idx) == 0:
            break
        e = np.concatenate([pose[:3, 3] - t[idx, :3, 3],
                            0.5 * np.cross(t[idx, :3, :3].transpose(0, 2, 1), pose[:3, :3].T).sum(axis=1)], axis=1)
        step, ok = np.zeros((len(idx), 6)), np.ones(len(idx), dtype=bool)
        try:
            step = np.linalg.solve(jac[idx], e[..., None])[..., 0]
        except np.linalg.LinAlgError:  # one row singular: solved row by row
            for k in range(len(idx)):
                try:
                    step[k] = np.linalg.solve(jac[idx[k]], e[k])
                except np.linalg.LinAlgError:
                    ok[k] = False
        size = np.max(np.abs(step), axis=1)
        t2, jac2 = g6_fk_many(frames, home, q[idx] + step)
        err2 = _g6_pose_error(t2, pose)
        take_m = ok & ((err2 < err[idx]) | ((err2 <= near) & (size <= 0.75 * last[idx])))
        take = idx[take_m]
        q[take], t[take], jac[take], err[take] = q[take] + step[take_m], t2[take_m], jac2[take_m], err2[take_m]
        last[take] = size[take_m]
        improved = take[err[take] < best_err[take]]
        best[improved], best_err[improved] = q[improved], err[improved]
        active[idx[~take_m]] = False
        active[take] = err[take] > done
    return best


def g6_refine(frames, home, pose, q, steps=G6_REFINE_STEPS):
    """g6_refine_many for one q (a list of floats)."""
    return [float(v) for v in g6_refine_many(frames, home, pose, q, steps)[0]]


def g6_solve(frames, home, pose, shift=0, reverse=False, hidden=0, clusters=False):
    """g6_solve_flagged's candidates."""
    return g6_solve_flagged(frames, home, pose, shift, reverse, hidden, clusters)[0]


def g6_solve_flagged(frames, home, pose, shift=0, reverse=False, hidden=0, clusters=False):
    """Joint candidates q (length 6, refined by Newton on the chain) of prod Z_i Rz(q_i) Z_i^-1 home = pose, and
    whether an eigenvalue pair lay near the real axis (g6_candidates)."""
    links, joints, sign = g6_labelled(g6_loop_links(frames, home, pose), shift, reverse)
    cands, near_pair = g6_candidates(links, hidden, clusters)
    if not cands:
        return [], near_pair
    q = np.zeros((len(cands), 6))
    q[:, joints] = sign * np.array(cands)
    return [[float(v) for v in row] for row in g6_refine_many(frames, home, pose, q)], near_pair
