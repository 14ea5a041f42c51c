"""Polynomial and vector helpers of the spatial-3 and subproblem-6 kernels (ascending coefficients).

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (own_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_shared_runtime.py)."""


# wristkin: inlined from here
def _poly_mul(a, b):
    out = [0.0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def _poly_add(a, b, sb=1.0):
    n = max(len(a), len(b))
    return [(a[i] if i < len(a) else 0.0) + sb * (b[i] if i < len(b) else 0.0) for i in range(n)]


def _scale3(p, s):
    return [e * s for e in p]
