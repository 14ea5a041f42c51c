"""A spherical wrist's centre and its Jacobian in the joints solved before the wrist: how much those joints amplify
the pose's rounding into the wrist's rotation, which sets the width of the wrist's family band at run time.

At an exact wrist singularity the computed |sin theta5| is pure rounding: the prefix joints carry the pose's rounding
(eps times the robot's size) through the inverse of the wrist centre's Jacobian J_c, and the wrist's rotation
R_prefix^T R carries their errors. The runtime reads kappa = size ||adj J_c||_F / |det J_c| >= size / sigma_min(J_c)
(serial_stages._wrist_amp, sr_stages.c's sr_wrist_amp: the same operations, no iteration), only when |sin theta5|
is already within the bands' reach. Measured at exact singularities (bench/wrist_band.py): the rounding stays
below eps kappa."""

from __future__ import annotations

import numpy as np
import sympy as sp

from ...checks import numeric_predicate, sampler
from ...model import Derivation, Step


def _off_line(p, z, o) -> float:
    """The distance of point p from the line through o along the unit direction z."""
    d = p - o
    return float(np.linalg.norm(d - np.dot(d, z) * z))


def centre_steps(dv: Derivation, spec, axes, candidates, draw) -> None:
    """For each wrist stage whose prefix (the joints the stages before it solve from the pose) is three joints: the
    candidate point on the three wrist axes (their meeting point, the wrist centre) and its Jacobian in those joints,
    recorded as a step with its checks and exported as dv.exports["wrist_centre"][k] (the 3 x 3 Jacobian). `axes`:
    each joint's (direction, point) in the world; `candidates`: points over the joints (a DH chain's frame origins);
    `draw(rng)` gives (joints, design) dicts as the derivation's checks sample them (a held joint's value in the
    design)."""
    solved: list[int] = []
    held = {spec.joints[spec.held[0]]: spec.held[1]} if spec.held else {}
    for k, st in enumerate(spec.stages, start=1):
        # a held joint's stage reads its design value, not the pose: the prefix is the joints solved from the pose
        prefix = [spec.joints[j] for j in solved if not (spec.held and j == spec.held[0])]
        if st.kind != "wrist" or len(prefix) != 3:
            solved.extend(st.joints)
            continue
        wrist_axes = [axes[j] for j in st.joints]
        later = set(spec.joints) - set(prefix) - set(held)
        args = (*spec.joints, *spec.design)
        lines = sampler(args, sp.Matrix.hstack(*(sp.Matrix.vstack(z, o) for z, o in wrist_axes)))
        rng = np.random.default_rng(k)
        samples = [draw(rng) for _ in range(8)]
        centre = None
        for o in candidates:
            p = o.xreplace(held)
            if p.free_symbols & later:
                continue  # a point a wrist joint (or a later one) moves is not the centre
            at = sampler(args, p)
            if all(max(_off_line(np.array(at(*q.values(), *d.values()), dtype=float).ravel(),
                                 *_unit_line(np.array(lines(*q.values(), *d.values()), dtype=float), i))
                       for i in range(3)) <= 1e-9 * _size(d) for q, d in samples):
                centre = p
                break
        if centre is None:  # no frame origin on the three axes: the band keeps the stages' product (amp_before)
            solved.extend(st.joints)
            continue
        jac = sp.Matrix.hstack(*(centre.diff(q) for q in prefix))
        f_p, f_j, f_l = sampler(args, centre), sampler(args, jac), lines

        def on_axes(rng, f_p=f_p, f_l=f_l):
            q, d = draw(rng)
            p = np.array(f_p(*q.values(), *d.values()), dtype=float).ravel()
            lv = np.array(f_l(*q.values(), *d.values()), dtype=float)
            return max(_off_line(p, *_unit_line(lv, i)) for i in range(3)) / _size(d)

        def fd(rng, f_p=f_p, f_j=f_j, prefix=prefix):
            q, d = draw(rng)
            jv = np.array(f_j(*q.values(), *d.values()), dtype=float)
            err = 0.0
            for i, s in enumerate(prefix):
                a, b = dict(q), dict(q)
                a[s] += 1e-6
                b[s] -= 1e-6
                col = (np.array(f_p(*a.values(), *d.values()), dtype=float) -
                       np.array(f_p(*b.values(), *d.values()), dtype=float)).ravel() / 2e-6
                err = max(err, float(np.max(np.abs(col - jv[:, i]))))
            return err / _size(d)
        names = ", ".join(str(s) for s in prefix)
        dv.add(Step(f"wrist_centre{k}", f"The wrist centre of stage {k} and its Jacobian in {names}",
                    "the frame origin on the three wrist axes (they meet there); J_c = d p_c / d(" + names + "): the "
                    "wrist's family band reads kappa = size ||adj J_c||_F / |det J_c| >= size / sigma_min(J_c), how "
                    "much those joints amplify the pose's rounding into the wrist's rotation",
                    ("T", f"ik_stage{k}"), {"p_c": centre, "J_c": jac},
                    (numeric_predicate(on_axes, "p_c lies on the three wrist axes (relative to the robot's size)",
                                       samples=50, tol=1e-12),
                     numeric_predicate(fd, "J_c equals central differences of p_c (h = 1e-6, relative to the size)",
                                       samples=20, tol=1e-7))))
        dv.exports.setdefault("wrist_centre", {})[k] = jac
        dv.exports.setdefault("wrist_centre_point", {})[k] = centre
        solved.extend(st.joints)


def _unit_line(lines: np.ndarray, i: int) -> tuple[np.ndarray, np.ndarray]:
    """Axis i's unit direction and point from the stacked (z; o) columns."""
    z, o = lines[:3, i], lines[3:, i]
    return z / np.linalg.norm(z), o


def _size(d: dict) -> float:
    """The scale lengths are compared at: 1 or the largest design length."""
    return max([1.0, *(abs(float(v)) for v in d.values())])
