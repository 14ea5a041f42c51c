"""The arm angle of a 7R arm with a spherical shoulder and a spherical wrist (an S-R-S arm: KUKA's iiwa), as its
redundancy parameter (`wristkin derive --redundancy arm-angle`).

Definition. S is where the shoulder's three axes meet, W where the wrist's three meet, E the elbow point: the point
of the elbow axis nearest S. The arm is S-R-S when E is also the point of the elbow axis nearest W (no offset along
the elbow axis), so the upper arm S-E and the forearm E-W both stand normal to the elbow axis. For a pose, W is fixed
(the wrist centre), and E lies on a circle about the line S-W: |E - S| = d_se and |W - E| = d_ew fix its distance
along the line (cos a = (d_se^2 + |SW|^2 - d_ew^2) / (2 d_se |SW|)) and from it. With u = (W - S) / |SW|,
n1 = the first axis h1's part normal to u (unit) and n2 = u x n1,

    E(psi) = S + d_se (cos a u + sin a (cos psi n1 + sin psi n2)),

so psi = 0 puts the elbow in the plane of the first axis and the line S-W, on the side h1 points to (for the iiwa
upright: the elbow up), and psi turns it about u. Every configuration with the elbow at E(psi) solves the pose at
psi: the elbow joint bent either way (subproblem 3), the shoulder's rotation about S fixed by the two directions
S -> W and S-W -> E (subproblem 2 and 1: two sets), the wrist's orientation (two sets): 8 sets. The definition is
the runtime's (runtime/python/arm_angle.py, runtime/c/wk_arm_angle.c); the derivation checks it on the
robot (replay below: the elbow point of sampled joints equals E(psi) at their own psi) and the audit states it.

Where W lies on the first axis the plane is undefined (u parallel to h1): the runtime takes any normal and flags
the sets indeterminate. Where the arm is stretched or folded (E on the line) every psi is the same configuration."""

from __future__ import annotations

import math

import numpy as np

from .geometry import common_point
from .poe import Chain
from .same_bits import dot, norm  # the centres and the elbow point are generated constants

SHOULDER, ELBOW, WRIST = (0, 1, 2), 3, (4, 5, 6)


def arm_plane(h1, s, w):
    """(u, n1, n2): the unit from s to w, the first axis's part normal to it (unit), u x n1."""
    u = (w - s) / norm(w - s)
    n1 = h1 - dot(h1, u) * u
    n1 = n1 / norm(n1)
    return u, n1, np.cross(u, n1)


def angle_of(h1, s, e, w) -> float:
    """psi of the elbow point e."""
    u, n1, n2 = arm_plane(h1, s, w)
    side = (e - s) - dot(e - s, u) * u
    return math.atan2(dot(side, n2), dot(side, n1))


def elbow_point(h1, s, w, psi, d_se, d_ew):
    """E(psi) (the definition above)."""
    u, n1, n2 = arm_plane(h1, s, w)
    length = norm(w - s)
    cos_a = (d_se ** 2 + length ** 2 - d_ew ** 2) / (2.0 * d_se * length)
    sin_a = math.sqrt(max(0.0, 1.0 - cos_a ** 2))
    return s + d_se * (cos_a * u + sin_a * (math.cos(psi) * n1 + math.sin(psi) * n2))


def centres(c: Chain):
    """(S, E0, W0): the shoulder and wrist centres and the elbow point of the chain at home."""
    s = common_point([c.points[j] for j in SHOULDER], [c.axes[j] for j in SHOULDER])[0]
    w = common_point([c.points[j] for j in WRIST], [c.axes[j] for j in WRIST])[0]
    he, pe = c.axes[ELBOW], c.points[ELBOW]
    return s, pe + dot(he, s - pe) * he, w


def numerics() -> dict:
    """The run-time core (runtime/python/geom3.py and arm_angle.py below their markers, as the generated solvers
    carry them) as a namespace: _arm_angle_core, _aa_angle_of."""
    from .. import runtime_files

    rt = runtime_files.load_python("python/_runtime.py")
    ns = {"math": math, **{k: getattr(rt, k) for k in ("FLAG_DOUBLE_ROOT", "FLAG_INDETERMINATE",
                                                        "FLAG_SINGULAR_INVERSE")}}
    exec(compile(runtime_files.inline("python/geom3.py") + runtime_files.inline("python/arm_angle.py"),
                 "wristkin_runtime_arm_angle", "exec"), ns)
    return ns


def residual(c: Chain, e, x, y) -> float:
    """The op's equations at true joints (e: their screws, 4 x 4; x, y: the wrist centre at home and placed): the
    elbow's distance |e_e x - S| = |y - S|, and the elbow point of the joints equal to E(psi) at their own psi."""
    s, e0, _ = centres(c)
    d_se, d_ew = float(np.linalg.norm(s - e0)), float(np.linalg.norm(x - e0))
    turned = e[ELBOW][:3, :3] @ x + e[ELBOW][:3, 3]
    dist = abs(float(np.linalg.norm(turned - s)) - float(np.linalg.norm(y - s)))
    shoulder = e[0] @ e[1] @ e[2]
    elbow = shoulder[:3, :3] @ e0 + shoulder[:3, 3]
    psi = angle_of(c.axes[0], s, elbow, y)
    return max(dist, float(np.linalg.norm(elbow - elbow_point(c.axes[0], s, y, psi, d_se, d_ew))))
