"""The atlas dataset: an xarray Dataset in Zarr, one dimension per swept design parameter (coordinates in degrees
or metres), one variable per measure (attrs: units, definition, which way is better), the sweep's settings in the
dataset attrs. open_atlas(DIR) opens it."""

from __future__ import annotations

import json
import math
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

import numpy as np


def design_dims(ds) -> tuple[str, ...]:
    """The dataset's design-parameter dimensions (the swept axes, in sweep order)."""
    return tuple(json.loads(ds.attrs["design_dims"]))


EXTRA_COORDS = {"modes": None, "motor": (1, 2, 3)}  # motor: Phi_1, Phi_2 (motors), Phi_3 (sensor)
CHUNK = 32  # design points per chunk along each design dimension


def _version() -> str:
    try:
        return version("wristkin")
    except PackageNotFoundError:
        return "(not installed)"


def write_dataset(path: Path, plan, mech, measures: dict, timing: dict):
    import xarray as xr

    sweep = plan.sweep
    dims = tuple(a.name for a in sweep.axes)
    coords = {a.name: (a.name, np.array(a.values), {"units": a.unit}) for a in sweep.axes}
    variables = {}
    for m in mech.measures(plan.options):
        arr = np.asarray(measures[m.name], dtype=float).reshape(*sweep.shape, *measures[m.name].shape[1:])
        variables[m.name] = (dims + m.extra, arr, {"units": m.unit, "definition": m.definition,
                                                   "better": m.better or ""})
        for extra, size in zip(m.extra, arr.shape[len(dims):], strict=True):
            labels = EXTRA_COORDS.get(extra)
            coords[extra] = (extra, np.array(labels if labels else np.arange(size)))
    ds = xr.Dataset(variables, coords=coords)
    ds.attrs.update({
        "mechanism": mech.key, "name": mech.name, "design_dims": json.dumps(list(dims)), "wristkin_version": _version(),
        "inputs_hash": getattr(mech.module, "INPUTS_HASH", ""), "backend": getattr(mech.module, "BACKEND", ""),
        "samples_per_design": plan.sample_count, "sampling": "grid" if plan.grid else "random", "seed": plan.seed,
        "threshold": plan.options.threshold, "tilt_max_deg": math.degrees(plan.options.tilt_max),
        "fixed_design": json.dumps(dict(sorted(sweep.fixed.items()))),
        "design_default": json.dumps({n: sweep.to_display(n, v) for n, v in
                                      zip(mech.module.DESIGN_NAMES, mech.module.DESIGN_DEFAULT, strict=True)}),
        "units_note": "angles in degrees, lengths in metres, fractions and indices dimensionless",
        "identity": json.dumps(plan.identity(), sort_keys=True), "timing": json.dumps(timing),
    })
    encoding = {name: {"chunks": tuple(min(CHUNK, n) for n in ds[name].shape)} for name in ds.data_vars}
    ds.to_zarr(str(path), mode="w", encoding=encoding, consolidated=False)
    return ds


def open_atlas(out: str | Path):
    """The measures of a finished sweep in `out` (its atlas.zarr) as an xarray Dataset."""
    import xarray as xr

    path = Path(out)
    path = path if path.name.endswith(".zarr") else path / "atlas.zarr"
    return xr.open_zarr(str(path), consolidated=False)
