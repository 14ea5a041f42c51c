"""Side-by-side per-call timings of the underactuated wrist's IK and FK implementations.

Run from the repository root:  .venv/bin/python bench/run.py [--regenerate] [--casadi PATH] [--quick]

Rows (all in one run, on the same machine):

* generated C in a C loop      bench/bench_underactuated_wrist.c, built with gcc into build/bench/
* generated C via ctypes       tests/c_solvers.py (UnderactuatedWristC.ik/fk, and the raw ctypes call)
* generated Python, scalar     wristkin.underactuated_wrist.ik / fk
* generated Python, batch      ik_batch (N=10000) / fk_batch (N=200), time per row
* numeric reference            tests/reference/underactuated_wrist.py (ik_reference / fk_reference)
* CasADi closed-form IK        uw_ik_branch from generated/casadi/underactuated_wrist.casadi, mapped
                               over the 8 branch sign sets (skipped with a note if the file is missing)
* regenerate (--regenerate)    wall time of `python -m derive.cli regenerate --out <tmpdir>`, once

Inputs are the first rows of the same seeded streams the C benchmark uses (xorshift64*): IK poses
the first FK mode of joint triples uniform in [0, 2pi) (so all reachable); FK joints uniform in [0, 2pi).
Python rows: time.perf_counter, a warm-up pass, best of 5 repeats. The C loop: best of 10 repeats.
Prints a Markdown table and writes the same results to build/bench/results.json.
"""

from __future__ import annotations

import argparse
import ctypes
import functools
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

# One thread per BLAS library, set before numpy loads one: an OpenBLAS worker left spinning after a numpy call
# took 25 % of a profile of the scalar verbs, and on this 2-vCPU VM it slowed the C-loop subprocesses measured
# next to it (3.6 -> 4.2 us per wrist FK); every row here is a single-threaded per-call time
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402
from timing import fastest_of_rounds, per_call  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BENCH_DIR = ROOT / "bench"
BUILD_DIR = ROOT / "build" / "bench"
C_DIR = ROOT / "generated" / "c"
CASADI_FILE = ROOT / "generated" / "casadi" / "underactuated_wrist.casadi"
C_FLAGS = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"]

# Must match bench/bench_underactuated_wrist.c.
IK_SEED = 0x9E3779B97F4A7C15
FK_SEED = 0xD1B54A32D192ED03
MASK64 = (1 << 64) - 1

REPEATS = 5


def atlas_bench():
    """bench/atlas.py (its tables), imported by its path: `import atlas` finds the repository's atlas/ package
    (wristkin_atlas, no `tables`) instead once a bench module has put the repository root ahead of bench/ on
    sys.path (bench/dh.py does, to import derive/)."""
    import importlib.util

    name = "wristkin_bench_atlas"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, BENCH_DIR / "atlas.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]
C_REPEATS = 10  # one repeat of the C loop is ~0.4 s


# ---------------------------------------------------------------------------------------- inputs
def _stream(seed: int):
    """The C benchmark's xorshift64* generator: uniform doubles in [0, 1)."""
    x = seed
    while True:
        x ^= x >> 12
        x ^= (x << 25) & MASK64
        x ^= x >> 27
        yield (((x * 0x2545F4914F6CDD1D) & MASK64) >> 11) * (1.0 / 9007199254740992.0)


def ik_poses(n: int) -> np.ndarray:
    """First FK assembly mode of joint triples from the IK stream: reachable poses over the whole workspace."""
    from wristkin import underactuated_wrist as uw

    u = _stream(IK_SEED)
    rows = []
    while len(rows) < n:
        q = [2.0 * math.pi * next(u) for _ in range(3)]
        sol = uw.fk(q)
        if sol.count:
            rows.append(tuple(sol.values[0]))
    return np.array(rows)


def fk_joints(n: int) -> np.ndarray:
    u = _stream(FK_SEED)
    return np.array([2.0 * math.pi * next(u) for _ in range(3 * n)]).reshape(n, 3)


# ---------------------------------------------------------------------------------------- machine
def machine_info() -> dict:
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.lower().startswith(("model name", "hardware", "cpu model")):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        gcc = subprocess.run(["gcc", "--version"], capture_output=True, text=True, check=True).stdout
        gcc = gcc.splitlines()[0].strip()
    except (OSError, subprocess.CalledProcessError):
        gcc = "not found"
    try:
        load = [round(x, 2) for x in os.getloadavg()]
    except OSError:
        load = None
    return {"arch": platform.machine(), "cpu": cpu, "cpus": os.cpu_count(), "loadavg": load,
            "python": platform.python_version(), "gcc": gcc, "numpy": np.__version__}


# ---------------------------------------------------------------------------------------- timing
def per_row_batch(fn: Callable[[np.ndarray], object], rows: np.ndarray, repeats: int = REPEATS) -> float:
    """Best-of-`repeats` seconds per row of one fn(rows) batch call, after a warm-up call."""
    fn(rows[: max(1, len(rows) // 10)])
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn(rows)
        best = min(best, time.perf_counter() - t0)
    return best / len(rows)


# ---------------------------------------------------------------------------------------- rows
@functools.cache
def _c_loop_binary() -> tuple[Path, list[str]]:
    """bench/bench_underactuated_wrist.c built once per run (the C loop runs three times)."""
    BUILD_DIR.mkdir(parents=True, exist_ok=True)
    exe = BUILD_DIR / "bench_underactuated_wrist"
    cmd = ["gcc", *C_FLAGS, f"-I{C_DIR}", "-o", str(exe), str(BENCH_DIR / "bench_underactuated_wrist.c"),
           str(C_DIR / "underactuated_wrist.c"), str(C_DIR / "wristkin_runtime.c"), "-lm"]
    subprocess.run(cmd, check=True)
    return exe, cmd


def c_loop(n_ik: int, n_fk: int) -> tuple[dict, dict]:
    exe, cmd = _c_loop_binary()
    out = subprocess.run([str(exe), str(n_ik), str(n_fk), str(C_REPEATS)], check=True, capture_output=True,
                         text=True)
    res = json.loads(out.stdout)
    same = (np.allclose(res["first_pose"], ik_poses(1)[0], rtol=0, atol=1e-12)  # C and Python FK agree to ~1e-14
            and np.allclose(res["first_joints"], fk_joints(1)[0], rtol=0, atol=0))
    if not same:
        raise RuntimeError("bench/run.py and the C benchmark generate different inputs")
    row = {"name": "generated C, C loop", "ik": res["ik_ns"] * 1e-9, "fk": res["fk_ns"] * 1e-9,
           "n_ik": n_ik, "n_fk": n_fk,
           "note": f"gcc {' '.join(C_FLAGS)}; best of {C_REPEATS}; mean FK modes {res['fk_mean_modes']:.2f}"}
    return row, {"compile": " ".join(cmd), **res}


def ctypes_rows(poses: np.ndarray, joints: np.ndarray) -> list[dict]:
    from c_solvers import UnderactuatedWristC

    c = UnderactuatedWristC()
    rows = [{"name": "generated C via ctypes (UnderactuatedWristC.ik/fk)", "ik": per_call(c.ik, poses),
             "fk": per_call(c.fk, joints), "n_ik": len(poses), "n_fk": len(joints),
             "note": "includes result conversion to numpy arrays"}]
    # The raw call: pointers and result structs made once, outside the loop.
    dptr = ctypes.POINTER(ctypes.c_double)
    ik_out, fk_out = c.IK(), c.FK()
    ik_ref, fk_ref = ctypes.byref(ik_out), ctypes.byref(fk_out)
    ik_fn, fk_fn = c.lib.wk_underactuated_wrist_ik, c.lib.wk_underactuated_wrist_fk
    # The arrays own the memory the pointers refer to: keep them alive while timing.
    pose_arrays = [np.ascontiguousarray(p) for p in poses]
    joint_arrays = [np.ascontiguousarray(q) for q in joints]
    pose_ptrs = [a.ctypes.data_as(dptr) for a in pose_arrays]
    joint_ptrs = [a.ctypes.data_as(dptr) for a in joint_arrays]
    rows.append({"name": "generated C via ctypes (raw call)",
                 "ik": per_call(lambda p: ik_fn(p, None, ik_ref), pose_ptrs),
                 "fk": per_call(lambda p: fk_fn(p, None, fk_ref), joint_ptrs),
                 "n_ik": len(poses), "n_fk": len(joints),
                 "note": "lib.wk_underactuated_wrist_*(ptr, None, byref(struct)); no conversion"})
    del pose_arrays, joint_arrays
    return rows


def python_rows(poses: np.ndarray, joints: np.ndarray, batch_poses: np.ndarray,
                batch_joints: np.ndarray) -> list[dict]:
    from wristkin import underactuated_wrist as uw

    reach = float(np.mean(uw.ik_batch(batch_poses).status == uw.STATUS_OK))
    return [
        {"name": f"generated Python, scalar (uw.ik/fk), backend {uw.BACKEND}", "ik": per_call(uw.ik, poses),
         "fk": per_call(uw.fk, joints), "n_ik": len(poses), "n_fk": len(joints), "note": ""},
        {"name": f"generated Python, batch (per row), backend {uw.BACKEND}",
         "ik": per_row_batch(uw.ik_batch, batch_poses),
         "fk": per_row_batch(uw.fk_batch, batch_joints), "n_ik": len(batch_poses), "n_fk": len(batch_joints),
         "note": f"ik_batch N={len(batch_poses)}, fk_batch N={len(batch_joints)}; "
                 f"{100 * reach:.0f}% of the IK poses are reachable"},
    ]


def reference_row(poses: np.ndarray, joints: np.ndarray) -> dict:
    from reference import underactuated_wrist as ref

    rotations = [ref.rotation_from_euler(*p) for p in poses]
    return {"name": "numeric reference (tests/reference)",
            "ik": per_call(ref.ik_reference, rotations, warmup=1),
            "fk": per_call(ref.fk_reference, list(joints), warmup=1), "n_ik": len(poses), "n_fk": len(joints),
            "note": "sampling + brentq / geometric sweep; IK time includes no Euler->R conversion"}


def casadi_row(path: Path, poses: np.ndarray) -> dict:
    if not path.exists():
        return {"name": "CasADi closed-form IK (uw_ik_branch)", "ik": None, "fk": None,
                "note": f"skipped: {path.relative_to(ROOT) if path.is_relative_to(ROOT) else path} not found "
                        "(derive/to_casadi.py writes it; not part of generated/ yet)"}
    import casadi as ca
    from wristkin import underactuated_wrist as uw

    from derive.casadi_export import load_casadi

    f = load_casadi(path)["uw_ik_branch"]
    p = np.array(uw.DESIGN_DEFAULT)
    # All 8 sign sets per pose, as the other IK rows return them: set k takes +acos on branch i when
    # bit i of k is 0.
    sigma = np.array([[1.0 if not (k >> i) & 1 else -1.0 for k in range(8)] for i in range(3)])
    f8 = f.map(8)
    ik = per_call(lambda e: f8(e, p, sigma), poses)
    # Sanity check against the generated Python module: set k of a reachable pose, wrapped difference.
    diff = math.nan
    for e in poses:
        want = uw.ik(e)
        if want.status == uw.STATUS_OK:
            got = np.array(f8(e, p, sigma)).T
            diff = float(np.max(np.abs(np.angle(np.exp(1j * (got - want.values))))))
            break
    note = f"Function.map(8) over the sign sets, casadi {ca.__version__}; max |dq| vs uw.ik {diff:.1e}"
    return {"name": "CasADi closed-form IK (uw_ik_branch)", "ik": ik, "fk": None, "n_ik": len(poses),
            "note": note}


def regenerate_row() -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "derive.cli", "regenerate", "--out", tmp], cwd=ROOT, check=True,
                       capture_output=True, text=True)
        wall = time.perf_counter() - t0
    return {"name": "`derive.cli regenerate` (wall, once)", "ik": None, "fk": None, "wall_s": wall,
            "note": f"{wall:.1f} s for the whole derivation + code generation"}


# ---------------------------------------------------------------------------------------- output
def fmt_time(t: float | None) -> str:
    if t is None:
        return "-"
    if t < 1e-6:
        return f"{t * 1e9:.0f} ns"
    if t < 1e-3:
        return f"{t * 1e6:.2f} µs"
    if t < 1.0:
        return f"{t * 1e3:.2f} ms"
    return f"{t:.2f} s"


def fmt_ratio(t: float | None, base: float | None) -> str:
    if t is None or not base:
        return "-"
    r = t / base
    return f"{r:.2f}x" if r < 10 else f"{r:,.0f}x"


def table(rows: list[dict], base: dict) -> str:
    lines = ["| implementation | IK ratio vs C loop | FK ratio vs C loop | IK per call | FK per call |",
             "|---|---:|---:|---:|---:|"]
    for r in rows:
        ik, fk = r.get("ik"), r.get("fk")
        if "wall_s" in r:
            lines.append(f"| {r['name']} | | | {fmt_time(r['wall_s'])} | |")
            continue
        lines.append(f"| {r['name']} | {fmt_ratio(ik, base['ik'])} | {fmt_ratio(fk, base['fk'])} | {fmt_time(ik)} | "
                     f"{fmt_time(fk)} |")
    return "\n".join(lines)


def goals(wrist_rows: list[dict], dh_measured: tuple[dict, list[dict]], regen: dict | None) -> list[dict]:
    """Issue 13's goals, each as (ratio or time measured in this run, the goal, met?)."""
    loops, rows = dh_measured
    by = {r["name"]: r for r in rows}
    py = next((r for r in rows if r["name"].startswith("wristkin from Python, backend")), {})
    batch = next((r for r in rows if r["name"].startswith("wristkin ik_batch / fk_batch from Python, per pose, "
                                                           "backend")), {})
    eaik, pin = by.get("EAIK (DhRobot)", {}), by.get("pinocchio", {})
    wrist_c = wrist_rows[0]
    wrist_py = next(r for r in wrist_rows if r["name"].startswith("generated Python, scalar"))

    def ratio(a, b):
        return None if a is None or not b else a / b
    out = [
        ("PUMA-560 IK from Python / EAIK's (scalar)", ratio(py.get("ik_us"), eaik.get("ik_us")), 0.5, "x"),
        ("PUMA-560 IK from Python / EAIK's (batch, per pose)", ratio(batch.get("ik_us"), eaik.get("ik_us")), 0.5,
         "x"),
        ("PUMA-560 FK from Python / pinocchio's", ratio(py.get("fk_us"), pin.get("fk_us")), 0.5, "x"),
        ("PUMA-560 Jacobian from Python / pinocchio's", ratio(py.get("jac_us"), pin.get("jac_us")), 0.5, "x"),
        ("underactuated wrist FK (every mode) from Python", wrist_py["fk"], 5e-6, "s"),
        ("underactuated wrist FK (every mode), C loop", wrist_c["fk"], 2e-6, "s"),
        ("underactuated wrist IK, C loop", wrist_c["ik"], 200e-9, "s"),
        ("PUMA-560 IK, C loop", loops["puma560"]["ik_ns"] * 1e-9, 600e-9, "s"),
    ]
    if regen is not None:
        out.append(("`derive.cli regenerate` of the catalogue, wall", regen["wall_s"], 40.0, "s"))
    return [{"goal": g, "measured": m, "target": t, "unit": u, "met": m is not None and m <= t} for g, m, t, u in out]


def goals_table(rows: list[dict]) -> str:
    lines = ["| goal | measured | target | met |", "|---|---:|---:|:---:|"]
    for r in rows:
        m = "-" if r["measured"] is None else (f"{r['measured']:.2f}x" if r["unit"] == "x" else fmt_time(r["measured"]))
        t = f"≤ {r['target']}x" if r["unit"] == "x" else f"≤ {fmt_time(r['target'])}"
        lines.append(f"| {r['goal']} | {m} | {t} | {'yes' if r['met'] else 'no'} |")
    return "\n".join(lines)


README_START, README_END = "<!-- bench:start (written by `make bench`) -->", "<!-- bench:end -->"


def write_readme(text: str, readme: Path = ROOT / "README.md") -> None:
    """Put `text` between the README's bench markers (the tables there come from this run only)."""
    src = readme.read_text()
    i, j = src.index(README_START), src.index(README_END)
    readme.write_text(src[:i + len(README_START)] + "\n" + text.strip() + "\n" + src[j:])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--regenerate", action="store_true", help="also time `derive.cli regenerate` once")
    ap.add_argument("--casadi", type=Path, default=CASADI_FILE,
                    help="the .casadi file (default: generated/casadi/underactuated_wrist.casadi)")
    ap.add_argument("--quick", action="store_true", help="fewer calls (smoke test)")
    ap.add_argument("--readme", action="store_true", help="write the tables into README.md (between its markers)")
    args = ap.parse_args(argv)
    for sub in (".", "tests", "generated/python"):
        sys.path.insert(0, str(ROOT / sub))
    if shutil.which("gcc") is None:
        print("error: gcc not found", file=sys.stderr)
        return 1

    q = args.quick
    n = {"c_ik": 20_000 if q else 200_000, "c_fk": 5_000 if q else 50_000, "py_ik": 200 if q else 2_000,
         "py_fk": 50 if q else 500, "b_ik": 1_000 if q else 10_000, "b_fk": 20 if q else 200,
         "ref_ik": 20 if q else 200, "ref_fk": 4 if q else 20}
    t_start = time.perf_counter()
    machine = machine_info()

    base, c_raw = c_loop(n["c_ik"], n["c_fk"])
    rows = [base]
    rows += fastest_of_rounds(lambda: ctypes_rows(ik_poses(n["py_ik"]), fk_joints(n["py_fk"]))
                              + python_rows(ik_poses(n["py_ik"]), fk_joints(n["py_fk"]), ik_poses(n["b_ik"]),
                                            fk_joints(n["b_fk"])), ("ik", "fk"), rounds=3)
    # the C loop twice more, after the Python rows and after the reference and CasADi rows: the VM's host has slow
    # phases of a few seconds (1.5x on every row, C loops included), so the base every ratio divides by is the
    # fastest of three runs spread over the wrist's part of the bench
    later = [c_loop(n["c_ik"], n["c_fk"])[0]]
    rows.append(reference_row(ik_poses(n["ref_ik"]), fk_joints(n["ref_fk"])))
    rows.append(casadi_row(args.casadi, ik_poses(n["py_ik"])))
    later.append(c_loop(n["c_ik"], n["c_fk"])[0])
    for k in ("ik", "fk"):
        base[k] = min(base[k], *(again[k] for again in later))
    base["note"] = base["note"].replace("best of", "three runs spread over the bench, best of")
    regen = regenerate_row() if args.regenerate else None
    if regen is not None:
        rows.append(regen)

    print(f"machine: {machine['arch']}, {machine['cpu']} ({machine['cpus']} CPUs), "
          f"Python {machine['python']}, {machine['gcc']}, numpy {machine['numpy']}; "
          f"load average {machine['loadavg']}")
    print()
    print(table(rows, base))
    print()
    notes = [f"- {r['name']}: {r['note']}" for r in rows if r.get("note")]
    print("\n".join(notes))
    print()
    import dh  # bench/dh.py: the DH chains and the PUMA-560 peers, measured in this same run

    dh_measured = dh.measure(quick=args.quick)
    dh_text = dh.tables(measured=dh_measured)
    print(dh_text)
    print()
    import rsr  # bench/rsr.py: the 3-RSR wrist and the SCARA + 3-RSR hybrid, same run

    rsr_text = rsr.tables(quick=args.quick)
    print(rsr_text)
    import screws  # bench/screws.py: the finite-screw 3T2R robots (seed 003), same run

    screws_text = screws.tables(quick=args.quick)
    print()
    print(screws_text)
    atlas_text = atlas_bench().tables(quick=args.quick)  # the design atlas's throughput and scaling, same run
    print()
    print(atlas_text)
    import own_robots  # bench/own_robots.py: `wristkin derive` on the test robots vs EAIK / ik-geo, same run

    print()
    own_text = own_robots.report(50 if args.quick else 200)
    print(own_text)
    import real_descriptions  # bench/real_descriptions.py: nine robots as shipped vs the URDF product and EAIK

    print()
    real_text = real_descriptions.report(30 if args.quick else 100)
    print(real_text)
    import general6r  # bench/general6r.py: arms no decomposition fits, by elimination (issue 23), same run

    print()
    g6_text = general6r.report(20 if args.quick else 100)
    print(g6_text)
    import near_singular  # bench/near_singular.py: own robots near their singularities (issue 22), same run

    print()
    near_text = near_singular.report()
    print(near_text)
    goal_rows = goals(rows, dh_measured, regen)
    machine_line = (f"Machine: {machine['cpu']} ({machine['cpus']} CPUs), Python {machine['python']}, "
                    f"{machine['gcc']}, numpy {machine['numpy']} (BLAS threads: "
                    f"{os.environ['OPENBLAS_NUM_THREADS']}); load average {machine['loadavg']}; peers: "
                    f"{dh.peer_versions()}.")
    summary = "\n\n".join([machine_line, "Goals (issue 13), measured in this run:", goals_table(goal_rows),
                            "Underactuated wrist (paper design), per call; ratio = time / generated C loop:",
                            table(rows, base), "\n".join(f"- {r['name']}: {r['note']}" for r in rows if r.get("note")),
                            dh_text, rsr_text, screws_text, atlas_text, own_text, real_text, g6_text, near_text])
    print("\n" + goals_table(goal_rows))
    if args.readme:
        write_readme(summary)
        print("README.md: the tables between the bench markers rewritten from this run")
    print(f"\ntimed in {time.perf_counter() - t_start:.1f} s; "
          f"results in {BUILD_DIR.relative_to(ROOT)}/results.json")

    BUILD_DIR.mkdir(parents=True, exist_ok=True)
    for r in rows:
        for k in ("ik", "fk"):
            t = r.get(k)
            r[f"{k}_ratio_vs_c_loop"] = None if t is None else t / base[k]
    result = {"machine": machine, "unit": "seconds per call", "repeats_python": REPEATS, "counts": n,
              "c_loop_raw": c_raw, "rows": rows, "dh_tables_markdown": dh_text,
              "rsr_tables_markdown": rsr_text, "screw_tables_markdown": screws_text,
              "atlas_tables_markdown": atlas_text, "goals": goal_rows}
    (BUILD_DIR / "results.json").write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
