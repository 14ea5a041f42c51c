"""DH chains in `make bench`: generated C loops for every chain and, for the PUMA-560, the peers a user
would pick instead (EAIK, ik-geo, pinocchio, CasADi-generated C), all measured in the same run.

Called from bench/run.py; also runs alone:  .venv/bin/python bench/dh.py [--quick]
"""

from __future__ import annotations

import argparse
import ctypes
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
from timing import fastest_of_rounds, per_call

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build" / "bench"
C_DIR = ROOT / "generated" / "c"
CASADI_DIR = ROOT / "generated" / "casadi"
FLAGS = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]
CHAINS = ("wrist_1dof", "spherical_wrist", "rpp_wrist", "scara_wrist", "puma560")


def _compile(name: str, sources: list[Path], defines: list[str]) -> Path:
    BUILD.mkdir(parents=True, exist_ok=True)
    exe = BUILD / f"bench_{name}"
    subprocess.run(["gcc", *FLAGS, *defines, f"-I{C_DIR}", f"-I{BUILD}", *map(str, sources), "-lm", "-o", str(exe)],
                   check=True, capture_output=True, text=True)
    return exe


def c_loops(n: int) -> dict[str, dict]:
    """ns per call of IK (all branches), FK and FK + Jacobian, in a C loop, for every generated chain."""
    import importlib

    out = {}
    for name in CHAINS:
        dof = importlib.import_module(f"wristkin.{name}").N_JOINTS
        exe = _compile(name, [ROOT / "bench" / "bench_serial.c", C_DIR / f"{name}.c", C_DIR / "wristkin_runtime.c"],
                       [f"-DMECH={name}", f'-DMECH_H="{name}.h"', f"-DN={dof}"])
        out[name] = json.loads(subprocess.run([str(exe), str(n)], check=True, capture_output=True,
                                              text=True).stdout)
    return out


CASADI_MAIN = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <time.h>
#include "puma560_casadi.h"
static double now(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
int main(void) {
    enum { N = 100000 };
    static double q[N][6], T[12], J[36], w[4096];
    static long long iw[1024];
    const double p[6] = {PUMA_DESIGN};
    const double *arg[2];
    double *res[1], best_fk = 1e9, best_fj = 1e9, sum = 0.0;
    unsigned long long s = 0x9E3779B97F4A7C15ULL;
    int i, j, r;
    for (i = 0; i < N; ++i) for (j = 0; j < 6; ++j) {
        s ^= s << 13; s ^= s >> 7; s ^= s << 17;
        q[i][j] = ((double)(s >> 11) / 9007199254740992.0 - 0.5) * 6.283185307179586;
    }
    arg[1] = p;
    for (r = 0; r < 5; ++r) {
        double t0 = now(), t1, t2;
        for (i = 0; i < N; ++i) { arg[0] = q[i]; res[0] = T; puma560_fk(arg, res, iw, w, 0); sum += T[0]; }
        t1 = now();
        for (i = 0; i < N; ++i) {
            arg[0] = q[i]; res[0] = T; puma560_fk(arg, res, iw, w, 0);
            res[0] = J; puma560_jacobian(arg, res, iw, w, 0); sum += J[0];
        }
        t2 = now();
        if ((t1 - t0) / N < best_fk) best_fk = (t1 - t0) / N;
        if ((t2 - t1) / N < best_fj) best_fj = (t2 - t1) / N;
    }
    printf("{\"fk_ns\": %.2f, \"fk_jac_ns\": %.2f, \"checksum\": %.6f}\n", best_fk * 1e9, best_fj * 1e9, sum);
    return 0;
}
"""


def casadi_c() -> dict:
    """CasADi's own C code generator on the PUMA FK and Jacobian functions, timed in a C loop."""
    import casadi as ca

    sys.path.insert(0, str(ROOT))
    from derive.casadi_export import load_casadi

    fns = load_casadi(CASADI_DIR / "puma560.casadi")
    BUILD.mkdir(parents=True, exist_ok=True)
    cg = ca.CodeGenerator("puma560_casadi.c", {"with_header": True, "casadi_int": "long long"})
    cg.add(fns["puma560_fk"])
    cg.add(fns["puma560_jacobian"])
    cg.generate(str(BUILD) + "/")
    (BUILD / "casadi_main.c").write_text(CASADI_MAIN)
    from wristkin import puma560

    exe = BUILD / "bench_casadi"
    design = ", ".join(repr(v) for v in puma560.DESIGN_DEFAULT)
    subprocess.run(["gcc", "-O2", f"-DPUMA_DESIGN={design}", f"-I{BUILD}", str(BUILD / "casadi_main.c"),
                    str(BUILD / "puma560_casadi.c"), "-lm",
                    "-o", str(exe)], check=True, capture_output=True, text=True)
    res = json.loads(subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout)
    return {"name": f"CasADi-generated C (casadi {ca.__version__}), C loop", "ik_us": None,
            "fk_us": res["fk_ns"] / 1e3, "jac_us": (res["fk_jac_ns"] - res["fk_ns"]) / 1e3,
            "fkjac_us": res["fk_jac_ns"] / 1e3, "note": "FK and geometric Jacobian functions of "
            "generated/casadi/puma560.casadi through casadi.CodeGenerator, gcc -O2"}


def _best(fn, args, repeats=3) -> float:
    return per_call(fn, args, repeats, warmup=min(len(args), 50)) * 1e6


def generated_python_and_ctypes(n: int) -> list[dict]:
    for sub in ("tests", "generated/python"):
        if str(ROOT / sub) not in sys.path:
            sys.path.insert(0, str(ROOT / sub))
    from c_solvers import SerialC
    from wristkin import puma560 as m

    rng = np.random.default_rng(7)
    qs = rng.uniform(-math.pi, math.pi, (n, 6))
    poses = [m.fk_matrix(q) for q in qs]
    rows = []
    native, fallback = m.make_design(), m.Design(m.make_design().params)  # the second has no C design: numpy
    for label, d in ((f"wristkin from Python, backend {m.BACKEND}", native), ("wristkin from Python, numpy", fallback)):
        rows.append({"name": label, "ik_us": _best(lambda T, d=d: m.ik(T, d), poses),
                     "fk_us": _best(lambda q, d=d: m.fk_matrix(q, d), qs),
                     "jac_us": _best(lambda q, d=d: m.jacobian(q, d), qs),
                     "note": "wristkin.puma560.ik / fk_matrix / jacobian: Solutions objects, all 8 branches "
                             "verified by FK"})
    batch = np.array(poses)
    for label, d in (("wristkin ik_batch / fk_batch from Python, per pose, backend " + m.BACKEND, native),
                     ("wristkin ik_batch / fk_batch from Python, per pose, numpy", fallback)):
        rows.append({"name": label, "ik_us": per_call(lambda b, d=d: m.ik_batch(b, d), [batch], 3, 1) * 1e6 / n,
                     "fk_us": per_call(lambda b, d=d: m.fk_batch(b, d), [qs], 3, 1) * 1e6 / n, "jac_us": None,
                     "note": f"{n} poses / joint rows per call"})
    c = SerialC("puma560", 6, m.MAX_IK, 6)
    out, jac = c.IK(), np.zeros(36)
    ik_fn, jac_fn = c.lib.wk_puma560_ik, c.lib.wk_puma560_jacobian
    flat = [np.ascontiguousarray(p[:3].ravel()) for p in poses]
    ptrs = [a.ctypes.data_as(ctypes.POINTER(ctypes.c_double)) for a in flat]
    qptr = [np.ascontiguousarray(q).ctypes.data_as(ctypes.POINTER(ctypes.c_double)) for q in qs]
    jptr = jac.ctypes.data_as(ctypes.POINTER(ctypes.c_double))
    ref = ctypes.byref(out)
    raw_ik = _best(lambda p: ik_fn(p, None, ref), ptrs)
    rows.append({"name": "wristkin generated C via ctypes (raw call)", "ik_us": raw_ik,
                 "fk_us": None, "jac_us": _best(lambda q: jac_fn(q, None, jptr), qptr),
                 "note": "pre-built pointers, no result conversion: the cost a Python caller pays at least"})
    return rows


def peers(n: int) -> list[dict]:
    sys.path.insert(0, str(ROOT / "bench"))
    import peers as p

    return p.run_all(n)


def fmt(x) -> str:
    if x is None:
        return "-"
    return f"{x * 1e3:.0f} ns" if x < 1 else f"{x:.2f} µs"


def peer_versions() -> str:
    """The peers' installed versions, as the tables name them."""
    from importlib.metadata import PackageNotFoundError, version

    out = []
    for label, dist in (("EAIK", "eaik"), ("ik-geo", "ik-geo"), ("pinocchio", "pin")):
        try:
            out.append(f"{label} {version(dist)}")
        except PackageNotFoundError:
            out.append(f"{label} not installed")
    return ", ".join(out)


TIMED = ("ik_us", "fk_us", "jac_us", "fkjac_us")  # the per-call timings of a PUMA-560 row


def measure(quick: bool = False) -> tuple[dict, list[dict]]:
    """(C-loop results per chain, PUMA-560 rows side by side): everything tables() prints, as numbers."""
    for sub in ("tests", "generated/python"):
        if str(ROOT / sub) not in sys.path:
            sys.path.insert(0, str(ROOT / sub))
    n_c = 20_000 if quick else 100_000
    n_py = 100 if quick else 1000
    loops = c_loops(n_c)
    for name, again in c_loops(n_c).items():  # a second round, the faster of the two (see fastest_of_rounds)
        for k in ("ik_ns", "fk_ns", "fk_jac_ns"):
            loops[name][k] = min(loops[name][k], again[k])
    base = loops["puma560"]
    rows = [{"name": "wristkin generated C, C loop", "ik_us": base["ik_ns"] / 1e3, "fk_us": base["fk_ns"] / 1e3,
             "jac_us": (base["fk_jac_ns"] - base["fk_ns"]) / 1e3,
             "note": "gcc -O2, best of 5; FK = wk_puma560_fk_matrix (bare pose; wk_puma560_fk adds the "
                     "manipulability aux)"}]
    # wristkin's Python rows and the peers' in the same rounds, so a slow phase of the VM meets both alike
    n_ours = []

    def ours_then_peers() -> list[dict]:
        ours = generated_python_and_ctypes(n_py)
        n_ours[:] = [len(ours)]
        return ours + peers(n_py)

    both = fastest_of_rounds(ours_then_peers, TIMED, rounds=3)
    rows += both[:n_ours[0]]
    try:
        rows.append(casadi_c())
    except Exception as exc:  # noqa: BLE001 - a missing compiler/casadi only skips the row
        rows.append({"name": "CasADi-generated C", "ik_us": None, "fk_us": None, "note": f"skipped: {exc!r}"})
    rows += both[n_ours[0]:]
    return loops, rows


def tables(quick: bool = False, measured: tuple[dict, list[dict]] | None = None) -> str:
    """The DH chains' C-loop table and the PUMA-560 side-by-side table (ratios first)."""
    loops, rows = measured or measure(quick)
    lines = ["DH chains, generated C in a C loop (IK returns every branch, each verified by FK):", "",
             "| chain | IK | FK | FK + Jacobian | IK solutions per pose |", "|---|---:|---:|---:|---:|"]
    for name, r in loops.items():
        lines.append(f"| {name} | {fmt(r['ik_ns'] / 1e3)} | {fmt(r['fk_ns'] / 1e3)} | {fmt(r['fk_jac_ns'] / 1e3)} | "
                     f"{r['ik_mean_count']:.2f} |")
    lines += ["", f"PUMA-560, side by side (peers from Python: {peer_versions()}; ratio = time / wristkin C loop):",
              "", "| implementation | IK ratio | FK ratio | IK (all branches) | FK | Jacobian | max error |",
              "|---|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        ik, fk, jac = r.get("ik_us"), r.get("fk_us"), r.get("jac_us")
        ikr = "-" if ik is None else f"{ik / rows[0]['ik_us']:.1f}x"
        fkr = "-" if fk is None else f"{fk / rows[0]['fk_us']:.1f}x"
        err = r.get("max_err")
        lines.append(f"| {r['name']} | {ikr} | {fkr} | {fmt(ik)} | {fmt(fk)} | {fmt(jac)} | "
                     f"{'-' if err is None else f'{err:.1e}'} |")
    lines += [""] + [f"- {r['name']}: {r['note']}" for r in rows if r.get("note")]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    print(tables(args.quick))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
