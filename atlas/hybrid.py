"""The SCARA + 3-RSR hybrid (scara_rsr) in the atlas: its measures are the 3-RSR wrist's, computed on the wrist's
own design (L, phi_min, phi_max, lbw_min, lbw_max) exactly as `wristkin atlas rsr_wrist` computes them, plus the
whole arm's: FK of joint samples of all seven joints (the wrist's legs within their limits), IK of those poses
(every branch of the 16), and the SCARA's reach, the horizontal distance of the platform centre from the base
axis over the samples."""

from __future__ import annotations

import math

import numpy as np

from .mechanisms import Measure, Mechanism, RsrWrist, _ratio
from .partials import MAX, MIN, SUM, Partial

WRIST_NAMES = ("L", "phi_min", "phi_max", "lbw_min", "lbw_max")


ARM_STREAM = 2  # the arm's 7-joint unit samples: a stream of their own (0 and 1 are the wrist's, as rsr_wrist's)
ARM_DIM = 7


class ScaraRsr(Mechanism):
    """The wrist's samples are rsr_wrist's, block for block (the same streams and shapes: the same numbers as
    `wristkin atlas rsr_wrist` with the same wrist design). The arm's: a third stream of 7-D unit points, theta1,
    theta2, theta4 uniform on [-pi, pi), d3 uniform on [0, d] (the column's stroke), phi_i uniform on
    [phi_min, phi_max]; the arm's poses are their FK. With --grid, the arm's lattice is side^7 points with side =
    round(N^(1/7)) (the wrist's side^3 sets the number of blocks; the arm's blocks past its lattice are empty)."""

    @staticmethod
    def fits(module) -> bool:
        return tuple(module.DESIGN_NAMES) == ("L1", "L2", "d", "d_f", *WRIST_NAMES)

    def __init__(self, module):
        import wristkin.rsr_wrist as wrist_module

        super().__init__(module)
        self.wrist = RsrWrist(wrist_module)
        self._split = [module.DESIGN_NAMES.index(n) for n in WRIST_NAMES]

    def wrist_design(self, design):
        params = np.ravel(design.params)
        return self.wrist.make_design([params[i] for i in self._split])

    def make_design(self, params):
        design = super().make_design(params)
        return design if design is not None and self.wrist_design(design) is not None else None

    def partials(self):
        return (*self.wrist.partials(), Partial("arm_n", SUM), Partial("arm_fk", SUM), Partial("arm_closes", SUM),
                Partial("arm_sets", SUM, (self.module.MAX_IK + 1,)), Partial("reach_max", MAX),
                Partial("reach_min", MIN))

    def measures(self, options):
        wrist = [Measure(m.name, m.unit, "3-RSR wrist: " + m.definition, m.better, m.extra)
                 for m in self.wrist.measures(options)]
        return [*wrist,
                Measure("arm_assembles", "1", "fraction of the arm's joint samples (legs within [phi_min, phi_max]) "
                        "whose wrist assembles", "max"),
                Measure("ik_closes", "1", "fraction of the arm's FK-sampled poses on which IK finds at least one "
                        "real set (1 for a complete solver)", "max"),
                Measure("ik_sets_mean", "1", "mean number of real IK sets (branches, of 16) per sampled arm pose",
                        None),
                Measure("reach_max", "m", "SCARA reach: the largest horizontal distance of the platform centre "
                        "from the base axis over the arm's samples", "max"),
                Measure("reach_min", "m", "the smallest such distance (the hole in the middle of the workspace)",
                        "min")]

    def unit_blocks(self, seed, block, samples, grid):
        from . import sampling

        u_pose, u_joint = super().unit_blocks(seed, block, samples, grid)
        return u_pose, (u_joint, sampling.unit_block(seed, ARM_STREAM, block, samples, ARM_DIM, grid))

    def solves(self, u_pose, u_joint):
        return len(u_pose) + len(u_joint[0]) + 2 * len(u_joint[1])  # the arm: FK and IK per sample

    def joints(self, u, design):
        p = dict(zip(self.module.DESIGN_NAMES, np.ravel(design.params), strict=True))
        lo, hi = p["phi_min"], p["phi_max"]
        rev = [2.0 * math.pi * u[:, i] - math.pi for i in (0, 1, 3)]
        return np.column_stack([rev[0], rev[1], p["d"] * u[:, 2], rev[2], *(lo + u[:, 4 + k] * (hi - lo)
                                                                          for k in range(3))])

    def evaluate(self, design, u_pose, u_joint, options):
        m = self.module
        u_wrist, u_arm = u_joint
        out = self.wrist.evaluate(self.wrist_design(design), u_pose, u_wrist, options)
        q = self.joints(u_arm, design)
        if len(q) == 0:  # a grid block past the arm's smaller lattice
            poses, ok = np.empty((0, 13)), np.zeros(0, dtype=bool)
        else:
            fk = m.fk_batch(q, design)
            ok = fk.valid[:, 0]
            poses = fk.values[ok, 0, :]
        count = m.ik_batch(poses, design).valid.sum(axis=1) if len(poses) else np.zeros(0, dtype=int)
        reach = np.hypot(poses[:, 3], poses[:, 7])
        out.update({"arm_n": len(q), "arm_fk": int(ok.sum()), "arm_closes": int((count > 0).sum()),
                    "arm_sets": np.bincount(count, minlength=m.MAX_IK + 1).astype(np.int64),
                    "reach_max": float(reach.max()) if reach.size else -np.inf,
                    "reach_min": float(reach.min()) if reach.size else np.inf})
        return out

    def design_partials(self, design, options) -> dict:
        return self.wrist.design_partials(self.wrist_design(design), options)

    def finalize(self, p, options):
        out = self.wrist.finalize(p, options)
        ok = p["design_ok"] > 0
        sets = p["arm_sets"].astype(float)
        out.update({"arm_assembles": _ratio(p["arm_fk"], p["arm_n"]),
                    "ik_closes": _ratio(p["arm_closes"], p["arm_fk"]),
                    "ik_sets_mean": _ratio(sets @ np.arange(sets.shape[1], dtype=float), p["arm_fk"]),
                    "reach_max": np.where(np.isfinite(p["reach_max"]), p["reach_max"], np.nan),
                    "reach_min": np.where(np.isfinite(p["reach_min"]), p["reach_min"], np.nan)})
        for k in ("arm_assembles", "ik_closes", "ik_sets_mean", "reach_max", "reach_min"):
            out[k] = np.where(ok, out[k], np.nan)
        return out
