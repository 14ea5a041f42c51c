"""What the user-robot templates print, prepared here so that no solver decision is taken in Jinja: the
decomposition's ops as rows of ck_plan[] (runtime/c/chain/ck_types.h: ck_op), and the runtime sources
(runtime/c/chain/ck_*.c, runtime/python/chain_*.py) a robot's module inlines, in order."""

from __future__ import annotations

# inlined after the robot's data, in this order (each reads only what the ones before it define)
_C_CORE = ("c/chain/ck_chain.c", "c/chain/ck_dense.c", "c/chain/ck_subproblems.c", "c/chain/ck_points.c",
           "c/chain/ck_verify.c")
_C_TAIL = ("c/chain/ck_interpreter.c", "c/chain/ck_api.c")
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
    poly = ["c/poly_real_roots.c", "c/wk_poly_ops.c"] if kinds & {"spatial3", "sp6"} else []
    geom = ["c/wk_geom3.c"] if kinds & {"spatial3", "sp6", "arm_angle"} else []  # the chain-free cores' helpers
    return [*_C_CORE, *poly, *geom, *(["c/wk_spatial3.c", "c/chain/ck_spatial3.c"] if "spatial3" in kinds else []),
            *(["c/wk_sp6.c", "c/chain/ck_sp6.c"] if "sp6" in kinds else []),
            *(["c/wk_arm_angle.c", "c/chain/ck_arm_angle.c"] if "arm_angle" in kinds else []), *_C_TAIL]


def py_runtime_files(ops) -> list[str]:
    """The Python runtime sources this decomposition calls, in inlining order (subproblem 6 and the general 3R
    stage register themselves in chain_stages._OP_STAGES, which _solve runs by the op's kind)."""
    kinds = _kinds(ops)
    poly = ["python/poly_real_roots.py", "python/chain_poly.py"] if kinds & {"spatial3", "sp6"} else []
    geom = ["python/geom3.py"] if kinds & {"spatial3", "sp6", "arm_angle"} else []  # the chain-free cores' helpers
    return [*(f"python/chain_{n}.py" for n in ("design", "rigid", "poe", "subproblems", "points", "stages")), *poly,
            *geom, *(["python/spatial3.py", "python/chain_spatial3.py"] if "spatial3" in kinds else []),
            *(["python/sp6.py", "python/chain_sp6.py"] if "sp6" in kinds else []),
            *(["python/arm_angle.py", "python/chain_arm_angle.py"] if "arm_angle" in kinds else []),
            *(["python/general6r.py", "python/chain_general6r.py"] if "general6r" in kinds else []),
            *(f"python/chain_{n}.py" for n in ("solve", "verify")), "python/pose_forms.py", "python/chain_api.py",
            "python/own_api.py"]


def c_flags(ops, free: int, reversed_: bool, calibrated: bool = False, degenerate_held=(),
            geometry_tol: float = 1e-6) -> dict:
    """The preprocessor switches the runtime sources read (ck_chain.c, ck_interpreter.c, ck_api.c)."""
    kinds = _kinds(ops)
    held = {"CK_DEGENERATE_HELD": "{" + ", ".join(repr(float(v)) for v in degenerate_held) + "}"} \
        if degenerate_held else {}
    return {**held, "CK_N_DEGENERATE_HELD": len(degenerate_held), "CK_GEOMETRY_TOL": repr(float(geometry_tol)),
            "CK_FREE": free, "CK_REVERSED": int(bool(reversed_)), "CK_CALIBRATED": int(bool(calibrated)),
            "CK_HAS_SP6": int("sp6" in kinds),
            "CK_HAS_SPATIAL3": int("spatial3" in kinds), "CK_HAS_GENERAL6R": int("general6r" in kinds),
            "CK_HAS_ARM_ANGLE": int("arm_angle" in kinds)}


def stage_tolerances(ops) -> dict:
    """The bands of the closed-form stages (the Python template's comments say why each holds), as literals.
    After closed-form stages the stage inputs carry rounding: a double root at 32 eps of u (roots ~1e-7 apart
    separate), a wrist family at 1e-12 of |sin| (the stages' stacked rounding split an exact PUMA-type wrist
    singularity at 1e-13: C and numpy 1.7e-5 apart, Haswell kernels, seed 444150), a point on a joint's axis or a
    vanishing trig equation at 64 eps of the chain's size. After a polynomial stage (spatial3, subproblem 6, the
    general 6R: its roots carry ~1e-12) the wider bands that keep its noise from splitting a singular pose into two
    "regular" sets."""
    if _kinds(ops) & {"spatial3", "sp6", "general6r"}:
        return {"double_root_tol": "1e-12", "family_tol": "1e-10", "on_axis_tol": "1e-12"}
    return {"double_root_tol": "32 * 2.220446049250313e-16", "family_tol": "1e-12",
            "on_axis_tol": "64 * 2.220446049250313e-16"}


def c_shared_files(ops) -> list[str]:
    """Runtime sources the robot's C calls as separate files beside it (compiled once per program: their symbols
    are extern): the general 6R's elimination and its eigen solver."""
    if "general6r" not in _kinds(ops):
        return []
    return ["c/wk_eigen.h", "c/wk_eigen.c", "c/wk_general6r.h", "c/wk_general6r.c"]


def c_includes(ops) -> list[str]:
    """The headers of c_shared_files the robot's C includes."""
    return [f.split("/")[-1] for f in c_shared_files(ops) if f.endswith(".h")]
