"""Typed views the serial arm's thin templates render (templates/{python,c}/serial.*.jinja): every choice that
depends on the chain (which solver a stage calls, with which joints and branch bit; which optional checks the
chain has; whether the odd sets may reuse the even sets' FK check) is made here, once, and the templates print
the result. The solvers themselves are runtime sources (runtime/python/serial_*.py, runtime/c/serial/sr_*.c)."""

from __future__ import annotations

PY_RUNTIME_FILES = ("python/pose_forms.py", "python/serial_frames.py",
                    *(f"python/serial_{part}.py" for part in ("input", "fk", "stages", "verify", "ik")))
# a user robot's module (derived stages): its branches, limits and command line
# (own_api.py, last: it ends with the command line's entry point), on the ideal chain's products (chain_rigid, _poe)
PY_OWN_RUNTIME_FILES = ("python/chain_rigid.py", "python/chain_poe.py", "python/serial_own.py", "python/own_api.py")
PY_SELECT_FILE = "python/select_plain.py"  # select without named branches (a user robot's: own_api.py's)
# the constants a user robot's module adds (its limits, decomposition, branches and the ideal chain they are read on)
OWN_PARTIALS = ("python/partials/own_constants.py.jinja", "python/partials/own_serial.py.jinja")
# the C sources before the stage functions (which call sr_stages.c) and the one after them (which runs them)
C_RUNTIME_FILES = tuple(f"c/serial/sr_{part}.c" for part in ("frames", "input", "fk", "stages", "verify"))
C_RUNTIME_AFTER_STAGES = ("c/serial/sr_ik.c",)
# a chain with a general6r stage: its stage solver after sr_verify.c (C) and the elimination it runs (Python: inlined;
# C: the shared sources written beside the robot's C, C_GENERAL6R_SHARED)
C_GENERAL6R_FILE = "c/serial/sr_general6r.c"
PY_GENERAL6R_FILES = ("python/general6r.py", "python/serial_general6r.py")
C_GENERAL6R_SHARED = ("c/wk_eigen.h", "c/wk_eigen.c", "c/wk_general6r.h", "c/wk_general6r.c")
# a chain with a spatial3 or sp6 stage: the root finder and the helpers its core calls, the core, then its stage
# solver (inlined)
C_POLY_FILES = ("c/poly_real_roots.c", "c/wk_poly_ops.c", "c/wk_geom3.c")
PY_POLY_FILES = ("python/poly_real_roots.py", "python/chain_poly.py", "python/geom3.py")
C_SPATIAL3_FILES = ("c/wk_spatial3.c", "c/serial/sr_spatial3.c")
PY_SPATIAL3_FILES = ("python/spatial3.py", "python/serial_spatial3.py")
C_SP6_FILES = ("c/wk_sp6.c", "c/serial/sr_sp6.c")
PY_SP6_FILES = ("python/sp6.py", "python/serial_sp6.py")
# an S-R-S arm's arm_angle stage: the 3-vector helpers, the arm angle's core, its stage solver and arm_angle verb
C_ARM_ANGLE_FILES = ("c/wk_geom3.c", "c/wk_arm_angle.c", "c/serial/sr_arm_angle.c")
PY_ARM_ANGLE_FILES = ("python/geom3.py", "python/arm_angle.py", "python/serial_arm_angle.py")


IDENTITY_3X4 = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)


# a serial arm's Design beyond (params, native): its base and tool frames (serial_frames.py)
DESIGN_FIELDS = ("base: tuple = _BASE  # 4x4 rows: the base frame (the chain's own unless make_design(base=))",
                 "tool: tuple = _TOOL  # 4x4 rows: the tool frame",
                 "frames: tuple | None = field(default=None, compare=False, repr=False)  # (left, right, inverses)",
                 "refused: str | None = field(default=None, compare=False, repr=False)  # why ik refuses a held value")


def _frame_literal(top12) -> str:
    """A frame's 12 entries (top 3x4, row-major, as reprs) as a 4x4 tuple literal."""
    rows = [top12[4 * i:4 * i + 4] for i in range(3)] + [["0.0", "0.0", "0.0", "1.0"]]
    return "(" + ", ".join("(" + ", ".join(r) + ")" for r in rows) + ")"


def _tuple(xs) -> str:
    return "(" + "".join(f"{x}, " for x in xs) + ")"


# the stages that compute several candidates once per prefix above their bits (besides the general 6R's): kind ->
# (Python solver, C solver, what each takes after the kernel, prefix, index, joints, q, c, s, pose, dp: previous for
# a family's member, or amp for the amplification it sets)
MULTI_CANDIDATE = {"spatial3": ("_spatial3_stage", "sr_spatial3", "prev"), "sp6": ("_sp6_stage", "sr_sp6", "amp"),
                   "arm_angle": ("_arm_angle_stage", "sr_arm_angle", "prev"),
                   "held_elbow": ("_held_elbow_stage", "sr_held_elbow", "prev")}


def _amp_before(st: dict) -> str:
    """The wrist's family band factor: the product of the amplifications of the angle stages before it (each reads
    the joints the ones before it solved, so their errors compound; 1 without)."""
    js = st.get("amp_joints", [])
    return " * ".join(f"amp[{j}]" for j in js) if js else "1.0"


def py_stage_body(st: dict) -> list[str]:
    """The body of the generated `_solve_stage<k>(k, pose, q, c, s, dp, prev, amp)`: the stage's kernel, then the
    runtime solver of its kind with its joints and branch bit. Returns (ok, flags)."""
    out = f"_k_stage{st['index']}(pose, q, c, s, dp)"
    j = st["joints"][0]
    if st["kind"] == "trig_linear":
        if not st.get("factored"):
            return [f"return _trig_linear({out}, {j}, _sign(k, {st['bit']}), q, c, s, prev, amp,",
                    "                    size=_design_size(dp))"]
        return [f"a = {_amp_before(st)}  # the angle stages' amplification",
                f"return _trig_linear({out}, {j}, _sign(k, {st['bit']}), q, c, s, prev, amp, a, {st['gap_tol']},",
                f"                    _design_size(dp), {st['floor_tol']})"]
    if st["kind"] == "rotation2d":
        if st.get("probe"):  # a family's member is the one its next stage reaches (serial_stages._family_by_reach)
            return [f"return _rotation2d({out}, {j}, q, c, s, prev, amp, _k_stage{st['probe']}, pose, dp)"]
        return [f"return _rotation2d({out}, {j}, q, c, s, prev, amp, None, pose, dp)"]
    if st["kind"] == "value":
        return [f"return _revolute_value({out}, {j}, q, c, s)" if st["joint_kind"] == "R" else
                f"return _prismatic_value({out}, {j}, q)"]
    if st["kind"] == "quadratic":
        return [f"return _slide_quadratic({out}, {j}, _sign(k, {st['bit']}), q)"]
    if st["kind"] == "general6r":  # its candidates once per prefix above its bits (ws), set k's by its bits
        shift, width = st["shift"], st["width"]
        readings = "(" + "".join(f"{_tuple(r)}, " for r in st["labelling"]) + ")"
        return [f"return _general6r(_k_stage{st['index']}, k >> {shift + width}, (k >> {shift}) & {2 ** width - 1},",
                f"                  {readings},",
                f"                  {_tuple(st['joints'])}, q, c, s, pose, dp, ws)"]
    if st["kind"] in MULTI_CANDIDATE:  # as general6r's: its candidates once per prefix above its bits
        fn, _, extra = MULTI_CANDIDATE[st["kind"]]
        shift, width = st["shift"], st["width"]
        return [f"return {fn}(_k_stage{st['index']}, k >> {shift + width}, (k >> {shift}) & {2 ** width - 1}, "
                f"{_tuple(st['joints'])}, q, c, s, pose, dp, {extra}, ws)"]
    if st["kind"] == "wrist":
        joints, signs = "(" + ", ".join(map(str, st["joints"])) + ")", "(" + ", ".join(map(str, st["signs"])) + ")"
        centre = f"_k_stage{st['index']}_centre, pose" if st.get("centre") else "None, pose"
        mirror = ["if k & 1:  # the second branch mirrors the first (set k - 1's prefix)",
                  f"    return _wrist_mirror({joints}, q, c, s, a, {centre}, dp)"] if st["bit"] == 0 else []
        return [f"a = {_amp_before(st)}  # the angle stages' amplification"] + mirror + [
            f"return _wrist({out}, _sign(k, {st['bit']}), {signs}, {joints}, q, c, s, dp, a,",
            f"              {centre})"]
    raise ValueError(f"stage kind {st['kind']!r}")


def c_stage_body(st: dict) -> list[str]:
    """The body of the generated `sr_solve_stage<k>`: as py_stage_body, on the C runtime's solvers."""
    if st["kind"] == "general6r":  # its candidates once per prefix above its bits (ws), set k's by its bits
        shift, width = st["shift"], st["width"]
        joints = ", ".join(map(str, st["joints"]))
        readings = ", ".join("{ " + ", ".join(map(str, r)) + " }" for r in st["labelling"])
        return [f"static const int joints[6] = {{ {joints} }};",
                f"static const int readings[{len(st['labelling'])}][3] = {{ {readings} }};", "(void)prev;",
                "(void)amp;", "*f = 0u;",
                f"return sr_general6r(sr_k_stage{st['index']}, (long)(k >> {shift + width}), (k >> {shift}) & "
                f"{2 ** width - 1}, readings, {len(st['labelling'])}, joints, q, c, s, pose, dp, ws, f);"]
    if st["kind"] in MULTI_CANDIDATE:  # as general6r's: its candidates once per prefix above its bits
        _, fn, extra = MULTI_CANDIDATE[st["kind"]]
        shift, width = st["shift"], st["width"]
        joints = ", ".join(map(str, st["joints"]))
        return [f"static const int joints[{len(st['joints'])}] = {{ {joints} }};",
                f"(void){'amp' if extra == 'prev' else 'prev'};",
                f"return {fn}(sr_k_stage{st['index']}, (long)(k >> {shift + width}), (k >> {shift}) & "
                f"{2 ** width - 1}, joints, q, c, s, pose, dp, {extra}, ws, f);"]
    size = {"trig_linear": 6 if st.get("factored") else 3, "rotation2d": 4, "value": 1, "wrist": 9,
            "quadratic": 3}[st["kind"]]
    call = f"sr_k_stage{st['index']}(pose, q, c, s, dp, out);"
    j = st["joints"][0]
    head = [f"double out[{size}];", "(void)k;", "(void)prev; /* a family's representative (trig_linear, "
            "rotation2d stages) */", "(void)amp; /* the angle stages' amplification */",
            "(void)ws; /* the multi-candidate stages' scratch */", "*f = 0u;"]
    if st["kind"] == "trig_linear":
        gap_tol = f"SR_{st['gap_tol']}" if st.get("factored") else "0.0"
        floor_tol = f"SR_{st['floor_tol']}" if st.get("factored") and st["floor_tol"] != "0.0" else "0.0"
        return head + [call, f"return sr_trig_linear(out, {int(bool(st.get('factored')))}, {gap_tol}, {floor_tol}, "
                             f"{j}, sr_sign(k, {st['bit']}), q, c, s, prev, amp, {_amp_before(st)}, "
                             "sr_design_size(dp), f);"]
    if st["kind"] == "rotation2d":
        probe = f"sr_k_stage{st['probe']}" if st.get("probe") else "NULL"
        return head + [call, f"return sr_rotation2d(out, {j}, q, c, s, prev, amp, f, {probe}, pose, dp);"]
    if st["kind"] == "value":
        return head + [call, f"return sr_revolute_value(out, {j}, q, c, s);" if st["joint_kind"] == "R" else
                       f"return sr_prismatic_value(out, {j}, q, c, s);"]
    if st["kind"] == "quadratic":
        return head + [call, f"return sr_slide_quadratic(out, {j}, sr_sign(k, {st['bit']}), q, c, s, f);"]
    if st["kind"] == "wrist":
        joints = ", ".join(map(str, st["joints"]))
        signs = ", ".join(f"{v}.0" for v in st["signs"])
        body = [f"static const int joints[3] = {{ {joints} }};",
                f"static const double signs[8] = {{ {signs} }};"] + head
        centre = f"sr_k_stage{st['index']}_centre" if st.get("centre") else "NULL"
        if st["bit"] == 0:
            body += [f"if ((k & 1) == 1) return sr_wrist_mirror(joints, q, c, s, {_amp_before(st)}, {centre}, pose, "
                     "dp, f); /* set k - 1's prefix */"]
        return body + [call, f"return sr_wrist(out, sr_sign(k, {st['bit']}), signs, joints, q, c, s, dp, "
                             f"{_amp_before(st)}, {centre}, pose, f);"]
    raise ValueError(f"stage kind {st['kind']!r}")


def _arm_angle_verb(name: str) -> dict:
    """The C header's and source's wk_NAME_arm_angle (sr_arm_angle.c's sr_api_arm_angle)."""
    sig = f"int wk_{name}_arm_angle(const double *joints, const wk_{name}_design *design, double *psi)"
    return {"declaration": "/* The arm angle of joint values (the design parameter at which ik returns them): where "
                           "they put the elbow on its\n * circle about the shoulder-wrist line. */\n" + sig + ";",
            "definition": sig + "\n{\n    return sr_api_arm_angle(joints, design, psi);\n}"}


def _py_tuple(items: list[str]) -> str:
    """A tuple literal: one line for up to 8 items, else rows of 9 (a screw chain's axes: 30 design values)."""
    if len(items) <= 8:
        return "(" + "".join(f"{x}, " for x in items) + ")"
    rows = [items[i:i + 9] for i in range(0, len(items), 9)]
    return "(\n" + "".join("    " + ", ".join(r) + ",\n" for r in rows) + ")"


def serial_views(ctx: dict) -> dict:
    """The template context of a serial arm (the family's extra_context or the finite-screw chains') with the
    views added: stage bodies, the optional checks normalised (empty where the chain has none), the wrist stage
    (-1 without one) and the C switches."""
    stages = ctx["stages"]
    wrist = [st for st in stages if st["kind"] == "wrist"]
    design_checks = ctx.get("design_checks", [])
    image_checks = ctx.get("image_checks", [])
    has_design_kernel, has_image_kernel = "design_checks" in ctx, "image_checks" in ctx
    # an odd set's FK check is its even neighbour's when the wrist mirror keeps fk_cs bit for bit (proven on the
    # kernel: stages.mirror_keeps_fk) and the wrist takes the lowest bit
    reuse = bool(ctx.get("mirror_keeps_fk")) and bool(wrist) and wrist[0]["bit"] == 0
    general = any(st["kind"] == "general6r" for st in stages)
    spatial3 = any(st["kind"] == "spatial3" for st in stages)
    sp6 = any(st["kind"] == "sp6" for st in stages)
    arm_angle = any(st["kind"] == "arm_angle" for st in stages)
    held_elbow = any(st["kind"] == "held_elbow" for st in stages)
    aa_core = arm_angle or held_elbow  # the arm-angle core, its stage solvers and the arm_angle verb
    multi = [st["kind"] for st in stages if st["kind"] in MULTI_CANDIDATE or st["kind"] == "general6r"]
    if len(multi) > 1:  # the call's scratch (sr_stages.c's sr_ws, serial_stages._ws_take) holds one stage's candidates
        raise ValueError(f"stages {multi}: a chain has one multi-candidate stage at most")
    poly = spatial3 or sp6
    c_flags = {
        "SR_N_STAGES": len(stages),
        "SR_WRIST_STAGE": wrist[0]["index"] - 1 if wrist else -1,
        "SR_WRIST_J4": wrist[0]["joints"][0] if wrist else -1,
        "SR_WRIST_J5": wrist[0]["joints"][1] if wrist else -1,
        "SR_WRIST_J6": wrist[0]["joints"][2] if wrist else -1,
        "SR_HAS_PRISMATIC": int("P" in ctx["joint_kinds"]),
        "SR_HAS_TRIG_LINEAR": int(any(st["kind"] == "trig_linear" for st in stages)),
        "SR_HAS_FAMILY_STAGE": int(any(st["kind"] in ("trig_linear", "rotation2d") for st in stages)),
        "SR_HAS_ROTATION2D": int(any(st["kind"] == "rotation2d" for st in stages)),
        "SR_HAS_FAMILY_PROBE": int(any(st.get("probe") for st in stages)),
        "SR_HAS_REVOLUTE_VALUE": int(any(st["kind"] == "value" and st["joint_kind"] == "R" for st in stages)),
        "SR_HAS_PRISMATIC_VALUE": int(any(st["kind"] == "value" and st["joint_kind"] != "R" for st in stages)),
        "SR_HAS_SLIDE_QUADRATIC": int(any(st["kind"] == "quadratic" for st in stages)),
        "SR_HAS_GENERAL6R": int(general),
        "SR_HAS_SPATIAL3": int(spatial3),
        "SR_HAS_SP6": int(sp6),
        "SR_HAS_ARM_ANGLE": int(arm_angle),
        "SR_HAS_HELD_ELBOW": int(held_elbow),
        "SR_HAS_WRIST_MIRROR": int(bool(wrist) and wrist[0]["bit"] == 0),
        "SR_REUSE_MIRROR_CHECK": int(reuse),
        "SR_N_FOLD_MASKS": len(ctx["fold_masks"]),
        # the stages' sets; a calibrated arm whose wrist is its last stage scans its near-singular wrist families into
        # the sets after them (SR_MAX_IK twice as many: from_table.own_context)
        "SR_STAGE_SETS": ctx.get("stage_sets", ctx["max_ik"]),
        "SR_FAMILY_SCAN": int(bool(ctx.get("family_scan"))),
        # such an arm's q1 where its first stage reads it from the wrist centre (its shoulder's self-motion scanned
        # too: serial_ik._shoulder_near); -1: none
        "SR_SHOULDER_JOINT": ctx.get("shoulder_family", -1),
        "SR_LENGTHS_FLOOR": int(bool(ctx.get("lengths_floor"))),
        # the design's first SR_N_LENGTHS values are lengths (a held joint's angle follows them); SR_HELD: that
        # joint (-1: none), which the Gauss-Newton steps leave alone
        "SR_N_LENGTHS": ctx.get("n_lengths", len(ctx["design_values"])),
        "SR_HELD": ctx.get("held", -1),
        # a calibrated robot: the stages solve its ideal geometry, its FK is the true chain's, every set polished
        "SR_CALIBRATED": int(bool(ctx.get("calibrated"))),
        "SR_POLISH_STEPS": 12 if ctx.get("calibrated") else 6,  # Python's POLISH_STEPS says why
        "SR_TANGENT_CALIBRATED": repr(float(ctx.get("tangent_calibrated", 0.0))),  # Python's TANGENT_CALIBRATED
        "SR_N_DESIGN_CHECKS": len(design_checks) if has_design_kernel else 0,
        "SR_N_IMAGE_CHECKS": len(image_checks) if has_image_kernel else 0,
    }
    # the chain's tables the C sources read (only those it has: C99 has no empty arrays)
    c_tables = []
    if ctx["fold_masks"]:
        masks = ", ".join(f"{m}u" for m in ctx["fold_masks"])
        # the set-index masks whose pairs wk_merge_indistinct compares (Python's _FOLD_MASKS)
        c_tables.append(f"static const unsigned sr_fold_masks[SR_N_FOLD_MASKS] = {{ {masks} }};")
    if c_flags["SR_N_DESIGN_CHECKS"]:
        zero = ", ".join({"zero": "1", "nonzero": "0", "held": "2"}[c["kind"]] for c in design_checks)
        c_tables += ["/* design conditions (Python DESIGN_CHECKS): 1 = |v| <= tol required, 0 = |v| > tol required, "
                     "2 = |v| > tol required by ik (a held joint's value) */",
                     f"static const int sr_check_zero[SR_N_DESIGN_CHECKS] = {{ {zero} }};",
                     f"static const double sr_check_tol[SR_N_DESIGN_CHECKS] = "
                     f"{{ {', '.join(c['tol'] for c in design_checks)} }};"]
    own = ctx.get("own_api")
    # the chain's own base and tool frames (the catalogue's identity, a user robot's description's), which its
    # kernels fold in: design_set_frames replaces them (sr_frames.c, serial_frames.py)
    base0, tool0 = (own["base0"], own["tool0"]) if own else ([repr(float(v)) for v in IDENTITY_3X4],) * 2
    c_tables += [f"static const double sr_base0[12] = {{ {', '.join(base0)} }};",
                 f"static const double sr_tool0[12] = {{ {', '.join(tool0)} }};"]
    if aa_core:  # the core's bands scale with the robot's size (sr_arm_angle.c)
        c_tables.append(f"static const double sr_scale = {own['scale']};")
    if own:
        # a user robot's limits as select_ik's defaults (NULL limits: the description's)
        c_flags["SR_HAS_LIMITS"] = 1
        c_tables += [f"static const double sr_lower[SR_N] = {{ {', '.join(own['c_lower'])} }};",
                     f"static const double sr_upper[SR_N] = {{ {', '.join(own['c_upper'])} }};"]
    else:
        c_flags["SR_HAS_LIMITS"] = 0
    names = [f'"{n}"' for n in ctx["design_names"]]
    return {**ctx, "design_names_literal": _py_tuple(names), "design_default_literal": _py_tuple(ctx["design_values"]),
            "design_checks": design_checks, "image_checks": image_checks,
            # a user's chain of fewer than six joints says what it controls when a pose is out of reach
            "unreachable_note": ctx.get("unreachable_note", "None"),
            "lengths_floor": bool(ctx.get("lengths_floor")),
            "n_lengths": ctx.get("n_lengths", len(ctx["design_values"])), "held": ctx.get("held", -1),
            "calibrated": bool(ctx.get("calibrated")),
            "tangent_calibrated": repr(float(ctx.get("tangent_calibrated", 0.0))),
            "design_check_kernel": "_k_design_check" if has_design_kernel else "None",
            "fk_ideal_kernel": "_k_fk_ideal" if ctx.get("calibrated") else "None",
            "image_check_kernel": "_k_image_check" if has_image_kernel else "None",
            "py_stages": [{"index": st["index"], "shift": st["shift"], "body": py_stage_body(st)} for st in stages],
            "c_stages": [{"index": st["index"], "shift": st["shift"], "body": c_stage_body(st)} for st in stages],
            "wrist_stage": c_flags["SR_WRIST_STAGE"],
            "wrist_joints": [wrist[0]["joints"][0], wrist[0]["joints"][2]] if wrist else [],
            "wrist_bend": c_flags["SR_WRIST_J5"],
            "stage_sets": c_flags["SR_STAGE_SETS"], "family_scan": bool(ctx.get("family_scan")),
            "shoulder_family": (f"({ctx['shoulder_family']}, _k_stage1)" if ctx.get("shoulder_family", -1) >= 0
                                else "None"),
            "revolute": [1 if k == "R" else 0 for k in ctx["joint_kinds"]], "c_flags": c_flags, "c_tables": c_tables,
            "own_api": own or None, "own_partials": OWN_PARTIALS if own else (), "base0": base0, "tool0": tool0,
            "identity": [repr(float(v)) for v in IDENTITY_3X4],
            # C has no empty arrays or initialisers: a chain without lengths (one joint on its axis) keeps one
            # unused slot (WK_NAME_N_PARAMS stays 0)
            "c_params_slots": max(1, len(ctx["design_values"])), "c_design_values": ctx["design_values"] or ["0.0"],
            "py_base0": _frame_literal(base0), "py_tool0": _frame_literal(tool0), "design_fields": DESIGN_FIELDS,
            "py_runtime_files": (PY_RUNTIME_FILES[:-1] + (PY_GENERAL6R_FILES if general else ())
                                 + (PY_POLY_FILES if poly else ()) + (PY_SPATIAL3_FILES if spatial3 else ())
                                 + (PY_SP6_FILES if sp6 else ()) + (PY_ARM_ANGLE_FILES if aa_core else ())
                                 + PY_RUNTIME_FILES[-1:]
                                 + (PY_OWN_RUNTIME_FILES if own else (PY_SELECT_FILE,))),
            "select_doc": ("Joint limits (NULL = the description's limits, as the Python select); nearest valid set "
                           "to previous, or the\n * first regular one (NULL): index or -1." if own else
                           "Joint limits (NULL = none); nearest valid set to previous, or the first regular one "
                           "(NULL): index or -1."),
            "c_runtime_files": C_RUNTIME_FILES + ((C_GENERAL6R_FILE,) if general else ())
                               + (C_POLY_FILES if poly else ()) + (C_SPATIAL3_FILES if spatial3 else ())
                               + (C_SP6_FILES if sp6 else ()) + (C_ARM_ANGLE_FILES if aa_core else ()),
            "c_runtime_after_stages": C_RUNTIME_AFTER_STAGES,
            "arm_angle": arm_angle, "arm_angle_literal": str(arm_angle),
            # verbs beyond every serial arm's (declaration, definition): an S-R-S arm's arm angle of joint values
            "c_extra_verbs": [_arm_angle_verb(ctx["name"])] if aa_core else [],
            "c_includes": [f.split("/")[-1] for f in C_GENERAL6R_SHARED if f.endswith(".h")] if general else []}
