"""wristkin's design atlas: sweep a mechanism's design parameters, measure each design over a seeded sample of
its workspace with the generated C batch solvers, on Dask, into a labelled Zarr store and a report (docs/atlas.md).

    wristkin atlas underactuated_wrist --sweep alpha1=40:80:9 --sweep beta2=30:60:7 --samples 2000 --out DIR

Needs the `atlas` extra (dask, distributed, xarray, zarr): pip install 'wristkin[atlas]'. One job per module:
sweep (the design grid), sampling (the seeded workspace sample), conditioning (1/kappa of batched 3x3 Jacobians),
partials (exact, order-independent reductions), mechanisms (what is measured per mechanism: the parallel wrists),
serial (the serial arms), runner (Dask, the resumable store), store (the xarray/Zarr dataset), maps (workspace and
singularity maps of one design), report (tables, figures, Markdown), html (the self-contained HTML report), seeds
(the seeds' claims), cli.
"""

from __future__ import annotations

__all__ = ["open_atlas", "run_sweep"]


def __getattr__(name):  # lazy: `wristkin atlas` reports a missing extra itself instead of failing on import
    if name == "run_sweep":
        from .runner import run_sweep

        return run_sweep
    if name == "open_atlas":
        from .store import open_atlas

        return open_atlas
    raise AttributeError(name)
