"""The design atlas in `make bench` (issue 24): solves per second per core inside the atlas against the bare
generated C batch calls, 2 Dask workers against 1, and a seed-000 sweep of 10^4 designs x 10^3 samples with its
wall time and an N-machine estimate (measured per-chunk cost x chunk count / N).

Called from bench/run.py; also runs alone:  .venv/bin/python bench/atlas.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import tempfile
import time

import numpy as np


def _per_core(name: str, designs: int, samples: int, repeats: int = 3) -> dict:
    """One thread, no Dask: the atlas's task function (sampling, C batch IK + FK, local index, reductions) vs
    the same ik_batch + fk_batch calls alone, on the same blocks."""
    from wristkin_atlas import sampling
    from wristkin_atlas.mechanisms import Options, mechanism
    from wristkin_atlas.runner import compute_task

    mech = mechanism(name)
    m = mech.module
    opts = Options()
    matrix = np.repeat(np.asarray(m.DESIGN_DEFAULT, dtype=float)[None, :], designs, axis=0)
    n_blocks = sampling.blocks(samples, 3, False)
    d = m.make_design(m.DESIGN_DEFAULT)
    blocks = [(sampling.unit_block(0, 0, b, samples, 3, False), sampling.unit_block(0, 1, b, samples, 3, False))
              for b in range(n_blocks)]
    poses = [mech.poses(u, opts) if name == "underactuated_wrist" else mech.poses(u, d, opts) for u, _ in blocks]
    joints = [mech.joints(u, d) for _, u in blocks]
    solves = designs * 2 * samples

    def bare():
        for _ in range(designs):
            for p, q in zip(poses, joints, strict=True):
                m.ik_batch(p, d)
                m.fk_batch(q, d)

    def atlas():
        compute_task(name, matrix, 0, samples, False, opts, 0, n_blocks)

    best = {}
    for label, fn in (("bare", bare), ("atlas", atlas)):
        fn()
        times = []
        for _ in range(repeats):
            t = time.perf_counter()
            fn()
            times.append(time.perf_counter() - t)
        best[label] = min(times)
    per_design = 0.0  # a mechanism's per-design (not per-sample) measures, e.g. the 3-RSR's exact swing profile
    if hasattr(mech, "design_partials"):
        mech.design_partials(d, opts)
        t = time.perf_counter()
        for _ in range(designs):
            mech.design_partials(d, opts)
        per_design = (time.perf_counter() - t) / designs
    sample_path = best["atlas"] - designs * per_design
    return {"mechanism": name, "solves": solves, "bare_per_s": solves / best["bare"],
            "atlas_per_s": solves / best["atlas"], "ratio": best["bare"] / best["atlas"],
            "per_design": per_design, "ratio_samples": best["bare"] / sample_path,
            "samples": samples}


def _sweep(sweeps: list[str], samples: int, workers: int, design_chunk: int | None = None) -> dict:
    import wristkin_atlas

    with tempfile.TemporaryDirectory() as out:
        t = time.perf_counter()
        ds = wristkin_atlas.run_sweep("underactuated_wrist", sweeps, out, samples=samples, workers=workers,
                                      design_chunk=design_chunk, progress=False)
        wall = time.perf_counter() - t
        timing = json.loads(ds.attrs["timing"])
        gci = ds["gci"].values
    secs = [s for s in timing["task_seconds"] if s == s]
    cpu = timing["task_cpu_seconds_this_run"]
    return {"workers": workers, "wall": wall, "compute": timing["compute_seconds_this_run"], "chunks": len(secs),
            "chunk_mean": float(np.mean(secs)), "chunk_total": float(np.sum(secs)), "gci": gci,
            "chunk_cpu_mean": float(np.mean(cpu)), "chunk_cpu_total": float(np.sum(cpu))}


def _scaling(quick: bool) -> tuple[dict, dict, list]:
    """1 worker and 2 workers on the same sweep, alternated, the faster of two runs each (the machine is shared:
    the other jobs' load changes between runs). The atlas's default chunking: 16 chunks of ~0.18 s here, so a
    task's fixed cost (Dask's scheduling, the client's store write, ~2-3 ms, on the cores the workers use) is a
    small part of a chunk and each worker gets 8. The load average is read around each run."""
    scale = ["alpha1=50:70:8", "beta2=35:55:8"] if quick else ["alpha1=50:70:16", "beta2=35:55:16"]
    runs, loads = {1: [], 2: []}, []
    for _ in range(1 if quick else 2):
        for workers in (1, 2):
            before = os.getloadavg()[0]
            runs[workers].append(_sweep(scale, 4000, workers))  # the atlas's own chunking (TARGET_TASK_SOLVES)
            loads.append((workers, before, os.getloadavg()[0]))
    one, two = (min(runs[w], key=lambda r: r["compute"]) for w in (1, 2))
    return one, two, loads


def measure(quick: bool = False) -> dict:
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    per_core = [_per_core("underactuated_wrist", 4 if quick else 16, 2048),
                _per_core("rsr_wrist", 4 if quick else 16, 2048)]
    one, two, loads = _scaling(quick)
    same = bool(np.array_equal(one["gci"], two["gci"], equal_nan=True))
    big_axes = (["alpha1=40:80:4", "alpha2=40:80:4", "beta1=20:40:4", "beta2=30:60:4"] if quick else
                ["alpha1=40:80:10", "alpha2=40:80:10", "beta1=20:40:10", "beta2=30:60:10"])
    big = _sweep(big_axes, 1000, 2)
    n_designs = math.prod(int(a.rsplit(":", 1)[1]) for a in big_axes)
    return {"per_core": per_core, "one": one, "two": two, "same_bits": same, "scaling_loads": loads, "big": big,
            "big_designs": n_designs,
            "big_samples": 1000, "cpus": os.cpu_count(), "load": os.getloadavg(), "cpu_model": _cpu_model()}


def _cpu_model() -> str:
    """The CPU's model name (Linux /proc/cpuinfo; the platform's processor string elsewhere)."""
    import platform

    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def tables(quick: bool = False, measured: dict | None = None) -> str:
    r = measured or measure(quick)
    lines = ["Design atlas (issue 24), measured in this run (the machine is shared with other jobs: load average "
             + ", ".join(f"{x:.1f}" for x in r["load"]) + f" on {r['cpus']} CPUs ({r['cpu_model']}), so wall times "
             "are noisy):", "",
             "| atlas measure | value | goal |", "|---|---|---|"]
    for pc in r["per_core"]:
        extra = (f"; without its per-design swing profile ({1e3 * pc['per_design']:.1f} ms per design, "
                 f"{pc['samples']} samples per design here): {100 * pc['ratio_samples']:.0f} %"
                 if pc["per_design"] else "")
        lines.append(f"| {pc['mechanism']}: solves/s per core inside the atlas / bare C batch ("
                     f"{pc['atlas_per_s']:,.0f} / {pc['bare_per_s']:,.0f}{extra}) | {100 * pc['ratio']:.0f} % | "
                     ">= 80 % |")
    one, two, big = r["one"], r["two"], r["big"]
    loads = "; ".join(f"{w} worker{'s' if w > 1 else ''}: {a:.1f} -> {b:.1f}" for w, a, b in r["scaling_loads"])
    lines.append(f"| 2 workers vs 1 ({one['chunks']} chunks, compute wall {one['compute']:.2f} s -> "
                 f"{two['compute']:.2f} s, the faster of the runs; identical results: "
                 f"{'yes' if r['same_bits'] else 'NO'}; 1-min load average around the runs: {loads}) | "
                 f"{one['compute'] / two['compute']:.2f}x | >= 1.7x |")
    cpu_ratio = one["chunk_cpu_mean"] / two["chunk_cpu_mean"] if two["chunk_cpu_mean"] else 0.0
    share1 = one["chunk_cpu_total"] / one["compute"]
    share2 = two["chunk_cpu_total"] / two["compute"]
    lines.append(f"| where the time went: CPU per chunk {1e3 * one['chunk_cpu_mean']:.1f} ms (1 worker) vs "
                 f"{1e3 * two['chunk_cpu_mean']:.1f} ms (2 workers), wall per chunk {1e3 * one['chunk_mean']:.1f} ms "
                 f"vs {1e3 * two['chunk_mean']:.1f} ms; chunk CPU / compute wall {share1:.2f} of 1 core vs "
                 f"{share2:.2f} of 2 (a chunk's CPU cost unchanged by a second worker, its wall time longer: the "
                 "cores went to other jobs) | CPU per chunk alone / with 2 workers "
                 f"{cpu_ratio:.2f} (1: no contention inside the atlas) | - |")
    n = r["big_designs"] * r["big_samples"] * 2
    lines.append(f"| seed-000 sweep, {r['big_designs']:,} designs x {r['big_samples']:,} pose + "
                 f"{r['big_samples']:,} joint samples ({n:,} solves) on 2 workers | wall {big['wall']:.1f} s "
                 f"(compute {big['compute']:.1f} s, {n / big['compute']:,.0f} solves/s) | - |")
    est = ", ".join(f"{k} machines ~{big['chunk_total'] / (k * 2):.1f} s" for k in (1, 4, 16))
    lines.append(f"| estimate on N 2-core machines: measured chunk cost x chunk count / (2 N) "
                 f"({big['chunks']} chunks x {big['chunk_mean']:.3f} s) | {est} | estimate |")
    return "\n".join(lines)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    print(tables(args.quick))
