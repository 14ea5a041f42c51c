"""Shared fixtures: the generated Python package on sys.path, the compiled C solver, the reference."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
for p in (ROOT / "generated" / "python", Path(__file__).resolve().parent):
    if str(p) not in sys.path:
        sys.path.insert(0, str(p))


@pytest.fixture(scope="session")
def uw():
    from wristkin import underactuated_wrist
    return underactuated_wrist


@pytest.fixture(scope="session")
def uw_c():
    from c_solvers import UnderactuatedWristC
    return UnderactuatedWristC()
