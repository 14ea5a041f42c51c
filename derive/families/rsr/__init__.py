"""3-RSR (2R1T) symmetric parallel wrists and the SCARA + 3-RSR hybrid (seed 002): mirror-plane geometry, the
wrist's derivation, the hybrid built on it, audit numbers and CasADi functions. Templates:
templates/{python,c}/{rsr_wrist,scara_rsr}.*.jinja and the rsr_* partials (named by the spec).

Spec fields (docs/specs.md): `kind` ("wrist" or "scara_hybrid"), `[wrist]` L (m), phi_min, phi_max (degrees),
lbw_min, lbw_max (m), for the hybrid `[arm]` L1, L2, d, d_f (m), and `seed = "002"` to audit seed 002's
claims and examples."""

from __future__ import annotations

import dataclasses
import math

from ...mechanism import MechanismDefaults
from ...spec import COMMON_FIELDS, Spec, common
from . import rsr_wrist, scara_rsr

SPEC_FIELDS = ("kind", "wrist", "arm", "seed")
SOURCE_SUFFIXES = ()
from_table = None  # `--stages derived` is the serial family's (Family.from_table)
SEEDS = ("002",)
KINDS = {"wrist": rsr_wrist, "scara_hybrid": scara_rsr}


class RsrMechanism(MechanismDefaults):
    """The 3-RSR wrist or the SCARA hybrid under a spec's name, title, source and default design."""

    def __init__(self, module, name: str, title: str, source: str, design: tuple[float, ...], seed: str | None):
        self.module, self.NAME, self.title, self.source = module, name, title, source
        self.design_default, self.seed = design, seed
        self.TEMPLATES, self.VECTORISED_KERNELS = module.TEMPLATES, module.VECTORISED_KERNELS
        self.DERIVE_SECONDS, self.DERIVE_GROUP = module.DERIVE_SECONDS, module.DERIVE_GROUP
        self.CASADI_DESIGN_NAMES = module.CASADI_DESIGN_NAMES
        self.C_API = module.C_API

    def derive(self):
        return dataclasses.replace(self.module.derive(), mechanism=self.NAME, title=self.title, seed=self.source)

    def kernels(self, dv):
        return self.module.kernels(dv)

    def extra_context(self, ks) -> dict:
        return self.module.extra_context(ks, self.NAME, self.design_default)

    def casadi_functions(self, dv, ks) -> dict:
        return self.module.casadi_functions(dv, ks)

    def audit_numbers(self, dv, solver, audit_dir) -> dict:
        return self.module.audit_numbers(dv, solver, audit_dir) if self.seed == "002" else {}


def _wrist_design(wrist: Spec) -> tuple[float, ...]:
    wrist.only(rsr_wrist.DESIGN_NAMES)
    length = wrist.number("L", lo=1e-5, unit="m")
    phi = tuple(math.radians(wrist.number(n, lo=-180.0, hi=180.0, unit="degrees")) for n in ("phi_min", "phi_max"))
    lbw = tuple(wrist.number(n, lo=0.0, unit="m") for n in ("lbw_min", "lbw_max"))
    if phi[0] >= phi[1]:
        raise wrist.error("phi_max", "a limit above phi_min", math.degrees(phi[1]))
    if lbw[0] >= lbw[1]:
        raise wrist.error("lbw_max", "a limit above lbw_min", lbw[1])
    if lbw[1] > 2 * length:
        raise wrist.error("lbw_max", f"at most 2 L = {2 * length:g} m (the legs cannot reach farther)", lbw[1])
    return (length, *phi, *lbw)


def from_spec(spec: Spec) -> RsrMechanism:
    spec.only((*COMMON_FIELDS, *SPEC_FIELDS))
    head = common(spec)
    kind = spec.choice("kind", tuple(KINDS))
    design = _wrist_design(spec.table("wrist"))
    if kind == "scara_hybrid":
        arm = spec.table("arm")
        arm.only(scara_rsr.DESIGN_NAMES[:4])
        design = (*(arm.number(n, lo=1e-5, unit="m") if n in ("L1", "L2") else arm.number(n, unit="m")
                    for n in scara_rsr.DESIGN_NAMES[:4]), *design)
    elif spec.has("arm"):
        raise spec.error("arm", "no [arm] table for kind = 'wrist'")
    seed = spec.choice("seed", SEEDS, None) if spec.has("seed") else None
    return RsrMechanism(KINDS[kind], head["name"], head["title"], head["source"], design, seed)
