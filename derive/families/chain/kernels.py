"""The robot's own FK and Jacobian as SymPy expressions with its constants folded: the product of exponentials
exp(S_1 q_1) ... exp(S_n q_n) M of the description's true chain (derive/kinematics/poe_symbolic.py), then lowered
and CSE'd into straight-line code (derive/lower.py). The emitted solver verifies every IK candidate and answers
fk / jacobian with these instead of walking the chain's table (runtime/c/chain/ck_api.c, chain_api.py)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...kinematics.poe_symbolic import joint_symbols, symbolic_chain
from ...lower import Kernel, lower
from ...serial_core.stages import POSE_SYMBOLS


def chain_kernels(chain) -> list[Kernel]:
    """fk (the end frame [R | p], row-major 3 x 4) and jacobian (6 x n row-major, linear velocity of the end frame's
    origin first) of the description's true chain, over (q, cos q, sin q) with the joints in the description's order
    (a free joint is one of them): every caller (fk_matrix, the IK's check of a candidate, the singular flag) takes
    the same cos and sin and evaluates the same fk, so its answers agree bit for bit."""
    groups = tuple(zip(("q", "c", "s"), joint_symbols(chain.n), strict=True))
    rot, end, cols = symbolic_chain(chain)
    pose = tuple((str(s), rot[i // 4, i % 4] if i % 4 < 3 else end[i // 4]) for i, s in enumerate(POSE_SYMBOLS))
    jac = tuple((f"j{r}{c}", cols[c][r]) for r in range(6) for c in range(chain.n))
    return [Kernel("fk", "The chain's end frame [R | p] (row-major 3 x 4; no base / tool) from the joints and the "
                   "cosines and sines of the revolute ones, the robot's constants folded.", groups, pose,
                   irrational=False),
            Kernel("jacobian", "The chain's geometric Jacobian (6 x n row-major, linear velocity of the end frame's "
                   "origin first) from the same inputs.", groups, jac, irrational=False)]


def _as_python(kernel):
    """The kernel as the emitted Python prints it (derive/lower.py, the CSE'd straight-line code), compiled: what
    the check evaluates is what the module runs, and the deep products are never printed un-CSE'd."""
    low = lower(kernel, "python")
    body = [f"    {sym} = {group}[{idx}]" for sym, group, idx in low.unpack]
    body += [f"    {name} = {code}" for name, code in low.temps]
    body.append("    return (" + ", ".join(code for _, code in low.outputs) + ",)")
    namespace: dict = {"math": math}
    exec(f"def f({', '.join(low.groups)}):\n" + "\n".join(body), namespace)  # noqa: S102 - our own printed code
    return namespace["f"]


def kernel_check(chain, kernels):
    """fn(rng) -> the largest difference, at a random configuration, between the kernels as printed (the emitted
    Python's straight-line code) and the chain's own product of 4 x 4 transforms and Jacobian (kinematics/poe.py;
    base and tool left out)."""
    bare = replace(chain, base=np.eye(4), tool=np.eye(4))
    fns = [_as_python(k) for k in kernels]

    def err(rng):
        q = np.array([rng.uniform(-np.pi, np.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in chain.kinds])
        args = (list(q), [math.cos(v) for v in q], [math.sin(v) for v in q])
        out = np.array([v for f in fns for v in f(*args)], dtype=float)
        ref = np.concatenate([bare.fk(q)[:3].ravel(), bare.jacobian(q).ravel()])
        return float(np.max(np.abs(out - ref)))
    return err
