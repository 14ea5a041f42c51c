"""Workspace and singularity maps of one design (the report's focus design), computed with the same C batch
solvers and local index as the sweep: 2-D slices a designer can read at a glance."""

from __future__ import annotations

import math

import numpy as np


def underactuated_maps(mech, design, options, n: int = 181) -> dict:
    """Tilt map: pure tilts R = Rz(psi) Rx(theta) Rz(-psi) (zero torsion) over tilt azimuth psi and tilt theta:
    best 1/kappa_F over the IK sets (0: unreachable) and the number of real IK sets. Mode map: the number of real
    FK assembly modes over (theta1, theta2) at theta3 = theta0."""
    m = mech.module
    az = np.linspace(-180.0, 180.0, n)
    tilt = np.linspace(0.0, math.degrees(options.tilt_max), n)
    a, t = np.meshgrid(np.radians(az), np.radians(tilt), indexing="xy")
    poses = np.column_stack([a.ravel(), t.ravel(), -a.ravel()])
    ik = m.ik_batch(poses, design)
    li = np.where(ik.valid, mech.local_index(design, poses, ik.values)[0], 0.0)
    q = np.linspace(0.0, 360.0, n)
    q1, q2 = np.meshgrid(np.radians(q), np.radians(q), indexing="xy")
    joints = np.column_stack([q1.ravel(), q2.ravel(), np.full(q1.size, design.theta0)])
    fk = m.fk_batch(joints, design)
    return {"tilt": {"x": az, "y": tilt, "xlabel": "tilt azimuth psi (deg)", "ylabel": "tilt theta (deg)",
                     "best_li": li.max(axis=1).reshape(t.shape), "sets": ik.valid.sum(axis=1).reshape(t.shape)},
            "modes": {"x": q, "y": q, "xlabel": "theta1 (deg)", "ylabel": "theta2 (deg)",
                      "theta3": math.degrees(design.theta0), "count": fk.valid.sum(axis=1).reshape(q1.shape)}}


def rsr_maps(mech, design, options, n_alpha: int = 361, n_beta: int = 241, n_lbw: int = 9) -> dict:
    """Swing map over (azimuth alpha, swing beta): reachable where the module's exact `workspace(alpha, beta)` gives
    an interval of centre distances (every leg within its limits, l_bw within [lbw_min, lbw_max]); coloured by the
    best 1/kappa_F of the in-limit IK sets at n_lbw distances across that interval. Max swing per azimuth from the
    same grid (its resolution is the beta step)."""
    m = mech.module
    alpha = np.linspace(0.0, 360.0, n_alpha)
    beta = np.linspace(0.0, math.degrees(options.tilt_max), n_beta)
    cells, spans = [], []
    for i, a in enumerate(np.radians(alpha)):
        for j, b in enumerate(np.radians(beta)):
            span = m.workspace(a, b, design)
            if span is not None:
                cells.append((i, j))
                spans.append(span)
    best = np.full((n_alpha, n_beta), -1.0)
    if cells:
        idx = np.array(cells)
        spans = np.array(spans)
        frac = (np.arange(n_lbw) + 0.5) / n_lbw
        lbw = spans[:, :1] + frac[None, :] * (spans[:, 1:] - spans[:, :1])
        poses = np.column_stack([np.repeat(np.radians(alpha[idx[:, 0]]), n_lbw),
                                 np.repeat(np.radians(beta[idx[:, 1]]), n_lbw), lbw.ravel()])
        ik = m.ik_batch(poses, design)
        lo, hi = design.params[1], design.params[2]
        within = np.all(np.mod(ik.values - lo, 2.0 * math.pi) <= hi - lo, axis=2)
        li = np.where(ik.valid & within, mech.local_index(design, poses, ik.values)[0], 0.0)
        best[idx[:, 0], idx[:, 1]] = li.max(axis=1).reshape(-1, n_lbw).max(axis=1)
    reach = best >= 0.0
    swing = np.array([beta[r].max() if r.any() else 0.0 for r in reach])
    return {"swing": {"alpha": alpha, "beta": beta, "best_li": np.where(reach, best, 0.0).T, "reach": reach.T,
                      "max_swing": swing, "beta_step": beta[1] - beta[0], "alpha_step": alpha[1] - alpha[0]}}


OTHER_JOINTS = 0.6  # the unit-cube coordinate of the joints a serial map holds fixed


def serial_maps(mech, design, options, n: int = 121) -> dict:
    """Conditioning map of a serial arm: the local index sigma_min / sigma_max of diag(I / L_c, I) J over two
    joints (the 2nd and 3rd where the arm has three or more: the first turns the whole arm and leaves the index
    unchanged), on an n x n grid of their sampled ranges, the other joints at 60 % of theirs (revolute 36 deg:
    a generic value; 0 is often a wrist singularity, which would blacken the whole map). One joint: a line."""
    dim = mech.joint_dim
    axes = (1, 2) if dim >= 3 else ((0, 1) if dim == 2 else (0,))
    grid = (np.arange(n) + 0.5) / n
    if len(axes) == 2:
        g0, g1 = np.meshgrid(grid, grid, indexing="xy")
        u = np.full((g0.size, dim), OTHER_JOINTS)
        u[:, axes[0]], u[:, axes[1]] = g0.ravel(), g1.ravel()
    else:
        u = np.full((n, dim), OTHER_JOINTS)
        u[:, axes[0]] = grid
    q = mech.joints(u, design)
    li = mech.local_index_numpy(design, q, mech.characteristic_length(design))

    def label(i):
        unit = "deg" if mech.module.JOINT_KINDS[i] == "R" else "m"
        return f"{mech.module.JOINT_NAMES[i]} ({unit})"

    def values(i):  # the grid's joint values along axis i (the same mapping as the samples)
        line = np.full((n, dim), OTHER_JOINTS)
        line[:, i] = grid
        col = mech.joints(line, design)[:, i]
        return np.degrees(col) if mech.module.JOINT_KINDS[i] == "R" else col

    if len(axes) == 2:
        return {"x": values(axes[0]), "y": values(axes[1]), "li": li.reshape(n, n), "xlabel": label(axes[0]),
                "ylabel": label(axes[1])}
    return {"x": values(axes[0]), "y": None, "li": li, "xlabel": label(axes[0]), "ylabel": None}
