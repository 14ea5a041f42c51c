"""SymPy -> CasADi and the .casadi files: the generic part every mechanism's CasADi functions go through.

* `to_sx(exprs, symbol_map)`: a deterministic converter of SymPy expressions to `casadi.SX`. It walks the
  expression tree (SymPy's canonical argument order) with a memo, so structurally equal subtrees become one
  shared SX node; numbers without free symbols are evaluated once to 30 digits and enter as double constants.
* `write_casadi(functions, out_dir, name, design_names)` serialises a mechanism's functions with
  `casadi.FileSerializer` into one file `<out_dir>/<name>.casadi` (a single packed list of Functions, sorted by
  name) plus a JSON index `<out_dir>/<name>.json`. The bytes are a pure function of the expression graphs: the
  same kernels give the same file in any process (checked across PYTHONHASHSEED values), so the file sits under
  the drift check of generated/ (the format is CasADi's, so it changes with the pinned casadi version).

Each family builds its functions from its checked kernels (derive/families/*/*_casadi.py); this module names
no mechanism.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path

import casadi as ca
import sympy as sp

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
               design_names: Sequence[str], docs: Mapping[str, str] | None = None) -> str:
    idx = {
        "mechanism": name,
        "file": file_name,
        "format": "casadi.FileSerializer; one packed list of Functions sorted by name; "
                  "load with casadi.FileDeserializer(path).unpack()",
        "casadi_version": ca.__version__,
        "sha256": hashlib.sha256(blob).hexdigest(),
        "design_names": list(design_names),
        "functions": {
            n: {"doc": (docs or {}).get(n, ""), "inputs": _io(f, "in"), "outputs": _io(f, "out"),
                "n_instructions": int(f.n_instructions())}
            for n, f in sorted(functions.items())
        },
    }
    return json.dumps(idx, sort_keys=True, indent=2) + "\n"


def write_casadi(functions: Mapping[str, ca.Function], out_dir, name: str,
                 design_names: Sequence[str], docs: Mapping[str, str] | None = None) -> list[Path]:
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
    contents = [blob, index_json(functions, blob, paths[0].name, name, design_names, docs).encode()]
    for path, data in zip(paths, contents, strict=True):
        if not path.exists() or path.read_bytes() != data:
            tmp = path.with_suffix(path.suffix + ".tmp")
            tmp.write_bytes(data)
            os.replace(tmp, path)
    return paths
