"""What the atlas measures per mechanism: how the unit sample maps into the workspace, the per-block evaluation
through the generated C batch solvers (`ik_batch`, `fk_batch`; they release the GIL), the exact partial results
and the measures made from them. Definitions and units: docs/atlas.md (and each Measure's text)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .conditioning import inverse_kappa_f
from .partials import FIXED, MAX, MIN, SUM, Partial, fixed_sum


@dataclass(frozen=True)
class Measure:
    name: str
    unit: str
    definition: str
    better: str | None  # "max", "min" or None (no ranking)
    extra: tuple[str, ...] = ()  # extra dimension names beyond the design axes


@dataclass(frozen=True)
class Options:
    threshold: float = 0.1  # conditioning measure below which a solution counts as near-singular
    tilt_max: float = math.pi / 2  # largest platform tilt sampled (rad)
    swing_bins: int = 72  # azimuth bins of the 3-RSR swing measures (5 deg)


ATLAS_MODES = 7  # the generated C's WK_ATLAS_MODES: the sums before the FK mode histogram (wristkin_common.h)


class UnknownMechanism(ValueError):
    pass


class UnsupportedMechanism(UnknownMechanism):
    """A mechanism wristkin solves but the atlas has no measures for (the message says why and what to run)."""


def _ratio(num, den):
    num, den = np.asarray(num, dtype=float), np.asarray(den, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), np.nan)


def _finite_or_nan(x):
    x = np.asarray(x, dtype=float)
    return np.where(np.isfinite(x), x, np.nan)


def _tilt(u, tilt_max):
    """Tilt angle with cos(tilt) uniform on [cos tilt_max, 1]: the area-uniform cap of directions."""
    return np.arccos(1.0 - u * (1.0 - math.cos(tilt_max)))


_COMMON_PARTIALS = (
    Partial("design_ok", SUM), Partial("n_pose", SUM), Partial("n_reach", SUM), Partial("n_sets", SUM),
    Partial("li_sum", SUM), Partial("li_best_sum", SUM), Partial("li_min", MIN), Partial("near_inv", SUM),
    Partial("near_dir", SUM), Partial("n_joint", SUM), Partial("fk_near_dir", SUM),
)


def _common_measures(threshold_text: str, fk_what: str) -> list[Measure]:
    return [
        Measure("reachable", "1", "fraction of the sampled pose workspace with at least one real IK set", "max"),
        Measure("gci", "1", "global conditioning index: mean of 1/kappa_F(J) over every real IK set of every "
                "reachable sampled pose (each IK branch is a working mode)", "max"),
        Measure("gci_best", "1", "mean over reachable sampled poses of the best IK set's 1/kappa_F(J) (the "
                "conditioning a mode-switching controller could keep)", "max"),
        Measure("worst_li", "1", "worst local index: min of 1/kappa_F(J) over every real IK set", "max"),
        Measure("near_inverse", "1", f"fraction of real IK sets with cond_inverse < {threshold_text} "
                "(inverse-singularity proximity)", "min"),
        Measure("near_direct", "1", f"fraction of real IK sets with cond_direct < {threshold_text} "
                "(direct-singularity proximity)", "min"),
        Measure("fk_modes", "1", f"distribution of the number of real FK assembly modes over {fk_what}", None,
                ("modes",)),
        Measure("fk_modes_mean", "1", f"mean number of real FK assembly modes over {fk_what}", None),
        Measure("fk_no_assembly", "1", f"fraction of {fk_what} with no real assembly mode", "min"),
        Measure("fk_near_direct", "1", f"fraction of {fk_what} with an assembly mode whose cond_direct < "
                f"{threshold_text}", "min"),
    ]


def _common_finalize(p: dict, max_fk: int) -> dict:
    ok = p["design_ok"] > 0
    modes = p["modes"].astype(float)
    out = {
        "reachable": _ratio(p["n_reach"], p["n_pose"]),
        "gci": _ratio(p["li_sum"] / FIXED, p["n_sets"]),
        "gci_best": _ratio(p["li_best_sum"] / FIXED, p["n_reach"]),
        "worst_li": _finite_or_nan(p["li_min"]),
        "near_inverse": _ratio(p["near_inv"], p["n_sets"]),
        "near_direct": _ratio(p["near_dir"], p["n_sets"]),
        "fk_modes": _ratio(modes, p["n_joint"][:, None]),
        "fk_modes_mean": _ratio(modes @ np.arange(max_fk + 1, dtype=float), p["n_joint"]),
        "fk_no_assembly": _ratio(modes[:, 0], p["n_joint"]),
        "fk_near_direct": _ratio(p["fk_near_dir"], p["n_joint"]),
    }
    for k, v in out.items():
        out[k] = np.where(ok.reshape((-1,) + (1,) * (v.ndim - 1)), v, np.nan)
    return out


def _ik_partials(out: dict, n_pose, valid, li, cond_inv, cond_dir, threshold):
    """Shared IK reductions of one block: the reachable poses' (n, MAX) sets (valid flags, 1/kappa_F and the
    conditioning measures) out of n_pose sampled poses."""
    li_v = np.where(valid, li, 0.0)
    out["n_pose"] = n_pose
    out["n_reach"] = int(valid.any(axis=1).sum())
    out["n_sets"] = int(valid.sum())
    out["li_sum"] = fixed_sum(li_v[valid])
    out["li_best_sum"] = fixed_sum(li_v.max(axis=1)) if valid.size else 0
    out["li_min"] = float(li[valid].min()) if valid.any() else np.inf
    out["near_inv"] = int((valid & (cond_inv < threshold)).sum())
    out["near_dir"] = int((valid & (cond_dir < threshold)).sum())


def _fk_partials(out: dict, valid, cond_dir, max_fk, threshold):
    count = valid.sum(axis=1)
    out["n_joint"] = valid.shape[0]
    out["modes"] = np.bincount(count, minlength=max_fk + 1).astype(np.int64)
    out["fk_near_dir"] = int((valid & (cond_dir < threshold)).any(axis=1).sum())


class Mechanism:
    """A catalogue mechanism the atlas can sweep: its module, sample spaces, partials and measures."""

    pose_dim = 3
    joint_dim = 3

    def __init__(self, module):
        self.module = module
        self.name = module.NAME
        self.key = module.NAME  # what mechanism() takes to make this again (a worker's task argument)

    def unit_blocks(self, seed: int, block: int, samples: int, grid: bool):
        """(pose, joint) unit samples of one block (sampling.py): what evaluate gets."""
        from . import sampling

        return (sampling.unit_block(seed, sampling.POSE_STREAM, block, samples, self.pose_dim, grid),
                sampling.unit_block(seed, sampling.JOINT_STREAM, block, samples, self.joint_dim, grid))

    def solves(self, u_pose, u_joint) -> int:
        """Solves one evaluate of these unit samples runs (the progress bar's rate)."""
        return len(u_pose) + len(u_joint)

    def partials(self) -> tuple[Partial, ...]:
        raise NotImplementedError

    def measures(self, options: Options) -> list[Measure]:
        raise NotImplementedError

    def make_design(self, params):
        """The module's Design, or None for an invalid design (its measures are NaN)."""
        try:
            return self.module.make_design(tuple(float(v) for v in params))
        except self.module.InvalidDesign:
            return None

    def evaluate(self, design, u_pose, u_joint, options: Options) -> dict:
        raise NotImplementedError

    def finalize(self, p: dict, options: Options) -> dict:
        raise NotImplementedError


class UnderactuatedWrist(Mechanism):
    """Seed 000. Poses: ZXZ (psi, theta, phi) with psi, phi uniform and the platform axis uniform on the cap of
    tilt theta <= tilt_max (Haar measure on SO(3) restricted to the cap). Joints: theta_i uniform on [0, 2 pi)."""

    @staticmethod
    def fits(module) -> bool:
        return tuple(module.DESIGN_NAMES) == ("alpha1", "alpha2", "beta1", "beta2") and hasattr(module,
                                                                                               "_kv_middle_axes")

    def partials(self):
        return (*_COMMON_PARTIALS, Partial("modes", SUM, (self.module.MAX_FK + 1,)),
                Partial("phi_lo", MIN, (3,)), Partial("phi_hi", MAX, (3,)))

    def measures(self, options):
        t = f"{options.threshold:g}"
        return [*_common_measures(t, "the sampled joint triples"),
                Measure("phi_lo", "deg", "smallest motor/sensor angle Phi_i = theta_i - theta0 (wrapped to "
                        "(-180, 180]) over the sampled poses the home working mode reaches (the IK set whose signs "
                        "of det[Zi1, Zi2, Zi3] are those of the home pose's set); i = 1, 2 motors, 3 sensor", None,
                        ("motor",)),
                Measure("phi_hi", "deg", "largest Phi_i over the sampled poses the home working mode reaches", None,
                        ("motor",)),
                Measure("phi_range", "deg", "phi_hi - phi_lo: the travel each motor (1, 2) and the sensor (3) "
                        "must cover", "min", ("motor",))]

    def poses(self, u, options):
        return np.column_stack([2.0 * math.pi * u[:, 0] - math.pi, _tilt(u[:, 1], options.tilt_max),
                                2.0 * math.pi * u[:, 2] - math.pi])

    def joints(self, u, design):
        return 2.0 * math.pi * u

    def __init__(self, module):
        super().__init__(module)
        self._home_cache: dict = {}
        self._pose_cache: dict = {}

    def home_mode(self, design) -> np.ndarray:
        """The home working mode: signs of g_i = det[Zi1, Zi2, Zi3] (the branch's elbow sense; a working mode
        ends where a g_i crosses 0, an inverse singularity) of the IK set with Phi = 0 at the home pose."""
        sol = self.module.ik((0.0, 0.0, 0.0), design)
        k = int(np.argmin(np.where(sol.valid[:, None], np.abs(sol.aux[:, :3]), np.inf).max(axis=1)))
        _, g = self.local_index(design, np.zeros((1, 3)), sol.values[None, k:k + 1])
        return np.array([x[0, 0] > 0.0 for x in g])

    def local_index(self, design, poses, values):
        """(1/kappa_F, g) of J (w -> qdot) per IK set: g_i = det[Zi1, Zi2, Zi3], x_i = Zi2 x Zi3 (the module's
        derived axis kernels: jq qdot = jx w, docs/API.md `jacobians`)."""
        m, dc = self.module, design.constants
        rot = m._rotation_columns(poses)
        z3 = [x[:, None] for x in np.broadcast_arrays(*m._kv_platform_axes(rot, dc))]
        vals = np.where(np.isfinite(values), values, 0.0)
        cq, sq = np.cos(vals), np.sin(vals)
        z2 = m._kv_middle_axes(tuple(cq[..., i] for i in range(3)), tuple(sq[..., i] for i in range(3)), dc)
        z1 = m._kv_base_axes(dc)
        rows, g = [], []
        for i in range(3):
            a, b, c = z1[3 * i:3 * i + 3], z2[3 * i:3 * i + 3], z3[3 * i:3 * i + 3]
            x = (b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0])
            rows.append(x)
            g.append(a[0] * x[0] + a[1] * x[1] + a[2] * x[2])
        return inverse_kappa_f(rows, g), g

    def evaluate(self, design, u_pose, u_joint, options):
        # the poses do not depend on the design: mapped once per block (the task holds its blocks alive: ids stay)
        key = (id(u_pose), options.tilt_max)
        poses = self._pose_cache.get(key)
        if poses is None:
            poses = self._pose_cache.setdefault(key, self.poses(u_pose, options))
        home = self._home_cache.get(design.params)
        if home is None:  # once per design, not per block
            home = self._home_cache.setdefault(design.params, self.home_mode(design))
        joints = self.joints(u_joint, design)
        c = getattr(self.module, "_C", None)
        batch = getattr(c, self.module.NAME + "_atlas_home_batch", None) if c is not None else None
        if batch is None or getattr(design, "native", None) is None:
            return self.evaluate_numpy(design, poses, joints, home, options)
        sums = np.zeros(ATLAS_MODES + self.module.MAX_FK + 1, dtype=np.int64)
        li_min, lo, hi = np.full(1, np.inf), np.full(3, np.inf), np.full(3, -np.inf)
        rc = batch(poses, joints, design.native, float(options.threshold), home.astype(np.int64), sums, li_min, lo, hi)
        if rc != 0:  # the samples are finite and the design valid: a failure here is a defect, not a measure
            raise RuntimeError(f"{self.module.NAME}_atlas_home_batch failed with code {rc}")
        n_reach, n_sets, li_sum, li_best_sum, near_inv, near_dir, fk_near_dir = (int(v) for v in sums[:ATLAS_MODES])
        return {"design_ok": 1, "n_pose": len(poses), "n_reach": n_reach, "n_sets": n_sets, "li_sum": li_sum,
                "li_best_sum": li_best_sum, "li_min": float(li_min[0]), "near_inv": near_inv, "near_dir": near_dir,
                "n_joint": len(joints), "fk_near_dir": fk_near_dir, "modes": sums[ATLAS_MODES:].copy(),
                "phi_lo": lo, "phi_hi": hi}

    def evaluate_numpy(self, design, poses, joints, home, options):
        """The same sums as the C atlas_home_batch, from ik_batch / fk_batch and numpy (tests compare the two)."""
        m, out = self.module, {"design_ok": 1}
        ik = m.ik_batch(poses, design)
        reach = ik.valid.any(axis=1)  # the conditioning is computed on reachable poses only (the cost is there)
        valid, aux = ik.valid[reach], ik.aux[reach]
        li, g = self.local_index(design, poses[reach], ik.values[reach])
        _ik_partials(out, len(poses), valid, li, aux[..., 3], aux[..., 4], options.threshold)
        in_mode = valid & ((g[0] > 0.0) == home[0]) & ((g[1] > 0.0) == home[1]) & ((g[2] > 0.0) == home[2])
        phi = np.degrees(aux[in_mode][:, :3])
        out["phi_lo"] = phi.min(axis=0) if len(phi) else np.full(3, np.inf)
        out["phi_hi"] = phi.max(axis=0) if len(phi) else np.full(3, -np.inf)
        fk = m.fk_batch(joints, design)
        _fk_partials(out, fk.valid, fk.aux[..., m.FK_AUX_NAMES.index("cond_direct")], m.MAX_FK, options.threshold)
        return out

    def finalize(self, p, options):
        out = _common_finalize(p, self.module.MAX_FK)
        ok = (p["design_ok"] > 0)[:, None]
        lo, hi = _finite_or_nan(p["phi_lo"]), _finite_or_nan(p["phi_hi"])
        out["phi_lo"], out["phi_hi"] = np.where(ok, lo, np.nan), np.where(ok, hi, np.nan)
        out["phi_range"] = out["phi_hi"] - out["phi_lo"]
        return out


class RsrWrist(Mechanism):
    """Seed 002. Poses: azimuth alpha uniform on [0, 2 pi), platform swing beta with the platform normal uniform
    on the cap beta <= tilt_max, centre distance l_bw uniform on [lbw_min, lbw_max]. An IK set counts only with
    every phi_i in [phi_min, phi_max] (the design's leg limits). Joints: phi_i uniform on [phi_min, phi_max]."""

    @staticmethod
    def fits(module) -> bool:
        return tuple(module.DESIGN_NAMES) == ("L", "phi_min", "phi_max", "lbw_min", "lbw_max") and hasattr(
            module, "LEG_ANGLES")

    def partials(self):
        return (*_COMMON_PARTIALS, Partial("modes", SUM, (self.module.MAX_FK + 1,)),
                Partial("swing_bins", MAX, (Options.swing_bins,)))

    def measures(self, options):
        t = f"{options.threshold:g}"
        w = 360.0 / options.swing_bins
        return [*_common_measures(t, "the sampled leg angles within the limits"),
                Measure("swing_all", "deg", f"maximum swing over the whole cycle (the seed's measure): min over "
                        f"azimuths 0, {w:g}, ..., {360 - w:g} deg of the largest reachable swing, computed exactly per "
                        f"attitude (leg ranges within the limits) on a {self.SWING_STEP:g} deg swing grid", "max"),
                Measure("swing_peak", "deg", "the largest reachable swing over those azimuths", "max"),
                Measure("swing_peak_azimuth", "deg", "the azimuth of swing_peak (the first, if several)", None)]

    def poses(self, u, design, options):
        lo, hi = design.params[3], design.params[4]
        return np.column_stack([2.0 * math.pi * u[:, 0], _tilt(u[:, 1], options.tilt_max), lo + u[:, 2] * (hi - lo)])

    def joints(self, u, design):
        lo, hi = design.params[1], design.params[2]
        return lo + u * (hi - lo)

    def local_index(self, design, poses, values):
        """1/kappa_F of J (v -> phi_dot) with v = (sin(beta) alpha_dot, beta_dot, l_bw_dot / L): the platform
        normal's velocity on the unit sphere and the centre distance in link lengths, so J is dimensionless and
        free of the azimuth's representation singularity at beta = 0. J = diag(1/g) X from the module's derived
        `atlas_rates` kernel (g phi_dot = X v; the C batch path evaluates the same kernel)."""
        vals = np.where(np.isfinite(values), values, 0.0)
        pose = (poses[:, 0:1], poses[:, 1:2], poses[:, 2:3])
        o = self.module._kv_atlas_rates(tuple(vals[..., i] for i in range(3)), pose, design.params)
        o = [np.broadcast_to(np.asarray(v, dtype=float), vals.shape[:-1]) for v in o]
        g = o[0:3]
        rows = (tuple(o[3:6]), tuple(o[6:9]), tuple(o[9:12]))
        return inverse_kappa_f(rows, g), g

    SWING_STEP = 0.5  # deg: the swing grid of the exact swing profile (72 x 181 attitudes: ~0.05 ms in C, ~1 ms numpy)

    def feasible(self, design, alpha, beta) -> np.ndarray:
        """Whether some centre distance reaches attitude (alpha, beta) (arrays, rad) with every leg within its
        limits: leg i reaches n . S_i = L (A_i cos phi + B sin phi) over phi in [phi_min, phi_max], a closed
        interval (end points, and the sinusoid's top or bottom where it falls inside the arc), intersected with
        [lbw_min, lbw_max] / 2. The module's workspace(alpha, beta), vectorised (tests compare the two)."""
        length, lo, hi, lbw_lo, lbw_hi = design.params
        sh, ch = np.sin(0.5 * beta), np.cos(0.5 * beta)
        shape = np.broadcast(alpha, beta).shape
        bottom, top = np.full(shape, 0.5 * lbw_lo), np.full(shape, 0.5 * lbw_hi)
        lo_w, width = math.remainder(lo, 2.0 * math.pi), hi - lo

        def in_arc(t):  # t in (-pi, pi]: t - lo_w in (-2 pi, 2 pi), so one comparison pair decides (no np.mod)
            off = t - lo_w
            return ((off >= 0.0) & (off <= width)) | (off <= width - 2.0 * math.pi)

        for a_i in self.module.LEG_ANGLES:
            a, b = sh * np.sin(alpha - a_i), ch
            ends = [length * (a * math.cos(p) + b * math.sin(p)) for p in (lo, hi)]
            t0, rho = np.arctan2(b, a), length * np.hypot(a, b)
            in_top = in_arc(t0)
            in_bottom = in_arc(np.where(t0 > 0.0, t0 - math.pi, t0 + math.pi))
            top = np.minimum(top, np.where(in_top, rho, np.maximum(*ends)))
            bottom = np.maximum(bottom, np.where(in_bottom, -rho, np.minimum(*ends)))
        return bottom <= top

    def swing_profile(self, design, options) -> np.ndarray:
        """Largest reachable swing (deg) per azimuth 0, 5, ..., 355 deg on a SWING_STEP grid up to tilt_max
        (feasibility need not be monotone in beta: the largest feasible grid value)."""
        alpha = np.radians(np.arange(options.swing_bins) * 360.0 / options.swing_bins)
        beta = np.arange(0.0, math.degrees(options.tilt_max) + 1e-9, self.SWING_STEP)
        c = getattr(self.module, "_C", None)
        if c is not None and getattr(design, "native", None) is not None:  # C: from the top, the module's workspace
            index = np.empty(len(alpha), dtype=np.int64)
            rc = getattr(c, self.module.NAME + "_max_swing")(alpha, np.radians(beta), design.native, index)
            if rc != 0:
                raise RuntimeError(f"{self.module.NAME}_max_swing failed with code {rc}")
            return np.where(index >= 0, beta[np.maximum(index, 0)], 0.0)
        ok = self.feasible(design, alpha[:, None], np.radians(beta)[None, :])
        return np.where(ok.any(axis=1), np.where(ok, beta[None, :], -np.inf).max(axis=1), 0.0)

    def design_partials(self, design, options) -> dict:
        """Per design (not per sample): the exact swing profile, once per design (the first sample chunk)."""
        return {"swing_bins": self.swing_profile(design, options)}

    def native_batch(self, design):
        """The generated C's atlas_batch (IK, leg limits, local index, conditioning and FK counts of a block in one
        C loop, GIL released), or None where C does not run (WRISTKIN_BACKEND=numpy): then evaluate's numpy path."""
        c = getattr(self.module, "_C", None)
        if c is None or getattr(design, "native", None) is None:
            return None
        return getattr(c, self.module.NAME + "_atlas_batch", None)

    def evaluate(self, design, u_pose, u_joint, options):
        poses = self.poses(u_pose, design, options)
        joints = self.joints(u_joint, design)
        batch = self.native_batch(design)
        if batch is None:
            return self.evaluate_numpy(design, poses, joints, options)
        sums = np.zeros(ATLAS_MODES + self.module.MAX_FK + 1, dtype=np.int64)
        li_min = np.full(1, np.inf)
        rc = batch(poses, joints, design.native, float(options.threshold), sums, li_min)
        if rc != 0:  # the samples are finite and the design valid: a failure here is a defect, not a measure
            raise RuntimeError(f"{self.module.NAME}_atlas_batch failed with code {rc}")
        n_reach, n_sets, li_sum, li_best_sum, near_inv, near_dir, fk_near_dir = (int(v) for v in sums[:ATLAS_MODES])
        return {"design_ok": 1, "n_pose": len(poses), "n_reach": n_reach, "n_sets": n_sets, "li_sum": li_sum,
                "li_best_sum": li_best_sum, "li_min": float(li_min[0]), "near_inv": near_inv, "near_dir": near_dir,
                "n_joint": len(joints), "fk_near_dir": fk_near_dir, "modes": sums[ATLAS_MODES:].copy()}

    def evaluate_numpy(self, design, poses, joints, options):
        """The same sums as the C atlas_batch, from ik_batch / fk_batch and numpy (tests compare the two)."""
        m, out = self.module, {"design_ok": 1}
        lo, hi = design.params[1], design.params[2]
        ik = m.ik_batch(poses, design)
        # leg limits: phi within the arc [lo, hi]. The values lie in (-pi, pi] (NaN where no set: False below), so
        # off = phi - lo (lo wrapped) lies in (-2 pi, 2 pi] and the arc is off in [0, hi - lo] or off <= hi - lo -
        # 2 pi (np.mod would cost ~20x these comparisons)
        width = hi - lo
        off = ik.values - math.remainder(lo, 2.0 * math.pi)
        with np.errstate(invalid="ignore"):
            within = ((off >= 0.0) & (off <= width)) | (off <= width - 2.0 * math.pi)
        valid = ik.valid & within.all(axis=2)
        reach = np.flatnonzero(valid.any(axis=1))
        # the conditioning of the in-limit sets only (usually one of the eight per reachable pose)
        rows, sets = np.nonzero(valid[reach])
        li = np.zeros(valid[reach].shape)
        li[rows, sets] = self.local_index(design, poses[reach][rows], ik.values[reach][rows, sets][:, None, :])[0][:, 0]
        aux = ik.aux[reach]
        _ik_partials(out, len(poses), valid[reach], li, aux[..., 1], aux[..., 2], options.threshold)
        fk = m.fk_batch(joints, design)
        _fk_partials(out, fk.valid, fk.aux[..., m.FK_AUX_NAMES.index("cond_direct")], m.MAX_FK, options.threshold)
        return out

    def finalize(self, p, options):
        out = _common_finalize(p, self.module.MAX_FK)
        ok = p["design_ok"] > 0
        swing = np.where(np.isfinite(p["swing_bins"]), p["swing_bins"], 0.0)
        width = 360.0 / options.swing_bins
        out["swing_all"] = np.where(ok, swing.min(axis=1), np.nan)
        out["swing_peak"] = np.where(ok, swing.max(axis=1), np.nan)
        out["swing_peak_azimuth"] = np.where(ok, np.argmax(swing, axis=1) * width, np.nan)
        return out


ADAPTERS = {"underactuated_wrist": UnderactuatedWrist, "rsr_wrist": RsrWrist}


FILE_PREFIX = "file:"  # a solver written by `wristkin derive` (a spec file's own folder), by its .py path
_DERIVED: dict = {}


def _derived_module(path: str):
    """Import a derived solver (its _wristkin_runtime and _wristkin_native beside it) once per process."""
    import importlib.util
    import sys
    from pathlib import Path

    if path not in _DERIVED:
        file = Path(path)
        if not file.is_file():
            raise UnknownMechanism(f"no derived solver at {file}")
        folder = str(file.parent)
        if folder not in sys.path:
            sys.path.insert(0, folder)  # its runtime and extension import by plain name
        spec = importlib.util.spec_from_file_location(f"_wristkin_atlas_{file.stem}", file)
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # dataclasses look their module up there
        spec.loader.exec_module(module)
        _DERIVED[path] = module
    return _DERIVED[path]


def mechanism(name: str) -> Mechanism:
    import importlib

    import wristkin

    if name.startswith(FILE_PREFIX):
        module = _derived_module(name[len(FILE_PREFIX):])
    elif name not in wristkin.MECHANISMS:
        raise UnknownMechanism(f"unknown mechanism {name!r} (catalogue: {', '.join(wristkin.MECHANISMS)}; or a "
                               "spec file / URDF)")
    else:
        module = importlib.import_module(f"wristkin.{name}")
    mech = None
    if name in ADAPTERS:
        mech = ADAPTERS[name](module)
    for adapter in ADAPTERS.values():
        if mech is None and adapter.fits(module):  # a spec of a parallel family, derived into its own folder
            mech = adapter(module)
    if mech is not None:
        mech.key = name
        return mech
    from .serial import SerialArm, is_serial

    if is_serial(module):
        mech = SerialArm(module)
        mech.key = name
        return mech
    from .hybrid import ScaraRsr

    if ScaraRsr.fits(module):
        mech = ScaraRsr(module)
        mech.key = name
        return mech
    raise UnsupportedMechanism(f"the atlas has no measures for {name!r} (it sweeps {', '.join(ADAPTERS)} and the "
                               "serial arms)")
