"""What the core asks of a family and of its mechanisms, as types (the pipeline, the audit and `wristkin derive`
read these members and nothing else; no hasattr / getattr probing).

A family is a package under derive/families/ (found by discovery) that satisfies `Family`; `from_spec` returns a
`Mechanism`. Mechanisms inherit `MechanismDefaults` for the optional members, so every member is always there.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar, Protocol, runtime_checkable

from .model import Derivation


@dataclass(frozen=True)
class CApi:
    """The verbs a mechanism's C header declares beyond the ones every mechanism has (design, ik, fk, ik_batch,
    fk_batch), as its family's templates emit them: the CPython binding (templates/c/native.c.jinja) is rendered
    from these records, never from reading a generated header (tests/test_native_api.py holds each record equal to
    its header)."""

    pose12: bool = False  # ik takes a 12-number pose (else the mechanism's own input)
    ik_near: bool = False  # ik_near(pose, design, previous)
    jacobian: bool = False
    fk_matrix: bool = False
    frames: bool = False  # design_set_frames (base and tool)
    atlas: bool = False  # atlas_batch and max_swing (the 3-RSR wrist)
    atlas_conditioning: bool = False
    atlas_home: bool = False

    def methods(self) -> list[str]:
        """The extension's functions for it, in its method table's order."""
        optional = [(self.jacobian, ["jacobian"]), (self.fk_matrix, ["fk_matrix"]),
                    (self.atlas, ["atlas_batch", "max_swing"]), (self.atlas_conditioning, ["atlas_conditioning"]),
                    (self.atlas_home, ["atlas_home_batch"])]
        return ["design", "ik", "fk", "ik_batch", "fk_batch"] + [f for on, fs in optional if on for f in fs]


SERIAL_C_API = CApi(pose12=True, ik_near=True, jacobian=True, fk_matrix=True, atlas_conditioning=True, frames=True)


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
    C_API: CApi  # the optional C verbs its templates emit

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
    C_API: ClassVar[CApi] = CApi()

    def audit_numbers(self, dv: Derivation, solver: Any, audit_dir: Path) -> dict:
        """Numeric findings for the audit beyond the derivation's own records (none by default)."""
        return {}

    def c_shared_files(self) -> list[str]:
        """Runtime sources (runtime/c/...) the mechanism's C calls as separate files written beside it (none by
        default: wristkin_common.h and wristkin_runtime.c are every mechanism's)."""
        return []


@runtime_checkable
class RobotDescription(Protocol):
    """A user's robot as a family reads it (a URDF, a DH table or a POE description): no solver of its own.
    `wristkin derive` hands its robot_table() to the family with from_table, which derives the robot's stages."""

    NAME: str

    def robot_table(self) -> Any: ...  # kinematics/dh_table.RobotTable, or NotDerivable naming why not


@runtime_checkable
class Family(Protocol):
    """A family package (derive/families/NAME/__init__.py)."""

    SPEC_FIELDS: tuple[str, ...]  # the spec fields it reads beside the common ones (documentation)
    SOURCE_SUFFIXES: tuple[str, ...]  # description files `wristkin derive` hands to it as they are (".urdf")

    # reads and validates its fields (SpecError naming them): a catalogue mechanism, or a user's robot description
    def from_spec(self, spec: Any) -> Mechanism | RobotDescription: ...

    # a robot's DH table (kinematics/dh_table.RobotTable) -> a Mechanism with derived stages (NotDerivable naming
    # why where they do not cover it), or None: the family that derives every robot description's IK (one does)
    from_table: Any
