"""The decomposition's interpreter (_solve): each op solves its joints, recurses into every root.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

import math

import chain_arm_angle  # noqa: F401  (registers its stage, as inlining it does)
import chain_sp6  # noqa: F401
import chain_spatial3  # noqa: F401
import numpy as np
from chain_poe import _between
from chain_points import _direction, _point
from chain_rigid import _add, _apply, _cross, _dot, _inverse, _mv, _norm, _rot, _scale, _screw, _sub
from chain_stages import _OP_STAGES
from chain_stand_in import (
    _PLAN,
    DEGENERATE_EPS,
    DOUBLE_ROOT_TOL,
    FAMILY_ANGLES,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_INVERSE,
    ON_AXIS_TOL,
    SCALE,
    TANGENT_TOL,
)
from chain_subproblems import _orient_rest, _perpendicular, _root_amplification, _sp1, _sp2, _sp3, _sp4


# wristkin: inlined from here
# ---------------------------------------------------------------------------- the decomposition
def _unit_angle(ch, unit, prev):
    """The angle of an orientation unit (one joint, or a parallel group turning as one) at `prev`."""
    u = ch.axes[unit[0]]
    return sum(math.copysign(1.0, _dot(u, ch.axes[m])) * prev[m] for m in unit)


def _solve(ch, g, prev, accept, params=(0.0,)):
    """Run the decomposition on exp(S_1 q_1) ... exp(S_n q_n) = g, handing every candidate (q in the chain's
    order, flags) to `accept`, which verifies and stores it (True when stored). `prev`: the previous solution in
    the chain's order (places a singular family's free angle), or None; `params`: the design's values (an arm
    angle op reads its angle there). Returns whether any op had a root."""
    n = len(ch.kinds)
    q = [0.0] * n
    theta = {}
    stored = [0]
    reached = [False]
    noise = [1.0]  # 1 / g of the near-singular orientation the current candidate went through (STAGE_NOISE)
    # how much its trig stages amplified the input's rounding (_root_amplification): the orientation's family band
    # (its rotation is read through every joint before it; a position pair or single joint reads a point the pose
    # gives to rounding, so their on-axis bands stay at ON_AXIS_TOL)
    amp = [1.0]
    probe, hits = [False], [0]  # a family's existence probed: candidates verified, not stored

    def count():
        """Sets stored so far (while probing: sets that would be)."""
        return hits[0] if probe[0] else stored[0]

    def run_family(k, x, y, flags, place, prev_angle):
        """A singular family from op k on: place(angle) sets its free angle. Without `previous`, the first of
        FAMILY_ANGLES with a verified set. With it, the family is kept exactly where it is kept without it (the grid
        probed first: previous picks the member, never whether the family or the split roots are returned), as
        previous's member when that verifies, else the grid's."""
        if prev_angle is not None and not probe[0]:
            probe[0], hits[0] = True, 0
            for grid_angle in FAMILY_ANGLES:
                place(grid_angle)
                run(k + 1, x, y, flags)
                if hits[0]:
                    break
            probe[0] = False
            if not hits[0]:
                return
            before = stored[0]
            place(prev_angle)
            run(k + 1, x, y, flags)
            if stored[0] == before:  # previous's member verifies nothing: the grid's, already found by the probe
                place(grid_angle)
                run(k + 1, x, y, flags)
            return
        for angle in FAMILY_ANGLES:
            before = count()
            place(angle)
            run(k + 1, x, y, flags)
            if count() > before:
                break

    def _with_split(roots_at, go):
        """A trig stage's roots at the noise-widened band, then, when that band merged two roots into one that
        verified nothing, the two roots at the stage's own band: the noise estimate may be generous (it stands
        for the worst rounding upstream) without losing two real roots it merged (one extra stage solve at most).
        A merged root that verifies stands for both: there the pose fixes the joints only to about its residual
        over sigma_min of J."""
        before = count()
        roots = roots_at(noise[0])
        go(roots)
        if noise[0] > 1.0 and count() == before and len(roots) == 1 and roots[0][1] & FLAG_DOUBLE_ROOT:
            split = roots_at(1.0)
            if len(split) == 2:
                go(split)

    def _orient_set(units, angles):
        for un, ang in zip(units, angles, strict=True):
            if len(un) == 1:
                q[un[0]] = ang
            else:
                theta[un] = ang

    def run(k, x, y, flags):
        if k == len(_PLAN):
            reached[0] = True
            if probe[0]:
                hits[0] += bool(accept(list(q), flags, dry=True))
            else:
                stored[0] += bool(accept(list(q), flags))
            return
        op = _PLAN[k]
        kind = op[0]
        if kind == "begin":
            _, xs, lo, hi = op
            x = _point(ch, xs)
            run(k + 1, x, _apply(_between(ch, q, g, lo, hi), x), flags)
        elif kind in ("first_plane", "last_plane"):
            _, j, jk, ns = op
            nv = _direction(ch, ns)
            h, r = ch.axes[j], ch.points[j]
            if jk == "P":
                den = _dot(nv, h)
                if den == 0.0:  # the planner keeps slides off the plane: only a degenerate input gets here
                    return
                v = _dot(nv, _sub(y, x)) / den
                q[j] = v
                if kind == "first_plane":
                    run(k + 1, x, _sub(y, _scale(h, v)), flags)
                else:
                    run(k + 1, _add(x, _scale(h, v)), y, flags)
                return
            def plane_roots(band):
                if kind == "first_plane":  # n . rot(h, -q)(y - r) = n . (x - r)
                    return [(-t, f) for t, f in _sp4(nv, h, _sub(y, r), _dot(nv, _sub(x, r)), SCALE, band)]
                return _sp4(nv, h, _sub(x, r), _dot(nv, _sub(y, r)), SCALE, band)  # n . rot(h, q)(x - r) = n . (y - r)

            def plane_run(roots):
                outer = amp[0]
                amp[0] = _root_amplification(roots, outer)
                for t, f in roots:
                    q[j] = t
                    e = _screw("R", h, r, t)
                    if kind == "first_plane":
                        run(k + 1, x, _apply(_inverse(e), y), flags | f)
                    else:
                        run(k + 1, _apply(e, x), y, flags | f)
                amp[0] = outer
            _with_split(plane_roots, plane_run)
        elif kind in ("first_dist", "last_dist"):
            _, j, jk, ss, planar = op
            s = _point(ch, ss)
            h, r = ch.axes[j], ch.points[j]
            first = kind == "first_dist"
            moving, other = (y, x) if first else (x, y)
            d = _norm(_sub(other, s))
            if jk == "P":  # |moving -+ v h - s| = d: a quadratic in v
                b = _dot(h, _sub(moving, s)) * (-1.0 if first else 1.0)
                c = _dot(_sub(moving, s), _sub(moving, s)) - d * d
                disc = b * b - c
                if disc < -TANGENT_TOL * SCALE * SCALE:
                    return
                if disc <= DOUBLE_ROOT_TOL * SCALE * SCALE:
                    roots = [(-b, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE)]
                else:
                    roots = [(-b + math.sqrt(disc), 0), (-b - math.sqrt(disc), 0)]
                for v, f in roots:
                    q[j] = v
                    if first:
                        run(k + 1, x, _sub(y, _scale(h, v)), flags | f)
                    else:
                        run(k + 1, _add(x, _scale(h, v)), y, flags | f)
                return
            def dist_run(roots):
                outer = amp[0]
                amp[0] = _root_amplification(roots, outer)
                for t, f in roots:
                    t = -t if first else t
                    q[j] = t
                    e = _screw("R", h, r, t)
                    if first:
                        run(k + 1, x, _apply(_inverse(e), y), flags | f)
                    else:
                        run(k + 1, _apply(e, x), y, flags | f)
                amp[0] = outer
            target = _sub(other, s) if planar else None  # the parts normal to h: a sum of squares (_sp3)
            _with_split(lambda band: _sp3(h, _sub(moving, r), _sub(s, r), d, SCALE, band, target, amp[0]), dist_run)
        elif kind == "pair":  # rot_j rot_k (x - s) = y - s
            _, j, kk, ss = op
            s = _point(ch, ss)
            args = (_sub(y, s), ch.axes[j], _sub(x, s), ch.axes[kk], SCALE)
            before = count()
            for split in (False, True):  # a near-double root's two roots when its merged one verified nothing
                if split and count() > before:
                    break
                for t1, t2, f in _sp2(*args, split=split, family_tol=ON_AXIS_TOL):
                    q[j] = (prev[j] if prev is not None else 0.0) if t1 is None else -t1
                    q[kk] = t2
                    run(k + 1, x, y, flags | f)
        elif kind == "single":
            _, j, jk = op
            h, r = ch.axes[j], ch.points[j]
            if jk == "P":
                q[j] = _dot(h, _sub(y, x))
                run(k + 1, x, y, flags)
                return
            # x or y on the axis (a shoulder family) at ON_AXIS_TOL of the chain's size: the pose fixes q to eps / its
            # offset from the axis, so a wrist centre 6e-14 of the size off the shoulder axis still has its regular sets
            t = _sp1(h, _sub(x, r), _sub(y, r), SCALE * (ON_AXIS_TOL / DEGENERATE_EPS))
            if t is None:
                q[j] = prev[j] if prev is not None else 0.0
                run(k + 1, x, y, flags | FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE)
            else:
                q[j] = t
                run(k + 1, x, y, flags)
        elif kind in _OP_STAGES:  # an op whose kernels the module inlines only when its plan uses them
            def go_on(f, stage_noise=1.0, k=k, x=x, y=y, flags=flags):
                outer = noise[0]
                noise[0] = max(outer, stage_noise)
                run(k + 1, x, y, flags | f)
                noise[0] = outer
            _OP_STAGES[kind](ch, g, prev, op, x, y, q, count, go_on,
                             lambda f, place, angle: run_family(k, x, y, flags | f, place, angle), params)
        elif kind == "linear":
            _, js = op
            a = np.array([ch.axes[j] for j in js]).T
            sol = np.linalg.lstsq(a, np.array(_sub(y, x)), rcond=None)[0]
            for j, v in zip(js, sol, strict=True):
                q[j] = float(v)
            run(k + 1, x, y, flags)
        elif kind == "orient":
            _, units, lo, hi = op
            rd = _between(ch, q, g, lo, hi)[0]
            u = [ch.axes[un[0]] for un in units]
            before_op = count()
            if len(units) == 3:
                v = u[2]
                sols = _sp2(_mv(rd, v), u[0], v, u[1], 1.0, amp=amp[0])
            elif len(units) == 2:
                t1 = _sp1(u[0], u[1], _mv(rd, u[1]), 1.0)
                sols = [(None if t1 is None else -t1, 0.0, 0)]
            else:
                sols = [(0.0, 0.0, 0)]
            for t1, t2, f in sols:
                if len(units) == 1:
                    w = _perpendicular(u[0])
                    t = _sp1(u[0], w, _mv(rd, w), 1.0)
                    _orient_set(units, [0.0 if t is None else t])
                    run(k + 1, x, y, flags | f)
                    continue
                if t1 is not None:
                    _orient_set(units, _orient_rest(u, rd, t1, t2))
                    outer = noise[0]
                    if len(units) == 3:  # g: how far the middle unit turns the last axis off the first
                        g_rel = _norm(_cross(u[0], _mv(_rot(u[1], t2), v)))
                        noise[0] = max(outer, 1.0 / max(g_rel, 1e-300))
                    run(k + 1, x, y, flags | f)
                    noise[0] = outer
                    continue
                # a singular family (the first and last axes line up): the first unit's angle is free. With
                # `previous`, its angle there; else the first of FAMILY_ANGLES for which the rest of the
                # decomposition has a verified solution (the position may depend on it: a parallel group)
                def place(angle, t2=t2):
                    _orient_set(units, _orient_rest(u, rd, -angle, t2))
                run_family(k, x, y, flags | f, place, None if prev is None else _unit_angle(ch, units[0], prev))
            if len(units) == 3 and count() == before_op:
                # near (not at) the singular family the merged root is a family that verifies nothing: its two
                # roots are two sets with every angle defined
                for t1, t2, f in _sp2(_mv(rd, v), u[0], v, u[1], 1.0, split=True, amp=amp[0]):
                    _orient_set(units, _orient_rest(u, rd, t1, t2))
                    outer = noise[0]
                    noise[0] = max(outer, 1.0 / max(_norm(_cross(u[0], _mv(_rot(u[1], t2), v))), 1e-300))
                    run(k + 1, x, y, flags | f)
                    noise[0] = outer
        elif kind == "group_rest":
            _, j, grp = op
            u = ch.axes[grp[0]]
            rest = theta[tuple(grp)] - sum(math.copysign(1.0, _dot(u, ch.axes[m])) * q[m] for m in grp if m != j)
            q[j] = rest * math.copysign(1.0, _dot(u, ch.axes[j]))
            run(k + 1, x, y, flags)

    run(0, None, None, 0)
    return reached[0]


