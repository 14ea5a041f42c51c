"""The serial arms' mechanism base (the catalogue's DH chains and the finite-screw chains render through the same
templates, templates/{python,c}/serial.*.jinja): a spec built on first use behind the pipeline's interface, and the
CasADi functions every serial arm has. Each family subclasses it with its own derivation and kernels."""

from __future__ import annotations

from ..mechanism import SERIAL_C_API, MechanismDefaults
from .views import C_GENERAL6R_SHARED


class SerialArm(MechanismDefaults):
    """A serial arm's spec (joints, kinds, design, IK stages) behind the interface the pipeline expects."""

    C_API = SERIAL_C_API

    TEMPLATES = ("python/serial.py.jinja", "c/serial.h.jinja", "c/serial.c.jinja")
    VECTORISED_KERNELS = ("fk",)
    DERIVE_SECONDS = 5  # a scheduling hint for parallel regeneration (a family's from_spec sets its own)

    def __init__(self, name: str, build):
        self.NAME = name
        self._spec, self._build = None, build

    @property
    def spec(self):
        """The spec with its IK stages, built on first use (symbolic work that reading a catalogue should not
        pay: the spec's fields were validated when it was read)."""
        if self._spec is None:
            self._spec = self._build()
        return self._spec

    def c_shared_files(self) -> list[str]:
        """The general 6R's elimination and eigen solver, written beside a chain's C that has a general6r stage."""
        return list(C_GENERAL6R_SHARED) if any(st.kind == "general6r" for st in self.spec.stages) else []

    def casadi_functions(self, dv, kernels) -> dict:
        from .casadi_functions import serial_functions
        return serial_functions(self.NAME, kernels)
