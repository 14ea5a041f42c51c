"""3-RSR wrist and SCARA + 3-RSR hybrid in `make bench`: generated C (C loop and ctypes), generated Python and
the independent numeric reference (tests/reference/rsr.py), all measured in the same run. No peer library
solves this parallel wrist, so the reference (what a user without closed forms would run) is the comparison.

Called from bench/run.py; also runs alone:  .venv/bin/python bench/rsr.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
from timing import per_call

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build" / "bench"
C_DIR = ROOT / "generated" / "c"
FLAGS = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def c_loop(n: int) -> dict:
    BUILD.mkdir(parents=True, exist_ok=True)
    exe = BUILD / "bench_rsr"
    subprocess.run(["gcc", *FLAGS, f"-I{C_DIR}", str(ROOT / "bench" / "bench_rsr.c"), str(C_DIR / "rsr_wrist.c"),
                    str(C_DIR / "scara_rsr.c"), str(C_DIR / "wristkin_runtime.c"), "-lm", "-o", str(exe)],
                   check=True, capture_output=True, text=True)
    return json.loads(subprocess.run([str(exe), str(n)], check=True, capture_output=True, text=True).stdout)


def _us(fn, rows, repeats=3) -> float:
    return per_call(fn, rows, repeats, warmup=min(len(rows), 20)) * 1e6


def fmt(x) -> str:
    if x is None:
        return "-"
    return f"{x * 1e3:.0f} ns" if x < 1 else (f"{x:.2f} µs" if x < 1e3 else f"{x / 1e3:.1f} ms")


def tables(quick: bool = False) -> str:
    for sub in ("tests", "generated/python"):
        if str(ROOT / sub) not in sys.path:
            sys.path.insert(0, str(ROOT / sub))
    from c_solvers import RsrC
    from reference import rsr as ref
    from wristkin import rsr_wrist as w
    from wristkin import scara_rsr as h

    n_c, n_py, n_ref = (20_000, 100, 3) if quick else (100_000, 1000, 10)
    loop = c_loop(n_c)
    rng = np.random.default_rng(5)
    wq = rng.uniform(math.radians(25), math.radians(75), (n_py, 3))
    wp = [w.fk(q).values[0] for q in wq]
    hq = np.column_stack([rng.uniform(-3, 3, n_py), rng.uniform(-3, 3, n_py), rng.uniform(0, 0.3, n_py),
                          rng.uniform(-3, 3, n_py), wq])
    hp = [h.fk(q).values[0] for q in hq]
    wc, hc = RsrC("rsr_wrist"), RsrC("scara_rsr")
    rows = [("generated C, C loop", loop["wrist_ik_ns"] / 1e3, loop["wrist_fk_ns"] / 1e3, loop["hybrid_ik_ns"] / 1e3,
             loop["hybrid_fk_ns"] / 1e3),
            ("generated C via ctypes (with result conversion)", _us(wc.ik, wp), _us(wc.fk, wq), _us(hc.ik, hp),
             _us(hc.fk, hq)),
            ("generated Python, scalar", _us(w.ik, wp), _us(w.fk, wq), _us(h.ik, hp), _us(h.fk, hq))]
    L = w.DESIGN_DEFAULT[0]
    design = ref.HybridDesign(*h.DESIGN_DEFAULT[:5])
    wposes = [ref.pose_from_params(*p) for p in wp[:n_ref]]
    hmats = [(h.fk_matrix(q), float(p[12])) for q, p in zip(hq[:n_ref], hp, strict=False)]
    rows.append(("numeric reference (brentq legs; multistart LM for all modes / hybrid IK)",
                 _us(lambda rp: ref.ik_all(rp[0], rp[1], L), wposes, 1),
                 _us(lambda q: ref.fk_all(q, L), list(wq[:n_ref]), 1),
                 _us(lambda t: ref.hybrid_ik_all(t[0], t[1], design), hmats[:max(2, n_ref // 3)], 1), None))
    base = rows[0]
    lines = ["3-RSR wrist and SCARA + 3-RSR hybrid (IK returns every branch: 8 and 16 sets; ratio = time / C loop):",
             "", "| implementation | wrist IK | wrist FK | hybrid IK | hybrid FK | wrist IK ratio | hybrid IK ratio |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for name, wik, wfk, hik, hfk in rows:
        lines.append(f"| {name} | {fmt(wik)} | {fmt(wfk)} | {fmt(hik)} | {fmt(hfk)} | {wik / base[1]:.0f}x | "
                     f"{hik / base[3]:.0f}x |")
    lines += ["", f"- C loop: gcc -O2, best of 5 over {n_c} seeded inputs; mean IK solution counts "
              f"{loop['wrist_ik_mean_count']:.2f} (wrist), {loop['hybrid_ik_mean_count']:.2f} (hybrid).",
              "- reference FK finds every assembly mode of the full closed chain (2000 starts), not only the "
              "symmetric one the generated FK returns; reference hybrid IK solves 7 joints by multistart least "
              "squares with the target's l_bw."]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    print(tables(args.quick))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
