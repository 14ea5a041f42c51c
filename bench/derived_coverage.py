"""Does every robot the planner decomposes get derived stages, and do they return its generating joints?

Run from the repository root:  .venv/bin/python bench/derived_coverage.py [--count 200] [--seed 2] [--poses 20]

Draws random standard DH arms (4 to 6 joints, one in six a slide; twists 0, +-90 or 60 degrees, lengths zero about
half the time, so that axes meet, lie parallel or neither) and keeps those the planner decomposes (counting those it
refuses as singular at every configuration). Each is derived (numpy backend: no compiler needed). It counts the arms
the derived stages refuse or fail to derive and, on the derived ones, random
poses (FK of uniform joints, the description's own product as the reference) whose generating joints the IK missed
(no set within 1e-9 + 1e-13 / sigma_min rad) or that returned a set off the pose by more than 1e-9. Prints one line
per refusal or miss and a summary.
"""

from __future__ import annotations

import argparse
import math
import random
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from chain_specs import dh_spec, poe_spec  # noqa: E402
from reference import chain as ref  # noqa: E402

from derive import own_robot  # noqa: E402
from derive.model import NoDecomposition, NotDerivable  # noqa: E402


def draw(rng: random.Random):
    n = rng.choice([4, 5, 6, 6, 6])
    kinds = [rng.choice("RRRRRP") for _ in range(n)]
    rows = [(rng.choice([0, 0, 0.3, 0.45]), rng.choice(["0", "pi/2", "-pi/2", "pi/2", "pi/3"]),
             rng.choice([0, 0, 0.2, 0.4])) for _ in range(n)]
    return rows, kinds


AXES = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, -1.0)]


def draw_poe(rng: random.Random):
    """A random revolute arm in POE form: axes along +-x, +-y, +-z (one in eight tilted 45 degrees), points on a 0.1 m
    grid with few values, so that axes meet, lie parallel, coincide or are skew; its tool 0.1 m past the last point."""
    n = rng.choice([5, 6, 6, 6])
    axes, points = [], []
    for _ in range(n):
        a = rng.choice(AXES)
        if rng.random() < 0.125:
            b = rng.choice([v for v in AXES if abs(sum(x * y for x, y in zip(a, v, strict=True))) < 0.5])
            a = tuple((x + y) / math.sqrt(2.0) for x, y in zip(a, b, strict=True))
        axes.append(a)
        points.append(tuple(rng.choice([0.0, 0.0, 0.1, 0.3]) for _ in range(3)))
    return axes, points


def gap(a, b, kinds) -> float:
    d = np.asarray(a, dtype=float) - np.asarray(b, dtype=float)
    rev = np.array([k == "R" for k in kinds])
    d[rev] = (d[rev] + math.pi) % (2 * math.pi) - math.pi
    return float(np.max(np.abs(d)))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--seed", type=int, default=2)
    ap.add_argument("--poses", type=int, default=20)
    ap.add_argument("--poe", action="store_true", help="random POE arms (axes along the frame's axes) instead of DH")
    ap.add_argument("--native", action="store_true", help="also compile the C and compare its sets with numpy's")
    args = ap.parse_args()
    rng, nrng = random.Random(args.seed), np.random.default_rng(args.seed)
    solved = derived = refused = missed = off_pose = poses = degenerate = c_differs = failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "arm_dh.toml"
        for trial in range(args.count):
            if args.poe:
                axes, points = draw_poe(rng)
                kinds = ["R"] * len(axes)
                rows = list(zip(axes, points, strict=True))  # printed as the arm's description
                last = points[-1]
                path.write_text(poe_spec("arm", "random POE arm", axes, points, (last[0], last[1], last[2] + 0.1)))
            else:
                rows, kinds = draw(rng)
                path.write_text(dh_spec("arm", "random DH arm", rows, kinds))
            try:
                own_robot.description(path).plan()
            except NoDecomposition as exc:
                degenerate += "singular at every configuration" in str(exc)
                continue
            solved += 1
            out = Path(tmp) / f"out{trial}"
            try:
                own_robot.derive(path, out, name="arm", native=args.native, progress=lambda _: None)
            except NotDerivable as exc:  # the planner decomposes it, the derived stages do not express it
                refused += 1
                print(f"arm {trial} {''.join(kinds)} {rows}: {exc}")
                continue
            except Exception as exc:  # noqa: BLE001 (a derivation that fails its own checks: reported, counted)
                failed += 1
                print(f"arm {trial} {''.join(kinds)} {rows}: derive failed: {type(exc).__name__}: {exc}")
                continue
            derived += 1
            m = own_robot.import_solver(out, "arm", backend="numpy")
            mc = own_robot.import_solver(out, "arm") if args.native else None
            reference = ref.load(path)
            for _ in range(args.poses):
                q = np.array([nrng.uniform(-math.pi, math.pi) if k == "R" else nrng.uniform(-0.5, 0.5)
                              for k in kinds])
                T = reference(q)
                sol = m.ik(T)
                poses += 1
                smin = np.linalg.svd(reference.jacobian(q), compute_uv=False)[-1]
                if not any(gap(v, q, kinds) <= 1e-9 + 1e-13 / max(smin, 1e-300) for v in sol):
                    missed += 1
                    print(f"arm {trial} {''.join(kinds)} {rows}: generating joints missed at q = {q.tolist()} "
                          f"(sigma_min {smin:.1e}, {sol.count} sets)")
                if any(ref.pose_error(reference(np.asarray(v)), T) > 1e-9 for v in sol):
                    off_pose += 1
                    print(f"arm {trial} {''.join(kinds)} {rows}: a set off the pose at q = {q.tolist()}")
                if mc is not None and mc.ik(T).count != sol.count:
                    c_differs += 1
                    print(f"arm {trial} {''.join(kinds)} {rows}: C {mc.ik(T).count} sets, numpy {sol.count} at "
                          f"q = {q.tolist()}")
    print(f"{args.count} random {'POE' if args.poe else 'DH'} arms (seed {args.seed}): {degenerate} refused as "
          f"singular at every configuration, {solved} decomposed by the planner, {failed} failed to "
          f"derive, {refused} refused by the derived stages, {derived} derived; {poses} poses on the derived ones: "
          f"{missed} missed the generating joints, {off_pose} returned a set off the pose"
          + (f", C's set count differed from numpy's on {c_differs}" if args.native else ""))


if __name__ == "__main__":
    main()
