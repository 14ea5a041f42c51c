"""What the seeds state about their designs, and what the atlas finds for the same design (numbers for the
report). Seed 000 (underactuated wrist): the chosen design alpha1 = alpha2 = 60 deg, beta1 = 30 deg, beta2 =
43.89 deg with a 140 deg initial input angle. Seed 002 (3-RSR wrist): maximum swing 60 deg over the whole cycle,
75 deg at some azimuths such as alpha = 30 deg."""

from __future__ import annotations

import math

import numpy as np

from .store import design_dims

SEED000_DESIGN = {"alpha1": 60.0, "alpha2": 60.0, "beta1": 30.0, "beta2": 43.89}
SEED000_HOME_DEG = 140.0
SEED002_SWING_ALL_DEG = 60.0
SEED002_SWING_AT = (30.0, 75.0)  # (azimuth, swing) in degrees


def beta2_for_home(module, home_deg: float = SEED000_HOME_DEG, design=SEED000_DESIGN) -> float | None:
    """beta2 (deg) at which the home input angle theta0 equals `home_deg` with the other parameters of `design`
    (bisection on make_design's theta0, which is monotone in beta2 near the paper's design), or None."""
    def theta0(b2):
        d = dict(design, beta2=b2)
        return math.degrees(module.make_design({k: math.radians(v) for k, v in d.items()}).theta0)

    lo, hi = design["beta2"] - 5.0, design["beta2"] + 5.0
    f_lo, f_hi = theta0(lo) - home_deg, theta0(hi) - home_deg
    if f_lo * f_hi > 0:
        return None
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        f_mid = theta0(mid) - home_deg
        if f_mid * f_lo <= 0:
            hi = mid
        else:
            lo, f_lo = mid, f_mid
    return 0.5 * (lo + hi)


def underactuated_claims(mech, ds) -> list[str]:
    m = mech.module
    d = m.make_design({k: math.radians(v) for k, v in SEED000_DESIGN.items()})
    home = math.degrees(d.theta0)
    b2 = beta2_for_home(m)
    lines = [f"- Seed 000's design (alpha1 = alpha2 = 60 deg, beta1 = 30 deg, beta2 = 43.89 deg): the home input "
             f"angle theta0 is **{home:.2f} deg**, not the {SEED000_HOME_DEG:.0f} deg the seed states "
             f"(|difference| {abs(home - SEED000_HOME_DEG):.2f} deg); theta0 = 140 deg exactly needs beta2 = "
             + (f"**{b2:.3f} deg**." if b2 is not None else "no beta2 within 5 deg of the seed's.")]
    lines += _rank_lines(ds, SEED000_DESIGN, "seed 000's design", mech)
    return lines


def rsr_claims(mech, ds, maps: dict | None) -> list[str]:
    lines = []
    if maps is not None:
        sw = maps["swing"]
        alpha, swing = sw["alpha"][:-1], sw["max_swing"][:-1]  # the grid's 360 deg repeats 0 deg
        at = float(np.interp(SEED002_SWING_AT[0], alpha, swing))
        lines.append(f"- Seed 002 states a maximum swing of {SEED002_SWING_ALL_DEG:.0f} deg over the whole cycle and "
                     f"{SEED002_SWING_AT[1]:.0f} deg at azimuth {SEED002_SWING_AT[0]:.0f} deg. The atlas, for the "
                     f"focus design on a {sw['alpha_step']:g} deg x {sw['beta_step']:.3g} deg (azimuth x swing) "
                     f"grid: **{swing.min():.2f} deg** over the whole cycle (smallest at azimuth "
                     f"{alpha[int(np.argmin(swing))]:.0f} deg), **{at:.2f} deg** at azimuth 30 deg, largest "
                     f"{swing.max():.2f} deg at azimuth {alpha[int(np.argmax(swing))]:.0f} deg. Differences from the "
                     f"seed: {swing.min() - SEED002_SWING_ALL_DEG:+.2f} deg and {at - SEED002_SWING_AT[1]:+.2f} deg "
                     "(the seed publishes neither link sizes nor joint limits: the catalogue's limits are a choice, "
                     "see the audit report).")
    if "swing_all" in ds:
        ok = ds["swing_all"].where(ds["swing_all"] >= SEED002_SWING_ALL_DEG)
        n_ok = int(ok.count())
        best = ds["swing_all"].where(ds["swing_all"] == ds["swing_all"].max(), drop=True)
        where = ", ".join(f"{d} = {float(best[d].values[0]):g}" for d in best.dims)
        lines.append(f"- Designs of this sweep whose whole-cycle swing reaches {SEED002_SWING_ALL_DEG:.0f} deg: "
                     f"{n_ok} of {int(ds['swing_all'].count())}; the largest, {float(ds['swing_all'].max()):.2f} deg, "
                     f"at {where} (5 deg azimuth x 0.5 deg swing grid).")
    return lines


def evaluate_design(mech, ds, values: dict) -> dict:
    """The measures of one design (display units, others at the sweep's fixed values) over the sweep's own
    samples, computed here (the seed's design is rarely a grid point)."""
    import json

    from . import sampling
    from .mechanisms import Options
    from .runner import compute_task
    from .sweep import angle_names

    ident = json.loads(ds.attrs["identity"])
    opts = Options(**ident["options"])
    fixed = json.loads(ds.attrs["design_default"])
    fixed.update(json.loads(ds.attrs["fixed_design"]))
    fixed.update(values)
    angles = set(angle_names(mech.module))
    params = np.array([[math.radians(fixed[n]) if n in angles else fixed[n] for n in mech.module.DESIGN_NAMES]])
    n_blocks = sampling.blocks(ident["samples"], mech.joint_dim, ident["grid"])
    part, *_ = compute_task(mech.key, params, ident["seed"], ident["samples"], ident["grid"], opts, 0, n_blocks)
    return {k: v[0] for k, v in mech.finalize(part, opts).items()}


def _rank_lines(ds, design: dict, label: str, mech=None) -> list[str]:
    """Where `design` (display units) sits among the sweep's designs, per ranked scalar measure: its own measures
    (evaluated on the same samples) against every valid design of the sweep."""
    measures = evaluate_design(mech, ds, design)
    out = []
    dims = design_dims(ds)
    for name in measures:  # the mechanism's own order of measures
        var = ds[name]
        better = var.attrs.get("better")
        if not better or var.dims != dims:
            continue
        value = float(measures[name])
        vals = var.values[np.isfinite(var.values)]
        if not np.isfinite(value) or vals.size == 0:
            continue
        best = vals.max() if better == "max" else vals.min()
        share = float(np.mean(vals > value) if better == "max" else np.mean(vals < value))
        out.append(f"- {label}: {name} = {value:.4g} (best in the sweep {best:.4g}; {100 * share:.0f} % of the "
                   f"{vals.size} valid swept designs do better)")
    extra = {k: v for k, v in measures.items() if np.ndim(v) == 1 and k.startswith("phi_range")}
    for name, v in extra.items():
        out.append(f"- {label}: {name} (motor 1, motor 2, sensor) = "
                   + ", ".join(f"{x:.1f}" for x in v) + " deg")
    return out
