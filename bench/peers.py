"""Peer kinematics libraries on the Corke PUMA-560 (standard DH), for side-by-side benchmarks.

Run from the repository root:  .venv/bin/python bench/peers.py [--n 1000] [--json PATH]

None of these is a runtime dependency of wristkin; each peer is optional and skipped with a note
when it does not import. Install for benchmarking:  .venv/bin/pip install eaik ik-geo pin

Every peer is built from ``tests/reference/dh.py`` (MECHANISMS["puma560"]) and verified against
its ``fk`` before it is timed: ``max_err`` is the largest |[R | p] entry| error of any returned
non-least-squares IK solution (or of the peer's FK) over the N poses. Poses are ``fk`` of joints
uniform in [-pi, pi)^6 (seeded), so every pose is reachable and generically has 8 IK branches.

Timings: time.perf_counter around a Python loop of single calls (so they include the Python binding
overhead), a warm-up pass, best of 3 repeats, reported as microseconds per call.

Peer notes / API gotchas:

* EAIK (``eaik.IK_DH.DhRobot(alpha, a, d)``): takes standard DH directly, argument order
  (alpha, a, d); ``IK(T4x4)`` returns an ``IKSolution`` with ``.Q`` (k x 6), ``.is_LS`` (k bools),
  ``.num_solutions()``. Poses are plain 4x4 base->tool transforms (same as ``dh.fk``).
* ik-geo (``ik_geo.Robot.spherical_two_parallel(H, P)``): product-of-exponentials input, H (6 x 3)
  unit axes and P (7 x 3) offsets at q = 0, tool orientation at q = 0 taken as the identity. So
  (1) the DH tool rotation M = R_6^0(0) must be factored out: pass R_6^0 M^T; (2) its Python
  binding takes AND returns rotation matrices TRANSPOSED (row-major / column-major mix-up):
  pass (R M^T)^T to ``get_ik`` and transpose what ``forward_kinematics`` returns; (3) the P
  reference points must be chosen so that intersecting axes really share a point (the wrist
  centre for axes 4, 5, 6): using the DH origins o_{i-1} as points gives P[4] != 0 and the
  "spherical" solvers silently return wrong (least-squares) answers. Here the point on axis i
  is o_{i-1} + d_i z_{i-1}, the foot of the common normal to axis i+1. Tiny (< 1e-12) entries
  of H and P are zeroed. The family constructor is not checked against H, P by the library.
* pinocchio (``pin``): no analytic IK (``ik_us`` is None). The DH chain becomes revolute-Z joints
  whose placement in the parent joint frame is Tz(d_{i-1}) Tx(a_{i-1}) Rx(alpha_{i-1}) (identity for
  joint 1) plus an OP_FRAME "tool" on joint 6 at Tz(d6) Tx(a6) Rx(alpha6). FK is
  ``framesForwardKinematics``; Jacobian is ``computeJointJacobians`` + ``getFrameJacobian`` in
  LOCAL_WORLD_ALIGNED (matches ``dh.geometric_jacobian``: linear first, then angular).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from timing import per_call

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT / "tests") not in sys.path:
    sys.path.insert(0, str(ROOT / "tests"))

from reference import dh  # noqa: E402

NAME = "puma560"


# --------------------------------------------------------------------------------------------
# Shared helpers
# --------------------------------------------------------------------------------------------


def sample(n: int, seed: int = 7) -> tuple[np.ndarray, np.ndarray]:
    """(joints n x 6, poses n x 4 x 4) with joints uniform in [-pi, pi)."""
    q = np.random.default_rng(seed).uniform(-math.pi, math.pi, (n, 6))
    return q, np.array([dh.fk(NAME, qi) for qi in q])


def per_call_us(fn, args: list, repeats: int = 3) -> float:
    """Best-of-``repeats`` microseconds per call of fn(arg) over args (bench/timing.py)."""
    return per_call(fn, args, repeats, warmup=min(len(args), 50)) * 1e6


def check_ik(solve, joints: np.ndarray, poses: np.ndarray) -> dict:
    """Verify an IK ``solve(T) -> list of (q, is_ls)`` against dh.fk.

    Returns max_err over exact (non-LS) solutions, how many poses lacked the generating q (within
    1e-6, angles wrapped), and the histogram of exact-solution counts.
    """
    max_err, missing, counts = 0.0, 0, {}
    for q0, T in zip(joints, poses, strict=True):
        exact = [np.asarray(q, dtype=float) for q, ls in solve(T) if not ls]
        counts[len(exact)] = counts.get(len(exact), 0) + 1
        for q in exact:
            max_err = max(max_err, dh.pose_error(NAME, q, T))
        if not any(dh.joint_distance(NAME, q0, q) < 1e-6 for q in exact):
            missing += 1
    return {"max_err": max_err, "missing_q": missing, "counts": dict(sorted(counts.items()))}


def compare_with_reference(solve, poses: np.ndarray, n: int = 20) -> int:
    """Number of the first n poses where the peer's exact solution set differs from dh.ik_reference."""
    bad = 0
    for T in poses[:n]:
        ref = dh.ik_reference(NAME, T)
        got = [dh.wrap_joints(NAME, q) for q, ls in solve(T) if not ls]
        same = len(ref) == len(got) and all(any(dh.joint_distance(NAME, r, g) < 1e-6 for g in got) for r in ref)
        bad += not same
    return bad


def _dh_arrays():
    rows = dh.numeric_rows(NAME)
    return (np.array([r[0] for r in rows]), np.array([r[1] for r in rows]), np.array([r[2] for r in rows]))


def _skipped(name: str, exc: BaseException) -> dict:
    return {"name": name, "ik_us": None, "fk_us": None, "max_err": None, "note": f"skipped: {exc!r}"}


# --------------------------------------------------------------------------------------------
# Peers
# --------------------------------------------------------------------------------------------


def peer_eaik(joints: np.ndarray, poses: np.ndarray) -> dict:
    name = "EAIK (DhRobot)"
    try:
        import eaik  # noqa: F401
        from eaik.IK_DH import DhRobot
    except Exception as exc:  # noqa: BLE001 - any import failure means "skip"
        return _skipped(name, exc)
    a, alpha, d = _dh_arrays()
    bot = DhRobot(alpha, a, d)

    def solve(T):
        s = bot.IK(T)
        return list(zip(s.Q, s.is_LS, strict=True))

    chk = check_ik(solve, joints, poses)
    fk_err = max(float(np.max(np.abs(bot.fwdKin(q) - T))) for q, T in zip(joints, poses, strict=True))
    ref_diff = compare_with_reference(solve, poses)
    ik_us = per_call_us(bot.IK, list(poses))
    fk_us = per_call_us(bot.fwdKin, list(joints))
    t0 = time.perf_counter()
    bot.IK_batched(list(poses), num_worker_threads=2)
    batched_us = (time.perf_counter() - t0) / len(poses) * 1e6
    return {"name": name, "ik_us": ik_us, "fk_us": fk_us, "max_err": max(chk["max_err"], fk_err),
            "note": (f"family {bot.getKinematicFamily()}; solution counts {chk['counts']}; generating q missing in "
                     f"{chk['missing_q']}/{len(poses)}; differs from ik_reference on {ref_diff}/20; "
                     f"IK_batched(2 threads) {batched_us:.2f} us/pose; fk err {fk_err:.1e}")}


def poe_from_dh() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(H 6x3, P 7x3, M 3x3) product-of-exponentials data of the PUMA at q = 0 (see module doc)."""
    rows = dh.numeric_rows(NAME)
    Ts = [np.eye(4), *dh.frames(NAME, np.zeros(6))]
    H = np.array([Ts[i][:3, 2] for i in range(6)])
    pts = [Ts[i][:3, 3] + rows[i][2] * Ts[i][:3, 2] for i in range(6)]
    P = np.array([pts[0], *(pts[i + 1] - pts[i] for i in range(5)), Ts[6][:3, 3] - pts[5]])
    H[np.abs(H) < 1e-12] = 0.0
    P[np.abs(P) < 1e-12] = 0.0
    return H, P, Ts[6][:3, :3]


def peer_ik_geo(joints: np.ndarray, poses: np.ndarray) -> dict:
    name = "ik-geo (spherical_two_parallel)"
    try:
        from ik_geo import Robot
    except Exception as exc:  # noqa: BLE001
        return _skipped(name, exc)
    H, P, M = poe_from_dh()
    bot = Robot.spherical_two_parallel(H, P)

    def solve(T):
        return bot.get_ik((T[:3, :3] @ M.T).T, T[:3, 3])  # binding wants R transposed

    def fkin(q):
        R, p = bot.forward_kinematics(q)
        T = np.eye(4)
        T[:3, :3] = np.asarray(R).T @ M  # binding returns R transposed
        T[:3, 3] = p
        return T

    chk = check_ik(solve, joints, poses)
    fk_err = max(float(np.max(np.abs(fkin(q) - T))) for q, T in zip(joints, poses, strict=True))
    ref_diff = compare_with_reference(solve, poses)
    ik_us = per_call_us(solve, list(poses))
    fk_us = per_call_us(lambda q: bot.forward_kinematics(q), list(joints))
    # the untransposed call, to document the gotcha
    wrong = bot.get_ik(poses[0][:3, :3] @ M.T, poses[0][:3, 3])
    wrong_err = max((dh.pose_error(NAME, q, poses[0]) for q, _ in wrong), default=float("nan"))
    return {"name": name, "ik_us": ik_us, "fk_us": fk_us, "max_err": max(chk["max_err"], fk_err),
            "note": (f"solution counts {chk['counts']}; generating q missing in {chk['missing_q']}/{len(poses)}; "
                     f"differs from ik_reference on {ref_diff}/20; fk err {fk_err:.1e}; ik_us includes the "
                     f"R M^T transpose in Python; untransposed R gives err {wrong_err:.2f}")}


def pinocchio_model():
    """(pin module, model, tool frame id) for the PUMA DH chain."""
    import pinocchio as pin

    rows = dh.numeric_rows(NAME)

    def se3(a, alpha, d):
        T = dh.dh_matrix(a, alpha, d, 0.0)
        return pin.SE3(T[:3, :3].copy(), T[:3, 3].copy())

    model = pin.Model()
    parent = 0
    placement = pin.SE3.Identity()
    for i, (a, alpha, d, _th, _kind) in enumerate(rows):
        parent = model.addJoint(parent, pin.JointModelRZ(), placement, f"theta{i + 1}")
        model.appendBodyToJoint(parent, pin.Inertia.Zero(), pin.SE3.Identity())
        placement = se3(a, alpha, d)
    fid = model.addFrame(pin.Frame("tool", parent, placement, pin.FrameType.OP_FRAME))
    return pin, model, fid


def peer_pinocchio(joints: np.ndarray, poses: np.ndarray) -> dict:
    name = "pinocchio"
    try:
        pin, model, fid = pinocchio_model()
    except Exception as exc:  # noqa: BLE001
        return _skipped(name, exc)
    data = model.createData()
    fk_err = jac_err = 0.0
    for q, T in zip(joints, poses, strict=True):
        pin.framesForwardKinematics(model, data, q)
        fk_err = max(fk_err, float(np.max(np.abs(data.oMf[fid].homogeneous - T))))
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        J = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
        jac_err = max(jac_err, float(np.max(np.abs(J - dh.geometric_jacobian(NAME, q)))))

    def fk_call(q):
        pin.framesForwardKinematics(model, data, q)
        return data.oMf[fid]

    def jac_call(q):
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        return pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)

    qs = [np.ascontiguousarray(q) for q in joints]
    fk_us = per_call_us(fk_call, qs)
    jac_us = per_call_us(jac_call, qs)
    fk_only_us = per_call_us(lambda q: pin.forwardKinematics(model, data, q), qs)
    return {"name": name, "ik_us": None, "fk_us": fk_us, "jac_us": jac_us, "max_err": max(fk_err, jac_err),
            "note": (f"no analytic IK; fk = framesForwardKinematics (+ oMf read); forwardKinematics alone "
                     f"{fk_only_us:.2f} us; jac = computeJointJacobians + updateFramePlacements + getFrameJacobian"
                     f"(LOCAL_WORLD_ALIGNED) {jac_us:.2f} us; fk err {fk_err:.1e}, jacobian err {jac_err:.1e}")}


PEERS = [peer_eaik, peer_ik_geo, peer_pinocchio]


def run_all(n: int = 1000, seed: int = 7) -> list[dict]:
    joints, poses = sample(n, seed)
    return [peer(joints, poses) for peer in PEERS]


def _fmt(x) -> str:
    return "-" if x is None else (f"{x:.2f}" if x >= 0.01 else f"{x:.1e}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="number of random poses / joint vectors")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--json", type=Path, default=None, help="also write the results here")
    args = ap.parse_args(argv)
    results = run_all(args.n, args.seed)
    print(f"PUMA-560, {args.n} random poses; us per call (Python loop)\n")
    print("| peer | IK us | FK us | max err | note |\n| --- | ---: | ---: | ---: | --- |")
    for r in results:
        err = "-" if r["max_err"] is None else f"{r['max_err']:.1e}"
        print(f"| {r['name']} | {_fmt(r['ik_us'])} | {_fmt(r['fk_us'])} | {err} | {r['note']} |")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
