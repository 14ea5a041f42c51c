"""Subproblem 6 for the interpreted plan's sp6 op: the chain-free core (sp6.py) with the chain's tolerances, then
joint l about the group's axis and the rest of the plan.

A wristkin runtime source: every user robot's generated module whose plan has an sp6 op inlines it from the marker
line on (derive/runtime_files.py), after the robot's constants and sp6.py; above the marker, what it reads from them
and from the other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

from chain_points import _direction
from chain_rigid import _cross, _dot, _mm, _mt, _mtv, _mv, _norm, _rot, _sub
from chain_stages import _OP_STAGES
from chain_stand_in import (
    DEGENERATE_EPS,
    DOUBLE_ROOT_TOL,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_INVERSE,
    ON_AXIS_TOL,
    SCALE,
    STAGE_NOISE,
    TANGENT_TOL,
)
from chain_subproblems import _sp1
from sp6 import _merged, _sp6_core, _sp6_split

# wristkin: inlined from here
# the core's tolerances (sp6._sp6_core): the chain's, with subproblem 4's bands as _trig widens them for noise 1
SP6_TOLS = (SCALE, DEGENERATE_EPS, max(DOUBLE_ROOT_TOL, 2.0 * STAGE_NOISE), max(TANGENT_TOL, STAGE_NOISE), ON_AXIS_TOL)


def _sp6(nv, h0, p0, h4, p4, d0, e0, g, h5):
    """(q0, q4, flags, order) of subproblem 6 (sp6._sp6_core) with the chain's tolerances."""
    return _sp6_core(nv, h0, p0, h4, p4, d0, e0, g, h5, SP6_TOLS)


def _sp6_stage(ch, g, prev, op, x, y, q, count, go_on, family, params=()):
    """Joints j and k of subproblem 6 (the op ("sp6", j, k, l, n)), then l about the group's axis; a merged
    near-double root that verified nothing is split into its two roots."""
    _, j, kk, ll, ns = op
    nv = _direction(ch, ns)
    h0, r0, h4, r4, h5 = ch.axes[j], ch.points[j], ch.axes[kk], ch.points[kk], ch.axes[ll]
    rg = g[0]
    p0, p4, d0, g5 = _sub(y, r0), _sub(x, r4), _dot(nv, r4) - _dot(nv, r0), _mv(rg, h5)  # g5: the group's axis

    def sp6_set(q0, q4, f, order, may_split=True):
        # the group keeps n: n^T R4 R5 = n^T R0^T Rg, so rot(h5, -q5) (R4^T n) = (R0^T Rg)^T n
        a = _mtv(_rot(h4, q4), nv)
        t5 = _sp1(h5, a, _mtv(_mm(_mt(_rot(h0, q0)), rg), nv), 1.0)
        q[j], q[kk] = q0, q4
        before = count()
        if t5 is not None:
            q[ll] = -t5
            # near the wrist singularity (a = R4^T n near h5, g = |h5 x a|) q5, read from a's small part off h5,
            # carries q4's error over g: q4 from the quartic and Newton on its equations carries eps / g, so q5
            # eps / g^2 (`order` 2), and the later stages' bands grow by 1 / g^2 (was: an elbow 9.4e-5 rad from
            # straight behind |sin q5| = 3e-6 saw u 1.3e-7 beyond its band, and the pose was called unreachable);
            # q4 from the split carries ~eps, q5 eps / g (`order` 1: a band of 1 / g^2 there merged the elbow's two
            # branches 1e-9 rad from the singularity)
            g_rel = _norm(_cross(h5, a))
            go_on(f, 1.0 / max(g_rel ** order, 1e-300))
        else:  # the wrist singularity: q5 and the group turn about one direction (a family); q5 from
            # `previous`, else the first of FAMILY_ANGLES with a verified set (it moves the position)
            def place(angle):
                q[ll] = angle
            family(f | FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE, place, None if prev is None else prev[ll])
        if count() == before and may_split and f & FLAG_SINGULAR_INVERSE:
            # a merged near-double root that verified nothing: the two roots it merged
            pair = _sp6_split(nv, h0, p0, h4, p4, d0, g5, h5, q0, q4, SP6_TOLS)
            for s0, s4 in pair:
                sp6_set(s0, s4, (f & ~FLAG_DOUBLE_ROOT) | _merged(pair) | FLAG_SINGULAR_INVERSE, 1, may_split=False)

    for q0, q4, f, order in _sp6(nv, h0, p0, h4, p4, d0, 0.0, g5, h5):
        sp6_set(q0, q4, f, order)


_OP_STAGES["sp6"] = _sp6_stage
