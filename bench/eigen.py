"""The runtime eigensolver (runtime/c/wk_eigen.c, issue 23) against numpy/scipy: printed, not asserted.

Rows, one run, same machine: wk_eig_real on random 24 x 24 matrices, the quadratic eigenproblem (m = 12: a
24 x 24 companion form after choosing its leading coefficient) and wk_null_vector / wk_null_vector_lu
(12 x 12), each in a C loop (bench/bench_eigen.c, gcc -O2, the project's strict flags); numpy.linalg.eigvals
on a 24 x 24 matrix, numpy's route to the same quadratic eigenvalues (solve for the companion block row +
eigvals), scipy's QZ on the 2m x 2m pencil, and numpy.linalg.svd of a 12 x 12, each called from Python (best
of 5, warm-up first).

Runs alone:  .venv/bin/python bench/eigen.py [--quick]
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one BLAS thread, set before numpy loads (2-vCPU VM)

import argparse  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import subprocess  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import scipy.linalg  # noqa: E402
from timing import per_call  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build" / "bench"
FLAGS = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def c_loop(cases: int) -> dict:
    BUILD.mkdir(parents=True, exist_ok=True)
    exe = BUILD / "bench_eigen"
    subprocess.run(["gcc", *FLAGS, f"-I{ROOT / 'runtime' / 'c'}", str(ROOT / "bench" / "bench_eigen.c"),
                    str(ROOT / "runtime" / "c" / "wk_eigen.c"), "-lm", "-o", str(exe)], check=True)
    out = subprocess.run([str(exe), str(cases)], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def python_rows(cases: int) -> dict:
    rng = np.random.default_rng(0)
    mats = [rng.uniform(-1, 1, (24, 24)) for _ in range(cases)]
    abc = [tuple(rng.uniform(-1, 1, (12, 12)) for _ in range(3)) for _ in range(cases)]
    eye, zero = np.eye(12), np.zeros((12, 12))

    def companion_eigvals(t):
        a, b, c = t
        comp = np.zeros((24, 24))
        comp[:12, 12:] = eye
        comp[12:, :] = -np.linalg.solve(a, np.hstack([c, b]))
        return np.linalg.eigvals(comp)

    def qz(t):
        a, b, c = t
        return scipy.linalg.eigvals(np.block([[zero, eye], [-c, -b]]), np.block([[eye, zero], [zero, a]]))

    return {"numpy_eigvals_n24_ns": 1e9 * per_call(np.linalg.eigvals, mats),
            "numpy_companion_m12_ns": 1e9 * per_call(companion_eigvals, abc),
            "scipy_qz_m12_ns": 1e9 * per_call(qz, abc),
            "numpy_svd_m12_ns": 1e9 * per_call(lambda t: np.linalg.svd(t[0]), abc)}


def machine() -> str:
    try:
        model = next(ln.split(":", 1)[1].strip() for ln in Path("/proc/cpuinfo").read_text().splitlines()
                     if ln.startswith("model name"))
    except (OSError, StopIteration):
        model = platform.processor() or "unknown CPU"
    return f"{model}, {os.cpu_count()} logical CPUs, {platform.system()} {platform.machine()}, numpy {np.__version__}"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    cases = 200 if args.quick else 2000
    c = c_loop(cases)
    py = python_rows(cases // 4)
    print(f"machine: {machine()}; OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}")
    print("| problem | wk_eigen, C loop | numpy/scipy from Python |")
    print("|---|---:|---:|")
    print(f"| real eigenvalues, 24 x 24 | {c['eig_real_n24_ns'] / 1e3:.1f} us | "
          f"{py['numpy_eigvals_n24_ns'] / 1e3:.1f} us (numpy.linalg.eigvals) |")
    print(f"| quadratic eigenproblem, m = 12 | {c['qep_m12_ns'] / 1e3:.1f} us | "
          f"{py['numpy_companion_m12_ns'] / 1e3:.1f} us (solve + eigvals), "
          f"{py['scipy_qz_m12_ns'] / 1e3:.1f} us (scipy QZ on the pencil) |")
    print(f"| null vector, 12 x 12 (Jacobi SVD) | {c['null_vector_m12_ns'] / 1e3:.1f} us | "
          f"{py['numpy_svd_m12_ns'] / 1e3:.1f} us (numpy.linalg.svd) |")
    print(f"| null vector, 12 x 12 (LU + inverse iteration) | {c['null_vector_lu_m12_ns'] / 1e3:.1f} us | |")
    print(f"C loop: {c['fails']} failures, {c['mean_real_roots_m12']:.2f} real roots per random m = 12 problem")


if __name__ == "__main__":
    main()
