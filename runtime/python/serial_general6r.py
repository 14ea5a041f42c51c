"""A general 6R's stage: every solved joint by elimination (general6r.py, inlined before it), on the axes, points
and product of exponentials its derived kernel gives. The candidates are computed once per prefix of the set index
above the stage's bits and kept in the call's scratch `ws`; set k takes candidate (k >> shift) & mask. Each is
checked on the chain's FK, polished to rounding where the elimination left it off (a near-double root: its two
eigenvalues resolved to sqrt(eps)), kept when it verifies, and dropped as a duplicate of a kept one (within
SAME_SET, or their midpoint on the pose as well: a double root's two eigenvalues polish onto one solution;
_g6_same). The C twin: runtime/c/serial/sr_general6r.c.

A wristkin runtime source: a serial arm's generated module with a general6r stage inlines it from the marker line on
(derive/runtime_files.py), after its constants, derived kernels, stage functions and the sources before it; above the
marker, what it reads from them (serial_stand_in.py: the PUMA-560 stands in for the names), so that it is linted and
tested as it is (tests/test_derived_robot.py)."""

from __future__ import annotations

import _runtime
import numpy as np
from general6r import g6_frames_of, g6_solve_flagged
from serial_fk import _spectrum
from serial_input import _REVOLUTE
from serial_stages import _ws_take
from serial_stand_in import (
    DOUBLE_ROOT_POLISH_TOL,
    FLAG_SINGULAR_INVERSE,
    IK_VERIFY_TOL,
    MAX_IK,
    N_JOINTS,
    SINGULAR_EPS,
    _k_fk,
    _k_jacobian,
    _wrap,
)
from serial_verify import _indistinct, _polish

# wristkin: inlined from here
# the sets are ordered by their first joint that differs by more than this (_g6_order)
G6_ORDER_TOL = 1e-6


# sigma_min / sigma_max of a kept set's Jacobian up to this: the pose is near a singularity, where solutions come
# and go in pairs and a reading can miss a pair (the KR 6 1e-5 from special with its wrist 1e-5 from singular: one
# reading's 8 verified sets, another's 10); every reading is then solved and their sets joined
G6_NEAR_SINGULAR = 1e-3
# why a reading asks for more (_g6_reading's bits): a kept set within G6_NEAR_SINGULAR of singular; an eigenvalue pair
# near the real axis; a candidate that is no solution, or two on one solution
G6_NEAR_SET, G6_NEAR_PAIR, G6_NEAR_ROOTS = 1, 2, 4


def _g6_conditioning(q, dp, joints):
    """sigma_min / sigma_max of the solved joints' Jacobian (a held joint's column left out; serial_fk's _spectrum)."""
    jac = np.array(_k_jacobian(q, dp), dtype=float).reshape(6, N_JOINTS)[:, list(joints)]
    return _spectrum(jac)[1]


def _g6_same(x, err, kept, kept_err, joints, q, pose, dp, floor):
    """Whether candidate x (every joint, residual err) and kept set `kept` (the solved joints' values, residual
    kept_err; the others q's) are one solution: within _runtime.SAME_SET, or the pose cannot tell them apart
    (serial_verify's _indistinct: the merge's midpoint test). Not a bound by sigma_min: the Gram matrix's spectrum
    reads sigma_min / sigma_max below sqrt(eps) as 0 (OpenBLAS's Haswell kernel, the tilted UR5e's q2 1e-6 from
    singular), which merged two solutions of a fold 2e-5 apart, each on the pose to 1e-12, whose midpoint is 1e-10
    off it; the midpoint measures what the pose tells apart at any conditioning."""
    y = list(q)
    for j, v in zip(joints, kept, strict=True):
        y[j] = v
    return _runtime.same_set(x, y, _REVOLUTE) or _indistinct(x, err, y, kept_err, pose, dp, floor)


def _g6_candidates(out, readings, joints, q, pose, dp):
    """The verified, distinct candidates of the readings (shift, reverse, hidden) in turn, sorted (_g6_order): the
    next is tried where none of one's verifies (its equations degenerate at this pose), and once more where their
    count is odd. Real solutions come in pairs: the determinant's real roots, counted with multiplicity, are even in
    number (real coefficients, even degree), so an odd count is a double root the pose cannot split or a solution
    this reading missed (a near-special arm near its singularities: the KR 6 1e-5 from special), which another
    reading, hiding another joint, finds. Not where two of the reading's candidates met in one set (a double root:
    its two eigenvalues, one solution), and once at most: such a pose costs one reading, any other two at most.
    The first pass reads no cluster subspaces (each costs an SVD in C). A reading whose only trouble is an
    eigenvalue pair near the real axis (G6_NEAR_PAIR) is read once more with them, the pair read as a root: such a
    pair is a real double root or a cluster's members that rounding moved off the axis, and this reading's clusters
    hold them; or an ordinary complex pair (the xArm6 shows one within 1e-2 of the axis on 18 % of random poses, which
    cost it every reading with clusters: 15-20x its median call). Near a singularity (a kept set's sigma_min /
    sigma_max within G6_NEAR_SINGULAR, then or in that second read), where a reading can miss a pair of solutions, or
    where the reading's candidates are no solution or meet (the near-special KR 6's far members; numpy lost four of
    its solutions so, C none), every reading is solved again with them."""
    kept, errs, tried_odd, near, clustered = [], [], False, 0, -1
    for i, labelling in enumerate(readings):
        merged, near = _g6_reading(out, labelling, joints, q, pose, dp, kept, errs, False)
        if near == G6_NEAR_PAIR:  # this reading with its clusters; their copies and far members are expected there
            near = _g6_reading(out, labelling, joints, q, pose, dp, kept, errs, True)[1] & G6_NEAR_SET
            clustered = i
        if near or kept and (len(kept) % 2 == 0 or tried_odd or merged):
            break
        tried_odd = bool(kept)
    if near:  # every reading, with its clusters' subspaces (a set kept already is kept once; the one read so already
        for i, labelling in enumerate(readings):  # gives its candidates again: skipped)
            if i != clustered:
                _g6_reading(out, labelling, joints, q, pose, dp, kept, errs, True)
    for i in range(1, len(kept)):  # insertion sort by _g6_order, as the C runtime's (stable)
        item, j = kept[i], i
        while j > 0 and _g6_order(kept[j - 1], item) > 0:
            kept[j] = kept[j - 1]
            j -= 1
        kept[j] = item
    return kept


def _g6_reading(out, labelling, joints, q, pose, dp, kept, errs, clusters):
    """The verified candidates of one reading of the loop appended to kept ((joint values of `joints`, flags), at
    most MAX_IK; their residuals to errs), each unless it is one solution with a
    kept one (_g6_same; then the better fit stands for it); returns how many of its candidates met one of its own
    and the G6_NEAR_* bits of why the reading asks for more (a kept set within G6_NEAR_SINGULAR of singular, an
    eigenvalue pair near the real axis: general6r.py's G6_CLUSTER_IM_TOL, a candidate that is no solution or two on
    one solution):
    out = the stage kernel's axes (18), points (18) and target [R | p] (12); q carries the joints solved before the
    stage (a held joint's value); `clusters`: the elimination reads its clusters' subspaces (general6r.py's
    g6_solve)."""
    axes = np.array(out[:18], dtype=float).reshape(6, 3)
    frames = g6_frames_of(axes, np.array(out[18:36], dtype=float).reshape(6, 3))
    g4 = np.vstack([np.array(out[36:48], dtype=float).reshape(3, 4), [0.0, 0.0, 0.0, 1.0]])
    shift, reverse, hidden = labelling
    size = max(abs(pose[3]), abs(pose[7]), abs(pose[11]))
    target, floor = DOUBLE_ROOT_POLISH_TOL * max(1.0, size), _runtime.fk_rounding(size)
    first, merged = len(kept), 0
    cands, pair = g6_solve_flagged(frames, np.eye(4), g4, shift, bool(reverse), hidden, clusters)
    near = G6_NEAR_PAIR if pair else 0
    for cand in cands:
        x = list(q)
        for j, v in zip(joints, cand, strict=True):
            x[j] = v
        err = max(abs(a - b) for a, b in zip(_k_fk(x, dp), pose, strict=True))
        if not err <= target:
            x, err = _polish(x, pose, dp, target=target)
        if not err <= IK_VERIFY_TOL:
            near |= G6_NEAR_ROOTS  # a root that is no solution: a cluster's far member, or a reading degenerating
            continue
        for j in joints:
            x[j] = _wrap(x[j])
        vals = [x[j] for j in joints]
        ratio = _g6_conditioning(x, dp, joints)
        dup = next((m for m, (other, _) in enumerate(kept)
                    if _g6_same(x, err, other, errs[m], joints, q, pose, dp, floor)), -1)
        if dup >= 0:  # one solution found twice: the better fit stands for it
            if dup >= first:  # two of its roots on one solution: a double root, or a cluster's
                merged += 1
                near |= G6_NEAR_ROOTS
            if err < errs[dup]:
                kept[dup], errs[dup] = (vals, kept[dup][1]), err
            continue
        if len(kept) == MAX_IK:  # more than 16: a degenerate pose's family, the first 16 kept
            continue
        near |= G6_NEAR_SET if ratio <= G6_NEAR_SINGULAR else 0
        kept.append((vals, FLAG_SINGULAR_INVERSE if ratio <= SINGULAR_EPS else 0))
        errs.append(err)
    return merged, near


def _g6_order(a, b):
    """The sets in joint order: by the first joint that differs by more than G6_ORDER_TOL (the C and numpy
    eigensolvers find the roots in different orders; a set's joints agree across them to far less)."""
    for x, y in zip(a[0], b[0], strict=True):
        if abs(x - y) > G6_ORDER_TOL:
            return -1 if x < y else 1
    return 0


def _general6r(kernel, parent, idx, readings, joints, q, c, s, pose, dp, ws):
    """Set k's candidate (ok, flags): `kernel` the stage's (axes, points, target), `parent` the set index's prefix
    above the stage's bits (the candidates are recomputed when it changes), `idx` the candidate, `readings` the
    loop's readings in the order they are tried."""
    cand = _ws_take(ws, parent, lambda: _g6_candidates(kernel(pose, q, c, s, dp), readings, joints, q, pose, dp),
                    idx, joints, q, c, s)
    return (False, 0) if cand is None else (True, cand[1])
