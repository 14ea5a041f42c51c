"""Shared fixtures: the generated Python package on sys.path, the compiled C solver, the reference."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
for p in (ROOT / "generated" / "python", Path(__file__).resolve().parent):
    if str(p) not in sys.path:
        sys.path.insert(0, str(p))

from seeding import TEST_SEED  # noqa: E402  (needs the tests folder on sys.path)


def pytest_report_header(config):
    return f"wristkin test seed: {TEST_SEED} (WRISTKIN_TEST_SEED; every seed must pass)"


def pytest_configure(config):
    # Hypothesis tests take `@hypothesis.seed(TEST_SEED)`, so a run is reproducible from its header line; no
    # example database (CI starts clean), no deadline (timing is for benchmarks, not tests).
    from hypothesis import settings

    settings.register_profile("wristkin", database=None, deadline=None, print_blob=True)
    settings.load_profile("wristkin")


@pytest.fixture(scope="session")
def uw():
    from wristkin import underactuated_wrist
    return underactuated_wrist


@pytest.fixture(scope="session")
def uw_c():
    from c_solvers import UnderactuatedWristC
    return UnderactuatedWristC()
