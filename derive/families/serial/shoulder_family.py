"""A first stage that reads q1 from the wrist centre's position off axis 1 (A cos q1 + B sin q1 = 0, C identically 0):
at A = B = 0 every q1 solves it, the ideal geometry's shoulder self-motion (the wrist centre on axis 1, q1 and the
wrist turning together). A calibration breaks it as it breaks the wrist's, so a calibrated robot's runtime scans that
family along q1 where the pose puts the centre within CALIBRATED_SHOULDER_SEARCH (times the design's size) of axis 1,
read as hypot(A, B) (serial_ik._shoulder_near, sr_ik.c's sr_shoulder_near). The step proves both readings: C is 0,
and hypot(A, B) is the centre's distance from axis 1 on the FK."""

from __future__ import annotations

import numpy as np
import sympy as sp

from ...checks import numeric_predicate, sampler, symbolic_identity
from ...model import Derivation, Step
from ...serial_core.stages import POSE_SYMBOLS


def shoulder_family_joint(spec) -> int | None:
    """The joint of the first stage when it reads that joint from the wrist centre's (x, y) off its axis (a non-
    factored trig_linear whose C is identically 0) ahead of a spherical wrist at the end; else None."""
    if not spec.stages or spec.stages[-1].kind != "wrist":
        return None
    first = spec.stages[0]
    if first.kind != "trig_linear" or first.factored or sp.sympify(first.exprs[2]) != 0:
        return None
    return first.joints[0]


def shoulder_step(dv: Derivation, spec, fT, axes, draw) -> None:
    """Record the shoulder family's reading as a checked step (see the module's docstring) when the robot has one
    and its wrist centre was derived (dv.exports["wrist_centre_point"]); `axes`: each joint's (direction, point) in
    the world; `fT` the FK sampler; `draw(rng)` the derivation's (joints, design) samples."""
    j = shoulder_family_joint(spec)
    centres = dv.exports.get("wrist_centre_point", {})
    if j is None or len(spec.stages) not in centres:
        return
    first = spec.stages[0]
    c = sp.sympify(first.exprs[2])
    args = (*spec.joints, *spec.design)
    f_ab = sp.lambdify((*POSE_SYMBOLS, *args), list(first.exprs[:2]), "numpy")
    f_c = sampler(args, centres[len(spec.stages)])
    f_axis = sampler(args, sp.Matrix.vstack(*axes[j]))

    def distance_error(rng):
        q, d = draw(rng)
        vals = (*q.values(), *d.values())
        pose = np.array(fT(*vals), dtype=float)[:3].ravel()
        a, b = (float(v) for v in f_ab(*pose, *vals))
        line = np.array(f_axis(*vals), dtype=float).ravel()
        z, o = line[:3] / np.linalg.norm(line[:3]), line[3:]
        off = np.array(f_c(*vals), dtype=float).ravel() - o
        dist = float(np.linalg.norm(off - np.dot(off, z) * z))
        return abs(np.hypot(a, b) - dist) / max([1.0, *(abs(float(v)) for v in d.values())])

    name = spec.joints[j]
    dv.add(Step("shoulder_family", f"Stage 1 reads {name} from the wrist centre's position off its axis",
                f"A cos {name} + B sin {name} + C = 0 with C = 0: {name} = atan2 of (A, B), the wrist centre's "
                f"coordinates normal to axis {j + 1}; at A = B = 0 (the centre on the axis) every {name} solves it, "
                "the ideal geometry's shoulder self-motion, which a calibration breaks and a calibrated robot's "
                "runtime scans where hypot(A, B) is within CALIBRATED_SHOULDER_SEARCH of the design's size",
                ("T", "ik_stage1", f"wrist_centre{len(spec.stages)}"), {"C": c},
                (symbolic_identity(c, sp.Integer(0), "C = 0"),
                 numeric_predicate(distance_error, "hypot(A, B) on the FK equals the wrist centre's distance from "
                                   f"axis {j + 1} (relative to the robot's size)", samples=50, tol=1e-12))))
    dv.exports["shoulder_family"] = j  # what a calibrated robot's module scans (from_table's own_context)
