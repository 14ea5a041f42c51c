"""select for a mechanism without named branches (the catalogue's serial arms and parallel wrists; a user robot's
module takes own_api.py's, with its description's limits and branches).

A wristkin runtime source: those generated modules inline it from the marker line on (derive/runtime_files.py);
above the marker, what it reads (serial_stand_in.py: the PUMA-560), so that it is linted and tested as it is
(tests/test_serial_runtime.py)."""

from __future__ import annotations

import _runtime
from serial_stand_in import JOINT_KINDS, Solutions


# wristkin: inlined from here
def select(solutions: Solutions, previous=None, lower=None, upper=None, weights=None) -> int:
    """Index of the solution to use, or -1: valid and within [lower, upper] (limits compared as given). With
    `previous`, the nearest such set (weighted, wrapped for angles; ties by plain distance, then index): a
    singular flag is information, not a reason to jump to a farther set. Without it, the first non-singular
    such set, else the first one."""
    return _runtime.select(solutions, previous, lower, upper, weights, joint_kinds=JOINT_KINDS)
