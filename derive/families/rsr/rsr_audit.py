"""Audit numbers and plots of the 3-RSR wrist (workspace, singularities, gamma) and of the hybrid (arc example).

Everything here runs through the freshly generated solvers (`solver`), so the report shows what users get.
The workspace limits are the design parameters phi_min, phi_max (leg swing) and lbw_min, lbw_max (centre
distance: platform-base interference and the spherical-joint bend, which depends only on l_bw / L).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...model import Finding
from ...report_numbers import error_bucket
from .rsr_geometry import max_gamma_difference, seed_fd

_BETA_GRID = np.radians(np.arange(0.0, 179.5, 0.25))


def _svg(fig, path: Path) -> Path:
    import matplotlib

    matplotlib.rcParams["svg.hashsalt"] = "wristkin"
    fig.savefig(path, format="svg", metadata={"Date": None, "Creator": None})
    return path


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def max_swing(solver, alpha: float, design) -> float:
    """Largest beta reachable continuously from beta = 0 at azimuth alpha (grid of 0.25 deg, then bisection)."""
    prev = 0.0
    for b in _BETA_GRID:
        if solver.workspace(alpha, b, design) is None:
            lo, hi = prev, float(b)
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if solver.workspace(alpha, mid, design) is not None else (lo, mid)
            return lo
        prev = float(b)
    return prev


def _swing_plot(solver, design, audit_dir):
    plt = _plt()
    alphas = np.radians(np.arange(0.0, 360.0, 2.0))
    swing = np.array([max_swing(solver, a, design) for a in alphas])
    fig = plt.figure(figsize=(4.5, 4.5))
    ax = fig.add_subplot(projection="polar")
    ax.plot(np.append(alphas, alphas[0]), np.degrees(np.append(swing, swing[0])))
    ax.set_title("maximum swing β (°) over azimuth α")
    path = _svg(fig, audit_dir / "rsr_wrist_max_swing.svg")
    plt.close(fig)
    return path, alphas, swing


def _centre_plot(solver, design, audit_dir, azimuths_deg=(0.0, 30.0)):
    plt = _plt()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
    table = {}
    for az in azimuths_deg:
        a = math.radians(az)
        betas = np.radians(np.arange(0.0, 91.0, 1.0))
        spans = [solver.workspace(a, b, design) for b in betas]
        ok = np.array([s is not None for s in spans])
        lo = np.array([s[0] if s else np.nan for s in spans]) * 1e3
        hi = np.array([s[1] if s else np.nan for s in spans]) * 1e3
        ax1.plot(np.degrees(betas), lo, "--", label=f"min, α = {az:g}°")
        ax1.plot(np.degrees(betas), hi, "-", label=f"max, α = {az:g}°")
        ax1.plot(np.degrees(betas), 0.5 * (lo + hi), ":", label=f"middle curve, α = {az:g}°")
        ax2.plot(np.degrees(betas), hi - lo, label=f"α = {az:g}°")
        table[az] = [(int(round(math.degrees(b))), lo[i], hi[i]) for i, b in enumerate(betas) if ok[i] and
                     int(round(math.degrees(b))) % 15 == 0]
    ax1.set_xlabel("swing β (°)")
    ax1.set_ylabel("centre distance l_bw (mm)")
    ax1.legend(fontsize=6)
    ax2.set_xlabel("swing β (°)")
    ax2.set_ylabel("translation range (mm)")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    path = _svg(fig, audit_dir / "rsr_wrist_centre_distance.svg")
    plt.close(fig)
    return path, table


def _gamma_plot(audit_dir):
    plt = _plt()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
    a1 = np.radians(np.linspace(-180.0, 180.0, 361))
    for bdeg in (15, 30, 45, 60, 75):
        b = math.radians(bdeg)
        gam = np.arctan2(np.sin(a1), math.cos(b) * np.cos(a1))
        ax1.plot(np.degrees(a1), np.degrees(np.remainder(gam - a1 + math.pi, 2 * math.pi) - math.pi),
                 label=f"β = {bdeg}°")
    ax1.set_xlabel("wrist azimuth α1 (°)")
    ax1.set_ylabel("γ − α1 (°)")
    ax1.legend(fontsize=7)
    bs = np.arange(0.0, 76.0, 1.0)
    ax2.plot(bs, [max_gamma_difference(math.radians(b)) for b in bs], label="this definition (closed form)")
    ax2.plot(bs, [seed_fd(b) for b in bs], "--", label="seed's fitted f_d(β)")
    ax2.set_xlabel("swing β (°)")
    ax2.set_ylabel("max(γ − α1) (°)")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    path = _svg(fig, audit_dir / "rsr_wrist_gamma.svg")
    plt.close(fig)
    return path


def _singularity_scan(solver, design, kernels):
    """Over the limited workspace on the middle curve: conditioning of the branch within the leg limits,
    the 6x6 closed-chain constraint Jacobian (CasADi), and where the unlimited singular sets lie."""
    from .rsr_casadi import wrist_functions

    jc = wrist_functions(kernels)["rsr_wrist_constraint_jacobian"]
    lo = [design.params[1]] * 3
    hi = [design.params[2]] * 3
    worst = {"cond_inverse": 1.0, "cond_direct": 1.0, "constraint": math.inf}
    n_poses = 0
    for a in np.radians(np.arange(0.0, 360.0, 10.0)):
        for b in np.radians(np.arange(0.0, 90.0, 5.0)):
            mid = solver.middle_lbw(a, b, design)
            if mid is None:
                continue
            sol = solver.ik((a, b, mid), design)
            k = solver.select(sol, lower=lo, upper=hi)
            if k < 0:
                continue
            n_poses += 1
            worst["cond_inverse"] = min(worst["cond_inverse"], float(sol.aux[k, 1]))
            worst["cond_direct"] = min(worst["cond_direct"], float(sol.aux[k, 2]))
            sv = np.linalg.svd(np.array(jc(sol.values[k], design.params[0])), compute_uv=False)
            worst["constraint"] = min(worst["constraint"], float(sv[-1] / sv[0]))
    return n_poses, worst


def _critical_swing(solver, design) -> tuple[float, float]:
    """Inverse singularity of the unlimited wrist at the middle of the full leg range: the swing where a leg's
    two roots merge (|C| = rho) at alpha = 0 and 30 deg, for l_bw = L (half the largest centre distance)."""
    length = design.params[0]
    out = []
    for az in (0.0, 30.0):
        a = math.radians(az)
        lo, hi = 0.0, math.pi * 0.999
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            ok = solver.ik((a, mid, length), design).count > 0
            lo, hi = (mid, hi) if ok else (lo, mid)
        out.append(math.degrees(lo))
    return out[0], out[1]


def _swing_text(deg: float) -> str:
    return "none below 180°" if deg > 179.5 else f"{deg:.2f}°"


def wrist_audit_numbers(dv, solver, audit_dir: Path, kernels) -> dict:
    d = solver.make_design()
    length, pmin, pmax, lmin, lmax = d.params
    swing_path, alphas, swing = _swing_plot(solver, d, audit_dir)
    centre_path, centre = _centre_plot(solver, d, audit_dir)
    gamma_path = _gamma_plot(audit_dir)
    n_poses, worst = _singularity_scan(solver, d, kernels)
    crit0, crit30 = _critical_swing(solver, d)
    s_min, s_max = float(np.min(swing)), float(np.max(swing))
    at = {int(round(math.degrees(a))): math.degrees(s) for a, s in zip(alphas, swing, strict=True)}
    arg_min = [k for k, v in at.items() if v <= math.degrees(s_min) + 1e-9][:6]
    arg_max = [k for k, v in at.items() if v >= math.degrees(s_max) - 1e-9][:6]
    centre_rows = "\n".join(
        f"| {az:g}° | {b}° | {lo_:.2f} | {hi_:.2f} | {0.5 * (lo_ + hi_):.2f} |"
        for az, rows in centre.items() for b, lo_, hi_ in rows)
    findings = [
        Finding("maximum swing", "60° over the whole cycle; 75° at some azimuths such as α = 30°",
                f"{math.degrees(s_min):.1f}° over the whole cycle, {at[30]:.1f}° at α = 30° (limits below)",
                "clarified",
                "the seed publishes neither link sizes nor joint limits; with phi in "
                f"[{math.degrees(pmin):g}°, {math.degrees(pmax):g}°] and l_bw in [{lmin * 1e3:g}, {lmax * 1e3:g}] "
                f"mm the limited workspace has the seed's shape: smallest swing {math.degrees(s_min):.1f}° at α = "
                f"{', '.join(f'{v:g}°' for v in arg_min)}, largest {math.degrees(s_max):.1f}° at α = "
                f"{', '.join(f'{v:g}°' for v in arg_max)} (2° grid)"),
    ]
    summary = [
        ("L (base and platform link length)", f"{length * 1e3:g} mm"),
        ("leg swing limits phi_min, phi_max", f"{math.degrees(pmin):g}°, {math.degrees(pmax):g}°"),
        ("centre distance limits lbw_min, lbw_max", f"{lmin * 1e3:g} mm, {lmax * 1e3:g} mm"),
        ("IK solution sets per pose", "8 (2 per leg), all returned"),
        ("maximum swing over the whole cycle / at α = 30°", f"{math.degrees(s_min):.2f}° / {at[30]:.2f}°"),
        ("torsion of the platform", "0 (proven: R_W = Rz(α) Ry(β) Rz(−α))"),
    ]
    sections = [
        {"title": "Workspace with explicit limits",
         "body": "Feasible centre distances at an attitude (α, β) are computed exactly: leg i reaches "
                 "n · S_i = L (A_i cos φ + B sin φ) over φ ∈ [φ_min, φ_max], whose range is a closed interval "
                 "(end points and the sinusoid's extrema), and the workspace is the intersection of the three "
                 "intervals with [lbw_min, lbw_max]/2. The maximum swing at each azimuth is then found by a "
                 "0.25° scan and bisection (feasibility in β is not monotone in general).\n\n"
                 "![maximum swing](rsr_wrist_max_swing.svg)\n\n"
                 "![centre distance](rsr_wrist_centre_distance.svg)\n\n"
                 "| azimuth | swing | min l_bw (mm) | max l_bw (mm) | middle curve (mm) |\n|---|---|---|---|---|\n"
                 + centre_rows},
        {"title": "Singularities",
         "body": "Inverse singularities (two roots of a leg merge, dF_i/dφ_i = 0) lie on the boundary of the "
                 "unlimited workspace |l_bw| = 2 L ρ_i; direct singularities of the mirror construction need "
                 "S1, S2, S3 collinear. The full closed chain (6 equations in the platform pose) can also lose "
                 "rank: where its 6x6 Jacobian with respect to the platform twist (CasADi function "
                 "`rsr_wrist_constraint_jacobian`) is singular, the symmetric mode can branch into another one.\n\n"
                 f"Scan over the limited workspace on the middle curve ({n_poses} attitudes, α every 10°, β every "
                 "5°, branch selected inside the leg limits): smallest leg conditioning "
                 f"{worst['cond_inverse']:.3f}, smallest direct conditioning {worst['cond_direct']:.3f}, smallest "
                 f"relative singular value of the closed-chain Jacobian {worst['constraint']:.3f}: no singularity "
                 "inside the limited workspace.\n\n"
                 f"Without the leg limits, at l_bw = L the leg roots merge (an inverse singularity) at swing "
                 f"{_swing_text(crit0)} for α = 0 and {_swing_text(crit30)} for α = 30°."},
        {"title": "Swing-rotation angle γ",
         "body": "γ = atan2(sin α1, cos β cos α1) (step gamma) with the exact inverse α1 = atan2(cos β sin γ, "
                 "cos γ) for β < 90°: no curve fit and no bisection are needed. γ = α1 at α1 = 0, ±90°, 180°, as the "
                 "seed states, and the largest difference is asin(tan²(β/2)); the seed's fitted f_d(β) is larger "
                 "(table in the findings), so the seed's γ is some other, unstated quantity.\n\n"
                 "![gamma](rsr_wrist_gamma.svg)"},
    ]
    decisions = [("symmetric assembly mode only",
                  "the generated FK returns the mirror-symmetric mode (the seed's construction, one solution); "
                  "the closed-chain Jacobian is monitored in the audit scan above and stays regular in the limited "
                  "workspace, so the symmetric mode cannot branch there")]
    return {"findings": findings, "summary": summary, "sections": sections, "decisions": decisions,
            "files": [swing_path, centre_path, gamma_path]}


# ------------------------------------------------------------------------------------------- hybrid: arc example
ARC_CENTRE_MM = (250.0, 0.0, -410.0)
ARC_RADIUS_MM = 400.0
ARC_POINTS = ((250.0, -200.0, -63.5898, 90.0, 30.0, -180.0), (250.0, 0.0, -10.0, 0.0, 0.0, 0.0),
              (250.0, 200.0, -63.5898, -90.0, 30.0, 180.0))


def arc_targets(n: int = 61):
    """Cartesian interpolation of the seed's arc: position on the circle with a cubic time law over the arc angle;
    (alpha, beta, gamma) piecewise linear in the arc angle through P2 (the seed's three poses)."""
    out = []
    for i in range(n):
        tau = i / (n - 1)
        s = -math.pi / 6 + (math.pi / 3) * (3 * tau**2 - 2 * tau**3)
        pos = (ARC_CENTRE_MM[0], ARC_CENTRE_MM[1] + ARC_RADIUS_MM * math.sin(s),
               ARC_CENTRE_MM[2] + ARC_RADIUS_MM * math.cos(s))
        u = abs(s) / (math.pi / 6)  # 1 at P1 / P3, 0 at P2
        end = ARC_POINTS[0] if s < 0 else ARC_POINTS[2]
        abg = tuple(math.radians(u * end[3 + j]) for j in range(3))
        out.append((tau, tuple(p / 1e3 for p in pos), abg))
    return out


def hybrid_audit_numbers(dv, solver, audit_dir: Path) -> dict:
    d = solver.make_design()
    lo = [-math.pi, -math.pi, 0.0, -math.pi, d.params[5], d.params[5], d.params[5]]
    hi = [math.pi, math.pi, 0.5, math.pi, d.params[6], d.params[6], d.params[6]]
    rows, prev, worst_rt, worst_step = [], None, 0.0, 0.0
    counts = set()
    for tau, pos, (a, b, g) in arc_targets():
        target = solver.pose_from_abg(pos, a, b, g)
        sol = solver.ik(target, d)
        counts.add(sol.count)
        w = None if prev is not None else (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # the seed's energy rule first
        k = solver.select(sol, previous=prev if prev is not None else np.zeros(7), lower=lo, upper=hi, weights=w)
        if k < 0:
            raise RuntimeError(f"arc example: no solution within the limits at tau = {tau:.3f}")
        q = sol.values[k]
        if prev is not None:
            diff = np.where(np.array(solver.JOINT_KINDS) == "R", np.remainder(q - prev + math.pi, 2 * math.pi) -
                            math.pi, q - prev)
            worst_step = max(worst_step, float(np.max(np.abs(diff))))
        worst_rt = max(worst_rt, float(np.max(np.abs(solver.fk_matrix(q, d) - target))))
        rows.append((tau, pos, q, sol.aux[k, 2]))
        prev = q
    path = _arc_plot(rows, audit_dir)
    first, last = rows[0], rows[-1]
    design_txt = ", ".join(f"{n} = {v * 1e3:g} mm" if n in ("L1", "L2", "d", "d_f", "L", "lbw_min", "lbw_max")
                           else f"{n} = {math.degrees(v):g}°" for n, v in zip(solver.DESIGN_NAMES, d.params,
                                                                                 strict=True))
    summary = [
        ("design (chosen; the seed publishes none)", design_txt),
        ("IK solution sets per pose", "16 = 2 elbows x 2^3 wrist legs, all returned"),
        ("arc example: IK solution counts along the path", ", ".join(str(c) for c in sorted(counts))),
        ("arc example: FK round trip, max abs(FK(q) - target)", error_bucket(worst_rt)),
        ("arc example: largest joint step between consecutive points", f"{worst_step:.4f} (rad or m)"),
    ]
    joints_txt = ", ".join(f"{n} {v:.4f}" for n, v in zip(solver.JOINT_NAMES, first[2], strict=True))
    sections = [{
        "title": "Arc example P1 → P2 → P3",
        "body": "The seed's path (circle of radius 400 mm about (250, 0, −410) mm in the plane x = 250) is "
                "interpolated with a cubic time law over 61 points; (α, β, γ) go linearly in the arc angle from "
                "P1's (90°, 30°, −180°) to P2's (0, 0, 0) and on to P3's (−90°, 30°, 180°). Each point is solved "
                "by the generated IK (l_bw on the middle curve); the first set is chosen by the seed's energy rule "
                "(least motion of joint 1 from the zero pose, within the limits), later sets by nearest-to-previous "
                "within the joint limits. Link dimensions are not published: L1 = L2 = 250 mm reach the path and "
                f"d = 200 mm keeps the stroke positive (d3 from {min(r[2][2] for r in rows) * 1e3:.1f} to "
                f"{max(r[2][2] for r in rows) * 1e3:.1f} mm).\n\n"
                f"Joints at P1: {joints_txt}.\n\n![arc example](scara_rsr_arc.svg)"}]
    _ = last
    return {"summary": summary, "sections": sections, "files": [path]}


def _arc_plot(rows, audit_dir):
    plt = _plt()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
    taus = [r[0] for r in rows]
    qs = np.array([r[2] for r in rows])
    names = ("θ1", "θ2", "d3", "θ4", "φ1", "φ2", "φ3")
    for j, n in enumerate(names):
        ax1.plot(taus, qs[:, j] * (1e3 if j == 2 else 180 / math.pi), label=n + (" (mm)" if j == 2 else " (°)"))
    ax1.set_xlabel("normalised time τ")
    ax1.set_ylabel("joint value")
    ax1.legend(fontsize=6, ncol=2)
    ys = [r[1][1] * 1e3 for r in rows]
    zs = [r[1][2] * 1e3 for r in rows]
    ax2.plot(ys, zs, "o", ms=2)
    ax2.set_xlabel("y (mm)")
    ax2.set_ylabel("z (mm)")
    ax2.set_title("platform centre along the arc (x = 250 mm)")
    ax2.set_aspect("equal")
    fig.tight_layout()
    path = _svg(fig, audit_dir / "scara_rsr_arc.svg")
    plt.close(fig)
    return path
