"""What the user-robot templates print, prepared here so that no solver decision is taken in Jinja: the
decomposition's ops as rows of ck_plan[] (runtime/c/chain/ck_types.h: ck_op), and the runtime sources
(runtime/c/chain/ck_*.c, runtime/python/chain_*.py) a robot's module inlines, in order."""

from __future__ import annotations

# inlined after the robot's data, in this order (each reads only what the ones before it define)
_C_CORE = ("c/chain/ck_chain.c", "c/chain/ck_dense.c", "c/chain/ck_subproblems.c", "c/chain/ck_points.c",
           "c/chain/ck_verify.c")
_C_TAIL = ("c/chain/ck_interpreter.c", "c/chain/ck_api.c")
# the Python module inlines every kernel (an op it does not use is never called; its interpreter names them all)
PY_RUNTIME_FILES = tuple(f"python/{name}.py" for name in (
    "chain_design", "chain_rigid", "chain_poe", "chain_subproblems", "chain_points", "poly_real_roots", "chain_poly",
    "chain_spatial3", "chain_sp6", "chain_solve", "chain_verify", "chain_api"))


def _vec(v) -> str:
    return "{ " + ", ".join(str(x) for x in v) + " }"


def _spec(s) -> str:
    """An op's point or direction spec: its kind, how many joints it names and those joints."""
    return f"CK_{s[0].upper()}, {len(s) - 1}, {_vec(s[1:] if len(s) > 1 else [0])}"


_NO_SPEC = "CK_NONE, 0, { 0 }"
_NO_UNITS = "0, 0, 0, { 0 }, { { 0 } }"


def _row(op: dict) -> str:
    """One ck_op initializer: op, j, k, prismatic, spec, n_spec, spec_js, lo, hi, n_units, unit_len, units, n_js,
    js (the field order of ck_op)."""
    o = op["op"]
    slide = 1 if op.get("kind") == "P" else 0
    if o == "begin":
        return f"CK_BEGIN, -1, -1, 0, {_spec(op['x'])}, {op['lo']}, {op['hi']}, 0, {{ 0 }}, {{ {{ 0 }} }}, 0, {{ 0 }}"
    if o in ("first_plane", "last_plane"):
        return f"CK_{o.upper()}, {op['j']}, -1, {slide}, {_spec(op['n'])}, {_NO_UNITS}, 0, {{ 0 }}"
    if o in ("first_dist", "last_dist"):
        return f"CK_{o.upper()}, {op['j']}, -1, {slide}, {_spec(op['s'])}, {_NO_UNITS}, 0, {{ 0 }}"
    if o == "pair":
        return f"CK_PAIR, {op['j']}, {op['k']}, 0, {_spec(op['s'])}, {_NO_UNITS}, 0, {{ 0 }}"
    if o == "single":
        return f"CK_SINGLE, {op['j']}, -1, {slide}, {_NO_SPEC}, {_NO_UNITS}, 0, {{ 0 }}"
    if o == "linear":
        return f"CK_LINEAR, -1, -1, 1, {_NO_SPEC}, {_NO_UNITS}, {len(op['js'])}, {_vec(op['js'])}"
    if o == "sp6":
        return f"CK_SP6, {op['j']}, {op['k']}, 0, {_spec(op['n'])}, {_NO_UNITS}, 1, {_vec([op['l']])}"
    if o == "spatial3":
        return f"CK_SPATIAL3, -1, -1, 0, {_NO_SPEC}, {_NO_UNITS}, 3, {_vec(op['js'])}"
    if o == "orient":
        units = ", ".join(_vec(u) for u in op["units"])
        return (f"CK_ORIENT, -1, -1, 0, {_NO_SPEC}, {op['lo']}, {op['hi']}, {len(op['units'])}, "
                f"{_vec([len(u) for u in op['units']])},\n      {{ {units} }}, 0, {{ 0 }}")
    if o == "group_rest":
        return (f"CK_GROUP_REST, {op['j']}, -1, 0, {_NO_SPEC}, {_NO_UNITS}, {len(op['group'])}, "
                f"{_vec(op['group'])}")
    raise ValueError(f"no C row for the plan op {o!r}")


def c_plan_rows(ops) -> list[str]:
    """ck_plan[]'s rows, each with a comment naming its op."""
    return [f"/* {i}: {op['op']} */\n    {{ {_row(op)} }}" for i, op in enumerate(ops)]


def _kinds(ops) -> set[str]:
    return {op["op"] for op in ops}


def c_runtime_files(ops) -> list[str]:
    """The C runtime sources this decomposition calls, in inlining order."""
    kinds = _kinds(ops)
    poly = ["c/poly_real_roots.c", "c/chain/ck_poly.c"] if kinds & {"spatial3", "sp6"} else []
    return [*_C_CORE, *poly, *(["c/chain/ck_spatial3.c"] if "spatial3" in kinds else []),
            *(["c/chain/ck_sp6.c"] if "sp6" in kinds else []), *_C_TAIL]


def c_flags(ops, free: int, reversed_: bool) -> dict:
    """The preprocessor switches the runtime sources read (ck_chain.c, ck_interpreter.c, ck_api.c)."""
    kinds = _kinds(ops)
    return {"CK_FREE": free, "CK_REVERSED": int(bool(reversed_)), "CK_HAS_SP6": int("sp6" in kinds),
            "CK_HAS_SPATIAL3": int("spatial3" in kinds)}
