"""Near-singular sweeps of every own robot (issue 22's second measure): are the generating joints returned, and
does any call take much longer than the median?

Run from the repository root:  .venv/bin/python bench/near_singular.py [--robots ur5e,kr6] [--json PATH]

For every test robot (tests/robots: the URDFs, the offset-wrist UR5e's DH file, the tilted UR5e's POE file (a general
6R) and the Panda's DH file with joint5 held (a spatial 3R); a 7-joint arm's free joint held at 0 as in
bench/own_robots.py), `wristkin derive` writes its solvers, then:

* singular configurations are found from the Jacobian alone (tests/reference/singular.py): for each joint j and
  two random joint sets, det J (the 6 x 6 Jacobian of the held chain; for fewer joints, J projected on the image
  it spans at a random configuration, each zero confirmed on J's singular values) is scanned over q_j on a
  720-point grid and every sign change bisected to the last bit: q_j* is a singular configuration (wrist, elbow
  or shoulder);
* each is moved off by delta = +-1e-12 ... 1e-3 rad in q_j and its FK pose solved, in C (a C loop timing every
  call on its own, best of 3) and in numpy;
* "generating joints returned": some valid set lies within the conditioning allowance of the joints that
  made the pose, 1e-6 + 1e-13 / delta rad per joint (a pose error of rounding size moves the joints along the
  near-null direction by about eps x scale / sigma_min, sigma_min ~ delta; the issue's allowance);
* the time cliff: the 99th percentile and the maximum of the sweep's calls over the median call on random poses.
* one solution twice: pairs of C's sets within 1e-3 rad whose midpoint is on the pose as well as they are (to 16 eps x
  size, the FK's rounding): a copy, not a second solution.

Prints one Markdown table; the numbers also go to the JSON file.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))
from reference.distinct import indistinct_pairs as reference_indistinct  # noqa: E402
from reference.singular import singular_configurations as reference_singular  # noqa: E402

ROBOTS = ROOT / "tests" / "robots"
FREE = {"iiwa14": "a3", "panda": "joint5"}
DELTAS = (1e-12, 1e-10, 1e-8, 1e-6, 1e-5, 1e-4, 1e-3)
SINGULAR_REL = 1e-10  # a projected det's zero is the chain's singularity when J's sigma_min / sigma_max is this small
VERBOSE = bool(os.environ.get("NEAR_SINGULAR_VERBOSE"))
C_FLAGS = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-pedantic", "-D_POSIX_C_SOURCE=199309L"]

HARNESS = r"""
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "NAME.h"
/* argv[1]: poses (12 doubles each) then the free joint's value; argv[2]: output, per pose: best time (ns) of 3
   calls, count, status, then MAX_IK x (valid, flags, N_JOINTS values) as doubles. */
int main(int argc, char **argv) {
    if (argc < 3) return 2;
    FILE *f = fopen(argv[1], "rb");
    if (!f) return 2;
    static double poses[65536][12];
    size_t n = fread(poses, sizeof(double) * 12, 65536, f);
    fclose(f);
    double free_value[1] = {0.0};
    wk_NAME_design d;
    (void)free_value; /* without a held joint: the defaults (NULL) */
    wk_NAME_design_init(PARAMS, &d);
    FILE *o = fopen(argv[2], "wb");
    if (!o) return 2;
    for (size_t i = 0; i < n; ++i) {
        wk_NAME_ik_solutions s;
        double best = 1e30;
        for (int rep = 0; rep < 3; ++rep) {
            struct timespec a, b;
            clock_gettime(CLOCK_MONOTONIC, &a);
            wk_NAME_ik(poses[i], &d, &s);
            clock_gettime(CLOCK_MONOTONIC, &b);
            double t = 1e9 * (double)(b.tv_sec - a.tv_sec) + (double)(b.tv_nsec - a.tv_nsec);
            if (t < best) best = t;
        }
        double head[3] = {best, (double)s.count, (double)s.status};
        fwrite(head, sizeof head, 1, o);
        for (int k = 0; k < WK_NAME_MAX_IK; ++k) {
            double row[2 + WK_NAME_N_JOINTS];
            row[0] = (double)s.valid[k]; /* the valid rows anywhere in the table (a serial arm's sit at their branch) */
            row[1] = (double)s.flags[k];
            for (int j = 0; j < WK_NAME_N_JOINTS; ++j) row[2 + j] = s.values[k][j];
            fwrite(row, sizeof row, 1, o);
        }
    }
    fclose(o);
    return 0;
}
"""


# the general 6R fixture (no decomposition: the elimination, a derived general6r stage by default)
GENERAL_SPEC = ROBOTS / "ur5e_tilted" / "ur5e_tilted_poe.toml"
# the spatial 3R fixture: the Panda with joint5 held (from the tool, joints 7, 6 and 4 place the wrist point by the
# degree-8 polynomial: a derived spatial3 stage by default)
SPATIAL3_SPEC = ROBOTS / "panda" / "panda_dh.toml"
# the offset wrist (the UR5e with its last two axes apart: subproblem 6's quartic, a derived sp6 stage by default)
SP6_SPEC = ROBOTS / "ur5e_offset" / "ur5e_offset_dh.toml"


def specs() -> list[Path]:
    return sorted([*ROBOTS.glob("*/*.urdf"), SP6_SPEC, GENERAL_SPEC, SPATIAL3_SPEC])


def _name(spec: Path) -> str:
    return spec.stem.removesuffix("_dh").removesuffix("_poe")


def _free(m) -> int:
    """The held joint's index, -1 for none."""
    return getattr(m, "_FREE", -1)


def _design(m):
    """The design the poses and sets are read with: the held joint at 0, else the defaults."""
    return [0.0] if _free(m) >= 0 else None


def held_jacobian(m, q):
    """The 6 x 6 Jacobian of the solved chain (the free joint's column dropped)."""
    J = np.asarray(m.jacobian(q, _design(m)), dtype=float)
    return np.delete(J, _free(m), axis=1) if _free(m) >= 0 else J


def singular_configurations(m, rng):
    """(joint index, q*) with det J(q*) = 0 to the last bit (tests/reference/singular.py), the free joint held. A
    chain of n < 6 solved joints (the youBot's 5, the SCARA's 4) has a 6 x n J: its det is taken of B^T J, B the n
    left singular vectors of J at a random configuration, and a sign change kept only where J itself is singular
    there (sigma_min / sigma_max <= SINGULAR_REL: the image turning away from B is no singularity)."""
    free = {_free(m): 0.0} if _free(m) >= 0 else {}
    joints = [j for j in range(m.N_JOINTS) if j != _free(m)]
    n = m.N_JOINTS - (_free(m) >= 0)
    if n == 6:
        return reference_singular(lambda q: held_jacobian(m, q), m.N_JOINTS, rng, joints, fixed=free)
    q0 = rng.uniform(-math.pi, math.pi, m.N_JOINTS)
    b = np.linalg.svd(held_jacobian(m, q0))[0][:, :n]
    found = reference_singular(lambda q: b.T @ held_jacobian(m, q), m.N_JOINTS, rng, joints, fixed=free)
    out = []
    for j, q in found:
        sv = np.linalg.svd(held_jacobian(m, q), compute_uv=False)
        if sv[-1] <= SINGULAR_REL * sv[0]:
            out.append((j, q))
    return out


def sweep_joints(m, rng):
    rows = []
    for j, qs in singular_configurations(m, rng):
        for delta in DELTAS:
            for sign in (1.0, -1.0):
                q = qs.copy()
                q[j] += sign * delta
                rows.append((j, delta, q))
    return rows


def run_c(out: Path, name: str, poses, params: bool = True) -> Path:
    """Compile the timing harness beside the robot's C, run it on the poses; the file of its results (`params`: the
    design is the held joint's value, else the module's defaults)."""
    cdir = out / "c"
    src = cdir / "near_singular_main.c"
    src.write_text(HARNESS.replace("NAME", name).replace("WK_" + name, "WK_" + name.upper())
                   .replace("PARAMS", "free_value" if params else "NULL"))
    exe = cdir / "near_singular"
    others = sorted(str(f) for f in cdir.glob("*.c") if f.name != src.name)
    subprocess.run(["gcc", *C_FLAGS, "-o", str(exe), str(src), *others, f"-I{cdir}", "-lm"], check=True)
    data, res = cdir / "poses.bin", cdir / "sets.bin"
    data.write_bytes(np.ascontiguousarray(np.array([T[:3].ravel() for T in poses])).tobytes())
    subprocess.run([str(exe), str(data), str(res)], check=True)
    return res


def read_c(res: Path, n_poses: int, max_ik: int, nj: int) -> list[dict]:
    raw = np.fromfile(res, dtype=float)
    per = 3 + max_ik * (2 + nj)
    raw = raw.reshape(n_poses, per)
    out = []
    for r in raw:
        sets = r[3:].reshape(max_ik, 2 + nj)
        out.append({"ns": r[0], "count": int(r[1]), "status": int(r[2]),
                    "sets": [s[2:] for s in sets if s[0]], "flags": [int(s[1]) for s in sets if s[0]]})
    return out


def wrapped(a, b):
    d = np.asarray(a) - np.asarray(b)
    return float(np.max(np.abs((d + math.pi) % (2 * math.pi) - math.pi)))


def missing(q, sets, delta, free):
    """True when no set lies within the allowance of the generating joints."""
    q = np.delete(q, free) if free >= 0 else q
    allowance = 1e-6 + 1e-13 / delta
    best = min((wrapped(np.delete(s, free) if free >= 0 else s, q) for s in sets), default=math.inf)
    return best > allowance, best


def indistinct_pairs(m, design, T, sets) -> int:
    """Pairs of returned sets within MERGE_SPAN (1e-3 rad) whose midpoint is on the pose as well as they are, to 16
    eps x size (tests/reference/distinct.py): one solution returned twice (none is spurious only where this is 0)."""
    def err(x):
        return float(np.max(np.abs(m.fk_matrix(x, design)[:3] - T[:3])))

    return len(reference_indistinct(sets, err, float(np.max(np.abs(T[:3, 3])))))


def bench_robot(spec: Path) -> dict:
    """One robot's sweep (its derived solvers; the singular configurations from a fixed rng and the robot's FK)."""
    from derive import own_robot

    out = Path(tempfile.mkdtemp(prefix="wk_near_"))
    name = _name(spec)
    own_robot.derive(spec, out, name=spec.stem, free=FREE.get(name), progress=lambda _: None)
    m = own_robot.import_solver(out, spec.stem)
    name = m.NAME
    rng = np.random.default_rng(20261126)
    rows = sweep_joints(m, rng)
    design = _design(m)
    random_q = rng.uniform(-math.pi, math.pi, (200, m.N_JOINTS))
    if _free(m) >= 0:
        random_q[:, _free(m)] = 0.0
    poses = [m.fk_matrix(q, design) for _, _, q in rows] + [m.fk_matrix(q, design) for q in random_q]
    res = run_c(out, m.NAME, poses, params=_free(m) >= 0)
    c = read_c(res, len(poses), m.MAX_IK, m.N_JOINTS)
    median = float(np.median([r["ns"] for r in c[len(rows):]]))
    sweep_ns = np.array([r["ns"] for r in c[: len(rows)]])
    py = own_robot.import_solver(out, spec.stem, backend="numpy")
    by_joint: dict[str, dict] = {}
    twice = 0
    for (j, delta, q), cr, T in zip(rows, c, poses, strict=False):
        ps = py.ik(T, design)
        psets = [ps.values[k] for k in np.flatnonzero(ps.valid)]
        c_miss, c_err = missing(q, cr["sets"], delta, _free(m))
        p_miss, _ = missing(q, psets, delta, _free(m))
        twice += indistinct_pairs(m, design, T, cr["sets"])
        key = f"q{j + 1}"
        d = by_joint.setdefault(key, {"poses": 0, "c_missing": {}, "py_missing": {}, "worst": 0.0})
        d["poses"] += 1
        if c_miss and VERBOSE:
            print(name, key, delta, "best", c_err, "count", cr["count"], "status", cr["status"], "flags", cr["flags"],
                  "q", q.tolist(), file=sys.stderr)
        if c_miss:
            d["c_missing"][f"{delta:.0e}"] = d["c_missing"].get(f"{delta:.0e}", 0) + 1
        if p_miss:
            d["py_missing"][f"{delta:.0e}"] = d["py_missing"].get(f"{delta:.0e}", 0) + 1
        if math.isfinite(c_err):
            d["worst"] = max(d["worst"], c_err * delta)
    return {"robot": name, "decomposition": m.DECOMPOSITION.split(":")[0], "poses": len(rows),
            "median_us": median / 1e3, "p99_over_median": float(np.percentile(sweep_ns, 99)) / median,
            "max_over_median": float(sweep_ns.max()) / median,
            "c_missing": sum(sum(d["c_missing"].values()) for d in by_joint.values()),
            "py_missing": sum(sum(d["py_missing"].values()) for d in by_joint.values()), "indistinct_pairs": twice,
            "by_joint": by_joint}


def report(names=None, json_path: Path = ROOT / "build" / "bench" / "near_singular.json") -> str:
    chosen = [p for p in specs() if names is None or _name(p) in names]
    rows = [bench_robot(p) for p in chosen]
    lines = ["Near-singular sweeps (every robot's derived stages): each joint's singular configurations (det J = 0, "
             "found by bisection) moved off "
             f"by +-delta, delta = {', '.join(f'{d:.0e}' for d in DELTAS)} rad (machine: "
             f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores):", "",
             "| robot | decomposition | poses | generating joints missing C / numpy | "
             "missing where (joint: delta x n) | one solution twice (C) | median call us | p99 / median | "
             "max / median |",
             "|---|---|---:|---:|---|---:|---:|---:|---:|"]
    for r in rows:
        if "skipped" in r:
            lines.append(f"| {r['robot']} | skipped: {r['skipped']} | | | | | | | |")
            continue
        where = "; ".join(f"{k}: " + ", ".join(f"{d} x{n}" for d, n in sorted(v["c_missing"].items()))
                          for k, v in r["by_joint"].items() if v["c_missing"]) or "-"
        lines.append(f"| {r['robot']} | {r['decomposition']} | {r['poses']} | {r['c_missing']} / {r['py_missing']} | "
                     f"{where} | {r['indistinct_pairs']} | {r['median_us']:.2f} | {r['p99_over_median']:.1f} | "
                     f"{r['max_over_median']:.1f} |")
    json_path.parent.mkdir(parents=True, exist_ok=True)
    json_path.write_text(json.dumps(rows, indent=2, default=str))
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--robots", default=None, help="comma-separated robot names (default: all)")
    ap.add_argument("--json", type=Path, default=ROOT / "build" / "bench" / "near_singular.json")
    args = ap.parse_args(argv)
    print(report(None if args.robots is None else set(args.robots.split(",")), args.json))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
