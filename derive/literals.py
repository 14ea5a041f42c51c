"""Numbers and texts as the generated files print them (Python and C literals): one spelling for every family."""

from __future__ import annotations

import math
import pprint
import textwrap

import numpy as np


def py_num(v: float) -> str:
    """A float as Python source, infinities as math.inf."""
    return repr(float(v)) if math.isfinite(v) else ("math.inf" if v > 0 else "-math.inf")


def c_num(v: float) -> str:
    """A float as C source, infinities as INFINITY (math.h)."""
    return repr(float(v)) if math.isfinite(v) else ("INFINITY" if v > 0 else "-INFINITY")


def floats(a) -> list:
    """Rows of numbers, each as its repr."""
    return [[repr(float(x)) for x in row] for row in np.asarray(a)]


def vectors(a) -> str:
    """Rows of numbers as a tuple literal, one row per line."""
    return "(\n" + "".join("    (" + ", ".join(repr(float(x)) for x in row) + "),\n" for row in a) + ")"


def text_literal(text: str) -> str:
    """A long string as implicitly joined lines of at most ~100 characters."""
    lines = textwrap.wrap(text, 100, break_on_hyphens=False)
    return "(\n" + "".join(f"    {(ln + (' ' if i < len(lines) - 1 else ''))!r}\n" for i, ln in enumerate(lines)) + ")"


def own_api_literals(api) -> dict:
    """A user robot's module constants beyond the verbs (kinematics/dh_table.OwnRobotApi: limits, named branches, the
    ideal axes their roles read, the decomposition's words) as a user robot's module prints them."""
    return {"limits_lower": [py_num(v) for v in api.lower], "limits_upper": [py_num(v) for v in api.upper],
            "strategy_literal": text_literal(api.decomposition), "controls_literal": text_literal(api.controls),
            "branch_names": api.branches, "roles": pprint.pformat(tuple(api.roles), width=110),
            "ideal_axes": vectors(api.ideal_axes), "ideal_points": vectors(api.ideal_points),
            "ideal_home": vectors(api.ideal_home), "scale": repr(float(api.scale)),
            "geometry_tol": repr(float(api.geometry_tol)), "geometry_deviation": repr(float(api.deviation)),
            "description_tol": repr(float(api.description_tol)),
            "calibrated": bool(api.calibrated)}
