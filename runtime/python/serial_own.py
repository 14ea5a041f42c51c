"""What a user robot's module with derived stages reads its named branches on, for own_api.py: the ideal chain
(its axes, points and home frame at the description's geometry, its relations made exact), and that its fk
takes no run-time joint (no held joint, no arm angle: the derived stages take neither).

A wristkin runtime source: a user robot's derived module inlines it from the marker line on
(derive/runtime_files.py), after its constants; above the marker, what it reads from them (own_stand_in.py: a
stand-in robot, whose constants have the same names), so that it is linted and tested as it is
(tests/test_derived_robot.py)."""

from __future__ import annotations

from chain_poe import _full_chain, _held
from own_stand_in import _FREE, _IDEAL_AXES, _IDEAL_HOME, _IDEAL_POINTS, JOINT_NAMES

# wristkin: inlined from here
_IDEAL = _full_chain(_IDEAL_AXES, _IDEAL_POINTS, _IDEAL_HOME)


def _branch_chain(d):
    """The chain the named branches are read on: the description's ideal one, whatever the lengths (a branch is a
    name for a configuration, read on one geometry), with a held joint at the design's value (its last)."""
    return _IDEAL if _FREE < 0 else _held(_IDEAL, _FREE, d.params[-1])


def _fk_design(q):
    """The design `fk` takes with the command line's joints: the default lengths, and a held joint's value."""
    return None if _FREE < 0 else {JOINT_NAMES[_FREE]: q[_FREE]}
