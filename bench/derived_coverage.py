"""Does every robot the plan interpreter solves get derived stages (issue 22's one serial-arm path)?

Run from the repository root:  .venv/bin/python bench/derived_coverage.py [--count 200] [--seed 2] [--poses 20]

Draws random standard DH arms (4 to 6 joints, one in six a slide; twists 0, +-90 or 60 degrees, lengths zero about
half the time, so that axes meet, lie parallel or neither) and keeps those the interpreter's planner solves (counting
those it refuses as singular at every configuration). Each is derived as the default module (`--stages auto`, numpy
backend: no compiler needed). It counts the arms that fell back to the interpreter and, on the derived ones, random
poses (FK of uniform joints, the description's own product as the reference) whose generating joints the IK missed
(no set within 1e-9 + 1e-13 / sigma_min rad) or that returned a set off the pose by more than 1e-9. Prints one line
per fallback or miss and a summary.
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

from chain_specs import dh_spec  # noqa: E402
from reference import chain as ref  # noqa: E402

from derive import own_robot  # noqa: E402
from derive.model import NoDecomposition  # noqa: E402


def draw(rng: random.Random):
    n = rng.choice([4, 5, 6, 6, 6])
    kinds = [rng.choice("RRRRRP") for _ in range(n)]
    rows = [(rng.choice([0, 0, 0.3, 0.45]), rng.choice(["0", "pi/2", "-pi/2", "pi/2", "pi/3"]),
             rng.choice([0, 0, 0.2, 0.4])) for _ in range(n)]
    return rows, kinds


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
    args = ap.parse_args()
    rng, nrng = random.Random(args.seed), np.random.default_rng(args.seed)
    solved = derived = fallback = missed = off_pose = poses = degenerate = 0
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "arm_dh.toml"
        for trial in range(args.count):
            rows, kinds = draw(rng)
            path.write_text(dh_spec("arm", "random DH arm", rows, kinds))
            try:
                own_robot.load(path, stages="interpreted").plan()
            except NoDecomposition as exc:
                degenerate += "singular at every configuration" in str(exc)
                continue
            solved += 1
            said: list[str] = []
            out = Path(tmp) / f"out{trial}"
            own_robot.derive(path, out, name="arm", native=False, progress=said.append)
            if "interpreter" in said[1]:
                fallback += 1
                print(f"arm {trial} {''.join(kinds)} {rows}: {said[1].strip()}")
                continue
            derived += 1
            m = own_robot.import_solver(out, "arm", backend="numpy")
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
    print(f"{args.count} random DH arms (seed {args.seed}): {degenerate} refused as singular at every configuration, "
          f"{solved} solved by the interpreter's planner, {derived} "
          f"derived, {fallback} fell back to the interpreter; {poses} poses on the derived ones: {missed} missed "
          f"the generating joints, {off_pose} returned a set off the pose")


if __name__ == "__main__":
    main()
