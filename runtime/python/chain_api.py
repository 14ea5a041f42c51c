"""Input handling, FK, Jacobian and IK of a user robot's interpreted module (its branches, limits and command line:
own_api.py, its pose forms: pose_forms.py).

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from chain_design import _JOINT_SHAPE, _POSE_SHAPES, _design
from chain_poe import _fk_chain, _full_chain, _held, _reversed
from chain_rigid import _as_rt, _compose, _inverse, _to_matrix
from chain_solve import _solve
from chain_stages import _OP_READERS
from chain_stand_in import (
    _ARM_ANGLE,
    _AXES,
    _C_FK,
    _C_FK_BATCH,
    _C_FK_MATRIX,
    _C_IK,
    _C_IK_BATCH,
    _C_JACOBIAN,
    _DEGENERATE_HELD,
    _FK_RESULT,
    _FREE,
    _HOME,
    _IDEAL_AXES,
    _IDEAL_HOME,
    _IDEAL_POINTS,
    _IK_RESULT,
    _PLAN,
    _POINTS,
    _REVERSED,
    CALIBRATED,
    CONTROLS,
    FLAG_INDETERMINATE,
    FLAG_PROJECTED,
    FLAG_SINGULAR_INVERSE,
    GEOMETRY_TOL,
    IK_VERIFY_TOL,
    JOINT_KINDS,
    JOINT_NAMES,
    LENGTH_MAX,
    MAX_IK,
    N_JOINTS,
    POLISH_TOL,
    ROTATION_TOL,
    SINGULAR_EPS,
    STATUS_INDETERMINATE,
    STATUS_OK,
    STATUS_UNREACHABLE,
    BatchSolutions,
    InvalidDesign,
    InvalidInput,
    Solutions,
    _array,
    _as_rotation,
    _k_fk,
    _k_jacobian,
    _projected_note,
    _rows,
    _stack,
    _vector,
    _wrap,
)
from chain_verify import _frame_error, _polish, _polish_read, _pose_error, _ratio, _ratio_of
from pose_forms import pose_matrix


# wristkin: inlined from here
# ---------------------------------------------------------------------------- input handling
def _pose(pose):
    """(the target as (R, t), rotation deviation): validated, the rotation projected onto SO(3) when it deviates
    by at most ROTATION_PROJECT_TOL."""
    a = pose_matrix(pose)
    if not np.max(np.abs(a[3] - (0.0, 0.0, 0.0, 1.0))) <= ROTATION_TOL:
        raise InvalidInput(f"pose: last row must be (0, 0, 0, 1) (within {ROTATION_TOL:g}), got {a[3].tolist()}")
    if not np.max(np.abs(a[:3, 3])) <= LENGTH_MAX:
        raise InvalidInput(f"pose: translation must be within {LENGTH_MAX:g} m, got {a[:3, 3].tolist()}")
    r, dev = _as_rotation(a[:3, :3])
    return (tuple(tuple(float(x) for x in row) for row in r), tuple(float(x) for x in a[:3, 3])), dev


def _joints(joints, what="joints"):
    q = _vector(joints, N_JOINTS, what)
    for v, kind, name in zip(q, JOINT_KINDS, JOINT_NAMES, strict=True):
        if kind == "P" and not abs(v) <= LENGTH_MAX:
            raise InvalidInput(f"{what}: prismatic joint {name} must be within {LENGTH_MAX:g} m, got {v!r}")
    return tuple(_wrap(v) if kind == "R" else v for v, kind in zip(q, JOINT_KINDS, strict=True))


def _frames(d):
    return _as_rt(d.base), _as_rt(d.tool)


_TRUE = _full_chain(_AXES, _POINTS, _HOME)
_IDEAL = _full_chain(_IDEAL_AXES, _IDEAL_POINTS, _IDEAL_HOME)


# ---------------------------------------------------------------------------- forward kinematics
# The robot's derived kernels (_k_fk, _k_jacobian: its product of exponentials with the constants folded, printed
# above by derive/families/chain/kernels.py) answer FK and the Jacobian; the chain's table (_fk_chain) serves the
# solver's own chains (held, reversed, ideal).
def _rt12(v):
    """[R | p] (12 entries, row-major) as a rigid transform."""
    return ((v[0], v[1], v[2]), (v[4], v[5], v[6]), (v[8], v[9], v[10])), (v[3], v[7], v[11])


def _trig_of(q):
    """cos and sin of the revolute joints (a prismatic joint's are unused: 1, 0), taken once for every kernel."""
    return ([math.cos(v) if k == "R" else 1.0 for v, k in zip(q, JOINT_KINDS, strict=True)],
            [math.sin(v) if k == "R" else 0.0 for v, k in zip(q, JOINT_KINDS, strict=True)])


def _fk_full(q, d, trig=None):
    """base . chain . tool (trig: the joints' cos and sin when the caller has them)."""
    base, tool = _frames(d)
    c, s = trig or _trig_of(q)
    return _compose(_compose(base, _rt12(_k_fk(q, c, s))), tool)


def _jacobian_held(full, trig):
    """The chain's Jacobian in the solver's joints: the kernel's columns without the free joint's (held, the
    solver's chain has the description's base and end frame, so its Jacobian is these columns)."""
    jac = np.array(_k_jacobian(full, *trig)).reshape(6, N_JOINTS)
    return np.delete(jac, _FREE, axis=1) if _FREE >= 0 else jac


def _jacobian_full(q, d):
    """Jacobian of base . chain . tool: the chain's columns rotated into the base frame, the tool's offset in
    the linear rows."""
    base, tool = _frames(d)
    c, s = _trig_of(q)
    jc = np.array(_k_jacobian(q, c, s)).reshape(6, N_JOINTS)
    r = np.array(base[0])
    chain_end = _rt12(_k_fk(q, c, s))
    end = _compose(chain_end, tool)[1]  # chain frame: the tool point
    t_end = np.array(chain_end[1])
    lin, ang = jc[:3], jc[3:]
    lin = lin + np.cross(ang.T, np.array(end) - t_end).T
    return np.vstack([r @ lin, r @ ang])


def fk(joints, design=None) -> Solutions:
    """The end pose (one solution; values = entries of [R | p]); aux = manipulability sqrt(det J J^T) (J^T J for
    fewer than 6 joints); flagged singular when sigma_min / sigma_max of J is at or below SINGULAR_EPS."""
    d = _design(design)
    if d.native is not None:
        sol = _C_FK(joints, d.native, _FK_RESULT)
        if sol.__class__ is not Solutions:  # a conversion, or words
            sol = _runtime.c_explained(sol, _C_FK, joints, _JOINT_SHAPE, (d.native, _FK_RESULT),
                                       _fk_numpy, (joints, d))
        if sol is not None:
            return sol
    return _fk_numpy(joints, d)


def _fk_numpy(joints, d):
    """fk on the numpy path (also what words the reason of an answer from C that needs one)."""
    q = _joints(joints)
    t = _fk_full(q, d)
    values = np.array([[*t[0][0], t[1][0], *t[0][1], t[1][1], *t[0][2], t[1][2]]])
    jac = _jacobian_full(q, d)
    s = np.linalg.svd(jac, compute_uv=False)
    ratio = float(s[-1] / s[0]) if s[0] > 0.0 else 0.0
    man = float(np.prod(s))
    flags = np.array([FLAG_SINGULAR_INVERSE if ratio <= SINGULAR_EPS else 0], dtype=np.int64)
    return Solutions(values, np.array([True]), flags, np.array([[man]]), STATUS_OK, "1 pose")


def fk_matrix(joints, design=None) -> np.ndarray:
    """The end pose as a 4x4 homogeneous matrix."""
    d = _design(design)
    if d.native is not None:
        t = _C_FK_MATRIX(joints, d.native)
        if t.__class__ is not np.ndarray:
            t = _runtime.c_retry(t, _C_FK_MATRIX, joints, _JOINT_SHAPE, d.native)
        if t.__class__ is np.ndarray:  # else an error: the Python path explains
            return t
    return _to_matrix(_fk_full(_joints(joints), d))


def fk_batch(joints, design=None) -> BatchSolutions:
    """FK over rows of an (N, n) array."""
    d = _design(design)
    if d.native is not None:
        q = _runtime.c_floats(joints, None)
        if q is not None and q.ndim == 2 and q.shape[1] == N_JOINTS:
            n = q.shape[0]
            out = (np.empty((n, 1, 12)), np.empty((n, 1), bool), np.empty((n, 1), np.int64), np.empty((n, 1, 1)),
                   np.empty(n, np.int64))
            if _C_FK_BATCH(q, d.native, *out, N_JOINTS) >= 0:
                return BatchSolutions(*out)
    q = _rows(joints, N_JOINTS, "joints")
    return _stack([fk(row, d) for row in q], 1, 12, 1)


def jacobian(joints, design=None) -> np.ndarray:
    """Geometric Jacobian (6 x n): linear velocity of the end frame's origin first, base frame."""
    d = _design(design)
    if d.native is not None:
        jac = _C_JACOBIAN(joints, d.native)
        if jac.__class__ is not np.ndarray:
            jac = _runtime.c_retry(jac, _C_JACOBIAN, joints, _JOINT_SHAPE, d.native)
        if jac.__class__ is np.ndarray:  # else an error: the Python path explains
            return jac
    return _jacobian_full(_joints(joints), d)



if _ARM_ANGLE:  # an S-R-S arm whose run-time parameter is its arm angle (chain_arm_angle.py)
    def arm_angle(joints, design=None) -> float:
        """The arm angle of joint values: where they put the elbow on its circle about the shoulder-wrist line (0 in
        the plane of the first axis and that line, on the side the axis points to; positive about the line from the
        shoulder to the wrist). ik(fk_matrix(q), [arm_angle(q)]) returns q among its sets."""
        q = _joints(joints)
        return _OP_READERS["arm_angle"](_solver_chains(_design(design))[0], _PLAN[1], q)

# ---------------------------------------------------------------------------- inverse kinematics
def _solver_chains(d):
    """(ideal chain, true chain) the decomposition reads: free joint held, maybe reversed (built once when no
    free joint makes them depend on the call)."""
    if _FREE < 0 and _STATIC_SOLVER:
        return _STATIC_SOLVER[0]
    ideal, true = _IDEAL, _TRUE
    if _FREE >= 0:
        ideal, true = _held(ideal, _FREE, d.params[0]), _held(true, _FREE, d.params[0])
    if _REVERSED:
        ideal, true = _reversed(ideal), _reversed(true)
    if _FREE < 0:
        _STATIC_SOLVER.append((ideal, true))
    return ideal, true


_STATIC_SOLVER = []


def _full_joints(qc, index, d):
    """A solution of the solver's chain (values in its order) as the description's joint values, wrapped."""
    full = [0.0] * N_JOINTS
    for v, i in zip(qc, index, strict=True):
        full[i] = v
    if _FREE >= 0:
        full[_FREE] = d.params[0]
    return [_wrap(v) if k == "R" else v for v, k in zip(full, JOINT_KINDS, strict=True)]


def _same(a, b):
    return all((abs(_wrap(x - y)) if k == "R" else abs(x - y)) <= 1e-9
               for x, y, k in zip(a, b, JOINT_KINDS, strict=True))


def _compensated(ideal, true, qc, target_rt, prev_c):
    """A calibrated robot's candidate whose polish failed (near a singularity the ideal geometry's answer is ~1e-7 /
    sigma_min off, outside Gauss-Newton's reach): the ideal chain's solution, nearest qc, of the pose it must reach
    for the true chain to reach target_rt at the same joints, target_rt E(qc) with E = F_true(qc)^-1 F_ideal(qc).
    E changes by ~ deviation x the joints' change, so that solution is the true one up to ~1e-7 of its error: the
    closed-form stages do near the singularity what the polish cannot. None when the ideal chain has none."""
    t2 = _compose(target_rt, _compose(_inverse(_fk_chain(true, qc)), _fk_chain(ideal, qc)))
    raw = []

    def take(q, f, dry=False):
        q = [_wrap(v) if k == "R" else v for v, k in zip(q, ideal.kinds, strict=True)]
        if not _pose_error(ideal, q, t2)[0] <= IK_VERIFY_TOL:
            return False
        if not dry:
            raw.append(q)
        return True
    _solve(ideal, _compose(t2, _inverse(ideal.home)), prev_c, take)

    def gap(q):
        return max(abs(_wrap(a - b)) if k == "R" else abs(a - b) for a, b, k in zip(q, qc, ideal.kinds, strict=True))
    return min(raw, key=gap, default=None)


def ik(pose, design=None, previous=None) -> Solutions:
    """Every IK solution (at most MAX_IK), each verified by FK on the true chain (and polished there when the
    decomposition used ideal axes). A singular family is returned once: its member nearest `previous` in the
    free angle when given, else with that angle 0."""
    d = _design(design)
    if d.native is not None:
        prev = None if previous is None else _runtime.c_floats(previous, _JOINT_SHAPE)
        if prev is not None or previous is None:
            sol = _C_IK(pose, d.native, prev, _IK_RESULT)
            if sol.__class__ is not Solutions:  # a conversion, or words
                sol = _runtime.c_explained(sol, _C_IK, pose, _POSE_SHAPES, (d.native, prev, _IK_RESULT),
                                           _ik_numpy, (pose, d, previous))
            if sol is not None:
                return sol
    return _ik_numpy(pose, d, previous)


def _ik_numpy(pose, d, previous):
    """ik on the numpy path (also what words the reason of an answer from C that needs one)."""
    target, dev = _pose(pose)
    prev = None if previous is None else _joints(previous, "previous")
    for v, why in _DEGENERATE_HELD:
        if abs(_wrap(d.params[0] - v)) <= GEOMETRY_TOL:
            raise InvalidDesign(f"{JOINT_NAMES[_FREE]} = {d.params[0]!r} (held): within {GEOMETRY_TOL:g} of {v!r}, "
                                f"where {why}; hold it further from that value")
    base, tool = _frames(d)
    g_chain = _compose(_compose(_inverse(base), target), _inverse(tool))  # the chain's end frame
    ideal, true = _solver_chains(d)
    target_rt = _inverse(g_chain) if _REVERSED else g_chain  # the end frame of the chain the solver reads
    g = _compose(target_rt, _inverse(ideal.home))  # its product of exponentials
    prev_c = None if prev is None else [prev[i] for i in ideal.index]
    values = np.full((MAX_IK, N_JOINTS), np.nan)
    aux = np.full((MAX_IK, 1), np.nan)
    valid = np.zeros(MAX_IK, dtype=bool)
    flags = np.zeros(MAX_IK, dtype=np.int64)
    found = []

    # the true solver chain, read as the C runtime reads it: through the derived kernels where it is the description
    # with the free joint held (same base and end frame), from the reversed chain's table otherwise
    def held_fk(qc):
        full = _full_joints(qc, ideal.index, d)
        return _rt12(_k_fk(full, *_trig_of(full)))

    def held_jacobian(qc):
        full = _full_joints(qc, ideal.index, d)
        return _jacobian_held(full, _trig_of(full))

    def true_error(qc):
        return _pose_error(true, qc, target_rt)[0] if _REVERSED else _frame_error(held_fk(qc), target_rt)

    def polish(qc):
        if _REVERSED:
            return _polish(true, qc, target_rt)
        return _polish_read(held_fk, held_jacobian, len(true.kinds), qc, target_rt)

    def accept(qc, f, dry=False):
        """Verify a candidate on the true chain (polished there when needed), deduplicate, flag, store (`dry`: say
        whether it would be stored)."""
        if len(found) >= MAX_IK:
            return False
        qc = [_wrap(v) if k == "R" else v for v, k in zip(qc, ideal.kinds, strict=True)]
        # the common case first: a set at rounding level (POLISH_TOL) by the module's own FK (the robot's derived
        # kernel, base . chain . tool) needs neither the solver chain's check nor a polish. Above it the verdicts
        # stay the two checks' (the solver chain's frame, then the module's): a set near the tolerance passes one
        # and fails the other (a reversed chain reads T^-1's entries), and which one decides whether a family's
        # member verifies
        full = _full_joints(qc, ideal.index, d)
        trig = _trig_of(full)
        err = _frame_error(_fk_full(full, d, trig), target)
        exact = err <= POLISH_TOL
        if not exact:
            err = true_error(qc)
            if err > POLISH_TOL:  # to rounding, not merely to the tolerance: near a singularity a set within
                # IK_VERIFY_TOL may be residual / sigma_min off (an offset wrist 1e-6 from its singularity: 2e-6 rad)
                qc, err = polish(qc)
            if CALIBRATED and not err <= IK_VERIFY_TOL:  # once per candidate: no retry loop (a second and third
                # compensation found 7 more of 168 near-singular sets of the calibrated KR 6 at 3x the time)
                near = _compensated(ideal, true, qc, target_rt, prev_c)
                if near is not None:
                    qc, err = polish(near)
            if not err <= IK_VERIFY_TOL:
                return False
            full = _full_joints(qc, ideal.index, d)
            trig = _trig_of(full)
            # the residual reported and checked is the module's own FK (fk_matrix) of the returned set: the
            # solver's chain (held, maybe reversed: T^-1's entries) and base . chain . tool round differently, and
            # the tool's lever scales an orientation error, so a set within IK_VERIFY_TOL there can miss it here;
            # such a set is polished on to POLISH_TOL and kept only if it then meets IK_VERIFY_TOL
            err = _frame_error(_fk_full(full, d, trig), target)
            if err > IK_VERIFY_TOL:
                qc, _ = polish(qc)
                full = _full_joints(qc, ideal.index, d)
                trig = _trig_of(full)
                err = _frame_error(_fk_full(full, d, trig), target)
                if not err <= IK_VERIFY_TOL:
                    return False
        if any(_same(full, other) for other, _, _ in found):
            return False
        # the solver chain's conditioning: read from the kernel where that chain is the description's with the
        # free joint held (same base and end frame), from the reversed chain's table otherwise
        if (_ratio(true, qc) if _REVERSED else _ratio_of(_jacobian_held(full, trig))) <= SINGULAR_EPS:
            f |= FLAG_SINGULAR_INVERSE
        if dry:
            return True
        found.append((full, f, err))
        return True

    reached = _solve(ideal, g, prev_c, accept, d.params)
    for k, (full, f, err) in enumerate(found[:MAX_IK]):
        values[k], valid[k], flags[k], aux[k] = full, True, f | (FLAG_PROJECTED if dev else 0), err
    note = _projected_note(dev)
    if valid.any():
        status = STATUS_INDETERMINATE if np.any(flags & FLAG_INDETERMINATE) else STATUS_OK
        return Solutions(values, valid, flags, aux, status, "; ".join([f"{int(valid.sum())} solution(s)"] +
                                                                      ([note] if note else [])))
    why = ("no branch passes the FK check" if reached else "a subproblem has no real solution (outside the "
           "workspace)")
    if N_JOINTS - (1 if _FREE >= 0 else 0) < 6:
        why += f"; this chain controls {CONTROLS} only"
    return Solutions(values, valid, flags, aux, STATUS_UNREACHABLE, "pose not reachable: " + why +
                     (f"; {note}" if note else ""))


def ik_batch(poses, design=None) -> BatchSolutions:
    """IK over a stack of poses: shape (N, 4, 4), (N, 3, 4), or (N, 12) / (N, 16) rows (what fk_batch returns)."""
    a = _array(poses, "poses")
    if not (a.ndim == 3 and a.shape[1:] in ((4, 4), (3, 4))) and not (a.ndim == 2 and a.shape[1] in (12, 16)):
        raise InvalidInput(f"poses: expected an (N, 4, 4), (N, 3, 4), (N, 12) or (N, 16) array, got shape {a.shape}")
    d = _design(design)
    if d.native is not None:
        n, c = a.shape[0], np.ascontiguousarray(a)
        out = (np.empty((n, MAX_IK, N_JOINTS)), np.empty((n, MAX_IK), bool), np.empty((n, MAX_IK), np.int64),
               np.empty((n, MAX_IK, 1)), np.empty(n, np.int64))
        if _C_IK_BATCH(c, d.native, *out, c[0].size if n else 12) >= 0:
            return BatchSolutions(*out)
    return _stack([ik(x, d) for x in a], MAX_IK, N_JOINTS, 1)


def _branch_chain(d):
    """The chain the named branches are read on (own_api.branch_of): the decomposition's ideal one."""
    return _solver_chains(d)[0]


def _fk_design(q):
    """The design `fk` takes with joints q given in full on the command line: the free joint's value, or the arm
    angle's (own_api.main)."""
    return [q[_FREE]] if _FREE >= 0 else ([arm_angle(q)] if _ARM_ANGLE else None)
