"""The 3-RSR wrist's leg roots, mirror plane and workspace, shared by the wrist and the SCARA hybrid built on it.

A wristkin runtime source: both mechanisms' generated modules inline it from the marker line on
(derive/runtime_files.py), after their constants and derived kernels; above the marker, what it reads from them
(rsr_stand_in.py: the catalogue's 3-RSR wrist), so that it is linted and tested as it is
(tests/test_rsr_runtime.py)."""

from __future__ import annotations

import math

from rsr_stand_in import (
    _TWO_PI,
    DEGENERATE_EPS,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_INVERSE,
    GIMBAL_EPS,
    SINGULAR_EPS,
    TANGENT_TOL,
    InvalidInput,
    _k_fk_plane,
    _k_fk_plane_cs,
    _k_fk_pose,
    _k_ik_coeffs,
    _vector,
)

# wristkin: inlined from here
_DIRECT_SCALE = 1.5 * math.sqrt(3.0)  # max |S1S2 x S1S3| / L^2 (equilateral triangle on a great circle)


# metres: the largest accepted length (the link L; scara_rsr: also L1, L2, d, d_f and the stroke d3), so products
# of lengths stay finite (C: RSR_LENGTH_MAX / HY_LENGTH_MAX)
LENGTH_MAX = 1e6


def _wrist_design_error(w):
    """Why the wrist part (L, phi_min, phi_max, lbw_min, lbw_max) is invalid, or None."""
    length, phi_min, phi_max, lbw_min, lbw_max = w
    if not 0.0 < length <= LENGTH_MAX:
        return f"L must be in (0, {LENGTH_MAX:g}] m, got {length!r}"
    if not (phi_min < phi_max and phi_max - phi_min < _TWO_PI):
        return f"need phi_min < phi_max < phi_min + 2 pi, got ({phi_min!r}, {phi_max!r})"
    if not (0.0 <= lbw_min < lbw_max <= 2.0 * length):
        return f"need 0 <= lbw_min < lbw_max <= 2 L, got ({lbw_min!r}, {lbw_max!r}) with L = {length!r}"
    return None


def _legs(pose, w):
    """Both roots of each leg equation A_i cos phi + B sin phi = C, with their cosine, sine and residual.

    Returns (roots, flags, conds, reason): roots[i] = ((phi, c, s, residual) for the + and - root) or None when
    leg i cannot reach. cos/sin come algebraically from (A, B, C), so checking a set needs no trigonometry.
    """
    a1, a2, a3, b, c = _k_ik_coeffs(pose, w)
    roots, flags, conds, reasons = [], [], [], []
    for i, a in enumerate((a1, a2, a3)):
        rho = math.hypot(a, b)
        if rho <= DEGENERATE_EPS:  # beta = pi with the leg axis in the swing plane: phi is free or impossible
            free = abs(c) <= DEGENERATE_EPS
            roots.append(((0.0, 1.0, 0.0, abs(c)),) * 2 if free else None)
            flags.append(FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE if free else 0)
            conds.append(0.0)
            if not free:
                reasons.append(f"leg {i + 1}: no solution at beta = pi")
            continue
        u = c / rho
        if abs(u) > 1.0 + TANGENT_TOL:
            roots.append(None)
            flags.append(0)
            conds.append(0.0)
            reasons.append(f"leg {i + 1}: l_bw / (2 L rho) = {u:.6g} exceeds 1")
            continue
        u = max(-1.0, min(1.0, u))
        sg = math.sqrt(1.0 - u * u)
        ca, sa = a / rho, b / rho  # phi = atan2(B, A) +/- acos(u)
        pair = []
        for sgn in (1.0, -1.0):
            cp, sp_ = ca * u - sgn * sa * sg, sa * u + sgn * ca * sg
            pair.append((math.atan2(sp_, cp), cp, sp_, abs(a * cp + b * sp_ - c)))
        roots.append(tuple(pair))
        # conditioning |dF_i/dphi_i| / L = rho sin(acos u) (0 at a tangent root and for a free leg, rho -> 0)
        flags.append((FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE if sg <= math.sqrt(TANGENT_TOL) else 0)
                     | (FLAG_SINGULAR_INVERSE if rho * sg <= SINGULAR_EPS else 0))  # a near-free leg, as FK flags it
        conds.append(rho * sg)
    return roots, flags, conds, "; ".join(reasons)


def _unit_plane(raw, w):
    """(n, h, cond_direct) from N = S1S2 x S1S3 and S1 with n_z >= 0, or None if S1, S2, S3 are collinear."""
    nx, ny, nz, s1x, s1y, s1z = raw
    norm = math.sqrt(nx * nx + ny * ny + nz * nz)
    cond = norm / (_DIRECT_SCALE * w[0] * w[0])
    if cond <= DEGENERATE_EPS:
        return None
    nx, ny, nz = nx / norm, ny / norm, nz / norm
    if nz < 0.0 or (nz == 0.0 and nx * s1x + ny * s1y < 0.0):
        nx, ny, nz = -nx, -ny, -nz
    return (nx, ny, nz, nx * s1x + ny * s1y + nz * s1z), min(1.0, cond)


def _plane_of_set(legs, w):
    """Mirror plane of one leg-root set ((phi, c, s, res) per leg)."""
    return _unit_plane(_k_fk_plane_cs((legs[0][1], legs[1][1], legs[2][1], legs[0][2], legs[1][2], legs[2][2]), w), w)


def _plane(q, w):
    """Mirror plane of a joint triple: (n, h, cond_direct), or None if S1, S2, S3 are collinear."""
    return _unit_plane(_k_fk_plane(q, w), w)


def _pose_of_plane(n):
    """(alpha, beta, l_bw), gimbal flag, and the platform pose [R_W | p_W] (12) of the unit plane (n, h)."""
    nx, ny, nz, h = n
    sxy = math.hypot(nx, ny)
    gimbal = sxy <= GIMBAL_EPS
    alpha = 0.0 if gimbal else math.atan2(ny, nx)
    return (alpha, 2.0 * math.atan2(sxy, nz), 2.0 * h), gimbal, _k_fk_pose(n)


def _leg_cond_inverse(q, pose, w):
    """min over legs of |dF_i/dphi_i| / L (in [0, 1]: A^2 + B^2 <= 1): 0 where the two roots of a leg merge and
    where a leg turns freely (A = B = 0, beta = pi with the leg axis in the swing plane)."""
    a1, a2, a3, b, _ = _k_ik_coeffs(pose, w)
    worst = 1.0
    for a, phi in zip((a1, a2, a3), q, strict=True):
        worst = min(worst, abs(-a * math.sin(phi) + b * math.cos(phi)))
    return worst


def _in_arc(t, lo, hi):
    return lo + (t - lo) % _TWO_PI <= hi


def _leg_range(a, b, w):
    """Range of n . S_i = L (a cos phi + b sin phi) over phi in [phi_min, phi_max] (exact: endpoints + extrema)."""
    length, lo, hi = w[0], w[1], w[2]
    vals = [length * (a * math.cos(p) + b * math.sin(p)) for p in (lo, hi)]
    t0, rho = math.atan2(b, a), length * math.hypot(a, b)
    top = rho if _in_arc(t0, lo, hi) else max(vals)
    bottom = -rho if _in_arc(t0 + math.pi, lo, hi) else min(vals)
    return bottom, top


def _workspace(alpha, beta, w):
    a1, a2, a3, b, _ = _k_ik_coeffs((alpha, beta, 0.0), w)
    lo, hi = 0.5 * w[3], 0.5 * w[4]
    for a in (a1, a2, a3):
        bottom, top = _leg_range(a, b, w)
        lo, hi = max(lo, bottom), min(hi, top)
    return (2.0 * lo, 2.0 * hi) if lo <= hi else None


def gamma_from_azimuth(alpha1, beta):
    """Swing-rotation angle gamma of the wrist at azimuth alpha1 and swing beta (tan gamma = tan alpha1 / cos beta)."""
    alpha1, beta = _vector((alpha1, beta), 2, "(alpha1, beta)")
    return math.atan2(math.sin(alpha1), math.cos(beta) * math.cos(alpha1))


def azimuth_from_gamma(gamma, beta):
    """Exact inverse of gamma_from_azimuth (no curve fit, no bisection).

    alpha1 = atan2(cos beta sin gamma, cos gamma) for beta < 90 deg."""
    gamma, beta = _vector((gamma, beta), 2, "(gamma, beta)")
    if abs(math.cos(beta)) <= GIMBAL_EPS:
        raise InvalidInput("beta = 90 deg: gamma does not determine the azimuth (representation singularity)")
    c = math.cos(beta)  # beyond 90 deg cos beta < 0 flips the quadrant
    return math.atan2(abs(c) * math.sin(gamma), math.copysign(1.0, c) * math.cos(gamma))
