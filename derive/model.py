"""Derivations as data: named steps, each with its rule, inputs and a check that ran.

The audit report is rendered from these records only, so everything a reader
should learn about how a formula was obtained must be stored here.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from .report_numbers import ROUNDING_FLOOR, error_bucket  # machine-independent bytes in the audit report


class DescriptionError(ValueError):
    """A description file (a URDF, a xacro file, ...) a family cannot read; the message names the file, the element
    and its line."""


class NoDecomposition(ValueError):
    """No closed form fits the mechanism (a family's planner refuses it); the message names what prevents it."""


class NotDerivable(NoDecomposition):
    """The derived stages do not cover the robot (the message says why); `why` is the reason alone."""

    def __init__(self, message: str, why: str | None = None):
        super().__init__(message)
        self.why = why or message

    @classmethod
    def because(cls, name: str, why: str, short: str | None = None) -> NotDerivable:
        """`short`: the reason in a few words where `why` is long (a planner's full refusal)."""
        return cls(f"{name}: the derived stages do not cover this robot ({why})", short or why)


class CheckFailed(AssertionError):
    """A derivation step failed its checks: nothing built on it is emitted. The message names the step and the
    claims that failed (`wristkin derive` prints it as a refusal of the robot, not a traceback)."""


@dataclass(frozen=True)
class Check:
    """Evidence that a step is right: a symbolic identity or a sampled numeric check."""

    kind: str  # "symbolic" | "numeric"
    claim: str  # what was checked, in words
    passed: bool
    max_error: float | None = None  # numeric checks: worst error seen
    tolerance: float | None = None
    samples: int | None = None
    # errors below this are one bucket: float rounding varies per CPU below ROUNDING_FLOOR; a check evaluated in
    # extended precision (mpmath) states a lower floor of its own
    floor: float = ROUNDING_FLOOR

    def summary(self) -> str:
        if self.kind == "symbolic":
            return f"symbolic identity: {'proven' if self.passed else 'FAILED'}"
        return (f"numeric, {self.samples} samples: max error {error_bucket(self.max_error, self.floor)} "
                f"(tolerance {self.tolerance:.0e}) {'passed' if self.passed else 'FAILED'}")


@dataclass(frozen=True)
class Step:
    """One derived quantity."""

    name: str  # identifier, also used to cross-reference depends_on
    title: str
    rule: str  # the first-principles rule applied
    depends_on: tuple[str, ...]
    result: Any  # SymPy expression, Matrix, or a dict of them
    checks: tuple[Check, ...]
    source: str = ""  # where the seed states it (e.g. "seed 000, formula (6)")
    note: str = ""

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.checks)


@dataclass(frozen=True)
class Finding:
    """A seed claim compared with what the derivation gives."""

    topic: str
    seed_says: str
    derived: str
    verdict: str  # "reproduced" | "wrong in seed" | "not reproducible" | "clarified"
    evidence: str


@dataclass
class Derivation:
    """Ordered steps for one mechanism; append-only while deriving."""

    mechanism: str
    title: str
    seed: str
    symbols: dict[str, sp.Symbol]
    steps: list[Step] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)
    decisions: list[tuple[str, str]] = field(default_factory=list)  # (decision, measured reason)
    exports: dict[str, Any] = field(default_factory=dict)  # checked expressions the kernels are built from

    def add(self, step: Step) -> Step:
        missing = [d for d in step.depends_on if d not in self.names()]
        if missing:
            raise ValueError(f"step {step.name!r} depends on unknown steps {missing}")
        if step.name in self.names():
            raise ValueError(f"duplicate step {step.name!r}")
        if not step.passed:
            failed = [c.claim for c in step.checks if not c.passed]
            raise CheckFailed(f"derivation step {step.name!r} failed its checks: {failed}")
        self.steps.append(step)
        return step

    def names(self) -> list[str]:
        return [s.name for s in self.steps]

    def __getitem__(self, name: str) -> Step:
        for s in self.steps:
            if s.name == name:
                return s
        raise KeyError(name)

    @property
    def all_passed(self) -> bool:
        return all(s.passed for s in self.steps)
