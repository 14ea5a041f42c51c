"""Closed-form IK plans for DH chains, chosen by a spec's `ik` field and built from its DH rows (no robot's
numbers or names inside). Each plan states the structure it needs; every stage it returns is checked against
the chain's own FK by the derivation before anything is emitted, so a plan applied to a chain it does not fit
fails there with the stage named.

  roll                               1 revolute joint about the base z axis
  spherical_wrist                    3 revolute joints with intersecting axes (the wrist alone)
  cylindrical_arm_spherical_wrist    R P P (base rotation, lift, reach) + spherical wrist
  scara                              R R P (parallel vertical axes, then the slide) + a roll
  articulated_arm_spherical_wrist    R R R (shoulder, shoulder pitch, elbow, an offset allowed) + spherical wrist
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ...identities.dh import DHRow, chain
from ...identities.polynomial import affine_cs_coefficients
from .dh_serial import P_POSE, R_POSE, Stage, wrist_stage

c, s = sp.cos, sp.sin


class PlanError(ValueError):
    """The chain does not have the structure the plan needs."""


@dataclass(frozen=True)
class Chain:
    rows: tuple[DHRow, ...]
    joints: tuple[sp.Symbol, ...]
    kinds: tuple[str, ...]


def check_structure(plan: str, kinds) -> None:
    """The cheap part of a plan's precondition, checked when the spec is read (the stages are built later)."""
    need = KINDS[plan]
    if "".join(kinds) != need:
        raise PlanError(f"plan {plan!r} needs joints {' '.join(need)} (R revolute, P prismatic), the table has "
                        f"{' '.join(kinds) or 'none'}")


def _need(ch: Chain, kinds: str, plan: str) -> None:
    check_structure(plan, ch.kinds)


def _wrist_rule(rows, joints) -> str:
    """R = Rz(q4) Rx(alpha4) Rz(q5) Rx(alpha5) Rz(q6) [Rx(alpha6)] in degrees, from the wrist rows."""
    parts = []
    for row, q in zip(rows, joints, strict=True):
        parts.append(f"Rz({q})")
        if row.alpha != 0:
            parts.append(f"Rx({sp.sstr(row.alpha * 180 / sp.pi)})")
    return "R = " + " ".join(parts)


def _wrist_centre(d6):
    return P_POSE - d6 * R_POSE[:, 2]


def roll(ch: Chain) -> list[Stage]:
    _need(ch, "R", "roll")
    return [Stage("value", (0,), (sp.atan2(R_POSE[1, 0], R_POSE[0, 0]),), "roll from the rotation",
                  f"R = Rz({ch.joints[0]}): {ch.joints[0]} = atan2(r10, r00)")]


def spherical_wrist(ch: Chain) -> list[Stage]:
    _need(ch, "RRR", "spherical_wrist")
    return [wrist_stage(list(ch.rows), ch.joints, tuple(R_POSE), "spherical wrist from R",
                        _wrist_rule(ch.rows, ch.joints) + " (Euler ZYZ up to signs)", (0, 1, 2))]


def cylindrical_arm_spherical_wrist(ch: Chain) -> list[Stage]:
    _need(ch, "RPPRRR", "cylindrical_arm_spherical_wrist")
    q1 = ch.joints[0]
    d1, d6 = ch.rows[0].d, ch.rows[5].d
    pc = _wrist_centre(d6)
    r30 = chain(ch.rows)[2][:3, :3]
    return [
        Stage("trig_linear", (0,), (pc[0], pc[1], 0), "base angle from the wrist centre",
              f"wrist centre (x, y) = d3 (-sin {q1}, cos {q1}): x cos {q1} + y sin {q1} = 0 (two roots, "
              f"{q1} and {q1} + pi, with opposite signs of d3)"),
        Stage("value", (2,), (-s(q1) * pc[0] + c(q1) * pc[1],), "reach d3", f"d3 = -x sin {q1} + y cos {q1}"),
        Stage("value", (1,), (pc[2] - d1,), "lift d2", f"z = {d1} + d2"),
        wrist_stage(list(ch.rows[3:]), ch.joints[3:], tuple(r30.T * R_POSE), "wrist from R_6^3 = (R_3^0)^T R",
                    f"kinematic decoupling at the wrist centre p - {d6} R e_z", (3, 4, 5)),
    ]


def scara(ch: Chain) -> list[Stage]:
    _need(ch, "RRPR", "scara")
    q1, q2 = ch.joints[0], ch.joints[1]
    a1, a2, d4 = ch.rows[0].a, ch.rows[1].a, ch.rows[3].d
    px, py, pz = P_POSE
    return [
        Stage("trig_linear", (1,), (2 * a1 * a2, 0, a1**2 + a2**2 - px**2 - py**2), "elbow angle",
              f"law of cosines: x^2 + y^2 = {a1}^2 + {a2}^2 + 2 {a1} {a2} cos {q2} (two elbows)"),
        Stage("rotation2d", (0,), (px, py, a1 + a2 * c(q2), a2 * s(q2)), "shoulder angle",
              f"(x, y) = Rot({q1}) ({a1} + {a2} cos {q2}, {a2} sin {q2})"),
        Stage("value", (2,), (-pz - d4,), "prismatic d3", f"z = -d3 - {d4}"),
        Stage("value", (3,), (q1 + q2 - sp.atan2(R_POSE[1, 0], R_POSE[0, 0]),), "wrist roll",
              f"r00 = cos({q1} + {q2} - {ch.joints[3]}), r10 = sin({q1} + {q2} - {ch.joints[3]})"),
    ]


def articulated_arm_spherical_wrist(ch: Chain) -> list[Stage]:
    _need(ch, "RRRRRR", "articulated_arm_spherical_wrist")
    q1, q3 = ch.joints[0], ch.joints[2]
    d1, d6 = ch.rows[0].d, ch.rows[5].d
    ts = chain(ch.rows)
    pc = _wrist_centre(d6)
    o4 = ts[3][:3, 3]
    # shoulder offset: -sin(q1) x + cos(q1) y of the wrist centre is a constant of the arm
    offset = sp.simplify(-s(q1) * o4[0] + c(q1) * o4[1])
    u_fk = sp.simplify(c(q1) * o4[0] + s(q1) * o4[1])
    v_fk = sp.simplify(o4[2] - d1)
    r2 = sp.expand(sp.simplify(sp.expand_trig(u_fk**2 + v_fk**2)))
    cq, sq = sp.symbols("cq sq")
    k0, kc, ks = affine_cs_coefficients(r2.subs({c(q3): cq, s(q3): sq}), cq, sq)
    u = c(q1) * pc[0] + s(q1) * pc[1]
    v = pc[2] - d1
    q2 = ch.joints[1]
    u0, v0 = sp.simplify(u_fk.subs(q2, 0)), sp.simplify(v_fk.subs(q2, 0))
    return [
        Stage("trig_linear", (0,), (pc[1], -pc[0], -offset), "shoulder (left / right)",
              f"the wrist centre keeps the shoulder offset: -x sin {q1} + y cos {q1} = {sp.sstr(offset)}"),
        Stage("trig_linear", (2,), (kc, ks, k0 - (u**2 + v**2)), "elbow (up / down)",
              f"u^2 + v^2 of the wrist centre in the arm plane depends on {q3} only: "
              f"{sp.sstr(k0)} + ({sp.sstr(kc)}) cos {q3} + ({sp.sstr(ks)}) sin {q3}"),
        Stage("rotation2d", (1,), (u, v, u0, v0), "shoulder pitch",
              f"(u, v) = Rot({q2}) (u0, v0) with (u0, v0) the wrist centre at {q2} = 0"),
        wrist_stage(list(ch.rows[3:]), ch.joints[3:], tuple(ts[2][:3, :3].T * R_POSE),
                    "wrist from R_6^3 = (R_3^0)^T R (flip / no flip)", "kinematic decoupling at the wrist centre",
                    (3, 4, 5)),
    ]


KINDS = {"roll": "R", "spherical_wrist": "RRR", "cylindrical_arm_spherical_wrist": "RPPRRR", "scara": "RRPR",
         "articulated_arm_spherical_wrist": "RRRRRR"}
PLANS = {f.__name__: f for f in (roll, spherical_wrist, cylindrical_arm_spherical_wrist, scara,
                                 articulated_arm_spherical_wrist)}
