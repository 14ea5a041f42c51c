"""Bring-your-own-robot benchmark: `wristkin derive` time per robot and IK per call, side by side with EAIK and
ik-geo on the same robots, in one run.

Run from the repository root:  .venv/bin/python bench/own_robots.py [--n 200] [--json PATH]

For every URDF in tests/robots/ (the free joint of the 7-joint arm held, as IKFast does; the iiwa14 also with its
arm angle as the parameter, solved at 0.3 rad):

* derive        wall time of own_robot.derive (read, derive with every check, emit Python + C + CasADi, audit
                with its 100 round trips), one run; IKFast's published generation times (16 s to 950 s per robot,
                UR5 55 min, some never finish) are quoted, not measured here
* wristkin py   the emitted Python solver's ik(T) (numpy / math only), best of 3, microseconds per call
* wristkin C    the emitted C solver (its derived straight-line stages) called in a C loop (-O2), best of 5
* EAIK          eaik.IK_HP.HPRobot(H, P) (its own decomposition from the same axes), ik(T) from Python
* ik-geo        ik_geo.Robot.<family>(H, P) chosen by the decomposition wristkin found (6R only)

Every peer is checked before it is timed: the solutions it returns (not least-squares) must reproduce the pose
(max |[R | p]| error) and their number is compared with wristkin's on the same poses. Poses: FK of joints
uniform in (-pi, pi] (seeded), so every pose is reachable. The machine is printed with the table.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from timing import per_call

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
ROBOTS = ROOT / "tests" / "robots"
FREE = {"iiwa14": "a3"}
ARM_ANGLE_ROBOTS = ("iiwa14",)  # also benched with --redundancy arm-angle
ARM_ANGLE = 0.3  # rad: the arm angle every such pose is solved at
C_FLAGS = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def _peer_points(axes, points, kinds):
    """Points on the axes a POE peer needs: the foot of the common normal with the next axis, so that axes that
    meet share their point (zero offsets between them, as EAIK and ik-geo detect intersections)."""
    out = [np.array(p, dtype=float) for p in points]
    n = len(axes)
    for i in range(n):
        j = i + 1 if i + 1 < n else i - 1
        a, b = np.array(axes[i]), np.array(axes[j])
        c = np.cross(a, b)
        if kinds[i] != "R" or np.linalg.norm(c) < 1e-9:
            continue
        d = np.array(points[j]) - np.array(points[i])
        ab = float(a @ b)
        s = (d @ a - ab * (d @ b)) / (1 - ab * ab)
        out[i] = np.array(points[i]) + s * a
    return out


def _hp(m, free_value=None):
    """(H, P, R_home) of the module's ideal chain (free joint held), for the POE peers."""
    axes, points, home = np.array(m._IDEAL_AXES), np.array(m._IDEAL_POINTS), np.array(m._IDEAL_HOME)
    kinds = list(m.JOINT_KINDS)
    if m._FREE >= 0:
        f = m._FREE
        ch = m._held(m._IDEAL, f, free_value)
        axes, points, kinds = np.array(ch.axes), np.array(ch.points), list(ch.kinds)
        home = np.vstack([np.hstack([np.array(ch.home[0]), np.array(ch.home[1])[:, None]]), [0, 0, 0, 1]])
    pts = _peer_points(axes, points, kinds)
    P = np.array([pts[0], *(pts[i + 1] - pts[i] for i in range(len(pts) - 1)), home[:3, 3] - pts[-1]])
    H = axes.copy()
    H[np.abs(H) < 1e-13] = 0.0
    P[np.abs(P) < 1e-13] = 0.0
    return H, P, home[:3, :3]


def _check(solve, m, poses, free_value):
    err, counts = 0.0, []
    for T in poses:
        sols = solve(T)
        counts.append(len(sols))
        for s in sols:
            full = list(s)
            if m._FREE >= 0:
                full.insert(m._FREE, free_value)
            design = [free_value] if m._FREE >= 0 or m._ARM_ANGLE else None
            err = max(err, float(np.max(np.abs(m.fk_matrix(full, design) - T))))
    return err, counts


def peer_eaik(m, joints, poses, free_value):
    try:
        from eaik.IK_HP import HPRobot
    except Exception as exc:  # noqa: BLE001 - not installed: skipped with a note
        return {"note": f"skipped: {exc!r}"}
    if "P" in m.JOINT_KINDS:
        return {"note": "revolute joints only"}
    H, P, R = _hp(m, free_value)
    try:
        bot = HPRobot(H, P)
    except Exception as exc:  # noqa: BLE001
        return {"note": f"refused the robot: {exc}"}
    fam = bot.getKinematicFamily()

    def solve(T):
        t = T.copy()
        t[:3, :3] = T[:3, :3] @ R.T
        s = bot.IK(t)
        return [q for q, ls in zip(s.Q, s.is_LS, strict=True) if not ls]
    err, counts = _check(solve, m, poses, free_value)

    def call(T):
        t = T.copy()
        t[:3, :3] = T[:3, :3] @ R.T
        return bot.IK(t)
    return {"us": per_call(call, list(poses), 3, warmup=20) * 1e6, "err": err, "counts": counts,
            "note": f"family {fam}"}


IK_GEO_FAMILY = {"spherical wrist": "spherical_two_parallel", "three parallel": "three_parallel_two_intersecting"}


def peer_ik_geo(m, joints, poses, free_value):
    try:
        from ik_geo import Robot
    except Exception as exc:  # noqa: BLE001
        return {"note": f"skipped: {exc!r}"}
    if m.N_JOINTS - (m._FREE >= 0) != 6:
        return {"note": "6R only"}
    fam = next((f for k, f in IK_GEO_FAMILY.items() if k in m.DECOMPOSITION), None)
    if fam is None:
        return {"note": "no matching family constructor"}
    H, P, R = _hp(m, free_value)
    bot = getattr(Robot, fam)(H, P)

    def solve(T):
        return [q for q, ls in bot.get_ik((T[:3, :3] @ R.T).T, T[:3, 3]) if not ls]  # binding wants R^T
    err, counts = _check(solve, m, poses, free_value)
    return {"us": per_call(lambda T: bot.get_ik((T[:3, :3] @ R.T).T, T[:3, 3]), list(poses), 3, warmup=20) * 1e6,
            "err": err, "counts": counts, "note": fam}


BENCH_C = r"""
#include <stdio.h>
#include <time.h>
#include "NAME.h"
int main(int argc, char **argv) {
    (void)argc;
    FILE *f = fopen(argv[1], "rb");
    static double poses[4096][12];
    static double free_value[1];
    size_t n = fread(poses, sizeof(double) * 12, 4096, f);
    if (fread(free_value, sizeof(double), 1, f) != 1) free_value[0] = 0.0;
    fclose(f);
    wk_NAME_design d;
    wk_NAME_design_init(PARAMS, &d);
    wk_NAME_ik_solutions s;
    double best = 1e30;
    long total = 0;
    for (int rep = 0; rep < 5; ++rep) {
        struct timespec a, b;
        clock_gettime(CLOCK_MONOTONIC, &a);
        for (size_t i = 0; i < n; ++i) { wk_NAME_ik(poses[i], &d, &s); total += s.count; }
        clock_gettime(CLOCK_MONOTONIC, &b);
        double t = (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec);
        if (t < best) best = t;
    }
    printf("%.6f %ld\n", best / (double)n * 1e6, total);
    return 0;
}
"""


def c_loop(out: Path, name: str, poses, free_value, params: bool = True) -> float | None:
    """`params`: the solver takes the held value (or the arm angle) as its design; else its defaults (NULL)."""
    src = out / "c" / "bench_main.c"
    src.write_text(BENCH_C.replace("NAME", name).replace("PARAMS", "free_value" if params else "NULL"))
    exe = out / "c" / "bench"
    # the robot's C and every runtime file written beside it (wristkin_runtime.c; the general 6R's wk_*.c)
    others = sorted(str(f) for f in (out / "c").glob("*.c") if f.name != src.name)
    cmd = ["gcc", *C_FLAGS, "-D_POSIX_C_SOURCE=199309L", "-o", str(exe), str(src), *others, f"-I{out / 'c'}", "-lm"]
    if subprocess.run(cmd, capture_output=True, check=False).returncode != 0:
        return None
    data = out / "c" / "poses.bin"
    with open(data, "wb") as f:
        f.write(np.ascontiguousarray(np.array([T[:3].ravel() for T in poses])).tobytes())
        f.write(np.array([free_value]).tobytes())
    run = subprocess.run([str(exe), str(data)], capture_output=True, text=True, check=False)
    return float(run.stdout.split()[0]) if run.returncode == 0 else None


def bench_robot(urdf: Path, n: int, arm_angle: bool = False) -> dict:
    """One robot's row (its design the table's lengths at their defaults, or a held joint's value); `arm_angle`:
    derived with --redundancy arm-angle and solved at arm angle ARM_ANGLE for every pose (8 sets each; no peer has
    this IK). The peers are timed on the same poses."""
    from derive import own_robot
    from derive.pipeline import default_jobs

    robot = urdf.stem
    out = Path(tempfile.mkdtemp(prefix=f"wk_bench_{robot}_"))
    t0 = time.perf_counter()
    if arm_angle:
        own_robot.derive(urdf, out, redundancy="arm-angle", progress=lambda _: None, jobs=default_jobs())
    else:
        own_robot.derive(urdf, out, free=FREE.get(robot), progress=lambda _: None, jobs=default_jobs())
    derive_s = time.perf_counter() - t0
    m = own_robot.import_solver(out, robot)
    rng = np.random.default_rng(7)
    joints = rng.uniform(-math.pi, math.pi, (n, m.N_JOINTS))
    free_value = ARM_ANGLE if arm_angle else 0.0
    held = m._FREE  # the held joint (its value is the design)
    if held >= 0:
        joints[:, held] = free_value
    design = [free_value] if held >= 0 or arm_angle else None
    poses = [m.fk_matrix(q, design) for q in joints]
    ours = [m.ik(T, design).count for T in poses]
    py_us = per_call(lambda T: m.ik(T, design), poses[: min(n, 100)], 3, warmup=5) * 1e6
    c_us = c_loop(out, robot, poses, free_value, params=held >= 0 or arm_angle)
    if arm_angle:
        peers = {k: {"note": "no arm-angle IK"} for k in ("EAIK", "ik-geo")}
        robot += " (arm angle)"
    else:
        peers = {"EAIK": peer_eaik(m, joints, poses, free_value),
                 "ik-geo": peer_ik_geo(m, joints, poses, free_value)}
    for p in peers.values():
        if "counts" in p:
            p["same_counts"] = sum(a == b for a, b in zip(p.pop("counts"), ours, strict=True))
    return {"robot": robot, "decomposition": m.DECOMPOSITION.split(":")[0], "derive_s": derive_s, "py_us": py_us,
            "c_us": c_us, "sets": sum(ours) / len(ours), "peers": peers, "n": n}


def _f(x, fmt="{:.2f}"):
    return "-" if x is None else fmt.format(x)


def report(n: int = 200, json_path: Path = ROOT / "build" / "bench" / "own_robots.json") -> str:
    """Derive every test robot's URDF, time its IK against the peers, and return the Markdown table (ratios
    first); the numbers also go to `json_path`."""
    rows = [bench_robot(p, n) for p in sorted(ROBOTS.glob("*/*.urdf"))]
    rows += [bench_robot(ROBOTS / r / f"{r}.urdf", n, arm_angle=True) for r in ARM_ANGLE_ROBOTS]
    versions = {}
    for mod in ("eaik", "ik_geo"):
        try:
            from importlib.metadata import version

            versions[mod] = version(mod.replace("_", "-"))
        except Exception:  # noqa: BLE001
            versions[mod] = "not installed"
    lines = [f"Your own robots: `wristkin derive` on each test robot's URDF (its IK derived as straight-line "
             f"stages), {n} poses each (machine: "
             f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, Python "
             f"{platform.python_version()}; peers: EAIK {versions['eaik']}, ik-geo {versions['ik_geo']}):", "",
             "| robot | C loop / EAIK | Python / EAIK | decomposition | derive s | IK sets/pose | wristkin C loop us | "
             "EAIK us (Python) | ik-geo us (Python) | wristkin Python us | peers' sets equal / N |",
             "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        e, g = r["peers"]["EAIK"], r["peers"]["ik-geo"]
        ratio = r["c_us"] / e["us"] if r["c_us"] and e.get("us") else None
        py_ratio = r["py_us"] / e["us"] if e.get("us") else None
        same = "; ".join(f"{k} {p['same_counts']}/{r['n']} (err {p['err']:.0e})" if "same_counts" in p else
                         f"{k}: {p['note']}" for k, p in r["peers"].items())
        lines.append(f"| {r['robot']} | {_f(ratio, '{:.2f}x')} | {_f(py_ratio, '{:.2f}x')} | {r['decomposition']} | "
                     f"{r['derive_s']:.1f} | {r['sets']:.2f} | {_f(r['c_us'])} | {_f(e.get('us'))} | "
                     f"{_f(g.get('us'))} | {r['py_us']:.1f} | {same} |")
    json_path.parent.mkdir(parents=True, exist_ok=True)
    json_path.write_text(json.dumps({"versions": versions, "rows": rows}, indent=2, default=str))
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--json", type=Path, default=ROOT / "build" / "bench" / "own_robots.json")
    args = ap.parse_args(argv)
    print(report(args.n, args.json))
    return 0


if __name__ == "__main__":
    sys.exit(main())
