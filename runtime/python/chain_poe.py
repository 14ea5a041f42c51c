"""A chain's variants (a joint held, read from the tool) and its product of exponentials.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (own_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_shared_runtime.py)."""

from __future__ import annotations

from chain_rigid import _ID, _apply, _as_rt, _compose, _mv, _screw
from own_stand_in import JOINT_KINDS, N_JOINTS


# wristkin: inlined from here
# ---------------------------------------------------------------------------- the chain of a call
class _Chain:
    """kinds, axes, points and home frame of the chain the solver reads (free joint held, maybe reversed)."""

    __slots__ = ("kinds", "axes", "points", "home", "index", "meets")

    def __init__(self, kinds, axes, points, home, index):
        self.kinds, self.axes, self.points, self.home, self.index = kinds, axes, points, home, index
        self.meets = {}  # common points of axes, computed once per chain


def _full_chain(axes, points, home):
    return _Chain(JOINT_KINDS, axes, points, _as_rt(home), tuple(range(N_JOINTS)))


def _held(ch, f, v):
    """The chain with joint f held at v: the joints after it and the end frame move rigidly with it."""
    m = _screw(ch.kinds[f], ch.axes[f], ch.points[f], v)
    keep = [i for i in range(len(ch.kinds)) if i != f]
    return _Chain(tuple(ch.kinds[i] for i in keep),
                  tuple(_mv(m[0], ch.axes[i]) if i > f else ch.axes[i] for i in keep),
                  tuple(_apply(m, ch.points[i]) if i > f else ch.points[i] for i in keep),
                  _compose(m, ch.home), tuple(ch.index[i] for i in keep))


def _product(ch, q, js):
    t = _ID
    for j in js:
        t = _compose(t, _screw(ch.kinds[j], ch.axes[j], ch.points[j], q[j]))
    return t
