"""Serial arms in the atlas (DH chains, the finite-screw robots, spec / URDF chains): joint-space samples, FK of
each (C batch), then IK of that pose (C batch): how many IK branches each sampled pose has, whether IK closes on
it, the manipulability sqrt(det J^T J) the generated FK reports, and the conditioning of the derived geometric
Jacobian: the local index sigma_min / sigma_max of diag(I / L_c, I) J (linear rows over a characteristic length, so
it is dimensionless), its mean (GCI), its worst value and the fraction of samples below the threshold
(singularity proximity). The catalogue arms compute it in their generated C (atlas_conditioning, GIL released); a
spec / URDF chain's module has no such batch, so its Jacobian comes from its `jacobian` per sample and numpy's SVD."""

from __future__ import annotations

import math

import numpy as np

from .mechanisms import Measure, Mechanism, _ratio
from .partials import FIXED, MIN, SUM, Partial, fixed_sum


def is_serial(module) -> bool:
    return hasattr(module, "JOINT_KINDS") and getattr(module, "POSE_NAMES", ())[:1] == ("r00",) \
        and getattr(module, "FK_AUX_NAMES", ()) == ("manipulability",)


class SerialArm(Mechanism):
    """Joints: revolute uniform on [-pi, pi); prismatic uniform on [0, s], s = the design's largest length
    (1 when it has none). Poses: the FK of the joint samples (so every sampled pose is reachable)."""

    def __init__(self, module):
        super().__init__(module)
        self.joint_dim = len(module.JOINT_NAMES)
        self.pose_dim = self.joint_dim

    def partials(self):
        return (Partial("design_ok", SUM), Partial("n_joint", SUM), Partial("ik_closes", SUM),
                Partial("sets", SUM, (self.module.MAX_IK + 1,)), Partial("singular", SUM),
                Partial("manip_sum", SUM), Partial("manip_min", MIN), Partial("li_sum", SUM),
                Partial("li_min", MIN), Partial("near_singular", SUM))

    def measures(self, options):
        kinds = self.module.JOINT_KINDS
        unit = "m^" + str(sum(k == "P" for k in kinds)) if "P" in kinds else "m^k"
        return [
            Measure("ik_closes", "1", "fraction of FK-sampled poses on which IK finds at least one real set (1 for "
                    "a complete solver)", "max"),
            Measure("ik_sets", "1", "distribution of the number of real IK sets over the FK-sampled poses", None,
                    ("sets",)),
            Measure("ik_sets_mean", "1", "mean number of real IK sets (branches) per sampled pose", None),
            Measure("singular", "1", "fraction of joint samples the FK flags singular (sigma_min / sigma_max of J "
                    "at or below the module's SINGULAR_EPS)", "min"),
            Measure("manipulability_mean", unit, "mean of sqrt(det J^T J) over the joint samples (units: metres "
                    "to the power of the Jacobian's linear rank; compare designs of one robot only)", "max"),
            Measure("manipulability_min", unit, "smallest sampled manipulability", "max"),
            Measure("gci", "1", "global conditioning index: mean over the joint samples of the local index "
                    "sigma_min / sigma_max (1/kappa_2) of diag(I / L_c, I) J, the geometric Jacobian with its linear "
                    "rows divided by the characteristic length L_c (the design's largest absolute parameter value, 1 m "
                    "if none)",
                    "max"),
            Measure("worst_li", "1", "worst local index: the smallest sampled sigma_min / sigma_max", "max"),
            Measure("near_singular", "1", f"fraction of joint samples whose local index is below "
                    f"{options.threshold:g} (singularity proximity)", "min"),
        ]

    def characteristic_length(self, design) -> float:
        """L_c: the design's largest |value| that is not a free joint (the prismatic stroke too), 1 when none."""
        m = self.module
        params = tuple(np.ravel(getattr(design, "params", ())))
        lengths = [abs(v) for n, v in zip(m.DESIGN_NAMES, params, strict=False)
                   if n not in m.JOINT_NAMES and np.isfinite(v)]
        return max(lengths) if lengths and max(lengths) > 0 else 1.0

    def conditioning(self, design, q, threshold) -> tuple[int, float, int]:
        """(fixed-point sum, min, count below threshold) of the local index over the joint samples q."""
        m, length = self.module, self.characteristic_length(design)
        c = getattr(m, "_C", None)
        batch = getattr(c, m.NAME + "_atlas_conditioning", None) if c is not None else None
        if batch is not None and getattr(design, "native", None) is not None:
            sums, li_min = np.zeros(2, dtype=np.int64), np.full(1, np.inf)
            rc = batch(np.ascontiguousarray(q, dtype=float), design.native, float(length), float(threshold), sums,
                       li_min)
            if rc != 0:
                raise RuntimeError(f"{m.NAME}_atlas_conditioning failed with code {rc}")
            return int(sums[0]), float(li_min[0]), int(sums[1])
        li = self.local_index_numpy(design, q, length)
        return fixed_sum(li), float(li.min()) if li.size else np.inf, int((li < threshold).sum())

    def local_index_numpy(self, design, q, length) -> np.ndarray:
        """sigma_min / sigma_max of diag(I / L_c, I) J per sample, J from the module's `jacobian` (the derived
        Jacobian; one call per sample) and numpy's SVD: the path of a module without the C batch."""
        if len(q) == 0:
            return np.empty(0)
        jac = np.array([self.module.jacobian(row, design) for row in q], dtype=float)
        jac[:, :3, :] /= length
        sv = np.linalg.svd(jac, compute_uv=False)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(sv[:, 0] > 0.0, sv[:, -1] / np.where(sv[:, 0] > 0.0, sv[:, 0], 1.0), 0.0)
        return np.clip(ratio, 0.0, 1.0)

    def joints(self, u, design):
        """Joint samples: within the module's LOWER / UPPER where it has finite ones (a derived arm), else
        revolute on [-pi, pi) and prismatic on [0, s] (s: the design's largest length, 1 when none); a derived
        redundant arm's free joint (a design parameter) at the design's value."""
        m = self.module
        names, kinds = m.JOINT_NAMES, m.JOINT_KINDS
        params = tuple(np.ravel(getattr(design, "params", ())))
        free = {n: v for n, v in zip(m.DESIGN_NAMES, params, strict=False) if n in names}
        lengths = [abs(v) for n, v in zip(m.DESIGN_NAMES, params, strict=False) if n not in names and np.isfinite(v)]
        stroke = max(lengths) if lengths and max(lengths) > 0 else 1.0
        lower, upper = getattr(m, "LOWER", None), getattr(m, "UPPER", None)
        cols = []
        for i, (name, kind) in enumerate(zip(names, kinds, strict=True)):
            lo = lower[i] if lower is not None else None
            hi = upper[i] if upper is not None else None
            if name in free:
                cols.append(np.full(len(u), free[name]))
            elif lo is not None and hi is not None and np.isfinite(lo) and np.isfinite(hi) and hi > lo:
                cols.append(lo + (hi - lo) * u[:, i])
            elif kind == "R":
                cols.append(2.0 * math.pi * u[:, i] - math.pi)
            else:
                cols.append(stroke * u[:, i])
        return np.column_stack(cols)

    def evaluate(self, design, u_pose, u_joint, options):
        m = self.module
        q = self.joints(u_joint, design)
        fk = m.fk_batch(q, design)
        poses = fk.values[:, 0, :]
        ok = fk.valid[:, 0]
        ik = m.ik_batch(poses[ok], design)
        count = ik.valid.sum(axis=1)
        manip = fk.aux[ok, 0, 0]
        li_sum, li_min, near = self.conditioning(design, q, options.threshold)
        return {"li_sum": li_sum, "li_min": li_min, "near_singular": near, "design_ok": 1, "n_joint": len(q),
                "ik_closes": int((count > 0).sum()),
                "sets": np.bincount(count, minlength=m.MAX_IK + 1).astype(np.int64),
                "singular": int(((fk.flags[:, 0] & m.FLAG_SINGULAR_INVERSE) != 0).sum()),
                # manipulability has units: summed exactly as an integer of 2^-32 of its unit (designs of metres)
                "manip_sum": int(np.rint(manip * 2.0**32).astype(np.int64).sum()),
                "manip_min": float(manip.min()) if manip.size else np.inf}

    def finalize(self, p, options):
        ok = p["design_ok"] > 0
        sets = p["sets"].astype(float)
        n = p["n_joint"]
        out = {"ik_closes": _ratio(p["ik_closes"], n), "ik_sets": _ratio(sets, n[:, None]),
               "ik_sets_mean": _ratio(sets @ np.arange(sets.shape[1], dtype=float), n),
               "singular": _ratio(p["singular"], n), "manipulability_mean": _ratio(p["manip_sum"] / 2.0**32, n),
               "manipulability_min": np.where(np.isfinite(p["manip_min"]), p["manip_min"], np.nan),
               "gci": _ratio(p["li_sum"] / FIXED, n),
               "worst_li": np.where(np.isfinite(p["li_min"]), p["li_min"], np.nan),
               "near_singular": _ratio(p["near_singular"], n)}
        for k, v in out.items():
            out[k] = np.where(ok.reshape((-1,) + (1,) * (v.ndim - 1)), v, np.nan)
        return out
