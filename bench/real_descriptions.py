"""Nine robots as their makers' description packages publish them (example-robot-data, in the bench extra: UR3, UR5,
UR10, Unitree Z1, Kinova j2s6s200, SO-100, Franka Panda, xArm7, TALOS left arm), each derived from the file as
shipped (transmissions, gazebo blocks, mimic grippers and all) and checked three ways in one run:

* FK against an independent product of the URDF's own transforms (tests/reference/chain.urdf_fk: its own XML
  reading and 4 x 4 products), max |T - T_ref| over random joints;
* IK: the generating joints among the sets (within 1e-7 rad) for random poses, every set reproducing its pose;
* EAIK (its own decomposition from the same axes): the number of sets it returns equals ours, and its sets
  reproduce the pose on our FK.

Run from the repository root:  .venv/bin/python bench/real_descriptions.py [--n 100]
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

# name -> (file under example-robot-data's robots/, base, tip, free joint)
ROBOTS = {
    "ur3": ("ur_description/urdf/ur3_robot.urdf", "base_link", "tool0", None),
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "base_link", "tool0", None),
    "ur10": ("ur_description/urdf/ur10_robot.urdf", "base_link", "tool0", None),
    "z1": ("z1_description/urdf/z1.urdf", "link00", "link06", None),
    "kinova_j2s6s200": ("kinova_description/robots/kinova.urdf", "j2s6s200_link_base", "j2s6s200_end_effector", None),
    "so100": ("so_arm_description/urdf/so100.urdf", "base", "gripper", None),
    "panda": ("panda_description/urdf/panda.urdf", "panda_link0", "panda_hand", "panda_joint7"),
    "xarm7": ("xarm_description/urdf/xarm7.urdf", "link_base", "link_eef", "joint4"),
    "talos_left_arm": ("talos_data/robots/talos_left_arm.urdf", "arm_left_1_link", "arm_left_7_link", None),
}


def robots_dir() -> Path:
    try:
        import cmeel  # noqa: F401 - example-robot-data installs under cmeel.prefix
    except ImportError:
        pass
    for p in map(Path, sys.path):
        cand = p / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
        if cand.is_dir():
            return cand
    raise SystemExit("example-robot-data is not installed: pip install -e '.[bench]'")


def check_robot(name: str, n: int) -> dict:
    from own_robots import _check, _hp  # noqa: F401 - the peers' axes, as the own-robot bench builds them
    from reference import chain as ref

    from derive import own_robot
    from derive.pipeline import default_jobs

    rel, base, tip, free = ROBOTS[name]
    file = robots_dir() / rel
    out = Path(tempfile.mkdtemp(prefix=f"wk_real_{name}_"))
    t0 = time.perf_counter()
    own_robot.derive(file, out, name=name, base=base, tip=tip, free=free, progress=lambda _: None, native=False,
                     jobs=default_jobs())
    derive_s = time.perf_counter() - t0
    m = own_robot.import_solver(out, name)
    r = ref.urdf_fk(file, base, tip)
    rng = np.random.default_rng(11)
    fk_err, missing, worst = 0.0, 0, 0.0
    joints = []
    for _ in range(n):
        q = np.array([rng.uniform(max(lo, -math.pi), min(hi, math.pi)) for lo, hi in r.limits])
        if m._FREE >= 0:
            q[m._FREE] = 0.0
        d = [q[m._FREE]] if m._FREE >= 0 or m._ARM_ANGLE else None
        T = m.fk_matrix(q, d)
        fk_err = max(fk_err, float(np.max(np.abs(T - r(q)))))
        sol = m.ik(T, d)
        gaps = [max(abs(math.remainder(a - b, 2 * math.pi)) if k == "R" else abs(a - b)
                    for a, b, k in zip(v, q, m.JOINT_KINDS, strict=True)) for v in sol]
        missing += not gaps or min(gaps) > 1e-7
        for v in sol:
            worst = max(worst, float(np.max(np.abs(m.fk_matrix(v, d) - T))))
        joints.append(q)
    poses = [m.fk_matrix(q, [q[m._FREE]] if m._FREE >= 0 or m._ARM_ANGLE else None) for q in joints]
    ours = [m.ik(T, [0.0] if m._FREE >= 0 or m._ARM_ANGLE else None).count for T in poses]
    eaik = eaik_counts(m, poses)
    same = None if eaik is None or isinstance(eaik, str) else sum(a == b for a, b in zip(eaik[0], ours, strict=True))
    return {"robot": name, "file": rel, "joints": m.N_JOINTS, "free": free or "-", "derive_s": derive_s,
            "decomposition": m.DECOMPOSITION.split(":")[0], "fk_err": fk_err, "missing": missing, "ik_err": worst,
            "sets": sum(ours) / len(ours), "eaik_same": same, "eaik_err": None if same is None else eaik[1],
            "eaik_note": eaik if isinstance(eaik, str) else "", "n": n}


def eaik_counts(m, poses):
    """(EAIK's set count per pose, the worst pose error of its sets on our FK), or a note why not."""
    try:
        from eaik.IK_HP import HPRobot
    except Exception as exc:  # noqa: BLE001 - not installed
        return f"EAIK not installed ({exc.__class__.__name__})"
    from own_robots import _check, _hp

    H, P, R = _hp(m, 0.0)
    try:
        bot = HPRobot(H, P)
    except Exception as exc:  # noqa: BLE001
        return f"EAIK refused the robot: {exc}"

    def solve(T):
        t = T.copy()
        t[:3, :3] = T[:3, :3] @ R.T
        s = bot.IK(t)
        return [q for q, ls in zip(s.Q, s.is_LS, strict=True) if not ls]
    err, counts = _check(solve, m, poses, 0.0)
    return counts, err


def report(n: int = 100) -> str:
    rows = [check_robot(k, n) for k in ROBOTS]
    lines = [f"Robots as shipped by their description packages (example-robot-data), {n} random poses each:", "",
             "| robot | joints (free) | decomposition | derive s | FK vs URDF product | generating joints missed | "
             "worst set residual | sets / pose | EAIK: same count / N (its worst residual) |",
             "|---|---|---|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        e = (f"{r['eaik_same']}/{r['n']} ({r['eaik_err']:.0e})" if r["eaik_same"] is not None else r["eaik_note"])
        lines.append(f"| {r['robot']} | {r['joints']} ({r['free']}) | {r['decomposition']} | {r['derive_s']:.1f} | "
                     f"{r['fk_err']:.0e} | {r['missing']} | {r['ik_err']:.0e} | {r['sets']:.2f} | {e} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100)
    print(report(ap.parse_args(argv).n))
    return 0


if __name__ == "__main__":
    sys.exit(main())
