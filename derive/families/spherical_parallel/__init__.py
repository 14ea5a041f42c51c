"""Spherical parallel wrists (seed 000: the underactuated 3-RRR wrist with 2 motors and a sensed passive
branch): the derivation (spherical trigonometry, IK coefficients, the degree-8 FK eliminant), its audit numbers
and CasADi functions. Templates: templates/{python,c}/underactuated_wrist.*.jinja (named by the spec).

Spec fields (docs/specs.md): `[design]` alpha1, alpha2, beta1, beta2 in degrees (the default design of the
generated module; every design is a run-time argument), `seed = "000"` to audit seed 000's printed numbers
(they hold at the paper's design only)."""

from __future__ import annotations

import dataclasses
import math

from ...mechanism import CApi, MechanismDefaults
from ...spec import COMMON_FIELDS, Spec, common
from . import underactuated_wrist as uw

SPEC_FIELDS = ("design", "seed")
SOURCE_SUFFIXES = ()
from_table = None  # `--stages derived` is the serial family's (Family.from_table)
SEEDS = ("000",)
# the hand-written numerics the generated files inline (runtime/python/uw_*.py, runtime/c/underactuated_wrist/),
# in the order their definitions need: compiled, linted and tested as they are (tests/test_uw_runtime.py)
PY_RUNTIME_FILES = tuple(f"python/uw_{part}.py" for part in ("design", "orientation", "ik", "fk_modes", "fk",
                                                             "fk_batch", "select", "rates"))
C_RUNTIME_FILES = tuple(f"c/underactuated_wrist/uw_{part}.c" for part in ("geometry", "design", "ik", "fk_modes", "fk",
                                                                          "select", "rates", "atlas"))


class SphericalParallelWrist(MechanismDefaults):
    TEMPLATES = ("python/underactuated_wrist.py.jinja", "c/underactuated_wrist.h.jinja",
                 "c/underactuated_wrist.c.jinja")
    VECTORISED_KERNELS = uw.VECTORISED_KERNELS
    CASADI_DOCS = uw.CASADI_DOCS
    C_API = CApi(atlas_home=True)
    DERIVE_SECONDS = uw.DERIVE_SECONDS
    DESIGN_CONSTANTS = uw.DESIGN_CONSTANTS

    def __init__(self, name: str, title: str, source: str, design_deg: tuple[float, ...], seed: str | None):
        self.NAME, self.title, self.source = name, title, source
        self.DESIGN_DEFAULT_DEG, self.seed = design_deg, seed

    def derive(self):
        return dataclasses.replace(uw.derive(), mechanism=self.NAME, title=self.title, seed=self.source)

    def kernels(self, dv):
        return uw.kernels(dv)

    def extra_context(self, ks) -> dict:
        return {"name": self.NAME, "upper": self.NAME.upper(), **uw.extra_context(ks, self.DESIGN_DEFAULT_DEG),
                "design_default": [repr(math.radians(v)) for v in self.DESIGN_DEFAULT_DEG],
                "n_design_constants": len(self.DESIGN_CONSTANTS), "py_runtime_files": PY_RUNTIME_FILES,
                "c_runtime_files": C_RUNTIME_FILES}

    def casadi_functions(self, dv, ks) -> dict:
        return uw.casadi_functions(dv, ks)

    def audit_numbers(self, dv, solver, audit_dir) -> dict:
        return uw.audit_numbers(dv, solver, audit_dir, self.DESIGN_DEFAULT_DEG) if self.seed == "000" else {}


def from_spec(spec: Spec) -> SphericalParallelWrist:
    spec.only((*COMMON_FIELDS, *SPEC_FIELDS))
    head = common(spec)
    design = spec.table("design")
    design.only(uw.DESIGN_NAMES)
    # the generated make_design's ranges (with its margin of a few 1e-x rad checked again at run time)
    ranges = {"alpha1": (0.0, 180.0), "alpha2": (0.0, 180.0), "beta1": (0.0, 90.0), "beta2": (0.0, 90.0)}
    degrees = tuple(design.number(n, lo=ranges[n][0], hi=ranges[n][1], unit="degrees") for n in uw.DESIGN_NAMES)
    if degrees[2] + degrees[3] >= 180.0:  # the home loop's theta coefficient is sin(beta1 + beta2)
        raise design.error("beta2", "beta1 + beta2 below 180 degrees (at 180 the home loop fixes no theta0)",
                           degrees[2] + degrees[3])
    seed = spec.choice("seed", SEEDS, None) if spec.has("seed") else None
    return SphericalParallelWrist(head["name"], head["title"], head["source"], degrees, seed)
