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


def c_plan_rows(stages, joint_names) -> list[str]:
    """ck_plan[]'s rows (stages.Stage.c_row), each with a comment naming its op and the joints it sets."""
    def named(s):
        groups = s.units if s.op == "orient" else [(j,) for j in s.solved]  # a parallel group turns as one
        names = ", ".join("+".join(joint_names[j] for j in g) for g in groups).replace("*/", "* /")
        return f"{s.op}: {names}" if names else s.op
    return [f"/* {s.index}: {named(s)} */\n    {{ {s.c_row()} }}" for s in stages]


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
