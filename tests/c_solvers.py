"""ctypes bindings of the generated C solvers, with results in the Python module's layout.

Used by the C tests and by the benchmarks ("generated C through the Python binding").
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from cbuild import RUNTIME_C, compile_shared, load

ROOT = Path(__file__).resolve().parent.parent
C_DIR = ROOT / "generated" / "c"


def _solutions_struct(max_n: int, n_values: int, n_aux: int):
    class S(ctypes.Structure):
        _fields_ = [("count", ctypes.c_int), ("status", ctypes.c_int), ("valid", ctypes.c_int * max_n),
                    ("flags", ctypes.c_uint * max_n), ("values", (ctypes.c_double * n_values) * max_n),
                    ("aux", (ctypes.c_double * n_aux) * max_n)]
    return S


def _result(rc, out) -> CResult:
    return CResult(rc, out.count, out.status, np.array(out.valid[:], dtype=bool), np.array(out.flags[:]),
                   np.array([list(r) for r in out.values]), np.array([list(r) for r in out.aux]))


@dataclass
class CResult:
    rc: int
    count: int
    status: int
    valid: np.ndarray
    flags: np.ndarray
    values: np.ndarray
    aux: np.ndarray


class UnderactuatedWristC:
    """Thin wrapper: same verbs and result layout as wristkin.underactuated_wrist."""

    def __init__(self, extra_flags=()):
        so = compile_shared([C_DIR / "underactuated_wrist.c", RUNTIME_C], [C_DIR], "underactuated_wrist",
                            extra_flags=list(extra_flags))
        self.lib = load(so)
        self.IK = _solutions_struct(8, 3, 5)
        self.FK = _solutions_struct(8, 3, 13)

        class Design(ctypes.Structure):
            _fields_ = [("params", ctypes.c_double * 4), ("c", ctypes.c_double * 22), ("theta0", ctypes.c_double)]
        self.Design = Design
        dp = ctypes.POINTER(Design)
        d3 = ctypes.POINTER(ctypes.c_double)
        L = self.lib
        L.wk_underactuated_wrist_design_init.argtypes = [d3, dp]
        L.wk_underactuated_wrist_ik.argtypes = [d3, dp, ctypes.POINTER(self.IK)]
        L.wk_underactuated_wrist_fk.argtypes = [d3, dp, ctypes.POINTER(self.FK)]
        L.wk_underactuated_wrist_ik_batch.argtypes = [ctypes.c_size_t, d3, dp, ctypes.POINTER(self.IK)]
        L.wk_underactuated_wrist_fk_batch.argtypes = [ctypes.c_size_t, d3, dp, ctypes.POINTER(self.FK)]
        L.wk_underactuated_wrist_select_ik.argtypes = [ctypes.POINTER(self.IK), d3, d3, d3]
        L.wk_underactuated_wrist_jacobians.argtypes = [d3, d3, dp, d3, d3]
        L.wk_underactuated_wrist_angular_velocity.argtypes = [d3, d3, d3, dp, d3]
        L.wk_underactuated_wrist_angular_acceleration.argtypes = [d3, d3, d3, d3, dp, d3]

    @staticmethod
    def _arr(v, n=None):
        a = np.ascontiguousarray(v, dtype=float)
        if n is not None and a.size != n:
            raise ValueError("wrong size")
        return a, a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))

    def design(self, params=None):
        d = self.Design()
        if params is None:
            rc = self.lib.wk_underactuated_wrist_design_init(None, ctypes.byref(d))
        else:
            a, p = self._arr(params, 4)
            rc = self.lib.wk_underactuated_wrist_design_init(p, ctypes.byref(d))
        return rc, d

    def _call(self, fn, struct, v, design):
        a, p = self._arr(v, 3)
        out = struct()
        rc = fn(p, None if design is None else ctypes.byref(design), ctypes.byref(out))
        return rc, out

    def ik(self, pose, design=None) -> CResult:
        return _result(*self._call(self.lib.wk_underactuated_wrist_ik, self.IK, pose, design))

    def fk(self, joints, design=None) -> CResult:
        return _result(*self._call(self.lib.wk_underactuated_wrist_fk, self.FK, joints, design))

    def ik_raw(self, pose_ptr, out):
        return self.lib.wk_underactuated_wrist_ik(pose_ptr, None, out)

    def batch(self, verb, rows, design=None):
        rows = np.ascontiguousarray(rows, dtype=float)
        struct = self.IK if verb == "ik" else self.FK
        outs = (struct * len(rows))()
        fn = getattr(self.lib, f"wk_underactuated_wrist_{verb}_batch")
        rc = fn(len(rows), rows.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
                None if design is None else ctypes.byref(design), outs)
        return rc, outs


class SerialC:
    """ctypes wrapper for a generated serial-chain mechanism (same layout as its Python module)."""

    def __init__(self, name: str, n_joints: int, max_ik: int, n_params: int, extra_flags=()):
        so = compile_shared([C_DIR / f"{name}.c", RUNTIME_C], [C_DIR], name, extra_flags=list(extra_flags))
        self.lib = load(so)
        self.name, self.n, self.max_ik = name, n_joints, max_ik
        self.IK = _solutions_struct(max_ik, n_joints, 1)
        self.FK = _solutions_struct(1, 12, 1)

        frames = ("base", "tool", "left", "right", "left_inv", "right_inv")

        class Design(ctypes.Structure):  # the header's wk_NAME_design: parameters, base and tool frames
            _fields_ = [("params", ctypes.c_double * n_params), *((f, ctypes.c_double * 12) for f in frames),
                        ("framed", ctypes.c_int)]
        self.Design = Design
        d = ctypes.POINTER(ctypes.c_double)
        getattr(self.lib, f"wk_{name}_ik").argtypes = [d, ctypes.POINTER(Design), ctypes.POINTER(self.IK)]
        getattr(self.lib, f"wk_{name}_fk").argtypes = [d, ctypes.POINTER(Design), ctypes.POINTER(self.FK)]
        getattr(self.lib, f"wk_{name}_jacobian").argtypes = [d, ctypes.POINTER(Design), d]
        getattr(self.lib, f"wk_{name}_design_init").argtypes = [d, ctypes.POINTER(Design)]
        getattr(self.lib, f"wk_{name}_select_ik").argtypes = [ctypes.POINTER(self.IK), d, d, d]
        getattr(self.lib, f"wk_{name}_ik_near").argtypes = [d, ctypes.POINTER(Design), d, ctypes.POINTER(self.IK)]

    @staticmethod
    def _ptr(a):
        return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))

    def design(self, params):
        d = self.Design()
        a = np.ascontiguousarray(params, dtype=float)
        return getattr(self.lib, f"wk_{self.name}_design_init")(self._ptr(a), ctypes.byref(d)), d

    def ik(self, pose, design=None) -> CResult:
        a = np.ascontiguousarray(np.asarray(pose, dtype=float)[:3].ravel())
        out = self.IK()
        rc = getattr(self.lib, f"wk_{self.name}_ik")(self._ptr(a), None if design is None else ctypes.byref(design),
                                                      ctypes.byref(out))
        return _result(rc, out)

    def ik_near(self, pose, previous, design=None):
        """(result, the raw struct for select)."""
        a = np.ascontiguousarray(np.asarray(pose, dtype=float)[:3].ravel())
        prev = np.ascontiguousarray(previous, dtype=float)
        out = self.IK()
        dptr = None if design is None else ctypes.byref(design)
        rc = getattr(self.lib, f"wk_{self.name}_ik_near")(self._ptr(a), dptr, self._ptr(prev), ctypes.byref(out))
        return _result(rc, out), out

    def fk(self, joints, design=None) -> CResult:
        a = np.ascontiguousarray(joints, dtype=float)
        out = self.FK()
        rc = getattr(self.lib, f"wk_{self.name}_fk")(self._ptr(a), None if design is None else ctypes.byref(design),
                                                      ctypes.byref(out))
        return _result(rc, out)

    def jacobian(self, joints):
        a = np.ascontiguousarray(joints, dtype=float)
        out = np.zeros(6 * self.n)
        rc = getattr(self.lib, f"wk_{self.name}_jacobian")(self._ptr(a), None, self._ptr(out))
        return rc, out.reshape(6, self.n)

    def select(self, res_struct, previous=None):
        prev = None if previous is None else self._ptr(np.ascontiguousarray(previous, dtype=float))
        return getattr(self.lib, f"wk_{self.name}_select_ik")(ctypes.byref(res_struct), prev, None, None)


class RsrC:
    """ctypes wrapper for the generated 3-RSR wrist (`rsr_wrist`) or the SCARA + 3-RSR hybrid (`scara_rsr`)."""

    LAYOUT = {"rsr_wrist": (3, 3, 8, 3, 3, 14, 5), "scara_rsr": (7, 13, 16, 6, 6, 6, 9)}

    def __init__(self, name: str, extra_flags=()):
        so = compile_shared([C_DIR / f"{name}.c", RUNTIME_C], [C_DIR], name, extra_flags=list(extra_flags))
        self.lib = load(so)
        self.name = name
        self.n, self.n_pose, self.max_ik, n_ik_aux, _, n_fk_aux, n_params = self.LAYOUT[name]
        self.IK = _solutions_struct(self.max_ik, self.n, n_ik_aux)
        self.FK = _solutions_struct(1, self.n_pose, n_fk_aux)

        class Design(ctypes.Structure):
            _fields_ = [("params", ctypes.c_double * n_params)]
        self.Design = Design
        d = ctypes.POINTER(ctypes.c_double)
        dp = ctypes.POINTER(Design)
        self._fn("ik").argtypes = [d, dp, ctypes.POINTER(self.IK)]
        self._fn("fk").argtypes = [d, dp, ctypes.POINTER(self.FK)]
        self._fn("ik_batch").argtypes = [ctypes.c_size_t, d, dp, ctypes.POINTER(self.IK)]
        self._fn("design_init").argtypes = [d, dp]
        sel = [ctypes.POINTER(self.IK), d, d, d] + ([d] if name == "scara_rsr" else [])
        self._fn("select_ik").argtypes = sel

    def _fn(self, verb):
        return getattr(self.lib, f"wk_{self.name}_{verb}")

    @staticmethod
    def _ptr(a):
        return None if a is None else a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))

    def design(self, params):
        d = self.Design()
        a = np.ascontiguousarray(params, dtype=float)
        return self._fn("design_init")(self._ptr(a), ctypes.byref(d)), d

    def ik(self, pose, design=None) -> CResult:
        a = np.ascontiguousarray(np.asarray(pose, dtype=float).ravel())
        out = self.IK()
        rc = self._fn("ik")(self._ptr(a), None if design is None else ctypes.byref(design), ctypes.byref(out))
        return _result(rc, out)

    def fk(self, joints, design=None) -> CResult:
        a = np.ascontiguousarray(joints, dtype=float)
        out = self.FK()
        rc = self._fn("fk")(self._ptr(a), None if design is None else ctypes.byref(design), ctypes.byref(out))
        return _result(rc, out)

    def select(self, pose, previous=None, lower=None, upper=None, weights=None):
        a = np.ascontiguousarray(np.asarray(pose, dtype=float).ravel())
        out = self.IK()
        self._fn("ik")(self._ptr(a), None, ctypes.byref(out))
        args = [self._ptr(None if v is None else np.ascontiguousarray(v, dtype=float))
                for v in (previous, lower, upper)]
        if self.name == "scara_rsr":
            args.append(self._ptr(None if weights is None else np.ascontiguousarray(weights, dtype=float)))
        return self._fn("select_ik")(ctypes.byref(out), *args)


class RuntimeC:
    """The shared C runtime alone (wristkin_runtime.c): its exact angle reduction."""

    def __init__(self, extra_flags=()):
        self.lib = load(compile_shared([RUNTIME_C], [C_DIR], "wristkin_runtime", extra_flags=list(extra_flags)))
        self.lib.wk_wrap.argtypes = [ctypes.c_double]
        self.lib.wk_wrap.restype = ctypes.c_double

    def wrap(self, a: float) -> float:
        return self.lib.wk_wrap(a)
