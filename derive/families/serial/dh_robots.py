"""The DH robots of seed 001 (plus the PUMA-560 reference arm), as SerialSpecs of the generic module."""

from __future__ import annotations

import math

import sympy as sp

from ...identities.dh import DHRow, chain
from ...model import Finding
from . import dh_serial
from .dh_serial import P_POSE, R_POSE, SerialSpec, Stage, wrist_stage

SEED = "seed 001: MCE4101 Robotic Engineering, ch. 5 'Wrists and End Effectors' (lecture slides)"
PI2 = sp.pi / 2
th = {i: sp.Symbol(f"theta{i}", real=True) for i in range(1, 7)}
c, s = sp.cos, sp.sin


def _wrist_rows(d6):
    """Seed 001 rows 4-6: (0, -90, 0, theta4), (0, 90, 0, theta5), (0, 0, d6, theta6)."""
    return [DHRow(0, -PI2, 0, th[4], th[4]), DHRow(0, PI2, 0, th[5], th[5]), DHRow(0, 0, d6, th[6], th[6])]


def _wrist_centre(d6):
    return P_POSE - d6 * R_POSE[:, 2]


# ------------------------------------------------------------------------------------- 1-DOF wrist
def wrist_1dof() -> SerialSpec:
    dw = sp.Symbol("dw", positive=True)
    rows = [DHRow(0, 0, dw, th[1], th[1])]
    stages = [Stage("value", (0,), (sp.atan2(R_POSE[1, 0], R_POSE[0, 0]),), "roll from the rotation",
                    "R = Rz(theta1): theta1 = atan2(r10, r00)")]
    return SerialSpec("wrist_1dof", "1-DOF wrist (a roll about the last axis)", SEED, rows, (th[1],), ("R",), (dw,),
                      (0.1,), stages)


# ------------------------------------------------------------------------------------- spherical wrist
def spherical_wrist() -> SerialSpec:
    d6 = sp.Symbol("d6", positive=True)
    rows = _wrist_rows(d6)
    joints = (th[4], th[5], th[6])
    stages = [wrist_stage(rows, joints, tuple(R_POSE), "spherical wrist from R",
                          "R = Rz(theta4) Rx(-90) Rz(theta5) Rx(90) Rz(theta6) (Euler ZYZ up to signs)", (0, 1, 2))]
    c4, s4, c5, s5, c6, s6 = c(th[4]), s(th[4]), c(th[5]), s(th[5]), c(th[6]), s(th[6])
    ts = chain(rows)
    a = [r.transform() for r in rows]
    printed = {
        "A4 (seed 001)": (a[0], sp.Matrix([[c4, 0, -s4, 0], [s4, 0, c4, 0], [0, -1, 0, 0], [0, 0, 0, 1]])),
        "A5 (seed 001)": (a[1], sp.Matrix([[c5, 0, s5, 0], [s5, 0, -c5, 0], [0, 1, 0, 0], [0, 0, 0, 1]])),
        "A6 (seed 001)": (a[2], sp.Matrix([[c6, -s6, 0, 0], [s6, c6, 0, 0], [0, 0, 1, d6], [0, 0, 0, 1]])),
        "T_6^3 = A4 A5 A6 (seed 001)": (ts[-1], sp.Matrix([
            [c4 * c5 * c6 - s4 * s6, -c4 * c5 * s6 - s4 * c6, c4 * s5, c4 * s5 * d6],
            [s4 * c5 * c6 + c4 * s6, -s4 * c5 * s6 + c4 * c6, s4 * s5, s4 * s5 * d6],
            [-s5 * c6, s5 * s6, c5, c5 * d6], [0, 0, 0, 1]])),
    }
    return SerialSpec("spherical_wrist", "3-DOF spherical wrist (seed 001 rows 4-6)", SEED, rows, joints,
                      ("R", "R", "R"), (d6,), (0.1,), stages, printed)


# ------------------------------------------------------------------------------------- RPP + wrist
def rpp_wrist() -> SerialSpec:
    d1, d6 = sp.symbols("d1 d6", positive=True)
    d2, d3 = sp.symbols("d2 d3", real=True)
    rows = [DHRow(0, 0, d1, th[1], th[1]), DHRow(0, -PI2, d2, 0, d2, "P"), DHRow(0, 0, d3, 0, d3, "P"),
            *_wrist_rows(d6)]
    joints = (th[1], d2, d3, th[4], th[5], th[6])
    ts = chain(rows)
    pc = _wrist_centre(d6)
    r30 = ts[2][:3, :3]
    stages = [
        Stage("trig_linear", (0,), (pc[0], pc[1], 0), "base angle from the wrist centre",
              "wrist centre (x, y) = d3 (-sin theta1, cos theta1): x cos theta1 + y sin theta1 = 0 (two roots, "
              "theta1 and theta1 + pi, with opposite signs of d3)"),
        Stage("value", (2,), (-s(th[1]) * pc[0] + c(th[1]) * pc[1],), "reach d3",
              "d3 = -x sin theta1 + y cos theta1"),
        Stage("value", (1,), (pc[2] - d1,), "lift d2", "z = d1 + d2"),
        wrist_stage(rows[3:], (th[4], th[5], th[6]), tuple(r30.T * R_POSE), "wrist from R_6^3 = (R_3^0)^T R",
                    "kinematic decoupling at the wrist centre p - d6 R e_z", (3, 4, 5)),
    ]
    c1, s1 = c(th[1]), s(th[1])
    printed = {"T_3^0 = A1 A2 A3 (seed 001)": (ts[2], sp.Matrix([[c1, 0, -s1, -s1 * d3], [s1, 0, c1, c1 * d3],
                                                                  [0, -1, 0, d1 + d2], [0, 0, 0, 1]]))}
    t30_zero = ts[2].subs(d1, 0)
    findings = [
        Finding("RPP table, link 1 d", "d1 = '0 (offset)'", "d1 is a constant offset, not 0",
                "wrong in seed", f"with d1 = 0 the chain gives T_3^0[2, 3] = {sp.sstr(t30_zero[2, 3])}, but the "
                "seed's own T_3^0 prints d1 + d2"),
        Finding("T_6^0", "heading only ('Final forward kinematic equations')", "T_6^0 = T_3^0 T_6^3 (step T)",
                "clarified", "derived and checked here; IK by kinematic decoupling (ik stages)"),
    ]
    return SerialSpec("rpp_wrist", "RPP arm + 3-DOF spherical wrist (seed 001)", SEED, rows, joints,
                      ("R", "P", "P", "R", "R", "R"), (d1, d6), (0.5, 0.1), stages, printed, findings)


# ------------------------------------------------------------------------------------- SCARA + 1-DOF wrist
def scara_wrist() -> SerialSpec:
    a1, a2, d4 = sp.symbols("a1 a2 d4", positive=True)
    d3 = sp.Symbol("d3", real=True)
    rows = [DHRow(a1, 0, 0, th[1], th[1]), DHRow(a2, sp.pi, 0, th[2], th[2]), DHRow(0, 0, d3, 0, d3, "P"),
            DHRow(0, 0, d4, th[4], th[4])]
    joints = (th[1], th[2], d3, th[4])
    px, py, pz = P_POSE
    stages = [
        Stage("trig_linear", (1,), (2 * a1 * a2, 0, a1**2 + a2**2 - px**2 - py**2), "elbow angle",
              "law of cosines: x^2 + y^2 = a1^2 + a2^2 + 2 a1 a2 cos theta2 (two elbows)"),
        Stage("rotation2d", (0,), (px, py, a1 + a2 * c(th[2]), a2 * s(th[2])), "shoulder angle",
              "(x, y) = Rot(theta1) (a1 + a2 cos theta2, a2 sin theta2)"),
        Stage("value", (2,), (-pz - d4,), "prismatic d3", "z = -d3 - d4"),
        Stage("value", (3,), (th[1] + th[2] - sp.atan2(R_POSE[1, 0], R_POSE[0, 0]),), "wrist roll",
              "r00 = cos(theta1 + theta2 - theta4), r10 = sin(theta1 + theta2 - theta4)"),
    ]
    ts = chain(rows)
    a = [r.transform() for r in rows]
    c1, s1, c2, s2, c4, s4 = c(th[1]), s(th[1]), c(th[2]), s(th[2]), c(th[4]), s(th[4])
    c12, s12 = c(th[1] + th[2]), s(th[1] + th[2])
    printed = {
        "A1 (seed 001)": (a[0], sp.Matrix([[c1, -s1, 0, a1 * c1], [s1, c1, 0, a1 * s1], [0, 0, 1, 0], [0, 0, 0, 1]])),
        "A2 (seed 001)": (a[1], sp.Matrix([[c2, s2, 0, a2 * c2], [s2, -c2, 0, a2 * s2], [0, 0, -1, 0], [0, 0, 0, 1]])),
        "A3 (seed 001)": (a[2], sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, d3], [0, 0, 0, 1]])),
        "A4 (seed 001)": (a[3], sp.Matrix([[c4, -s4, 0, 0], [s4, c4, 0, 0], [0, 0, 1, d4], [0, 0, 0, 1]])),
        "T_4^0 (seed 001)": (ts[-1], sp.Matrix([
            [c12 * c4 + s12 * s4, -c12 * s4 + s12 * c4, 0, a1 * c1 + a2 * c12],
            [s12 * c4 - c12 * s4, -s12 * s4 - c12 * c4, 0, a1 * s1 + a2 * s12],
            [0, 0, -1, -d3 - d4], [0, 0, 0, 1]])),
    }
    return SerialSpec("scara_wrist", "SCARA (RRP) + 1-DOF wrist (seed 001)", SEED, rows, joints,
                      ("R", "R", "P", "R"), (a1, a2, d4), (0.4, 0.3, 0.1), stages, printed)


# ------------------------------------------------------------------------------------- PUMA-560
def puma560() -> SerialSpec:
    d1, a2, d3, a3, d4, d6 = sp.symbols("d1 a2 d3 a3 d4 d6", real=True)
    rows = [DHRow(0, PI2, d1, th[1], th[1]), DHRow(a2, 0, 0, th[2], th[2]), DHRow(a3, -PI2, d3, th[3], th[3]),
            DHRow(0, PI2, d4, th[4], th[4]), DHRow(0, -PI2, 0, th[5], th[5]), DHRow(0, 0, d6, th[6], th[6])]
    joints = tuple(th[i] for i in range(1, 7))
    ts = chain(rows)
    pc = _wrist_centre(d6)
    o4 = ts[3][:3, 3]
    # shoulder offset: -sin(theta1) x + cos(theta1) y of the wrist centre is a constant of the arm
    offset = sp.simplify(-s(th[1]) * o4[0] + c(th[1]) * o4[1])
    u_fk = sp.simplify(c(th[1]) * o4[0] + s(th[1]) * o4[1])
    v_fk = sp.simplify(o4[2] - d1)
    r2 = sp.expand(sp.simplify(sp.expand_trig(u_fk**2 + v_fk**2)))
    cq, sq = sp.symbols("cq sq")
    from ...identities.polynomial import affine_cs_coefficients

    k0, kc, ks = affine_cs_coefficients(r2.subs({c(th[3]): cq, s(th[3]): sq}), cq, sq)
    u = c(th[1]) * pc[0] + s(th[1]) * pc[1]
    v = pc[2] - d1
    u0, v0 = sp.simplify(u_fk.subs(th[2], 0)), sp.simplify(v_fk.subs(th[2], 0))
    stages = [
        Stage("trig_linear", (0,), (pc[1], -pc[0], -offset), "shoulder (left / right)",
              f"the wrist centre keeps the shoulder offset: -x sin theta1 + y cos theta1 = {sp.sstr(offset)}"),
        Stage("trig_linear", (2,), (kc, ks, k0 - (u**2 + v**2)), "elbow (up / down)",
              "u^2 + v^2 of the wrist centre in the arm plane depends on theta3 only: "
              f"{sp.sstr(k0)} + ({sp.sstr(kc)}) cos theta3 + ({sp.sstr(ks)}) sin theta3"),
        Stage("rotation2d", (1,), (u, v, u0, v0), "shoulder pitch",
              "(u, v) = Rot(theta2) (u0, v0) with (u0, v0) the wrist centre at theta2 = 0"),
        wrist_stage(rows[3:], (th[4], th[5], th[6]), tuple(ts[2][:3, :3].T * R_POSE),
                    "wrist from R_6^3 = (R_3^0)^T R (flip / no flip)", "kinematic decoupling at the wrist centre",
                    (3, 4, 5)),
    ]
    return SerialSpec("puma560", "Articulated RRR arm + spherical wrist, PUMA-560 DH (Corke's standard DH)",
                      "PUMA-560 standard DH parameters (Corke, Robotics Toolbox mdl_puma560): the field's IK "
                      "reference arm", rows, joints, ("R",) * 6, (d1, a2, d3, a3, d4, d6),
                      (0.6718, 0.4318, 0.15005, 0.0203, 0.4318, 0.0), stages)


SPECS = {f.__name__: f for f in (wrist_1dof, spherical_wrist, rpp_wrist, scara_wrist, puma560)}


class SerialMechanism:
    """Registry adapter: gives a SerialSpec the module interface the pipeline expects."""

    TEMPLATES = ("python/serial.py.jinja", "c/serial.h.jinja", "c/serial.c.jinja")
    VECTORISED_KERNELS = ("fk",)
    SPECS = SPECS  # name -> spec factory; subclasses for other chain families replace it
    DERIVE_SECONDS = 5  # a scheduling hint for parallel regeneration

    def __init__(self, name: str):
        self.NAME = name
        self._spec = None

    @property
    def spec(self):
        if self._spec is None:
            self._spec = self.SPECS[self.NAME]()
        return self._spec

    def derive(self):
        return dh_serial.derive_spec(self.spec)

    def kernels(self, dv):
        return dh_serial.kernels_spec(self.spec, dv)

    def casadi_functions(self, dv, kernels) -> dict:
        from .serial_casadi import serial_functions
        return serial_functions(self.NAME, kernels)

    def extra_context(self, ks) -> dict:
        sp_ = self.spec
        n = len(sp_.joints)
        n_combos = 2 ** sum(st.branches - 1 for st in sp_.stages)
        return {"name": self.NAME, "title": sp_.title, "joint_names": [str(q) for q in sp_.joints],
                "joint_kinds": list(sp_.kinds), "design_names": [str(d) for d in sp_.design],
                "design_values": [repr(float(v)) for v in sp_.design_default], "n_joints": n,
                "max_ik": n_combos, "stages": dh_serial.stage_view(sp_), "upper": self.NAME.upper(),
                "design_default": [repr(float(v)) for v in sp_.design_default],
                # DH design values are link lengths and offsets: each is 0 or at least DESIGN_SCALE_MIN
                "lengths_floor": True}


    def audit_numbers(self, dv, solver, audit_dir) -> dict:
        """Seeded round trips through the generated solver (counts only: byte-stable across machines)."""
        import numpy as np

        rng = np.random.default_rng(2024)
        counts: dict[int, int] = {}
        worst_ok, contains = True, 0
        n = 300
        for _ in range(n):
            q = [rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in solver.JOINT_KINDS]
            sol = solver.ik(solver.fk_matrix(q))
            counts[sol.count] = counts.get(sol.count, 0) + 1
            worst_ok &= all(float(np.max(np.abs(solver.fk_matrix(v) - solver.fk_matrix(q)))) < 1e-9 for v in sol)
            diffs = [np.where(np.array(solver.JOINT_KINDS) == "R", np.remainder(v - q + math.pi, 2 * math.pi) - math.pi,
                              v - q) for v in sol]
            contains += any(float(np.max(np.abs(dq))) < 1e-6 for dq in diffs)
        spec = self.spec
        return {
            "summary": [("design (defaults)", ", ".join(f"{d} = {v:g} m" for d, v in zip(spec.design,
                                                                                         spec.design_default,
                                                                                         strict=True))),
                        ("joints", ", ".join(f"{q} ({'revolute' if k == 'R' else 'prismatic'})"
                                             for q, k in zip(spec.joints, spec.kinds, strict=True))),
                        ("IK solution sets per pose (max)", str(solver.MAX_IK))],
            "sections": [{"title": "Round trips through the generated solver",
                          "body": f"{n} seeded random joint vectors (revolute uniform in (-pi, pi], prismatic in "
                                  f"(-0.5, 0.5) m): IK solution counts {dict(sorted(counts.items()))}; the generating "
                                  f"joints were among the solutions {contains} of {n} times; every returned solution "
                                  f"reproduced the pose to 1e-9: {'yes' if worst_ok else 'NO'}. The independent "
                                  "reference comparison (multistart Levenberg-Marquardt over joint space) is in "
                                  "tests/test_dh.py."}],
        }


MECHANISMS = {name: SerialMechanism(name) for name in SPECS}

