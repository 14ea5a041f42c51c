"""Audit reports rendered from derivation records and numeric findings (never written by hand)."""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import os
import sys
from pathlib import Path

import sympy as sp

from .render import header_lines, render
from .tolerances import TOLERANCES

MAX_PRINT_OPS = 160  # larger expressions are summarised by their size instead of printed


def _distinct_operations(value) -> int:
    """How many distinct non-atomic subexpressions value has (each shared one once), in one pass over the distinct
    ones (sp.count_ops walks a shared subexpression at each use: a general 6R's nested FK, 34,000 operations, took
    seconds). Each is at least one operation where count_ops meets it, or a term its parent counts for it (-y in
    x - y: SUB; 1 / y in x / y: DIV), so this is at most twice the count."""
    seen: set = set()
    stack = list(value) if isinstance(value, sp.MatrixBase) else [value]
    while stack:
        e = stack.pop()
        if e.is_Atom or e in seen:
            continue
        seen.add(e)
        stack.extend(e.args)
    return len(seen)


def _fmt(value) -> str:
    if isinstance(value, sp.MatrixBase | sp.Basic):
        distinct = _distinct_operations(value)
        if distinct > 2 * MAX_PRINT_OPS:  # far too large to print: counted no further
            return f"({distinct} distinct operations; emitted as a kernel, not printed)"
        ops = sp.count_ops(value)
        if ops > MAX_PRINT_OPS:
            return f"({int(ops)} operations; emitted as a kernel, not printed)"
        return sp.sstr(value)
    return str(value)


def step_view(step) -> dict:
    results = step.result.items() if isinstance(step.result, dict) else [("result", step.result)]
    return {"name": step.name, "title": step.title, "rule": step.rule, "depends_on": ", ".join(step.depends_on),
            "source": step.source, "note": step.note, "results": [(k, _fmt(v)) for k, v in results],
            "checks": [c.summary() + f" — {c.claim}" for c in step.checks] or ["definition (no check needed)"]}


def load_generated(out: Path, name: str):
    """Import the freshly generated solver from `out` (not whatever is installed), as a module of a package
    of its own so that it imports the fresh runtime beside it."""
    folder = out / "python" / "wristkin"
    pkg_name = "_wristkin_audit_" + hashlib.sha256(str(folder.resolve()).encode()).hexdigest()[:12]
    saved, sys.dont_write_bytecode = sys.dont_write_bytecode, True  # no __pycache__ inside generated/
    # the audit's numbers come from the numpy modules: they must not depend on whether an extension was built
    backend, os.environ["WRISTKIN_BACKEND"] = os.environ.get("WRISTKIN_BACKEND"), "numpy"
    try:
        if pkg_name not in sys.modules:
            spec = importlib.util.spec_from_file_location(pkg_name, folder / "__init__.py",
                                                          submodule_search_locations=[str(folder)])
            pkg = importlib.util.module_from_spec(spec)
            sys.modules[pkg_name] = pkg
            spec.loader.exec_module(pkg)
        return importlib.import_module(f"{pkg_name}.{name}")
    finally:
        sys.dont_write_bytecode = saved
        if backend is None:
            del os.environ["WRISTKIN_BACKEND"]
        else:
            os.environ["WRISTKIN_BACKEND"] = backend


def write_report(mech, dv, out: Path, solver=None) -> list[Path]:
    """The audit report of one mechanism (and the figures it draws) into out/audit; `solver`: the generated module
    to audit (default: out's generated package)."""
    name = mech.NAME
    solver = solver or load_generated(out, name)
    audit_dir = out / "audit"
    audit_dir.mkdir(parents=True, exist_ok=True)
    numeric = {"summary": [], "sections": [], "findings": [], "decisions": [], "files": []}
    numeric.update(mech.audit_numbers(dv, solver, audit_dir))
    text = render("audit/report.md.jinja", header=header_lines(), dv=dv, tolerances=sorted(TOLERANCES.items()),
                  steps=[step_view(s) for s in dv.steps], findings=dv.findings + numeric.get("findings", []),
                  decisions=dv.decisions + numeric.get("decisions", []), numeric=numeric,
                  n_checks=sum(len(s.checks) for s in dv.steps),
                  n_symbolic=sum(c.kind == "symbolic" for s in dv.steps for c in s.checks))
    path = audit_dir / f"{name}.md"
    path.write_text(text)
    return [path, *numeric.get("files", [])]
