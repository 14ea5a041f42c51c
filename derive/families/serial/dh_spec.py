"""A DH chain's spec file -> SerialSpec: the table, the design parameters and the seed's printed matrices
(docs/specs.md, "serial"); the IK stages come from the geometric planner (planned.py)."""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from ...identities.dh import DHRow, chain
from ...model import Finding
from ...spec import COMMON_FIELDS, Spec, common
from .dh_serial import SerialSpec
from .planned import stages as planned_stages

SPEC_FIELDS = ("convention", "design", "positive", "joint", "printed", "finding")
JOINT_FIELDS = ("name", "type", "a", "alpha", "d", "theta")
_FUNCTIONS = {"pi": sp.pi, "sin": sp.sin, "cos": sp.cos, "sqrt": sp.sqrt}
VERDICTS = ("reproduced", "wrong in seed", "not reproducible", "clarified")


def expression(spec: Spec, field: str, symbols: dict, default=None) -> sp.Expr:
    """A number, or a string of +-*/ and parentheses over numbers, pi, sin, cos, sqrt and the given names."""
    v = spec.raw(field, default)
    if isinstance(v, bool):
        raise spec.error(field, "a number or an expression string", v)
    if isinstance(v, int):
        return sp.Integer(v)
    if isinstance(v, float):
        return sp.Float(v)
    if isinstance(v, sp.Basic):
        return v
    allowed = ", ".join(sorted(symbols)) or "none"
    what = f"a number or an expression of numbers, pi, sin, cos, sqrt and the names ({allowed})"
    if not isinstance(v, str) or not v.strip() or len(v) > 2000 or "__" in v:
        raise spec.error(field, what, v)
    try:
        e = sp.parse_expr(v, local_dict={**_FUNCTIONS, **symbols}, evaluate=True)
    except Exception:  # noqa: BLE001 - any parse failure is the same user error
        raise spec.error(field, what, v) from None
    if not isinstance(e, sp.Expr) or not e.free_symbols <= set(symbols.values()) or any(
            f.func not in (sp.sin, sp.cos) for f in e.atoms(sp.Function)):
        raise spec.error(field, what, v)
    return e


def _radians(spec: Spec, field: str, e: sp.Expr) -> sp.Expr:
    """A DH angle (radians; the joint variable aside): a constant part beyond one turn is degrees written by
    mistake, refused rather than taken as that many radians."""
    const = e.as_independent(*e.free_symbols, as_Add=True)[0] if e.free_symbols else e
    if const.is_number and abs(float(const)) > 2 * float(sp.pi) * (1 + 1e-9):
        raise spec.error(field, f"an angle in radians within one turn (e.g. \"pi/2\"): {float(const):g} looks "
                                "like degrees", str(e))
    return e


def _symbol(spec: Spec, field: str, taken: set, **assumptions) -> sp.Symbol:
    name = spec.identifier(field) if field == "name" else field  # a joint's `name`, or a design table's key
    if name in taken or name in _FUNCTIONS:
        raise spec.error(field, f"a name not used before (and not {', '.join(_FUNCTIONS)})", name)
    taken.add(name)
    return sp.Symbol(name, **assumptions)


def load(spec: Spec) -> tuple[SerialSpec, Callable[[], list]]:
    """The SerialSpec without its IK stages, and the function that builds them from the planner's decomposition
    (symbolic work, done when the mechanism is derived)."""
    spec.only((*COMMON_FIELDS, *SPEC_FIELDS))
    head = common(spec)
    convention = spec.choice("convention", ("standard", "modified"), "standard")
    taken: set[str] = set()
    design_tbl = spec.table("design", {})
    positive = spec.raw("positive", [])
    if not isinstance(positive, list) or not all(isinstance(p, str) and p in design_tbl.data for p in positive):
        raise spec.error("positive", "an array of design parameter names (assumed > 0 by the derivation)", positive)
    design, values = [], []
    for key in design_tbl.data:
        sym = _symbol(design_tbl, key, taken, **({"positive": True} if key in positive else {"real": True}))
        lo = 1e-9 if key in positive else None
        values.append(design_tbl.number(key, lo=lo, unit="m"))
        design.append(sym)
    names = {str(d): d for d in design}
    rows, joints, kinds = [], [], []
    for js in spec.tables("joint"):
        js.only(JOINT_FIELDS)
        kind = {"revolute": "R", "prismatic": "P"}[js.choice("type", ("revolute", "prismatic"))]
        q = _symbol(js, "name", taken, real=True)
        own = {**names, str(q): q}
        a = expression(js, "a", names, 0)
        alpha = _radians(js, "alpha", expression(js, "alpha", names, 0))
        d = expression(js, "d", own if kind == "P" else names, str(q) if kind == "P" else 0)
        theta = _radians(js, "theta", expression(js, "theta", own if kind == "R" else names,
                                                 str(q) if kind == "R" else 0))
        if q not in (theta if kind == "R" else d).free_symbols:
            raise js.error("theta" if kind == "R" else "d", f"an expression of the joint variable {q}")
        rows.append(DHRow(a, alpha, d, theta, q, kind))
        joints.append(q)
        kinds.append(kind)
    if not rows:
        raise spec.error("joint", "at least one [[joint]] row")
    base = SerialSpec(head["name"], head["title"], head["source"], rows, tuple(joints), tuple(kinds), tuple(design),
                      tuple(values), [], _printed(spec, rows, convention, {**names, **{str(q): q for q in joints}}),
                      _findings(spec), convention=convention)
    return base, lambda: planned_stages(rows, tuple(joints), tuple(kinds), tuple(design), tuple(values),
                                        convention)[0]


def _printed(spec: Spec, rows, convention, symbols) -> dict:
    """The seed's printed matrices: name -> (the chain product of rows i..j, as printed)."""
    out = {}
    for ps in spec.tables("printed", []):
        ps.only(("name", "rows", "matrix", "substitute"))
        name = ps.text("name")
        span = ps.raw("rows")
        if (not isinstance(span, list) or len(span) != 2 or not all(isinstance(i, int) for i in span)
                or not 1 <= span[0] <= span[1] <= len(rows)):
            raise ps.error("rows", f"[first, last] rows of the table, 1 <= first <= last <= {len(rows)}", span)
        m = ps.raw("matrix")
        if not isinstance(m, list) or len(m) != 4 or not all(isinstance(r, list) and len(r) == 4 for r in m):
            raise ps.error("matrix", "a 4 x 4 array of expressions", m)
        cells = Spec({f"{i}{j}": m[i][j] for i in range(4) for j in range(4)}, ps.file, ps.path("matrix"))
        printed = sp.Matrix(4, 4, [expression(cells, f"{i}{j}", symbols) for i in range(4) for j in range(4)])
        subs_tbl = ps.table("substitute", {})
        subs = {symbols[k]: expression(subs_tbl, k, {}) for k in subs_tbl.data if k in symbols}
        if set(subs_tbl.data) - set(symbols):
            raise subs_tbl.error(sorted(set(subs_tbl.data) - set(symbols))[0], "a design or joint name")
        ours = chain(rows[span[0] - 1:span[1]], convention)[-1].subs(subs)
        out[name] = (ours, printed)
    return out


def _findings(spec: Spec) -> list[Finding]:
    """Findings a reader recorded from the seed (text only; numeric claims belong in [[printed]])."""
    out = []
    for fs in spec.tables("finding", []):
        fs.only(("topic", "seed_says", "derived", "verdict", "evidence"))
        out.append(Finding(fs.text("topic"), fs.text("seed_says"), fs.text("derived"), fs.choice("verdict", VERDICTS),
                           fs.text("evidence")))
    return out
