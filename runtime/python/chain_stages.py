"""The stages of the ops whose kernels a module inlines only when its decomposition uses them (subproblem 6,
three general axes, the arm angle): each such source registers its stage here, and _solve runs it by the op's kind.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

# wristkin: inlined from here
# kind -> stage(ch, g, prev, op, x, y, q, count, go_on, family, params): sets its joints in q for each root and calls
# go_on(flags, noise=1.0) (the rest of the plan; noise: how much the stage's root amplified the input's rounding,
# which widens the later stages' tangent and double-root bands, STAGE_NOISE), or family(flags, place, previous
# angle) for a one-parameter family; params: the design's values (the arm angle op reads its angle)
_OP_STAGES = {}
# kind -> reader(ch, op, q): the op's design parameter read back from joint values (the arm angle)
_OP_READERS = {}
