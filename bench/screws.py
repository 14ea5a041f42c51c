"""Finite-screw 3T2R robots in `make bench`: generated C loop vs generated Python vs the numpy reference, one run.

Called from bench/run.py; also runs alone:  .venv/bin/python bench/screws.py [--quick]

Rows per robot (default design; joints seeded uniform, IK poses are their FK so every pose is reachable):
* generated C, C loop     bench/bench_serial.c (the DH chains' driver), gcc -O2, best of 5
* generated Python        wristkin.<robot>.ik / fk_matrix / jacobian, scalar, best of 5
* numpy reference         tests/reference/screws.py: fk = product of scipy expm, jacobian from spatial twists,
                          ik = multistart Levenberg-Marquardt (stops at the generic solution count)
"""

from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path

import numpy as np
from dh import _compile
from timing import per_call

ROOT = Path(__file__).resolve().parent.parent
C_DIR = ROOT / "generated" / "c"
ROBOTS = ("p1p2p3rarb", "rarararbrb")


def fmt(us: float) -> str:
    return f"{us * 1e3:.0f} ns" if us < 1 else (f"{us:.2f} µs" if us < 1000 else f"{us / 1e3:.1f} ms")


def _c_loop(name: str, dof: int, n: int) -> dict:
    import json
    import subprocess

    exe = _compile(name, [ROOT / "bench" / "bench_serial.c", C_DIR / f"{name}.c", C_DIR / "wristkin_runtime.c"],
                   [f"-DMECH={name}", f'-DMECH_H="{name}.h"', f"-DN={dof}"])
    return json.loads(subprocess.run([str(exe), str(n)], check=True, capture_output=True, text=True).stdout)


def measure(name: str, n_c: int, n_py: int, n_ref: int) -> list[dict]:
    from reference import screws as ref

    mod = importlib.import_module(f"wristkin.{name}")
    robot = ref.axes(name, mod.DESIGN_DEFAULT)
    rng = np.random.default_rng(0)
    qs = [np.array([rng.uniform(-np.pi, np.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in mod.JOINT_KINDS])
          for _ in range(n_py)]
    poses = [mod.fk_matrix(q) for q in qs]
    c = _c_loop(name, mod.N_JOINTS, n_c)
    rows = [{"name": "generated C, C loop", "ik": c["ik_ns"] * 1e-9, "fk": c["fk_ns"] * 1e-9,
             "jac": (c["fk_jac_ns"] - c["fk_ns"]) * 1e-9},
            {"name": "generated Python (scalar)", "ik": per_call(mod.ik, poses), "fk": per_call(mod.fk_matrix, qs),
             "jac": per_call(mod.jacobian, qs)},
            {"name": "numpy reference (expm products, multistart LM)",
             "ik": per_call(lambda T: ref.ik_reference(robot, T, ref.MAX_SOLUTIONS[name]), poses[:n_ref], repeats=1,
                            warmup=1),
             "fk": per_call(lambda q: ref.fk(robot, q), qs), "jac": per_call(lambda q: ref.jacobian(robot, q), qs)}]
    return rows


def tables(quick: bool = False) -> str:
    for sub in ("tests", "generated/python"):
        if str(ROOT / sub) not in sys.path:
            sys.path.insert(0, str(ROOT / sub))
    n_c, n_py, n_ref = (20_000, 100, 3) if quick else (100_000, 500, 10)
    lines = ["Finite-screw 3T2R robots (seed 003), default designs, side by side in this run "
             "(ratio = time / generated C loop):", "",
             "| robot | implementation | IK (all branches) | FK (pose) | Jacobian | IK ratio | FK ratio |",
             "|---|---|---:|---:|---:|---:|---:|"]
    for name in ROBOTS:
        rows = measure(name, n_c, n_py, n_ref)
        base = rows[0]
        for r in rows:
            lines.append(f"| {name} | {r['name']} | {fmt(r['ik'] * 1e6)} | {fmt(r['fk'] * 1e6)} | "
                         f"{fmt(r['jac'] * 1e6)} | {r['ik'] / base['ik']:.0f}x | {r['fk'] / base['fk']:.0f}x |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    print(tables(args.quick))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
