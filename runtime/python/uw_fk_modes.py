"""The underactuated wrist's assembly modes for one joint triple: the degree-8 eliminant in
x = tan((eta - eta_c) / 2), its real roots, zeta at each, and a damped Gauss-Newton polish on the two loop
equations that accepts or rejects each candidate.

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import math

from uw_design import _wrap_2pi, _wrap_pi
from uw_stand_in import (
    _POLY_FLAG_DOUBLE,
    _POLY_STATUS_ZERO,
    FK_DUPLICATE_TOL,
    FK_FOLD_TOL,
    FK_RESIDUAL_TOL,
    FLAG_DOUBLE_ROOT,
    FLAG_SINGULAR_DIRECT,
    NO_ASSEMBLY_REASON,
    POLISH_ITERS,
    STATUS_INDETERMINATE,
    STATUS_NO_ASSEMBLY,
    STATUS_OK,
    TOUCH_TOL,
    _k_fk_def,
    _poly_real_roots,
)


# wristkin: inlined from here
# ---------------------------------------------------------------------------- forward kinematics
def _def_at(trip, eta):
    """(D1, E1, F1, D2, E2, F2) and their eta-derivatives at eta."""
    ce, se = math.cos(eta), math.sin(eta)
    v = [t[0] + t[1] * ce + t[2] * se for t in trip]
    dv = [-t[1] * se + t[2] * ce for t in trip]
    return v, dv


def _elimination(v):
    d1, e1, f1, d2, e2, f2 = v
    return (e1 * f2 - e2 * f1) ** 2 + (d2 * f1 - d1 * f2) ** 2 - (d1 * e2 - d2 * e1) ** 2


def _quad(t, ce, se):
    """(1 + x^2)(k0 + kc cos + ks sin) in x = tan((eta - eta_c)/2), ascending; coefficients rotated by eta_c."""
    rc = t[1] * ce + t[2] * se
    rs = -t[1] * se + t[2] * ce
    return (t[0] + rc, 2.0 * rs, t[0] - rc)


def _pmul(a, b):
    out = [0.0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def _psub(a, b):
    return [x - y for x, y in zip(a, b, strict=True)]


def _k_polynomial(trip, eta_c):
    """K0..K8 of K(x) = (1 + x^2)^4 * elimination identity, x = tan((eta - eta_c)/2)."""
    ce, se = math.cos(eta_c), math.sin(eta_c)
    d1, e1, f1, d2, e2, f2 = (_quad(t, ce, se) for t in trip)
    t1 = _psub(_pmul(e1, f2), _pmul(e2, f1))
    t2 = _psub(_pmul(d2, f1), _pmul(d1, f2))
    t3 = _psub(_pmul(d1, e2), _pmul(d2, e1))
    return [x + y - z for x, y, z in zip(_pmul(t1, t1), _pmul(t2, t2), _pmul(t3, t3), strict=True)]


def _residual(trip, zeta, eta):
    v, dv = _def_at(trip, eta)
    cz, sz = math.cos(zeta), math.sin(zeta)
    g = (v[0] * cz + v[1] * sz + v[2], v[3] * cz + v[4] * sz + v[5])
    jac = ((-v[0] * sz + v[1] * cz, dv[0] * cz + dv[1] * sz + dv[2]),
           (-v[3] * sz + v[4] * cz, dv[3] * cz + dv[4] * sz + dv[5]))
    return g, jac


def _polish(trip, zeta, eta, iters=POLISH_ITERS):
    """Damped Gauss-Newton on the two loop equations; returns (zeta, eta, max |residual|, |det J|)."""
    g, jac = _residual(trip, zeta, eta)
    err = max(abs(g[0]), abs(g[1]))
    for _ in range(iters):
        if err <= 1e-16:
            break
        (a, b), (c, dd) = jac
        # (J^T J + mu I) step = -J^T g, mu tiny: Newton when J is regular, bounded near a direct singularity
        jtj = (a * a + c * c, a * b + c * dd, b * b + dd * dd)
        mu = 1e-14 * (jtj[0] + jtj[2]) + 1e-300
        rhs = (-(a * g[0] + c * g[1]), -(b * g[0] + dd * g[1]))
        det = (jtj[0] + mu) * (jtj[2] + mu) - jtj[1] * jtj[1]
        dz = (rhs[0] * (jtj[2] + mu) - jtj[1] * rhs[1]) / det
        de = ((jtj[0] + mu) * rhs[1] - jtj[1] * rhs[0]) / det
        g2, jac2 = _residual(trip, zeta + dz, eta + de)
        err2 = max(abs(g2[0]), abs(g2[1]))
        if not err2 < err:
            break
        zeta, eta, g, jac, err = zeta + dz, eta + de, g2, jac2, err2
    (a, b), (c, dd) = jac
    return zeta, eta, err, abs(a * dd - b * c)


def _zeta_candidates(trip, eta):
    """zeta from Cramer's rule, or from one equation when the two are proportional (D1 E2 - D2 E1 ~ 0)."""
    v, _ = _def_at(trip, eta)
    d1, e1, f1, d2, e2, f2 = v
    den = d1 * e2 - d2 * e1
    nc, ns = e1 * f2 - e2 * f1, d2 * f1 - d1 * f2
    if abs(den) > 1e-8 * math.hypot(d1, e1) * math.hypot(d2, e2):
        sgn = 1.0 if den > 0.0 else -1.0
        return [math.atan2(sgn * ns, sgn * nc)]
    d, e, f = (d1, e1, f1) if math.hypot(d1, e1) >= math.hypot(d2, e2) else (d2, e2, f2)
    r = math.hypot(d, e)
    if r == 0.0 or abs(f) > r * (1.0 + 1e-6):
        return []
    base, g = math.atan2(e, d), math.acos(max(-1.0, min(1.0, -f / r)))
    return [base + g, base - g]


def _zeta_all(trip, eta):
    """Every zeta candidate at an unresolved (double) root of the eliminant: Cramer's rule and both roots of each
    equation alone. Two modes can share eta where the equations are nearly proportional (D1 E2 - D2 E1 ~ 0); the
    eliminant then has two roots closer than rounding resolves, and Cramer's zeta between them fits neither."""
    v, _ = _def_at(trip, eta)
    out = list(_zeta_candidates(trip, eta))
    for d, e, f in (v[:3], v[3:]):
        r = math.hypot(d, e)
        if r > 0.0 and abs(f) <= r * (1.0 + 1e-6):
            base, g = math.atan2(e, d), math.acos(max(-1.0, min(1.0, -f / r)))
            out += [base + g, base - g]
    return out


def _fk_modes(cq, sq, d):
    """Assembly modes (zeta, eta, residual, |det J|) for the joint angles' cosines cq and sines sq; plus a status
    and reason."""
    cf = _k_fk_def(cq, sq, d.constants)
    trip = [cf[3 * j:3 * j + 3] for j in range(6)]
    # eta_c: put the largest sampled |identity| at x = infinity so no root is lost there
    samples = [_elimination(_def_at(trip, 2.0 * math.pi * k / 16)[0]) for k in range(16)]
    kmax = max(range(16), key=lambda k: abs(samples[k]))
    eta_c = 2.0 * math.pi * kmax / 16 - math.pi
    coef = _k_polynomial(trip, eta_c)
    roots, rflags, pstatus = _poly_real_roots(coef, tol_touch=TOUCH_TOL)
    if pstatus & _POLY_STATUS_ZERO:
        return [], STATUS_INDETERMINATE, "the elimination polynomial vanishes identically: a continuum of assemblies"
    modes = []
    for ir, (x, rflag) in enumerate(zip(roots, rflags, strict=True)):
        eta = eta_c + 2.0 * math.atan(x)
        # a touching root is two modes merging (direct singularity): accept it within the fold tolerance, flagged
        touching = bool(rflag & _POLY_FLAG_DOUBLE)
        for zeta in (_zeta_all if touching else _zeta_candidates)(trip, eta):
            z, e, err, jdet = _polish(trip, zeta, eta)
            if not err <= (FK_FOLD_TOL if touching else FK_RESIDUAL_TOL):
                continue
            fold_only = touching and not err <= FK_RESIDUAL_TOL
            pair = _split_fold(trip, z, e) if fold_only else None  # in the fold band only: two modes after all?
            if pair is not None:
                for z2, e2, err2, jdet2 in pair:
                    _add_mode(modes, _wrap_2pi(z2), _wrap_2pi(e2), err2, jdet2, 0, ir)
                continue
            _add_mode(modes, _wrap_2pi(z), _wrap_2pi(e), err, jdet,
                      FLAG_DOUBLE_ROOT | FLAG_SINGULAR_DIRECT if fold_only else 0, ir)
    modes = [m[:5] for m in modes]
    modes.sort(key=lambda m: (m[1], m[0]))
    if not modes:
        return [], STATUS_NO_ASSEMBLY, NO_ASSEMBLY_REASON
    return modes, STATUS_OK, f"{len(modes)} assembly mode(s)"


def _split_fold(trip, zeta, eta):
    """Two regular modes on either side of a point (zeta, eta) polished only into the fold band, or None: polished
    from (zeta, eta) +- s v (v the near-null direction of the loop equations' Jacobian there; s = 1e-6, 1e-5,
    1e-4), kept when both reach a regular residual FK_DUPLICATE_TOL apart. The eliminant cannot tell apart roots
    closer than its rounding (4e-8 in its variable put two modes 2e-5 apart, fuzz seed 917), the loop equations
    can: the merge is confirmed, not assumed."""
    _, ((a, b), (c, d)) = _residual(trip, zeta, eta)
    p, q, r = a * a + c * c, a * b + c * d, b * b + d * d
    lam = 0.5 * (p + r) - math.hypot(0.5 * (p - r), q)  # J^T J's smaller eigenvalue: its vector is v
    v = (q, lam - p) if abs(q) + abs(lam - p) >= abs(lam - r) + abs(q) else (lam - r, q)
    nv = math.hypot(v[0], v[1])
    if not nv > 0.0:
        return None
    v = (v[0] / nv, v[1] / nv)
    for s in (1e-6, 1e-5, 1e-4):
        one = _polish(trip, zeta + s * v[0], eta + s * v[1])
        two = _polish(trip, zeta - s * v[0], eta - s * v[1])
        if (one[2] <= FK_RESIDUAL_TOL and two[2] <= FK_RESIDUAL_TOL
                and max(abs(_wrap_pi(one[0] - two[0])), abs(_wrap_pi(one[1] - two[1]))) >= FK_DUPLICATE_TOL):
            return one, two
    return None


def _add_mode(modes, z, e, err, jdet, f, ir):
    """Add a polished mode to `modes` ([zeta, eta, err, |det J|, flags, root index, fold]) or merge it into one it
    duplicates."""
    # the merge is confirmed, not assumed: a candidate that polishes to a regular residual is a regular
    # mode; only one accepted within the fold band alone (and not split by _split_fold) is the merged pair
    # of a direct singularity: its flags f
    # Modes from a touching root closer than the fold's resolution sqrt(FK_FOLD_TOL) (a mode accepted at
    # residual r is fixed only to ~sqrt(r) along the fold) are the two halves of one double root.
    # Two modes polished to regular residuals are distinct beyond FK_DUPLICATE_TOL however close their roots.
    def same(m):
        near = math.sqrt(FK_FOLD_TOL) if f or m[6] else FK_DUPLICATE_TOL
        return abs(_wrap_pi(m[0] - z)) < near and abs(_wrap_pi(m[1] - e)) < near
    dup = next((m for m in modes if same(m)), None)
    if dup is None:
        modes.append([z, e, err, jdet, f, ir, bool(f)])
    elif dup[5] != ir:  # two roots of the eliminant polish to one mode: they merge (a double root)
        dup[4] |= FLAG_DOUBLE_ROOT | f
    elif max(abs(_wrap_pi(dup[0] - z)), abs(_wrap_pi(dup[1] - e))) >= FK_DUPLICATE_TOL:
        dup[4] |= FLAG_DOUBLE_ROOT | FLAG_SINGULAR_DIRECT  # a fold pair, merged: reported once, flagged
