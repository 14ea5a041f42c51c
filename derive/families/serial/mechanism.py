"""The serial family's mechanism: a SerialSpec (read from a spec file by dh_spec) behind the pipeline's
interface, on the serial arms' base (derive/serial_core/mechanism.py) the finite-screw family shares."""

from __future__ import annotations

import math

from ...serial_core import stages, views
from ...serial_core.mechanism import SerialArm
from . import dh_serial


class SerialMechanism(SerialArm):
    """A DH chain's SerialSpec behind the interface the pipeline expects (derive/families/__init__.py)."""

    def derive(self):
        return dh_serial.derive_spec(self.spec)

    def kernels(self, dv):
        return stages.serial_kernels(self.spec, dv)

    def extra_context(self, ks) -> dict:
        sp_ = self.spec
        n = len(sp_.joints)
        n_combos = 2 ** sum(st.width for st in sp_.stages)
        return views.serial_views({"name": self.NAME, "title": sp_.title, "joint_names": [str(q) for q in sp_.joints],
                "joint_kinds": list(sp_.kinds), "design_names": [str(d) for d in sp_.design],
                "design_values": [repr(float(v)) for v in sp_.design_default], "n_joints": n,
                "max_ik": n_combos, "stages": stages.stage_view(sp_, {k.name for k in ks}),
                "fold_masks": stages.fold_masks(sp_), "upper": self.NAME.upper(),
                "mirror_keeps_fk": stages.mirror_keeps_fk(sp_, next(k for k in ks if k.name == "fk_cs")),
                "design_default": [repr(float(v)) for v in sp_.design_default],
                # DH design values are link lengths and offsets: each is 0 or at least DESIGN_SCALE_MIN
                "lengths_floor": True, **self.own_context()})

    def own_context(self) -> dict:
        """A user robot's limits, named branches and command line (from_table's robots): none in the catalogue."""
        return {}

    def round_trips(self) -> int:
        """How many seeded poses the audit solves on numpy: 300, and 100 for an elimination (~2 ms a pose)."""
        return 100 if any(st.kind == "general6r" for st in self.spec.stages) else 300

    def audit_numbers(self, dv, solver, audit_dir) -> dict:
        """Seeded round trips through the generated solver (counts only: byte-stable across machines)."""
        import numpy as np

        rng = np.random.default_rng(2024)
        counts: dict[int, int] = {}
        worst_ok, contains = True, 0
        spec = self.spec
        n = self.round_trips()
        for _ in range(n):
            q = [rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-0.5, 0.5) for k in solver.JOINT_KINDS]
            # a held joint: at its joint value (the design's last entry); the arm angle: the joints' own
            design = {solver.DESIGN_NAMES[-1]: q[spec.held[0]]} if spec.held else (
                {"arm_angle": solver.arm_angle(q)} if spec.arm_angle is not None else None)
            sol = solver.ik(solver.fk_matrix(q), design)
            counts[sol.count] = counts.get(sol.count, 0) + 1
            worst_ok &= all(float(np.max(np.abs(solver.fk_matrix(v) - solver.fk_matrix(q)))) < 1e-9 for v in sol)
            diffs = [np.where(np.array(solver.JOINT_KINDS) == "R", np.remainder(v - q + math.pi, 2 * math.pi) - math.pi,
                              v - q) for v in sol]
            contains += any(float(np.max(np.abs(dq))) < 1e-6 for dq in diffs)
        held = spec.held[1] if spec.held else spec.arm_angle
        return {
            "summary": [("design (defaults)", ", ".join(f"{d} = {v:g} {'rad (run time)' if d == held else 'm'}"
                                                        for d, v in zip(spec.design, spec.design_default,
                                                                        strict=True))),
                        ("joints", ", ".join(f"{q} ({'revolute' if k == 'R' else 'prismatic'})"
                                             for q, k in zip(spec.joints, spec.kinds, strict=True))),
                        ("IK solution sets per pose (max)", str(solver.MAX_IK))],
            "sections": [{"title": "Round trips through the generated solver",
                          "body": f"{n} seeded random joint vectors (revolute uniform in (-pi, pi], prismatic in "
                                  f"(-0.5, 0.5) m{', the held joint at its value' if spec.held else ''}"
                                  f"{', at their own arm angle' if spec.arm_angle is not None else ''}): IK solution "
                                  f"counts {dict(sorted(counts.items()))}; the generating "
                                  f"joints were among the solutions {contains} of {n} times; every returned solution "
                                  f"reproduced the pose to 1e-9: {'yes' if worst_ok else 'NO'}. The independent "
                                  "reference comparison (multistart Levenberg-Marquardt over joint space) is in "
                                  "tests/test_dh.py."}],
        }
