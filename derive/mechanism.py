"""What the core asks of a family and of its mechanisms, as types (the pipeline, the audit and `wristkin derive`
read these members and nothing else; no hasattr / getattr probing).

A family is a package under derive/families/ (found by discovery) that satisfies `Family`; `from_spec` returns a
`Mechanism`. Mechanisms inherit `MechanismDefaults` for the optional members, so every member is always there.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any, ClassVar, Protocol, runtime_checkable

from .model import Derivation


@runtime_checkable
class Mechanism(Protocol):
    """One mechanism of a family: derived, emitted through its templates, audited."""

    NAME: str  # generated/python/wristkin/NAME.py, generated/c/NAME.{h,c}, ...
    TEMPLATES: tuple[str, str, str]  # (Python module, C header, C source) templates
    VECTORISED_KERNELS: tuple[str, ...]  # kernels also printed for numpy
    DERIVE_SECONDS: float  # a scheduling hint for parallel regeneration
    DERIVE_GROUP: str | None  # mechanisms sharing a cached derivation run in one process (None: on its own)
    CASADI_DESIGN_NAMES: tuple[str, ...] | None  # the CasADi functions' design inputs (None: the solver's)
    CASADI_DOCS: dict[str, str] | None  # the CasADi index's function texts

    def derive(self) -> Derivation: ...

    def kernels(self, dv: Derivation) -> list: ...

    def extra_context(self, kernels: Sequence) -> dict: ...

    def casadi_functions(self, dv: Derivation, kernels: Sequence) -> dict: ...

    def audit_numbers(self, dv: Derivation, solver: Any, audit_dir: Path) -> dict: ...

    def c_shared_files(self) -> list[str]: ...


class MechanismDefaults:
    """The optional members of a `Mechanism`, with their defaults."""

    VECTORISED_KERNELS: ClassVar[tuple[str, ...]] = ()
    DERIVE_SECONDS: ClassVar[float] = 5
    DERIVE_GROUP: ClassVar[str | None] = None
    CASADI_DESIGN_NAMES: ClassVar[tuple[str, ...] | None] = None
    CASADI_DOCS: ClassVar[dict[str, str] | None] = None

    def audit_numbers(self, dv: Derivation, solver: Any, audit_dir: Path) -> dict:
        """Numeric findings for the audit beyond the derivation's own records (none by default)."""
        return {}

    def c_shared_files(self) -> list[str]:
        """Runtime sources (runtime/c/...) the mechanism's C calls as separate files written beside it (none by
        default: wristkin_common.h and wristkin_runtime.c are every mechanism's)."""
        return []


@runtime_checkable
class Family(Protocol):
    """A family package (derive/families/NAME/__init__.py)."""

    SPEC_FIELDS: tuple[str, ...]  # the spec fields it reads beside the common ones (documentation)
    SOURCE_SUFFIXES: tuple[str, ...]  # description files `wristkin derive` hands to it as they are (".urdf")

    def from_spec(self, spec: Any) -> Mechanism: ...  # reads and validates its fields, SpecError naming them
