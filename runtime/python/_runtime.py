"""wristkin runtime: the status codes, flags, errors and result types every generated module shares (generated,
do not edit).

@generated-by@

Every mechanism module imports these, so `except wristkin.InvalidInput` catches bad input from any of them and
a `Solutions` of one mechanism is the same class as another's. numpy only; Python >= 3.10. See docs/API.md.
"""

from __future__ import annotations

import copy
import math
import os
from dataclasses import dataclass

import numpy as np

STATUS_OK = 0
STATUS_UNREACHABLE = 1
STATUS_NO_ASSEMBLY = 2
STATUS_INDETERMINATE = 3
STATUS_NAMES = {0: "ok", 1: "unreachable", 2: "no_assembly", 3: "indeterminate"}

FLAG_SINGULAR_INVERSE = 1
FLAG_SINGULAR_DIRECT = 2
FLAG_GIMBAL = 4
FLAG_DOUBLE_ROOT = 8
FLAG_INDETERMINATE = 16
FLAG_PROJECTED = 32  # the input rotation was projected onto SO(3) before solving (deviation in `reason`)
# internal, never in a returned set: a two-root stage's half-gap within its upstream noise of a double root, or a
# several-candidate stage's candidate within MERGE_SPAN of another (the pairs merge_indistinct compares)
FLAG_MERGE_CANDIDATE = 0x10000
# internal, never returned: a wrist within rounding of its family whose member the pose's own entries placed (a
# serial arm's wrist stage); `previous` moves only a family's representative, not such a set
FLAG_READ_MEMBER = 0x20000
FLAG_NAMES = {1: "singular_inverse", 2: "singular_direct", 4: "gimbal", 8: "double_root", 16: "indeterminate",
              32: "projected"}
# An input rotation R with max|R^T R - I| <= ROTATION_PROJECT_TOL is replaced by its polar factor U V^T (the
# nearest rotation in the Frobenius norm) and FLAG_PROJECTED is set; a farther one is rejected. 1e-6 admits
# float32 poses (eps32 ~ 6e-8 per entry) and poses printed with 7+ significant digits; below ROTATION_EXACT_TOL
# (a few hundred ulps) the matrix is a rotation up to rounding and is used as given.
ROTATION_PROJECT_TOL = 1e-6
ROTATION_EXACT_TOL = 1e-13
_TWO_PI = 2.0 * math.pi


class WristkinError(ValueError):
    """Base class of every error a wristkin module raises."""


class InvalidInput(WristkinError):
    """Non-finite, wrongly shaped or out-of-range input."""


class InvalidDesign(WristkinError):
    """Design parameters out of range, or a design that cannot be assembled."""


@dataclass(frozen=True)
class Solutions:
    """Every solution of one IK or FK call: MAX rows, `valid` marks the real ones (NaN rows otherwise)."""

    values: np.ndarray  # (MAX, n); NaN rows where not valid
    valid: np.ndarray  # (MAX,) bool
    flags: np.ndarray  # (MAX,) int, FLAG_* bits
    aux: np.ndarray  # (MAX, naux)
    status: int
    reason: str

    @property
    def count(self) -> int:
        return int(self.valid.sum())

    def __iter__(self):
        return iter(self.values[self.valid])

    def flag_names(self, k: int) -> list:
        return [n for b, n in FLAG_NAMES.items() if int(self.flags[k]) & b]

    def __getattr__(self, name):
        # Only for an attribute not in __dict__: the reason of a result the C path made for an outcome it does not
        # word itself (an unreachable or projected pose, ...). The numpy path words it on first use, so a caller
        # who reads the status alone never pays for it (it cost 30-700x the C call).
        if name == "reason":
            explain = self.__dict__.get("_explain")
            if explain is not None:  # (two threads may both word it: the first text is kept)
                text = self.__dict__.setdefault("reason", explain(self))
                self.__dict__.pop("_explain", None)
                return text
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def __getstate__(self):
        """Pickling and copying take the worded reason, not the pending words."""
        _ = self.reason
        return dict(self.__dict__)


@dataclass(frozen=True)
class BatchSolutions:
    """N calls at once: the fields of Solutions with a leading axis of N (no reasons)."""

    values: np.ndarray  # (N, MAX, n)
    valid: np.ndarray  # (N, MAX)
    flags: np.ndarray  # (N, MAX)
    aux: np.ndarray  # (N, MAX, naux)
    status: np.ndarray  # (N,)

    @property
    def count(self) -> np.ndarray:
        return self.valid.sum(axis=1)


def _stack(results, max_n, n_values, n_aux) -> BatchSolutions:
    n = len(results)
    if not n:
        return BatchSolutions(np.empty((0, max_n, n_values)), np.empty((0, max_n), bool),
                              np.empty((0, max_n), np.int64), np.empty((0, max_n, n_aux)), np.empty(0, np.int64))
    return BatchSolutions(np.stack([r.values for r in results]), np.stack([r.valid for r in results]),
                          np.stack([r.flags for r in results]), np.stack([r.aux for r in results]),
                          np.array([r.status for r in results], dtype=np.int64))


def native(name, inputs_hash):
    """The compiled C solvers (wristkin._native, built by `pip install`) when they were built from the same
    generated files as the module `name` (INPUTS_HASH), else None: the module then runs on numpy.
    WRISTKIN_BACKEND=numpy forces numpy."""
    if os.environ.get("WRISTKIN_BACKEND", "").strip().lower() == "numpy":
        return None
    try:
        from . import _native
    except ImportError:  # a `wristkin derive` folder: the extension beside this runtime (loaded from its path:
        _native = _folder_extension()  # two folders' extensions share a name, not a file)
        if _native is None:
            return None
    if getattr(_native, "INPUTS_HASH", None) != inputs_hash or not hasattr(_native, f"{name}_ik"):
        return None
    return _native


_FOLDER_EXTENSION = []


def _folder_extension():
    """_wristkin_native<EXT_SUFFIX> beside this file, or None."""
    if not _FOLDER_EXTENSION:
        import importlib.machinery
        import importlib.util

        found = None
        here = os.path.dirname(os.path.abspath(__file__))
        for suffix in importlib.machinery.EXTENSION_SUFFIXES:
            path = os.path.join(here, "_wristkin_native" + suffix)
            if os.path.isfile(path):
                try:
                    spec = importlib.util.spec_from_file_location("_wristkin_native", path)
                    found = importlib.util.module_from_spec(spec)
                    spec.loader.exec_module(found)
                except ImportError:
                    found = None
                break
        _FOLDER_EXTENSION.append(found)
    return _FOLDER_EXTENSION[0]


def c_floats(v, shapes=None):
    """v as a C-contiguous float64 array (no copy when it is one) of one of `shapes` (None: any shape), accepting
    what _array accepts (bool, int, float; no strings or complex values); else None: the caller then takes the
    Python path, which validates and explains."""
    if type(v) is not np.ndarray or v.dtype != np.float64:
        try:
            v = _array(v, "")
        except InvalidInput:
            return None
    if shapes is not None and v.shape not in shapes:
        return None
    return v if v.flags.c_contiguous else np.ascontiguousarray(v)


C_CONVERT = -100  # the extension's answer for an input that is not a C-contiguous float64 array


def c_call(fn, x, shapes, *args):
    """fn(x, *args) of the C extension. An input that is not a C-contiguous float64 array of one of `shapes` is
    converted once (c_floats) and the call repeated; None when it cannot be (the Python path then explains)."""
    return c_retry(fn(x, *args), fn, x, shapes, *args)


def c_retry(r, fn, x, shapes, *args):
    """r, the answer of fn(x, *args) the caller already made; when that was C_CONVERT, x converted once and the
    call repeated (None when it cannot be converted: the Python path then explains)."""
    if r.__class__ is int and r == C_CONVERT:
        x = c_floats(x, shapes)
        return None if x is None else fn(x, *args)
    return r


def c_result(reason, most, fixed=None):
    """The last argument of an extension's scalar ik / fk: (Solutions, the reason text for each count 0..most,
    {status: its fixed reason text}). With it the extension returns a finished Solutions wherever these texts are
    the whole explanation (built in C: a third of the call's time went to making it in Python, and a status that
    needs only a fixed text would otherwise take the numpy path); `reason` is a format string of the count n."""
    return (Solutions, tuple(reason.format(n=n) for n in range(most + 1)), dict(fixed or {}))


def c_solutions(r, reason=None):
    """A Solutions from the C path's tuple (summary, values, valid, flags, aux), summary = status | count << 8 |
    projected << 16, when its count is the whole explanation (solved, nothing projected); else None (c_explained
    then has the numpy path word it). `reason` is a format string of the count n ("{n} solution(s)")."""
    summary, values, valid, flags, aux = r
    st = summary & 255
    if (st == STATUS_OK or st == STATUS_INDETERMINATE) and not summary >> 16:
        # the same frozen object its __init__ makes, without six frozen-attribute calls (a third of the call)
        sol = _new_object(Solutions)
        key = (reason, summary >> 8)
        text = _REASONS.get(key)
        if text is None:
            text = (reason or "{n} solution(s)").format(n=summary >> 8)
            if len(_REASONS) < _REASONS_MAX:  # bounded: a reason may carry a per-call number (l_bw)
                _REASONS[key] = text
        sol.__dict__.update(values=values, valid=valid, flags=flags, aux=aux, status=st, reason=text)
        return sol
    return None


def c_explained(r, fn, x, shapes, args, numpy_verb, numpy_args, reason=None,
                worded=(STATUS_OK, STATUS_INDETERMINATE)):
    """The answer of a scalar verb whose extension call fn(x, *args) returned `r` (args end with the result spec,
    or r is the plain tuple): the same Solutions C made, with the reason worded now where it is the count
    (statuses in `worded`, nothing projected), else on first use by numpy_verb(*numpy_args), the numpy path of the
    same call (an unreachable or projected pose, a status only the numpy path words). None when the input is not
    C's (a conversion that fails, an error code): the numpy path then raises the typed error."""
    r = c_retry(r, fn, x, shapes, *args)
    if r.__class__ is Solutions:  # the extension words a count (right where worded) or a status's fixed text
        if r.status in worded or r.status not in (STATUS_OK, STATUS_INDETERMINATE):
            return r
        values, valid, flags, aux, st = r.values, r.valid, r.flags, r.aux, r.status
    elif r.__class__ is tuple:
        if (r[0] & 255) in worded:
            sol = c_solutions(r, reason)
            if sol is not None:
                return sol
        summary, values, valid, flags, aux = r
        st = summary & 255
    else:
        return None
    sol = _new_object(Solutions)
    # the caller's input as it is now (an array or list may be changed in place before the reason is read); a
    # Design is frozen
    snapshot = tuple(a.copy() if a.__class__ is np.ndarray else copy.deepcopy(a) if a.__class__ in _CONTAINERS
                     else a for a in numpy_args)
    sol.__dict__.update(values=values, valid=valid, flags=flags, aux=aux, status=st,
                        _explain=lambda made: _numpy_words(made, numpy_verb, snapshot))
    return sol


def _numpy_words(made, numpy_verb, args):
    """The reason the numpy path gives for the call that made `made`, where it reaches the same outcome (status and
    count); else both outcomes, in words (the two paths part only within their tolerances, near a boundary)."""
    try:
        other = numpy_verb(*args)
    except WristkinError as exc:
        return f"{STATUS_NAMES[made.status]}: {made.count} solution(s) (the numpy path rejects the input: {exc})"
    if other.status == made.status and other.count == made.count:
        return other.reason
    return (f"{STATUS_NAMES[made.status]}: {made.count} solution(s) (the numpy path, asked for the reason, finds "
            f"{STATUS_NAMES[other.status]}: {other.reason})")


_CONTAINERS = (list, tuple, dict)
_REASONS: dict = {}  # (format, count) -> reason text: formatting once per count, not per call
_REASONS_MAX = 256


_new_object = object.__new__


def _array(v, what):
    """A float array from numbers; strings, complex values and other objects are InvalidInput."""
    try:
        raw = np.asarray(v)
    except (TypeError, ValueError) as exc:
        raise InvalidInput(f"{what}: expected numbers, got {v!r}") from exc
    if raw.dtype.kind not in "biuf":  # bool, int, float: no strings, complex, objects, None
        raise InvalidInput(f"{what}: expected real numbers, got {raw.dtype} values ({v!r})")
    return raw.astype(float)


def _vector(v, n, what):
    if v.__class__ in (list, tuple) and len(v) == n and all(x.__class__ is float for x in v):
        # plain floats (a design or joints per call): numpy's conversion costs more than the call it feeds
        if all(math.isfinite(x) for x in v):
            return tuple(v)
        raise InvalidInput(f"{what}: values must be finite, got {list(v)}")
    a = _array(v, what)
    if a.shape != (n,):
        raise InvalidInput(f"{what}: expected {n} numbers, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise InvalidInput(f"{what}: values must be finite, got {a.tolist()}")
    return tuple(float(x) for x in a)


def _rows(a, n, what):
    a = _array(a, what)
    if a.ndim != 2 or a.shape[1] != n:
        raise InvalidInput(f"{what}: expected an (N, {n}) array, got shape {a.shape}")
    return a


def _as_rotation(r, what="pose"):
    """(R, deviation): a finite 3x3 `r` within ROTATION_PROJECT_TOL of SO(3), projected onto it when needed."""
    with np.errstate(all="ignore"):  # huge entries overflow to inf: rejected below, with the deviation
        dev = float(np.max(np.abs(r.T @ r - np.eye(3))))
        det = float(np.linalg.det(r))
    if not dev <= ROTATION_PROJECT_TOL or not det > 0.0:
        raise InvalidInput(f"{what}: the 3x3 block is not a rotation: max|R^T R - I| = {dev:.3g} (accepted up to "
                           f"{ROTATION_PROJECT_TOL:g}, then projected onto SO(3)), det R = {det:.6g}; orthonormalise "
                           "it (e.g. the polar factor U V^T of its SVD) or pass it with more digits")
    if dev <= ROTATION_EXACT_TOL:
        return r, 0.0
    u, _, vt = np.linalg.svd(r)
    return u @ vt, dev


def _projected_note(dev):
    """Text appended to a result's reason when the input rotation was projected."""
    return f"input rotation projected onto SO(3) (max|R^T R - I| was {dev:.3g})" if dev > 0.0 else ""
# 2 pi = _TWO_PI_HI + _TWO_PI_LO + O(6e-33) and floor(2 pi 2^_TWO_PI_FIX_BITS), from pi at high precision
# (derive/angle_reduction.py): remainder(a, 2.0 * math.pi) reduces against fl(2 pi), 2.45e-16 short of 2 pi per turn
_TWO_PI_HI = 6.283185307179586
_TWO_PI_LO = 2.4492935982947064e-16
_TWO_PI_FIX_BITS = 1280
_TWO_PI_FIX = int(
    "6487ed5110b4611a62633145c06e0e68948127044533e63a0105df531d89cd9128a5043cc71a026ef7ca8cd9e69d218d"
    "98158536f92f8a1ba7f09ab6b6a8e122f242dabb312f3f637a262174d31bf6b585ffae5b7a035bf6f71c35fdad44cfd2"
    "d74f9208be258ff324943328f6722d9ee1003e5c50b1df82cc6d241b0e2ae9cd348b1fd47e9267afc1b2ae91ee51d6cb"
    "0e3179ab1042a95dcf6a9483b84b4b36b", 16)
_ONE_TURN_MAX = 9.4  # < 3 pi: one turn from the reduced angle


def _wrap(a):
    """The angle a - 2 pi k in [-pi, pi] nearest a, correctly rounded for every finite double (as the C runtime's
    wk_wrap); NaN and inf give NaN. |a| <= fl(pi) < pi is already reduced; up to _ONE_TURN_MAX, |a| - fl(2 pi) is
    exact (Sterbenz) and the second part of 2 pi is subtracted once; beyond, exact integer arithmetic against 2 pi
    to 200 bits below the last bit of k 2 pi: the reduced angle of a double is at least 4.7e-19 (the closest
    multiple of pi / 2, 6381956970095103 x 2^797), so the truncated 2 pi moves it by under 2^-90 of itself."""
    x = abs(a)
    if not x > math.pi:
        return a
    if x <= _ONE_TURN_MAX:
        r = (x - _TWO_PI_HI) - _TWO_PI_LO
    elif x <= 1.7976931348623157e308:
        m, ex = math.frexp(x)
        e = ex - 53  # x = mant 2^e exactly
        bits = abs(e) + 200
        num = int(math.ldexp(m, 53)) << (e + bits)  # x 2^bits, an integer
        two_pi = _TWO_PI_FIX >> (_TWO_PI_FIX_BITS - bits)  # floor(2 pi 2^bits)
        k = (2 * num + two_pi) // (2 * two_pi)
        r = (num - k * two_pi) / (1 << bits)  # int / int is correctly rounded
    else:
        return math.nan
    return -r if a < 0.0 else r


def _wrap_all(a):
    """_wrap of every element of an array (the one-turn case vectorised, the rare longer ones one by one)."""
    a = np.asarray(a, dtype=float)
    x = np.abs(a)
    one = (x - _TWO_PI_HI) - _TWO_PI_LO
    one = np.where(a < 0.0, -one, one)
    out = np.where(x > math.pi, one, a)
    far = np.flatnonzero(x > _ONE_TURN_MAX)  # NaN stays NaN from the line above
    if far.size:
        flat = out.reshape(-1)
        flat[far] = [_wrap(float(v)) for v in a.reshape(-1)[far]]
    return out


def _design_values(params, names, default):
    """A sequence in `names` order, a dict (missing names take the default) or None -> finite tuple."""
    if params is None:
        return default
    if isinstance(params, dict):
        unknown = sorted(set(params) - set(names))
        if unknown:
            raise InvalidDesign(f"unknown design parameter(s) {unknown}; expected {names}")
        params = tuple(params.get(n, v) for n, v in zip(names, default, strict=True))
    try:
        return _vector(params, len(names), "design")
    except InvalidInput as exc:
        raise InvalidDesign(str(exc)) from exc


MERGE_ULPS = 16.0  # the FK of 6-7 joints rounds to a few eps of the pose's size
MERGE_SPAN = 1e-3  # sets farther apart in a joint are distinct at any curvature above 1e-7: not compared


def fk_rounding(scale):
    """The FK's own rounding of a pose of size `scale` (max |p|): MERGE_ULPS eps max(1, scale)."""
    return MERGE_ULPS * 2.220446049250313e-16 * max(1.0, scale)


SAME_SET = 1e-9  # two valid sets within this in every joint are one (wristkin_common.h's WK_SAME_SET)
CARRIED_MOVE = 1e-6  # a set its checks moved further than this from its stages' answer was carried (WK_CARRIED_MOVE)


def set_gap(x, y, revolute=None, stop=math.inf):
    """The largest |x[j] - y[j]| of two sets of joints, revolute differences (revolute[j] true, every joint when
    `revolute` is None) wrapped to [-pi, pi]; the scan stops at the first joint beyond `stop`, whose gap it returns
    (the C runtime's wk_set_gap)."""
    gap = 0.0
    for j, (a, b) in enumerate(zip(x, y, strict=True)):
        d = float(b) - float(a)
        d = abs(_wrap(d) if revolute is None or revolute[j] else d)
        if not d <= gap:
            gap = d
            if not gap <= stop:
                break
    return gap


def same_set(x, y, revolute=None):
    """Whether two sets are one solution by identity: within SAME_SET in every joint (set_gap)."""
    return set_gap(x, y, revolute, SAME_SET) <= SAME_SET


def pair_indistinct(x, rx, y, ry, revolute, refit, floor):
    """Whether sets x and y (residuals rx, ry) are one solution the pose cannot tell apart, merge_indistinct's test:
    within MERGE_SPAN in every joint, and their midpoint, refitted by one step of at most an eighth of their span
    (`refit(mid, max_step, accept)`), within `floor` of their residuals. Returns (the refitted midpoint's residual,
    the midpoint) when they are, else None (the C runtime's wk_pair_indistinct)."""
    span = set_gap(x, y, revolute, MERGE_SPAN)
    if not span <= MERGE_SPAN:
        return None
    mid = []
    for j, (a, b) in enumerate(zip(x, y, strict=True)):
        rev = revolute is None or revolute[j]
        m = float(a) + 0.5 * (_wrap(float(b) - float(a)) if rev else float(b) - float(a))
        mid.append(_wrap(m) if rev else m)
    accept = max(rx, ry) + floor
    rm = refit(mid, 0.125 * span, accept)  # a midpoint on the pose takes no step
    return (rm, mid) if rm <= accept else None


def drop_carried(values, valid, flags, aux, carried, revolute):
    """A set its checks carried far from its stages' answer (the polish on a 5-joint arm's inconsistent candidate, a
    calibrated arm's search along the near-null direction) may have reached another branch's solution: one flagged in
    `carried` is dropped where it is within SAME_SET in every joint (revolute differences wrapped) of another valid
    set, an uncarried one or a carried one before it (the C runtime's wk_drop_carried). Returns the count dropped."""
    dropped = 0
    for k in range(len(valid)):
        if not (valid[k] and carried[k]):
            continue
        for j in range(len(valid)):
            if j == k or not valid[j] or (carried[j] and j > k):
                continue
            if same_set(values[k], values[j], revolute):
                valid[k], flags[k] = False, 0
                values[k] = np.nan
                aux[k] = np.nan
                dropped += 1
                break
    return dropped


def merge_indistinct(values, valid, flags, aux, masks, revolute, refit, scale, candidates_only=True):
    """Two valid sets that differ only in the branch of one stage (k ^ k2 within one of `masks`: a two-root stage's
    bit, or the bits of a stage that gives several candidates at once, a spatial 3R's or the general 6R's) are one
    solution, a double root, when the pose cannot tell them apart: a point between them fits the pose as well as they
    do. At a fold of the chain the residual grows with the square of the distance along the fold, so the joints
    solved before the stage, off by rounding, push the two computed roots ~1e-6 apart while both fit the pose to
    rounding; their midpoint misses it only by that upstream error, which one Gauss-Newton step far shorter than the
    span removes. Two distinct roots leave the midpoint off by curvature x (span / 2)^2, which a short step cannot
    remove. So: `refit(midpoint, span / 8)` (the residual after one such step, the midpoint updated in place) within
    MERGE_ULPS eps max(1, scale) of the pair's residuals. The pair becomes whichever of the two and the refitted
    midpoint fits best, flagged a double root (in place; the C runtime's wk_merge_indistinct). Pairs are taken mask
    by mask, k ascending, then k2 > k ascending (a single bit's pairs are (k, k | bit)). `candidates_only`: only pairs
    both flagged FLAG_MERGE_CANDIDATE (their stage's roots within its upstream noise, or within MERGE_SPAN of
    another candidate of the same stage) are compared (a square chain; one of fewer than six joints carries the
    pose's own inconsistency into its stages, which their amplification does not bound: every pair within
    MERGE_SPAN). The flag is cleared from every set. Returns the sets removed."""
    floor = fk_rounding(scale)
    candidate = [bool(int(f) & FLAG_MERGE_CANDIDATE) for f in flags]
    for k in range(len(flags)):
        flags[k] = int(flags[k]) & ~FLAG_MERGE_CANDIDATE  # internal: never returned
    removed = 0
    for m in masks:
        for k in range(len(values)):
            if k & m == m or not valid[k]:  # every mask bit set: no k2 above k
                continue
            sub = 0
            while sub := (sub - m) & m:  # k2: k's bits outside the mask with each nonzero submask, ascending
                k2 = (k & ~m) | sub
                if k2 <= k or k2 >= len(values) or not (valid[k] and valid[k2]):
                    continue
                if candidates_only and not (candidate[k] and candidate[k2]):
                    continue  # apart beyond their stage's noise: distinct
                if int(flags[k]) & int(flags[k2]) & FLAG_INDETERMINATE:
                    # two members of a one-parameter family (a UR's wrist at q5 = pi, its elbow 2.7e-5 from
                    # straight): the refit's step moves along the family, so the midpoint's fit proves nothing, and
                    # each is a solution (merged, `previous`'s member came back 2.7e-5 off: seed 413261)
                    continue
                y, rx, ry = values[k2], float(aux[k][0]), float(aux[k2][0])
                one = pair_indistinct(values[k], rx, y, ry, revolute, refit, floor)
                if one is None:
                    continue
                rm, mid = one
                if rm < rx and rm < ry:
                    values[k], aux[k][0] = mid, rm
                elif ry < rx:
                    values[k], aux[k][0] = y.copy(), ry
                flags[k] |= flags[k2] | FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE
                valid[k2], flags[k2], aux[k2][0] = False, 0, math.nan
                values[k2] = math.nan
                removed += 1
    return removed


def select(solutions: Solutions, previous=None, lower=None, upper=None, weights=None, joint_kinds=None) -> int:
    """Index of the solution to use, or -1: valid and within [lower, upper] (limits compared as given). With
    `previous`, the nearest such set (weighted, wrapped for revolute joints; ties by plain distance, then index):
    a singular flag is information, not a reason to jump to a farther set. Without it, the first non-singular
    such set, else the first one. `joint_kinds`: "R" (wrapped) or "P" per value, default every value revolute;
    each module's own `select` passes its JOINT_KINDS."""
    vals = solutions.values
    n = vals.shape[1]
    lo = None if lower is None else np.asarray(_vector(lower, n, "lower"))
    hi = None if upper is None else np.asarray(_vector(upper, n, "upper"))
    prev = None if previous is None else np.asarray(_vector(previous, n, "previous"))
    wts = np.ones(n) if weights is None else np.asarray(_vector(weights, n, "weights"))
    kinds = tuple("R" * n if joint_kinds is None else joint_kinds)
    if len(kinds) != n or not set(kinds) <= {"R", "P"}:
        raise InvalidInput(f"joint_kinds: expected {n} of 'R' / 'P', got {joint_kinds!r}")
    rev = np.array([k == "R" for k in kinds])
    cand = [int(k) for k in np.flatnonzero(solutions.valid)
            if (lo is None or np.all(vals[k] >= lo)) and (hi is None or np.all(vals[k] <= hi))]
    if not cand:
        return -1
    if prev is None:
        regular = [k for k in cand if not solutions.flags[k] & (FLAG_SINGULAR_INVERSE | FLAG_SINGULAR_DIRECT)]
        return (regular or cand)[0]

    def dist(k):
        diff = np.abs(np.where(rev, _wrap_all(_wrap_all(vals[k]) - _wrap_all(prev)), vals[k] - prev))
        return float(np.sum(wts * diff)), float(np.sum(diff)), k

    return min(cand, key=dist)


def solve_square(a, b, rel_pivot):
    """a^-1 b for a square a by elimination with partial pivoting, or None when a pivot is at or below rel_pivot of
    the largest entry (near rank deficiency, a zeroed column: the caller's least squares decide). The C runtime's
    wk_square_solve step for step, so that both languages polish to the same bits."""
    n = len(b)
    m = [[float(a[i][j]) for j in range(n)] + [float(b[i])] for i in range(n)]
    big = max(abs(m[i][j]) for i in range(n) for j in range(n))
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(m[i][k]) > abs(m[p][k]):
                p = i
        if not abs(m[p][k]) > rel_pivot * big:
            return None
        if p != k:
            m[k], m[p] = m[p], m[k]
        for i in range(k + 1, n):
            f = m[i][k] / m[k][k]
            row, pivot = m[i], m[k]
            for j in range(k + 1, n + 1):
                row[j] -= f * pivot[j]
    x = [0.0] * n
    for i in range(n - 1, -1, -1):
        acc = m[i][n]
        for j in range(i + 1, n):
            acc -= m[i][j] * x[j]
        x[i] = acc / m[i][i]
    return x
