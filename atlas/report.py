"""The atlas's outputs beside the store: best.csv (the best designs per measure), figures/*.png (measure maps
over two design parameters with the catalogue (seed) design marked; workspace and singularity maps of the focus
design), report.md, which shows them with the measures' definitions and the seeds' claims checked, and
report.html, the same report in one self-contained file (figures embedded as base64 PNG). Deterministic bytes: the
same store gives the same files (matplotlib's Agg with a fixed dpi and no Software metadata; the report states no
timings, which stay in the store's attrs)."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

from . import html as html_mod
from . import maps as maps_mod
from . import seeds
from .hybrid import ScaraRsr
from .mechanisms import Options, RsrWrist, UnderactuatedWrist, mechanism
from .serial import SerialArm
from .store import design_dims

MAP_MEASURES = ("reachable", "gci", "gci_best", "worst_li", "near_inverse", "near_direct", "fk_modes_mean",
                "fk_no_assembly", "fk_near_direct", "swing_all", "swing_peak", "ik_sets_mean", "singular",
                "near_singular", "manipulability_mean", "manipulability_min", "arm_assembles", "reach_max",
                "reach_min")
TOP = 5  # designs listed per measure
DPI = 110  # fixed: the figures' bytes depend on nothing but the data


def _save(fig, path: Path) -> None:
    """PNG without the Software tag (matplotlib's version: the bytes would change with it); Agg writes no date."""
    fig.savefig(path, dpi=DPI, metadata={"Software": None})


def _scalar_measures(ds):
    dims = design_dims(ds)
    return [n for n, v in ds.data_vars.items() if v.dims == dims]


def best_rows(ds) -> list[dict]:
    """The TOP designs per ranked scalar measure (ties broken by design order: deterministic)."""
    rows = []
    dims = design_dims(ds)
    for name in _scalar_measures(ds):
        var = ds[name]
        better = var.attrs.get("better")
        if not better:
            continue
        flat = var.values.ravel()
        key = np.where(np.isfinite(flat), -flat if better == "max" else flat, np.inf)
        for rank, idx in enumerate(np.argsort(key, kind="stable")[:TOP], start=1):
            if not np.isfinite(key[idx]):
                break
            where = np.unravel_index(idx, var.shape)
            row = {"measure": name, "better": better, "rank": rank, "value": float(flat[idx]),
                   "units": var.attrs.get("units", "")}
            row.update({d: float(ds[d].values[i]) for d, i in zip(dims, where, strict=True)})
            rows.append(row)
    return rows


def _write_csv(path: Path, rows: list[dict]):
    if not rows:
        path.write_text("")
        return
    fields = list(dict.fromkeys(k for r in rows for k in r))
    with path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)


def _slice_2d(ds, var, default: dict):
    """var over its first two design dims, the others at the value nearest the catalogue design."""
    dims = var.dims
    rest = {d: default.get(d, float(ds[d].values[0])) for d in dims[2:]}
    return var.sel(rest, method="nearest") if rest else var, rest


def _plot_measure(plt, ds, name, default, path: Path):
    var = ds[name]
    dims = var.dims
    fig, ax = plt.subplots(figsize=(5.2, 4.0))
    if len(dims) == 1:
        ax.plot(ds[dims[0]].values, var.values, marker=".")
        if dims[0] in default:
            ax.axvline(default[dims[0]], color="k", ls="--", lw=0.8, label="catalogue design")
            ax.legend()
        ax.set_xlabel(f"{dims[0]} ({ds[dims[0]].attrs.get('units', '')})")
        ax.set_ylabel(f"{name} ({var.attrs.get('units', '')})")
        rest = {}
    else:
        sl, rest = _slice_2d(ds, var, default)
        x, y = ds[dims[0]].values, ds[dims[1]].values
        mesh = ax.pcolormesh(x, y, np.asarray(sl.values, dtype=float).T, shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=f"{name} ({var.attrs.get('units', '')})")
        if dims[0] in default and dims[1] in default:
            ax.plot(default[dims[0]], default[dims[1]], marker="*", ms=14, mfc="w", mec="k", ls="none",
                    label="catalogue (seed) design")
            ax.legend(loc="upper right", fontsize=7)
        ax.set_xlabel(f"{dims[0]} ({ds[dims[0]].attrs.get('units', '')})")
        ax.set_ylabel(f"{dims[1]} ({ds[dims[1]].attrs.get('units', '')})")
    title = name + (" at " + ", ".join(f"{k} = {float(v):g}" for k, v in rest.items()) if rest else "")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    _save(fig, path)
    plt.close(fig)


def _focus_design(mech, ds, focus: list[str] | None):
    names = mech.module.DESIGN_NAMES
    angles = set(json.loads(ds.attrs["design_default"]))
    values = json.loads(ds.attrs["design_default"])
    values.update(json.loads(ds.attrs["fixed_design"]))
    for item in focus or []:
        k, _, v = item.partition("=")
        if k in names:
            values[k] = float(v)
    from .sweep import angle_names

    ang = set(angle_names(mech.module)) & angles
    params = [math.radians(values[n]) if n in ang else values[n] for n in names]
    return mech.make_design(params), values


def _focus_plots(plt, mech, design, options, figdir: Path) -> tuple[list[tuple[str, str]], dict | None]:
    figs = []
    if isinstance(mech, ScaraRsr):  # the hybrid's workspace maps are its wrist's (its reach is a measure)
        mech, design = mech.wrist, mech.wrist_design(design)
    if isinstance(mech, UnderactuatedWrist):
        mp = maps_mod.underactuated_maps(mech, design, options)
        t = mp["tilt"]
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        m0 = axes[0].pcolormesh(t["x"], t["y"], t["best_li"], shading="nearest", cmap="magma")
        fig.colorbar(m0, ax=axes[0], label="best 1/kappa_F (0 = unreachable)")
        axes[0].set(xlabel=t["xlabel"], ylabel=t["ylabel"], title="orientation workspace, zero torsion")
        f = mp["modes"]
        m1 = axes[1].pcolormesh(f["x"], f["y"], f["count"], shading="nearest", cmap="tab10", vmin=0, vmax=9)
        fig.colorbar(m1, ax=axes[1], label="real FK assembly modes")
        axes[1].set(xlabel=f["xlabel"], ylabel=f["ylabel"], title=f"assembly modes at theta3 = {f['theta3']:.2f} deg")
        fig.tight_layout()
        _save(fig, figdir / "focus_workspace.png")
        plt.close(fig)
        figs.append(("focus_workspace.png", "Focus design. Left: the orientation workspace over pure tilts (zero "
                     "torsion, R = Rz(psi) Rx(theta) Rz(-psi)), coloured by the best IK set's 1/kappa_F (black: "
                     "unreachable or singular). Right: the number of real FK assembly modes over (theta1, theta2) "
                     "at theta3 = theta0; its boundaries are direct singularities (two modes merge)."))
        return figs, None
    if isinstance(mech, RsrWrist):
        mp = maps_mod.rsr_maps(mech, design, options)
        s = mp["swing"]
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        m0 = axes[0].pcolormesh(s["alpha"], s["beta"], s["best_li"], shading="nearest", cmap="magma")
        fig.colorbar(m0, ax=axes[0], label="best 1/kappa_F over l_bw (0 = unreachable)")
        axes[0].axhline(seeds.SEED002_SWING_ALL_DEG, color="c", ls="--", lw=0.8, label="seed: 60 deg all round")
        axes[0].plot(*seeds.SEED002_SWING_AT, marker="*", ms=12, mfc="w", mec="k", ls="none",
                     label="seed: 75 deg at 30 deg")
        axes[0].legend(fontsize=7, loc="lower right")
        axes[0].set(xlabel="azimuth alpha (deg)", ylabel="swing beta (deg)", title="swing workspace")
        axes[1].plot(s["alpha"], s["max_swing"])
        axes[1].axhline(seeds.SEED002_SWING_ALL_DEG, color="c", ls="--", lw=0.8)
        axes[1].plot(*seeds.SEED002_SWING_AT, marker="*", ms=12, mfc="w", mec="k", ls="none")
        axes[1].set(xlabel="azimuth alpha (deg)", ylabel="max reachable swing (deg)", title="maximum swing")
        fig.tight_layout()
        _save(fig, figdir / "focus_workspace.png")
        plt.close(fig)
        figs.append(("focus_workspace.png", "Focus design. Left: reachable swing workspace over (azimuth, swing), "
                     "some l_bw in [lbw_min, lbw_max] with every leg within its limits, coloured by the best "
                     "1/kappa_F. Right: the maximum reachable swing per azimuth, with the seed's claims."))
        return figs, mp
    if isinstance(mech, SerialArm):
        mp = maps_mod.serial_maps(mech, design, options)
        fig, ax = plt.subplots(figsize=(5.6, 4.2))
        if mp["y"] is None:
            ax.plot(mp["x"], mp["li"])
            ax.set(xlabel=mp["xlabel"], ylabel="local index sigma_min / sigma_max")
        else:
            mesh = ax.pcolormesh(mp["x"], mp["y"], mp["li"], shading="nearest", cmap="magma", vmin=0.0)
            fig.colorbar(mesh, ax=ax, label="local index sigma_min / sigma_max")
            ax.contour(mp["x"], mp["y"], mp["li"], levels=[options.threshold], colors="c", linewidths=0.8)
            ax.set(xlabel=mp["xlabel"], ylabel=mp["ylabel"])
        ax.set_title("conditioning over two joints (the others at 60 % of their range)", fontsize=9)
        fig.tight_layout()
        _save(fig, figdir / "focus_workspace.png")
        plt.close(fig)
        figs.append(("focus_workspace.png", "Focus design: the local index sigma_min / sigma_max of diag(I / L_c, I) "
                     f"J over {mp['xlabel']} and {mp['ylabel'] or 'nothing else'} (the other joints at 60 % of their "
                     "sampled range: revolute 36 deg, a generic value; 0 is often a wrist singularity); black is a "
                     "singularity, the cyan line the threshold "
                     f"{options.threshold:g} below which a sample counts as near-singular."))
    return figs, None


def _canonical_order(ds):
    """The measures in the mechanism's own order (a store read back lists them alphabetically): the summary and the
    report are the same bytes whether they are written from the sweep's result or from the store."""
    order = [m.name for m in mechanism(ds.attrs["mechanism"]).measures(Options(threshold=float(ds.attrs["threshold"])))]
    names = [n for n in order if n in ds.data_vars] + sorted(n for n in ds.data_vars if n not in order)
    return ds[names]


def write_outputs(out, ds, focus: list[str] | None = None, report: bool = True) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    ds = _canonical_order(ds)
    rows = best_rows(ds)
    _write_csv(out / "best.csv", rows)
    paths = [out / "atlas.zarr", out / "best.csv"]
    if not report:
        return paths
    # the figures' bytes: a fixed hash salt (SVG ids; PNG has none), no date, a fixed dpi (_save)
    with matplotlib.rc_context({"svg.hashsalt": "wristkin-atlas", "savefig.dpi": DPI}):
        return paths + _write_report(plt, out, ds, rows, focus)


def _write_report(plt, out: Path, ds, rows, focus) -> list[Path]:
    mech = mechanism(ds.attrs["mechanism"])
    options = Options(threshold=float(ds.attrs["threshold"]), tilt_max=math.radians(float(ds.attrs["tilt_max_deg"])))
    default = json.loads(ds.attrs["design_default"])
    figdir = out / "figures"
    figdir.mkdir(exist_ok=True)
    measure_figs = []
    for name in MAP_MEASURES:
        if name in ds:
            _plot_measure(plt, ds, name, default, figdir / f"map_{name}.png")
            measure_figs.append(name)
    design, focus_values = _focus_design(mech, ds, focus)
    focus_figs, maps = _focus_plots(plt, mech, design, options, figdir) if design is not None else ([], None)
    claims = (seeds.underactuated_claims(mech, ds) if isinstance(mech, UnderactuatedWrist) else
              seeds.rsr_claims(mech, ds, maps) if isinstance(mech, RsrWrist) else [])
    text = _markdown(ds, rows, measure_figs, focus_figs, focus_values, claims)
    (out / "report.md").write_text(text)
    title = f"Design atlas: {ds.attrs.get('name', ds.attrs['mechanism'])}"
    (out / "report.html").write_text(html_mod.render(text, out, title))
    return [out / "report.md", out / "report.html", figdir]


def _fmt(v) -> str:
    return f"{v:.4g}" if isinstance(v, float) else str(v)



def _fixed_text(fixed: str) -> str:
    """The fixed design values to 12 significant digits (degrees converted back from radians show 59.99999999999999)."""
    try:
        values = json.loads(fixed)
    except (TypeError, ValueError):
        return str(fixed)
    return ", ".join(f"{k} = {v:.12g}" for k, v in values.items()) if isinstance(values, dict) else str(fixed)

def _seed_text(ds, dims) -> str:
    """The catalogue (seed) design at the maps' axes, as the star marks it."""
    default = json.loads(ds.attrs["design_default"])
    return "seed design: " + ", ".join(f"{d} = {default[d]:.6g} {ds[d].attrs.get('units', '')}".rstrip()
                                       for d in dims[:2] if d in default)


def _markdown(ds, rows, measure_figs, focus_figs, focus_values, claims) -> str:
    dims = list(design_dims(ds))
    n_designs = int(np.prod([ds.sizes[d] for d in dims]))
    lines = [f"# Design atlas: {ds.attrs.get('name', ds.attrs['mechanism'])}", "",
             f"{n_designs} designs ("
             + " x ".join(f"{d} {float(ds[d].min()):g}..{float(ds[d].max()):g} {ds[d].attrs.get('units', '')} "
                          f"({ds.sizes[d]})" for d in dims)
             + f"), each measured over {ds.attrs['samples_per_design']} samples of each kind (docs/atlas.md) "
             f"({ds.attrs['sampling']}, seed {ds.attrs['seed']}; platform tilt up to {ds.attrs['tilt_max_deg']:g} "
             f"deg; near-singular threshold {ds.attrs['threshold']:g}). Fixed parameters: "
             f"{_fixed_text(ds.attrs['fixed_design'])}. Solvers: wristkin {ds.attrs['wristkin_version']} (inputs "
             f"{ds.attrs['inputs_hash']}, backend {ds.attrs['backend']}). The run's timing per chunk is in the "
             "store's `timing` attribute (not here: the report's bytes depend on the numbers only).", "",
             "Open the numbers with `wristkin_atlas.open_atlas(DIR)` (xarray; `atlas.zarr`); best designs per "
             "measure: `best.csv`. Units: angles in degrees, lengths in metres, fractions and indices "
             "dimensionless. 1/kappa_F is the Frobenius-norm local conditioning index (docs/atlas.md).", "",
             "## Measures", "", "| measure | units | better | definition |", "|---|---|---|---|"]
    for name, var in ds.data_vars.items():
        lines.append(f"| {name} | {var.attrs.get('units', '')} | {var.attrs.get('better', '') or '-'} | "
                     f"{var.attrs.get('definition', '')} |")
    lines += ["", "## Best designs", "", "| measure | best value | " + " | ".join(dims) + " | runner-up values |",
              "|---|---|" + "---|" * len(dims) + "---|"]
    by_measure: dict[str, list[dict]] = {}
    for r in rows:
        by_measure.setdefault(r["measure"], []).append(r)
    for name, rs in by_measure.items():
        first = rs[0]
        lines.append(f"| {name} ({first['better']}) | {_fmt(first['value'])} | "
                     + " | ".join(_fmt(first[d]) for d in dims) + " | "
                     + ", ".join(_fmt(r["value"]) for r in rs[1:]) + " |")
    lines += ["", "## Where the seeds' claims stand", ""] + (claims or ["- (no seed claims for this mechanism)"])
    lines += ["", "## Measure maps", "",
              "Each map spans the first two swept parameters (any others at the catalogue design's value); the star "
              "marks the catalogue (seed) design, **" + _seed_text(ds, dims) + "**; white cells are designs "
              "make_design rejects (or, for a ratio, designs with nothing to average: no reachable sampled pose).",
              ""]
    for name in measure_figs:
        lines += [f"### {name}", "", f"{ds[name].attrs.get('definition', '')}", "",
                  f"![{name}](figures/map_{name}.png)", ""]
    if focus_figs:
        lines += ["## Workspace and singularities of the focus design", "",
                  "Focus design: " + ", ".join(f"{k} = {v:g}" for k, v in sorted(focus_values.items())), ""]
        for fname, caption in focus_figs:
            lines += [caption, "", f"![focus](figures/{fname})", ""]
    return "\n".join(lines) + "\n"
