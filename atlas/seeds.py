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
    lines += _rank_lines(ds, SEED000_DESIGN, "seed 000's design")
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
        lines.append(f"- Designs of this sweep whose sampled whole-cycle swing reaches {SEED002_SWING_ALL_DEG:.0f} "
                     f"deg: {n_ok} of {int(ds['swing_all'].count())} (sampled swing is a lower bound of the exact "
                     "one: the map above is finer).")
    return lines


def _rank_lines(ds, design: dict, label: str) -> list[str]:
    """Where `design` (display units) sits in the sweep, per ranked scalar measure (nearest grid point)."""
    dims = list(design_dims(ds))
    sel = {d: design[d] for d in dims if d in design}
    off = {d: abs(float(ds[d].sel({d: v}, method="nearest")) - v) for d, v in sel.items()}
    if any(v > 1e-6 * max(1.0, abs(sel[d])) for d, v in off.items()):
        return [f"- {label} is not a grid point of this sweep (nearest grid point used below, off by "
                + ", ".join(f"{d} {v:.3g}" for d, v in off.items()) + ")."] + _ranks(ds, sel, label)
    return _ranks(ds, sel, label)


def _ranks(ds, sel: dict, label: str) -> list[str]:
    out = []
    for name, var in ds.data_vars.items():
        better = var.attrs.get("better")
        if not better or var.ndim != len(design_dims(ds)):
            continue
        value = float(var.sel(sel, method="nearest"))
        vals = var.values[np.isfinite(var.values)]
        if not np.isfinite(value) or vals.size == 0:
            continue
        best = vals.max() if better == "max" else vals.min()
        share = float(np.mean(vals > value) if better == "max" else np.mean(vals < value))
        out.append(f"- {label}: {name} = {value:.4g} (best in the sweep {best:.4g}; {100 * share:.0f} % of the "
                   "valid designs do better)")
    return out
