"""How much rounding does a spherical wrist's sin(theta5) carry at an exact wrist singularity, measured against the
factors that scale its family band?

Run from the repository root:  .venv/bin/python bench/wrist_band.py [--poses 1500] [--seed 1]

The derived wrist stage reads |sin theta5| as the family (one representative) below WRIST_FAMILY_TOL (64 eps) times a
factor: `amp_before`, the product of the angle stages' own amplifications before it, narrowed where smaller to
WRIST_KAPPA_SHARE kappa (serial_stages._wrist_amp), kappa = size ||adj J_c||_F / |det J_c| of the wrist centre's
Jacobian in the prefix joints (the stage's derived kernel). This bench derives the spherical-wrist fixtures (numpy
backend), sets theta5 = 0 or pi exactly at random joints, solves the FK pose, and for the generating branch records
the |sin theta5| the stage computed (pure rounding: it is 0 in exact arithmetic) over

* eps x amp_before (the product alone, the band before the kernel),
* eps x kappa (an independent reading: size / sigma_min of the wrist centre's 3 x 3 Jacobian in joints 1-3 by central
  differences of the FK, size = max(1, |position|)), and
* eps x the factor the stage now uses.

A factor is safe when the largest ratio stays below 64 with room. It also solves the LR Mate pose the near-singular
bench missed at theta5 = 1e-12 (the product's band there was 7.7e-12) and says whether its generating joints come
back. Prints one line per robot.
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))
from reference import wrist_centre as reference  # noqa: E402  (the centre and kappa from the FK alone)

EPS = float(np.finfo(float).eps)
ROBOTS = ("lrmate", "kr6", "irb120", "tx2_60")
# bench/near_singular.py's LR Mate pose missed at theta5 = 1e-12 (2026-11-29)
LRMATE_MISS = (-0.9821104536660639, 1.1159593609618579, -1.747828137939208, 0.3288563662222219, 1.0004574458673634e-12,
               -0.21650171387252692)


def measure(robot: str, poses: int, seed: int) -> str:
    from derive import own_robot

    out = Path(tempfile.mkdtemp(prefix=f"wk_band_{robot}_"))
    own_robot.derive(ROOT / "tests" / "robots" / robot / f"{robot}.urdf", out, progress=lambda _: None, native=False)
    m = own_robot.import_solver(out, robot, backend="numpy")
    rng = np.random.default_rng(seed)
    centre = reference.centre_in_end_frame(m.fk_matrix, rng.uniform(-2.0, 2.0, 6), rng)
    seen, plain = [], m._wrist

    def wrist(out_, sgn, signs, joints, q, c, s, dp, amp_before, kernel=None, pose=None):
        # the factor the stage reads (the gate passed: sin theta5 = 0)
        factor = m._wrist_amp(0.0, amp_before, kernel, pose, q, c, s, dp)
        seen.append((abs(math.hypot(out_[2], out_[5])), amp_before, factor, list(q[:3])))
        return plain(out_, sgn, signs, joints, q, c, s, dp, amp_before, kernel, pose)
    m._wrist = wrist
    by_amp, by_kappa, by_factor = [], [], []
    for i in range(poses):
        q = rng.uniform(-2.8, 2.8, 6)
        q[4] = 0.0 if i % 2 == 0 else math.pi
        seen.clear()
        m.ik(m.fk_matrix(q))
        for s5, amp, factor, q123 in seen:
            if np.max(np.abs(np.remainder(np.array(q123) - q[:3] + math.pi, 2.0 * math.pi) - math.pi)) < 1e-6:
                by_amp.append(s5 / (EPS * amp))
                by_kappa.append(s5 / (EPS * reference.kappa(m.fk_matrix, centre, q)))
                by_factor.append(s5 / (EPS * factor))
    a, k, f = np.array(by_amp), np.array(by_kappa), np.array(by_factor)

    def spread(x):
        return f"max {x.max():.2f}, p99 {np.percentile(x, 99):.2f}, median {np.median(x):.3f}"
    line = (f"{robot}: {len(a)} generating branches; |sin theta5| over eps x amp_before {spread(a)}; over eps x "
            f"kappa {spread(k)}; over eps x the stage's factor {spread(f)}")
    if robot == "lrmate":
        m._wrist = plain
        q = np.array(LRMATE_MISS)
        sol = m.ik(m.fk_matrix(q))
        off = min(float(np.max(np.abs(np.remainder(np.asarray(v) - q + math.pi, 2.0 * math.pi) - math.pi)))
                  for v in sol)
        kap = reference.kappa(m.fk_matrix, centre, q)
        line += (f"; the pose missed before (kappa {kap:.1f}): its generating joints "
                 f"{'returned' if off < 1e-6 + 1e-13 / LRMATE_MISS[4] else 'missed'} ({off:.1e} rad off)")
    return line


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--poses", type=int, default=1500)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    for robot in ROBOTS:
        print(measure(robot, args.poses, args.seed))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
