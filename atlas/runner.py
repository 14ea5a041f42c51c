"""Run a sweep on Dask: designs x sample blocks split into tasks, each task calling the generated C batch
solvers for its designs over its blocks; the client writes each finished task's partial results into a Zarr
store (one writer, chunk-aligned regions), so an interrupted sweep resumes from the tasks already stored. Exact
partials (partials.py) make the result the same bits for any chunking, worker count or scheduler."""

from __future__ import annotations

import json
import math
import os
import shutil
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from . import sampling
from .mechanisms import Options, mechanism
from .partials import merge, reduce_axis
from .sweep import Sweep, parse_sweep

FORMAT = 3  # of partials.zarr: a store written under another format is not resumed
TARGET_TASK_SOLVES = 131072  # solves per task by default: ~0.2-1 s of C work; at 65536 (~0.09 s tasks) the
# client and scheduler, on the cores the workers use, held 2 local workers to 1.68x one (1.75x at this size)


class StoreMismatch(ValueError):
    """--out holds a sweep with other settings (resuming it would mix two sweeps)."""


@dataclass(frozen=True)
class Plan:
    sweep: Sweep
    samples: int
    seed: int
    grid: bool
    options: Options
    design_chunk: int
    blocks_per_task: int
    dim: int = 3  # sample dimension (joints of a serial arm; 3 for the wrists)
    n_blocks: int = field(init=False, default=0)

    def __post_init__(self):
        object.__setattr__(self, "n_blocks", sampling.blocks(self.samples, self.dim, self.grid))

    @property
    def n_design_chunks(self) -> int:
        return math.ceil(self.sweep.size / self.design_chunk)

    @property
    def n_sample_chunks(self) -> int:
        return math.ceil(self.n_blocks / self.blocks_per_task)

    @property
    def sample_count(self) -> int:
        return sampling.sample_count(self.samples, self.dim, self.grid)

    def identity(self) -> dict:
        """What the stored partials depend on (the chunking too: it is the store's layout)."""
        return {"format": FORMAT, "sweep": self.sweep.to_json(), "samples": self.samples, "seed": self.seed,
                "grid": self.grid, "options": asdict(self.options), "design_chunk": self.design_chunk,
                "blocks_per_task": self.blocks_per_task, "block": sampling.BLOCK}

    def tasks(self):
        for i in range(self.n_design_chunks):
            for j in range(self.n_sample_chunks):
                yield i, j


def make_plan(mechanism_name: str, sweeps: list[str], designs: list[str] | None = None, samples: int = 1000,
              seed: int = 0, grid: bool = False, options: Options | None = None, design_chunk: int | None = None,
              sample_chunk: int | None = None) -> Plan:
    mech = mechanism(mechanism_name)
    sweep = parse_sweep(mech.module, sweeps, designs)
    if samples < 1:
        raise ValueError("--samples must be at least 1")
    dim = mech.joint_dim
    n_blocks = sampling.blocks(samples, dim, grid)
    blocks_per_task = n_blocks if sample_chunk is None else max(1, math.ceil(sample_chunk / sampling.BLOCK))
    blocks_per_task = min(blocks_per_task, n_blocks, max(1, TARGET_TASK_SOLVES // sampling.BLOCK))
    per_design = 2 * min(blocks_per_task * sampling.BLOCK, sampling.sample_count(samples, dim, grid))
    if design_chunk is None:
        design_chunk = max(1, TARGET_TASK_SOLVES // per_design)
    return Plan(sweep, samples, seed, grid, options or Options(), max(1, min(design_chunk, sweep.size)),
                blocks_per_task, dim)


def _warm(name: str) -> None:
    mechanism(name)


def compute_task(name: str, designs: np.ndarray, seed: int, samples: int, grid: bool, options: Options,
                 block_lo: int, block_hi: int) -> tuple[dict, float, int, float]:
    """Partial results of `designs` (k, n_params) over sample blocks [block_lo, block_hi): (partials, seconds of
    this task, solves, CPU seconds of its thread). Runs on a worker; the C batch calls release the GIL. The CPU
    time tells a task slowed by other jobs on the machine (wall > CPU) from one that does more work."""
    t0, c0 = time.perf_counter(), time.thread_time()
    mech = mechanism(name)
    specs = mech.partials()
    out = {s.name: s.empty(len(designs)) for s in specs}
    units = [mech.unit_blocks(seed, b, samples, grid) for b in range(block_lo, block_hi)]
    solves = 0
    for k, params in enumerate(designs):
        design = mech.make_design(params)
        if design is None:
            continue
        for u_pose, u_joint in units:
            part = mech.evaluate(design, u_pose, u_joint, options)
            solves += mech.solves(u_pose, u_joint)
            for s in specs:
                if s.name in part:  # per-design partials (design_partials) are not per block
                    out[s.name][k] = merge(s, out[s.name][k], part[s.name])
        out["design_ok"][k] = 1  # once per design, not per block
        if block_lo == 0 and hasattr(mech, "design_partials"):  # per-design measures: in the first sample chunk
            for name, value in mech.design_partials(design, options).items():
                out[name][k] = value
    return out, time.perf_counter() - t0, solves, time.thread_time() - c0


# ---------------------------------------------------------------------------- the partials store
def _layout(specs) -> list[tuple]:
    """(spec, start, size) of each partial in a task's packed int64 row (floats stored bit for bit)."""
    out, start = [], 0
    for s in specs:
        size = math.prod(s.shape)
        out.append((s, start, size))
        start += size
    return out


def pack(specs, part: dict) -> np.ndarray:
    """A task's partials as one (k, K) int64 array: one Zarr write per task instead of one per partial (the
    client writes every finished task; 16 small writes cost ~10x one)."""
    cols = []
    for s, _, size in _layout(specs):
        arr = np.ascontiguousarray(part[s.name], dtype=s.dtype).reshape(-1, size)
        cols.append(arr if s.dtype == np.int64 else arr.view(np.int64))
    return np.concatenate(cols, axis=1)


def unpack(specs, packed: np.ndarray) -> dict:
    """The partials from packed rows (..., K), each with its dtype and shape."""
    out = {}
    for s, start, size in _layout(specs):
        block = np.ascontiguousarray(packed[..., start:start + size])
        block = block if s.dtype == np.int64 else block.view(np.float64)
        out[s.name] = block.reshape(*packed.shape[:-1], *s.shape)
    return out


def _open_partials(path: Path, plan: Plan, mech, overwrite: bool):
    import zarr

    ident = json.dumps(plan.identity(), sort_keys=True)
    if path.exists() and overwrite:
        shutil.rmtree(path)
    if path.exists():
        group = zarr.open_group(str(path), mode="a")
        if group.attrs.get("identity") != ident:
            raise StoreMismatch(f"{path.parent} holds a sweep with other settings; use another --out, the same "
                                "settings to resume, or --overwrite")
        return group
    group = zarr.open_group(str(path), mode="w")
    group.attrs["identity"] = ident
    size, s_chunks = plan.sweep.size, plan.n_sample_chunks
    width = sum(n for _, _, n in _layout(mech.partials()))
    group.create_array("packed", shape=(size, s_chunks, width), chunks=(plan.design_chunk, 1, width),
                       dtype=np.int64, fill_value=0)
    # a task's seconds, NaN until it is stored: one small write per finished task marks it done (a separate done
    # flag was a second read-modify-write of the same chunk, ~1 ms of the client's CPU per task)
    group.create_array("seconds", shape=(plan.n_design_chunks, s_chunks), chunks=(plan.n_design_chunks, s_chunks),
                       dtype=np.float64, fill_value=np.nan)
    return group


class _Progress:
    """A one-line progress bar on stderr (redrawn in place on a terminal, every 10 % otherwise)."""

    def __init__(self, total: int, done: int, enabled: bool, stream=None):
        self.total, self.done, self.enabled = total, done, enabled
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self.t0, self.solves, self.last_decile = time.perf_counter(), 0, -1

    def step(self, solves: int):
        self.done += 1
        self.solves += solves
        if not self.enabled:
            return
        frac = self.done / max(1, self.total)
        decile = int(frac * 10)
        if not self.tty and decile == self.last_decile and self.done != self.total:
            return
        self.last_decile = decile
        dt = time.perf_counter() - self.t0
        rate = self.solves / dt if dt > 0 else 0.0
        bar = "#" * int(30 * frac) + "." * (30 - int(30 * frac))
        line = f"atlas [{bar}] {self.done}/{self.total} chunks  {rate:,.0f} solves/s  {dt:.1f} s"
        self.stream.write(("\r" + line) if self.tty else line + "\n")
        if self.tty and self.done == self.total:
            self.stream.write("\n")
        self.stream.flush()


def _client(workers: int | None, scheduler: str | None):
    """(client, closer): an existing cluster (--scheduler), a local cluster of `workers` processes (--workers),
    else the local in-process scheduler with one thread per core (the C releases the GIL)."""
    from distributed import Client, LocalCluster

    if scheduler:
        client = Client(scheduler)
        return client, client.close
    import dask

    # the clusters the atlas starts: no dashboard, and no statistical profiler in the workers (a thread that takes
    # the GIL every 10 ms to sample the stack: CPU a 2-core machine's second worker needs)
    with dask.config.set({"distributed.worker.profile.enabled": False}):
        if workers:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        else:
            cluster = LocalCluster(n_workers=1, threads_per_worker=os.cpu_count() or 1, processes=False,
                                   dashboard_address=None)
    client = Client(cluster)

    def close():
        client.close()
        cluster.close()

    return client, close


def run_sweep(mechanism_name: str, sweeps: list[str], out: str | Path, designs: list[str] | None = None,
              samples: int = 1000, seed: int = 0, grid: bool = False, options: Options | None = None,
              workers: int | None = None, scheduler: str | None = None, design_chunk: int | None = None,
              sample_chunk: int | None = None, progress: bool = True, overwrite: bool = False,
              max_tasks: int | None = None):
    """Run (or resume) a sweep into `out`; returns the xarray Dataset of measures (also `out`/atlas.zarr), or None
    when `max_tasks` stopped it before the end (a test's interruption)."""
    from distributed import as_completed

    plan = make_plan(mechanism_name, sweeps, designs, samples, seed, grid, options, design_chunk, sample_chunk)
    mech = mechanism(mechanism_name)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    group = _open_partials(out / "partials.zarr", plan, mech, overwrite)
    done = np.isfinite(np.asarray(group["seconds"][...]))
    todo = [(i, j) for i, j in plan.tasks() if not done[i, j]]
    if max_tasks is not None:
        todo = todo[:max_tasks]
    matrix = plan.sweep.design_matrix()
    bar = _Progress(plan.n_design_chunks * plan.n_sample_chunks, int(done.sum()), progress)
    t0 = time.perf_counter()
    if todo:
        client, close = _client(workers, scheduler)
        try:
            client.run(_warm, mech.key)  # imports on every worker before the clock starts
            futures = {}
            for i, j in todo:
                d0, d1 = i * plan.design_chunk, min(plan.sweep.size, (i + 1) * plan.design_chunk)
                b0, b1 = j * plan.blocks_per_task, min(plan.n_blocks, (j + 1) * plan.blocks_per_task)
                fut = client.submit(compute_task, mech.key, matrix[d0:d1], plan.seed, plan.samples, plan.grid,
                                    plan.options, b0, b1, pure=False)
                futures[fut] = (i, j, d0, d1)
            specs = mech.partials()
            t_compute = time.perf_counter()
            cpu = []
            for fut in as_completed(futures):
                i, j, d0, d1 = futures.pop(fut)
                part, secs, solves, cpu_secs = fut.result()
                cpu.append(cpu_secs)
                group["packed"][d0:d1, j] = pack(specs, part)
                group["seconds"][i, j] = secs  # after the data: a task counts as stored only once it is
                done[i, j] = True
                bar.step(solves)
            compute_wall = time.perf_counter() - t_compute
        finally:
            close()
    else:
        compute_wall, cpu = 0.0, []
    wall = time.perf_counter() - t0
    if not done.all():
        return None
    from .store import write_dataset

    stored = unpack(mech.partials(), np.asarray(group["packed"][...]))
    totals = {s.name: reduce_axis(s, stored[s.name], 1) for s in mech.partials()}
    measures = mech.finalize(totals, plan.options)
    timing = {"wall_seconds_this_run": wall, "compute_seconds_this_run": compute_wall,
              "tasks_this_run": len(todo), "tasks": int(done.size), "task_cpu_seconds_this_run": cpu,
              "task_seconds": np.asarray(group["seconds"][...]).ravel().tolist()}
    return write_dataset(out / "atlas.zarr", plan, mech, measures, timing)
