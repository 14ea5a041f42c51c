"""SymPy -> CasADi: the underactuated wrist's kernels as algorithmic-differentiation-ready functions.

Two layers:

* `to_sx(exprs, symbol_map)`: a generic, deterministic converter of SymPy expressions to
  `casadi.SX`. It walks the expression tree (SymPy's canonical argument order) with a memo, so
  structurally equal subtrees become one shared SX node; numbers without free symbols are
  evaluated once to 30 digits and enter as double constants.
* `casadi_functions(dv, kernels)`: the underactuated wrist's CasADi functions, assembled only from
  the checked kernel expressions of `derive.mechanisms.underactuated_wrist.kernels` (the design
  constants kernel is composed in, so every function takes the design parameters
  p = (alpha1, alpha2, beta1, beta2) as an explicit input). Outputs are densified.

`write_casadi(functions, out_dir)` serialises them with `casadi.FileSerializer` into one file
`<out_dir>/underactuated_wrist.casadi` (a single packed list of Functions, sorted by name) plus a
JSON index `<out_dir>/underactuated_wrist.json`; the pipeline passes out_dir = generated/casadi.
The bytes are a pure function of the expression graphs: the same kernels give the same file in
any process (checked across PYTHONHASHSEED values), so the file can sit under the drift check of
generated/ (the format is CasADi's, so it changes with the pinned casadi version).

Conventions (as in docs/API.md): angles in radians; e = (psi, theta, phi) are ZXZ Euler angles,
R = Rz(psi) Rx(theta) Rz(phi); q = (theta1, theta2, theta3) the exterior joint angles; loop i is
Zi2(theta_i) . (R p_i) - cos(alpha2) = A_i cos theta_i + B_i sin theta_i + C_i; jq * qdot = jx @ w.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import tempfile
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

import casadi as ca
import sympy as sp

MECHANISM = "underactuated_wrist"
DESIGN_NAMES = ("alpha1", "alpha2", "beta1", "beta2")
_EVAL_DIGITS = 30

# ------------------------------------------------------------------------------ SymPy -> SX
_UNARY = {
    sp.sin: ca.sin, sp.cos: ca.cos, sp.tan: ca.tan,
    sp.asin: ca.asin, sp.acos: ca.acos, sp.atan: ca.atan,
    sp.sinh: ca.sinh, sp.cosh: ca.cosh, sp.tanh: ca.tanh,
    sp.asinh: ca.asinh, sp.acosh: ca.acosh, sp.atanh: ca.atanh,
    sp.exp: ca.exp, sp.log: ca.log, sp.Abs: ca.fabs, sp.sign: ca.sign,
    sp.floor: ca.floor, sp.ceiling: ca.ceil, sp.erf: ca.erf,
}
_BINARY = {sp.atan2: ca.atan2, sp.Mod: ca.fmod}
_RELATIONAL = {
    sp.StrictLessThan: lambda a, b: a < b, sp.LessThan: lambda a, b: a <= b,
    sp.StrictGreaterThan: lambda a, b: a > b, sp.GreaterThan: lambda a, b: a >= b,
    sp.Equality: lambda a, b: a == b, sp.Unequality: lambda a, b: a != b,
}


class _Converter:
    def __init__(self, symbol_map: Mapping[sp.Symbol, object]):
        self.symbol_map = {}
        for s, v in symbol_map.items():
            sx = ca.SX(v)
            if sx.shape != (1, 1):
                raise ValueError(f"symbol {s} maps to a {sx.shape} expression, expected a scalar")
            self.symbol_map[s] = sx
        self.memo: dict[sp.Basic, ca.SX] = {}

    def __call__(self, e) -> ca.SX:
        e = sp.sympify(e)
        hit = self.memo.get(e)
        if hit is None:
            hit = self._convert(e)
            self.memo[e] = hit
        return hit

    @staticmethod
    def _number(e) -> ca.SX:
        if e.is_Integer or e.is_Float:
            return ca.SX(float(e))
        if e.is_Rational:
            return ca.SX(float(e.p) / float(e.q)) if e.q != 1 else ca.SX(float(e.p))
        if e is sp.S.Infinity:
            return ca.SX(float("inf"))
        if e is sp.S.NegativeInfinity:
            return ca.SX(float("-inf"))
        if e is sp.S.NaN:
            return ca.SX(float("nan"))
        v = sp.N(e, _EVAL_DIGITS)
        if not v.is_Float:
            raise ValueError(f"constant {e} does not evaluate to a real number (got {v})")
        return ca.SX(float(v))

    def _convert(self, e) -> ca.SX:
        if e.is_Symbol:
            try:
                return self.symbol_map[e]
            except KeyError:
                raise KeyError(f"symbol {e} has no entry in symbol_map") from None
        if e is sp.true:
            return ca.SX(1.0)
        if e is sp.false:
            return ca.SX(0.0)
        if e.is_number:
            return self._number(e)
        if e.is_Add:
            acc = None
            for term in e.args:  # canonical order: deterministic graph
                coeff, _ = term.as_coeff_Mul()
                if coeff.is_negative:
                    v = self(-term)
                    acc = -v if acc is None else acc - v
                else:
                    v = self(term)
                    acc = v if acc is None else acc + v
            return acc
        if e.is_Mul:
            coeff, factors = e.as_coeff_mul()
            num, den = [], []
            for f in factors:
                b, x = f.as_base_exp()
                if x.is_number and x.is_negative:
                    den.append(b if x == -1 else b ** (-x))
                else:
                    num.append(f)
            neg = bool(coeff.is_negative)
            coeff = abs(coeff)
            if coeff.is_Rational:
                if coeff.p != 1:
                    num.insert(0, sp.Integer(coeff.p))
                if coeff.q != 1:
                    den.insert(0, sp.Integer(coeff.q))
            elif coeff != 1:
                num.insert(0, coeff)
            out = _product([self(f) for f in num]) if num else ca.SX(1.0)
            if den:
                out = out / _product([self(f) for f in den])
            return -out if neg else out
        if e.is_Pow:
            b, x = e.as_base_exp()
            if b is sp.E:
                return ca.exp(self(x))
            if x.is_Integer:
                n = int(x)
                if n == 0:
                    return ca.SX(1.0)
                pos = self(b) if abs(n) == 1 else self(b) ** abs(n)
                return pos if n > 0 else 1.0 / pos
            if x.is_Rational and x.q == 2:
                r = ca.sqrt(self(b))
                k = (abs(int(x.p)) - 1) // 2  # b^(n/2) = sqrt(b) b^k
                pos = r if k == 0 else r * (self(b) if k == 1 else self(b) ** k)
                return pos if x.p > 0 else 1.0 / pos
            if x.is_number:
                return ca.power(self(b), self._number(x))
            return ca.power(self(b), self(x))
        fn = type(e)
        if fn in _UNARY:
            return _UNARY[fn](self(e.args[0]))
        if fn in _BINARY:
            return _BINARY[fn](self(e.args[0]), self(e.args[1]))
        if fn in (sp.Min, sp.Max):
            op = ca.fmin if fn is sp.Min else ca.fmax
            acc = self(e.args[0])
            for a in e.args[1:]:
                acc = op(acc, self(a))
            return acc
        if fn is sp.Piecewise:
            out = None
            for val, cond in reversed(e.args):
                if out is None:
                    if cond is not sp.true:
                        raise ValueError("Piecewise without a final True branch is not supported")
                    out = self(val)
                else:
                    out = ca.if_else(self(cond), self(val), out)
            return out
        if type(e) in _RELATIONAL:
            return _RELATIONAL[type(e)](self(e.lhs), self(e.rhs))
        if isinstance(e, sp.And | sp.Or):
            op = ca.logic_and if isinstance(e, sp.And) else ca.logic_or
            args = [self(a) for a in e.args]
            acc = args[0]
            for a in args[1:]:
                acc = op(acc, a)
            return acc
        if isinstance(e, sp.Not):
            return ca.logic_not(self(e.args[0]))
        raise NotImplementedError(f"to_sx: no CasADi counterpart for {type(e).__name__} ({e})")


def _product(xs: list[ca.SX]) -> ca.SX:
    acc = xs[0]
    for x in xs[1:]:
        acc = acc * x
    return acc


def to_sx(exprs, symbol_map: Mapping[sp.Symbol, object]) -> ca.SX:
    """Convert SymPy expression(s) to a dense `casadi.SX`.

    exprs: one expression (-> 1x1), a sequence of expressions (-> n x 1 column) or a SymPy
    Matrix (-> same shape). symbol_map: SymPy Symbol -> scalar SX expression (or number); every
    free symbol must be mapped. Subexpressions shared between the expressions of one call are
    converted once and become shared nodes of the CasADi graph.
    """
    conv = _Converter(symbol_map)
    if isinstance(exprs, sp.MatrixBase):
        rows = [[conv(exprs[i, j]) for j in range(exprs.cols)] for i in range(exprs.rows)]
        if rows and rows[0]:
            out = ca.vertcat(*[ca.horzcat(*r) for r in rows])
        else:
            out = ca.SX(exprs.rows, exprs.cols)
    elif isinstance(exprs, Iterable) and not isinstance(exprs, sp.Basic | str):
        items = [conv(x) for x in exprs]
        out = ca.vertcat(*items) if items else ca.SX(0, 1)
    else:
        out = conv(exprs)
    return ca.densify(out)


# ------------------------------------------------------------------------------ kernels -> SX
def _kernel_sx(kernel, groups: Mapping[str, object]) -> dict[str, ca.SX]:
    """Evaluate one kernel on SX inputs: groups maps each input group name to a sequence of scalars."""
    symbol_map = {}
    for gname, syms in kernel.inputs:
        vals = groups[gname]
        if len(vals) != len(syms):
            raise ValueError(f"kernel {kernel.name}: group {gname} needs {len(syms)} values, got {len(vals)}")
        symbol_map.update(zip(syms, vals, strict=True))
    sx = to_sx([e for _, e in kernel.outputs], symbol_map)
    return {name: sx[k] for k, (name, _) in enumerate(kernel.outputs)}


def _elems(v: ca.SX) -> list[ca.SX]:
    """Column vector -> list of scalars; matrix -> row-major list (the kernels' r00, r01, ... order)."""
    return [v[i, j] for i in range(v.shape[0]) for j in range(v.shape[1])]


def _rot_x(a):
    c, s = ca.cos(a), ca.sin(a)
    return ca.vertcat(ca.horzcat(1, 0, 0), ca.horzcat(0, c, -s), ca.horzcat(0, s, c))


def _rot_z(a):
    c, s = ca.cos(a), ca.sin(a)
    return ca.vertcat(ca.horzcat(c, -s, 0), ca.horzcat(s, c, 0), ca.horzcat(0, 0, 1))


def rotation_zxz(e: ca.SX) -> ca.SX:
    """R = Rz(psi) Rx(theta) Rz(phi) for e = (psi, theta, phi) (docs/API.md)."""
    return ca.mtimes([_rot_z(e[0]), _rot_x(e[1]), _rot_z(e[2])])


def _mat3(out: Mapping[str, ca.SX], prefix: str) -> ca.SX:
    return ca.vertcat(*[ca.horzcat(*[out[f"{prefix}{i}{j}"] for j in range(3)]) for i in range(3)])


FUNCTION_DOCS = {
    "uw_loop": "g_i = A_i cos q_i + B_i sin q_i + C_i = Zi2(q_i) . (R(e) p_i) - cos(alpha2), i = 1..3.",
    "uw_ik_branch": "Closed-form IK per branch: q_i = atan2(B_i, A_i) + sigma_i acos(-C_i / "
                    "sqrt(A_i^2 + B_i^2)), sigma_i = +/-1; not wrapped (q_i in (-2 pi, 2 pi]); "
                    "NaN where branch i is unreachable.",
    "uw_fk_rotation": "R = Rx(pi - beta1) Rz(theta1) Rx(alpha1) Rz(zeta) Rx(alpha2) Rz(eta) G for "
                      "tze = (theta1, zeta, eta).",
    "uw_jacobians": "jq_i = det[Zi1, Zi2, Zi3], row i of jx = Zi2 x Zi3, with R = R(e): jq * qdot = jx @ w.",
    "uw_rates": "w = jx^-1 (jq * qd); wdot = jx^-1 (jq * qdd + jqdot * qd - jxdot w); ed = E^-1 w; "
                "edd = E^-1 (wdot - Edot ed) with w = E(e) ed (singular at sin theta = 0).",
    "uw_loop_jac": "dg/dq and dg/de of uw_loop (CasADi AD).",
    "uw_singularity": "det_jq = jq1 jq2 jq3 (inverse/serial singularity at 0), det_jx = det jx "
                      "(direct/parallel singularity at 0).",
}


def casadi_functions(dv=None, kernels=None) -> dict[str, ca.Function]:
    """The underactuated wrist's CasADi functions, built from the kernels' SymPy expressions.

    dv: the Derivation (`underactuated_wrist.derive()`); kernels: `underactuated_wrist.kernels(dv)`
    (computed from dv when None). Returns a dict name -> casadi.Function (insertion order fixed).
    """
    if kernels is None:
        if dv is None:
            raise ValueError("need the derivation or its kernels")
        from .mechanisms import underactuated_wrist as uw
        kernels = uw.kernels(dv)
    if dv is not None and not dv.all_passed:
        raise AssertionError("derivation has failed steps")
    K = {k.name: k for k in kernels}
    missing = {"design_constants", "ik_abc", "fk_rotation", "jacobians", "jacobian_rates",
               "euler_rate_matrix"} - set(K)
    if missing:
        raise ValueError(f"missing kernels: {sorted(missing)}")
    (pname, psyms), = K["design_constants"].inputs
    if tuple(s.name for s in psyms) != DESIGN_NAMES:
        raise ValueError(f"design_constants takes {[s.name for s in psyms]}, expected {DESIGN_NAMES}")

    q = ca.SX.sym("q", 3)
    e = ca.SX.sym("e", 3)
    p = ca.SX.sym("p", 4)
    sigma = ca.SX.sym("sigma", 3)
    tze = ca.SX.sym("tze", 3)
    qd = ca.SX.sym("qd", 3)
    qdd = ca.SX.sym("qdd", 3)

    dc_out = _kernel_sx(K["design_constants"], {pname: _elems(p)})
    dc = [dc_out[name] for name, _ in K["design_constants"].outputs]

    # ik_abc takes the entries of R (row-major), built here from the ZXZ angles
    abc = _kernel_sx(K["ik_abc"], {"rot": _elems(rotation_zxz(e)), "dc": dc})
    A = [abc[f"A{i}"] for i in (1, 2, 3)]
    B = [abc[f"B{i}"] for i in (1, 2, 3)]
    C = [abc[f"C{i}"] for i in (1, 2, 3)]
    g = ca.vertcat(*[A[i] * ca.cos(q[i]) + B[i] * ca.sin(q[i]) + C[i] for i in range(3)])
    q_ik = ca.vertcat(*[ca.atan2(B[i], A[i]) + sigma[i] * ca.acos(-C[i] / ca.sqrt(A[i] ** 2 + B[i] ** 2))
                        for i in range(3)])

    R_fk = _mat3(_kernel_sx(K["fk_rotation"], {"tze": _elems(tze), "dc": dc}), "r")

    R = rotation_zxz(e)
    jac = _kernel_sx(K["jacobians"], {"q": _elems(q), "rot": _elems(R), "dc": dc})
    jq = ca.vertcat(*[jac[f"jq{i}"] for i in (1, 2, 3)])
    jx = _mat3(jac, "jx")

    w = ca.solve(jx, jq * qd)
    rates = _kernel_sx(K["jacobian_rates"], {"q": _elems(q), "rot": _elems(R), "qd": _elems(qd),
                                            "w": _elems(w), "dc": dc})
    jqdot = ca.vertcat(*[rates[f"jqd{i}"] for i in (1, 2, 3)])
    jxdot = _mat3(rates, "jxd")
    wdot = ca.solve(jx, jq * qdd + jqdot * qd - ca.mtimes(jxdot, w))
    E = _mat3(_kernel_sx(K["euler_rate_matrix"], {"pose": _elems(e)}), "e")
    ed = ca.solve(E, w)
    Edot = ca.jtimes(E, e, ed)  # dE/dt along e' = ed
    edd = ca.solve(E, wdot - ca.mtimes(Edot, ed))

    d = ca.densify
    specs = [
        ("uw_loop", [q, e, p], [g], ["q", "e", "p"], ["g"]),
        ("uw_ik_branch", [e, p, sigma], [q_ik], ["e", "p", "sigma"], ["q"]),
        ("uw_fk_rotation", [tze, p], [R_fk], ["tze", "p"], ["R"]),
        ("uw_jacobians", [q, e, p], [jq, jx], ["q", "e", "p"], ["jq", "jx"]),
        ("uw_rates", [q, e, qd, qdd, p], [w, wdot, ed, edd], ["q", "e", "qd", "qdd", "p"],
         ["w", "wdot", "ed", "edd"]),
        ("uw_loop_jac", [q, e, p], [ca.jacobian(g, q), ca.jacobian(g, e)], ["q", "e", "p"],
         ["dg_dq", "dg_de"]),
        ("uw_singularity", [q, e, p], [jq[0] * jq[1] * jq[2], ca.det(jx)], ["q", "e", "p"],
         ["det_jq", "det_jx"]),
    ]
    return {name: ca.Function(name, ins, [d(o) for o in outs], nin, nout)
            for name, ins, outs, nin, nout in specs}


# ------------------------------------------------------------------------------ serialisation
def serialize_functions(functions: Mapping[str, ca.Function]) -> bytes:
    """The bytes of the .casadi file: one `FileSerializer.pack` of the Functions sorted by name."""
    for name, f in functions.items():
        if f.name() != name:
            raise ValueError(f"function stored as {name!r} is named {f.name()!r}")
    ordered = [functions[n] for n in sorted(functions)]
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "f.casadi")
        s = ca.FileSerializer(path)
        s.pack(ordered)
        del s  # the file is flushed and closed when the serializer goes away
        return Path(path).read_bytes()


def load_casadi(path) -> dict[str, ca.Function]:
    """Read a file written by `write_casadi` back into {name: Function}."""
    fs = ca.FileDeserializer(str(path)).unpack()
    return {f.name(): f for f in fs}


def _load_bytes(blob: bytes) -> dict[str, ca.Function]:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "f.casadi"
        path.write_bytes(blob)
        return load_casadi(path)


def _io(f: ca.Function, kind: str) -> list[dict]:
    n = f.n_in() if kind == "in" else f.n_out()
    name = f.name_in if kind == "in" else f.name_out
    shape = f.size_in if kind == "in" else f.size_out
    return [{"name": name(i), "shape": list(shape(i))} for i in range(n)]


def index_json(functions: Mapping[str, ca.Function], blob: bytes, file_name: str, name: str,
               design_names: Sequence[str]) -> str:
    idx = {
        "mechanism": name,
        "file": file_name,
        "format": "casadi.FileSerializer; one packed list of Functions sorted by name; "
                  "load with casadi.FileDeserializer(path).unpack()",
        "casadi_version": ca.__version__,
        "sha256": hashlib.sha256(blob).hexdigest(),
        "design_names": list(design_names),
        "functions": {
            n: {"doc": FUNCTION_DOCS.get(n, ""), "inputs": _io(f, "in"), "outputs": _io(f, "out"),
                "n_instructions": int(f.n_instructions())}
            for n, f in sorted(functions.items())
        },
    }
    return json.dumps(idx, sort_keys=True, indent=2) + "\n"


def serial_functions(name: str, kernels) -> dict[str, ca.Function]:
    """A DH chain's FK (3x4 [R | p]) and geometric Jacobian (6 x n) from its kernels, plus the Jacobian of
    the position by CasADi's AD, which must equal the linear rows of the geometric one (tested)."""
    K = {k.name: k for k in kernels}
    n = len(K["fk"].inputs[0][1])
    q = ca.SX.sym("q", n)
    p = ca.SX.sym("p", len(K["fk"].inputs[1][1]))
    groups = {"q": _elems(q), "dp": _elems(p)}
    fk = _kernel_sx(K["fk"], groups)
    T = ca.reshape(ca.vertcat(*[fk[k] for k, _ in K["fk"].outputs]), 4, 3).T
    jo = _kernel_sx(K["jacobian"], groups)
    J = ca.reshape(ca.vertcat(*[jo[k] for k, _ in K["jacobian"].outputs]), n, 6).T
    return {
        f"{name}_fk": ca.Function(f"{name}_fk", [q, p], [ca.densify(T)], ["q", "p"], ["T"]),
        f"{name}_jacobian": ca.Function(f"{name}_jacobian", [q, p], [ca.densify(J)], ["q", "p"], ["J"]),
        f"{name}_position_jacobian_ad": ca.Function(f"{name}_position_jacobian_ad", [q, p],
                                                    [ca.densify(ca.jacobian(T[:, 3], q))], ["q", "p"], ["Jp"]),
    }


def write_casadi(functions: Mapping[str, ca.Function], out_dir, name: str = MECHANISM,
                 design_names: Sequence[str] = DESIGN_NAMES) -> list[Path]:
    """Write `<out_dir>/<name>.casadi` and `<out_dir>/<name>.json` (index); return both paths.

    design_names: the mechanism's design parameters in the order of the functions' design input (the
    generated module's DESIGN_NAMES).

    out_dir is the CasADi directory itself (the pipeline passes generated/casadi).

    Self-check before writing: the bytes, loaded back and serialised again, give the same bytes
    (serialisation is a function of the expression graphs alone). Files are only rewritten when
    their bytes change.
    """
    blob = serialize_functions(functions)
    if serialize_functions(_load_bytes(blob)) != blob:
        raise RuntimeError("CasADi serialisation does not round-trip to the same bytes")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / f"{name}.casadi", out / f"{name}.json"]
    contents = [blob, index_json(functions, blob, paths[0].name, name, design_names).encode()]
    for path, data in zip(paths, contents, strict=True):
        if not path.exists() or path.read_bytes() != data:
            tmp = path.with_suffix(path.suffix + ".tmp")
            tmp.write_bytes(data)
            os.replace(tmp, path)
    return paths


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="Write the underactuated wrist's CasADi functions.")
    ap.add_argument("--out", default="generated/casadi", help="output directory")
    args = ap.parse_args(argv)
    from .mechanisms import underactuated_wrist as uw
    dv = uw.derive()
    for path in write_casadi(casadi_functions(dv, uw.kernels(dv)), args.out):
        print(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
