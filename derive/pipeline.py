"""regenerate / check / audit: mechanism -> derivation -> kernels -> rendered files in generated/."""

from __future__ import annotations

import dataclasses
import difflib
import filecmp
import hashlib
import json
import multiprocessing
import os
import shutil
import tempfile
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from . import cli_commands, runtime_files
from .catalogue import CATALOGUE, registry
from .lower import lower, lower_ahead
from .mechanism import Mechanism
from .render import ROOT, header_lines, input_hash, render, tool_versions
from .tolerances import TOLERANCES

GENERATED = ROOT / "generated"


def write_file(path: Path, text: str | bytes) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    data = text.encode() if isinstance(text, str) else text
    path.write_bytes(data)
    return path


def _context(mod, ks) -> dict:
    ctx = {
        "header": "\n".join(header_lines()),
        "header_lines": header_lines(),
        "kernels": [lower(k, "python") for k in ks if k.python],
        "vkernels": [lower(k, "numpy") for k in ks if k.name in mod.VECTORISED_KERNELS],
        "ckernels": [lower(k, "c") for k in ks],
        "tol": TOLERANCES,
        "inputs_hash": input_hash(),
    }
    ctx.update(mod.extra_context(ks))
    return ctx


def tasks(names=None, catalogue: Path = CATALOGUE) -> list[tuple[str, ...]]:
    """Mechanisms grouped into independent jobs, costliest first: mechanisms that share a cached derivation
    (the same DERIVE_GROUP) run one after another in one process, costliest first."""
    reg = registry(catalogue)
    chosen = sorted(n for n in reg if not names or n in names)
    cost = {n: reg[n].DERIVE_SECONDS for n in chosen}
    groups: dict[str, list[str]] = {}
    for n in chosen:
        groups.setdefault(reg[n].DERIVE_GROUP or n, []).append(n)
    jobs = [tuple(sorted(g, key=lambda n: (-cost[n], n))) for g in groups.values()]
    return sorted(jobs, key=lambda g: (-sum(cost[n] for n in g), g))


def emit_solvers(name: str, mod: Mechanism, ks, py_dir: Path, c_dir: Path, jobs: int = 1) -> list[Path]:
    """The mechanism's Python module (py_dir/name.py) and C header and source (c_dir) rendered from its kernels:
    the catalogue's and a `wristkin derive` folder's alike. `jobs` > 1: the kernels are lowered in that many
    processes first (the same bytes)."""
    lower_ahead([(k, (*(("python",) if k.python else ()), *(("numpy",) if k.name in mod.VECTORISED_KERNELS else ()),
                      "c")) for k in ks], jobs)
    ctx = _context(mod, ks)
    t_py, t_h, t_c = mod.TEMPLATES
    return [write_file(py_dir / f"{name}.py", render(t_py, **ctx)),
            write_file(c_dir / f"{name}.h", render(t_h, **ctx)), write_file(c_dir / f"{name}.c", render(t_c, **ctx))]


def emit_c_runtime(c_dir: Path, shared=()) -> list[Path]:
    """The C runtime every generated solver compiles with (wristkin_common.h, wristkin_runtime.c), and the shared
    runtime sources (c/...) some mechanisms call beside it (Mechanism.c_shared_files)."""
    header = header_lines()
    names = ["c/wristkin_common.h", "c/wristkin_runtime.c", *(f for f in shared if f not in (
        "c/wristkin_common.h", "c/wristkin_runtime.c"))]
    return [write_file(c_dir / name.split("/")[-1], runtime_files.emit(name, header)) for name in names]


def emit_casadi(name: str, mod: Mechanism, dv, ks, casadi_dir: Path, solver) -> list[Path]:
    """The mechanism's CasADi functions; their design input has the solver's DESIGN_NAMES unless the mechanism's
    functions take fewer (the 3-RSR wrist's take only L)."""
    from . import casadi_export

    design_names = mod.CASADI_DESIGN_NAMES or solver.DESIGN_NAMES
    return casadi_export.write_casadi(mod.casadi_functions(dv, ks), casadi_dir, name=name, design_names=design_names,
                                      docs=mod.CASADI_DOCS)


def mechanism_products(name: str, out: Path, catalogue: Path = CATALOGUE) -> list[Path]:
    """Everything one mechanism contributes to `out`: its Python and C solvers, CasADi functions and audit
    report (the audit imports the freshly written solver)."""
    from . import audit

    mod = registry(catalogue)[name]
    dv = mod.derive()
    ks = mod.kernels(dv)
    written = emit_solvers(name, mod, ks, out / "python" / "wristkin", out / "c")
    solver = audit.load_generated(out, name)
    written += emit_casadi(name, mod, dv, ks, out / "casadi", solver)
    written += audit.write_report(mod, dv, out, solver=solver)
    return written


def _job(args) -> list[Path]:
    group, out, catalogue = args
    return [p for name in group for p in mechanism_products(name, out, catalogue)]


def _shared_files(out: Path, catalogue: Path = CATALOGUE) -> list[Path]:
    """The runtime and package files every mechanism's products import (written before any mechanism)."""
    pkg = out / "python" / "wristkin"
    extra = {"cli": {"derivation_commands": cli_commands.literal()}}  # the table wristkin/cli.py carries
    files = [write_file(pkg / "_runtime.py", runtime_files.emit("python/_runtime.py", header_lines()))]
    files += [write_file(pkg / f"{stem}.py", render(f"python/{stem}.py.jinja", header=header_lines(),
                                                   **extra.get(stem, {})))
              for stem in ("cli", "__main__")]
    files.append(write_file(pkg / "__init__.py", render("python/__init__.py.jinja", header=header_lines(),
                                                     names=sorted(registry(catalogue)))))
    files += emit_c_runtime(out / "c")
    files.append(write_file(out / "c" / "CMakeLists.txt", render("c/CMakeLists.txt.jinja", header=header_lines(),
                                                             names=sorted(registry(catalogue)))))
    return files


def _c_api(name: str, api) -> dict:
    """What the binding's template prints for a mechanism: its name, its declared C verbs (Mechanism.C_API) and the
    extension's functions for it."""
    return {"name": name, **dataclasses.asdict(api), "methods": api.methods()}


# the binding's hand-written helpers (compiled and tested as they are: tests/test_native_helpers.py)
NATIVE_RUNTIME_FILES = ("c/native/wkn_inputs.c", "c/native/wkn_results.c")


def solver_names(out: Path) -> list[str]:
    """The mechanisms whose C is in out/c: their headers' names (the runtime's own headers are copies, not
    mechanisms)."""
    runtime_headers = {p.name for p in (runtime_files.RUNTIME / "c").glob("*.h")}
    return sorted(p.stem for p in (out / "c").glob("*.h") if p.name not in runtime_headers)


def native_binding(out: Path, apis: dict, module_path: str = "wristkin._native") -> Path:
    """The CPython extension source over the mechanisms `apis` names (name -> its declared Mechanism.C_API; their
    C in out/c; setup.py compiles it); `module_path`: the extension's import name (a `wristkin derive` folder's is
    the top-level _wristkin_native)."""
    mechs = [_c_api(name, apis[name]) for name in sorted(apis)]
    return write_file(out / "native" / "_native.c", render("c/native.c.jinja", header_lines=header_lines(), mechs=mechs,
                                                        inputs_hash=input_hash(), row_tol="WK_ROTATION_PROJECT_TOL",
                                                        runtime_sources=NATIVE_RUNTIME_FILES,
                                                        module_path=module_path))


def default_jobs() -> int:
    """Worker processes: WRISTKIN_JOBS, else one per core."""
    env = os.environ.get("WRISTKIN_JOBS", "")
    return max(1, int(env)) if env.strip().isdigit() else max(1, os.cpu_count() or 1)


def generate(out: Path, names=None, jobs: int | None = None, catalogue: Path = CATALOGUE) -> list[Path]:
    """Derive and write the given mechanisms (all by default) with `jobs` processes. Each job's bytes depend on
    its mechanism alone, so the output is the same whatever the number of processes or their order."""
    shared = _shared_files(out, catalogue)
    work = [(g, out, Path(catalogue)) for g in tasks(names, catalogue)]
    jobs = min(jobs or default_jobs(), len(work)) or 1
    if jobs == 1:
        results = [_job(w) for w in work]
    else:
        ctx = multiprocessing.get_context("fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn")
        with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
            results = list(pool.map(_job, work))
    written = shared + [p for r in results for p in r]
    # the binding covers every mechanism whose C the folder holds (a partial regeneration rewrites some of them)
    reg = registry(catalogue)
    return written + [native_binding(out, {n: reg[n].C_API for n in solver_names(out) if n in reg})]


BUILD_OUTPUTS = (".so", ".pyd", ".o")  # the compiled extension an editable install puts beside the modules


def generated_files(folder: Path) -> list[Path]:
    """Every file regeneration writes in `folder` (not caches, not the compiled extension)."""
    return [p for p in Path(folder).rglob("*")
            if p.is_file() and "__pycache__" not in p.parts and p.suffix not in BUILD_OUTPUTS]


def _manifest(out: Path) -> Path:
    files = sorted(p for p in generated_files(out) if p.name != "MANIFEST.json")
    entries = {p.relative_to(out).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest() for p in files}
    return write_file(out / "MANIFEST.json", json.dumps({"tools": tool_versions(), "files": entries},
                                                    sort_keys=True, indent=2) + "\n")


def regenerate(out_dir: Path = GENERATED, jobs: int | None = None, catalogue: Path = CATALOGUE) -> list[Path]:
    registry(catalogue)  # every spec read and validated before anything in out_dir is touched
    out = Path(out_dir)
    for sub in ("python", "c", "casadi", "audit", "native"):
        if (out / sub).exists():
            shutil.rmtree(out / sub)
    written = generate(out, jobs=jobs, catalogue=catalogue)
    written.append(_manifest(out))
    return written


def check(out_dir: Path = GENERATED, jobs: int | None = None) -> tuple[bool, str]:
    """Regenerate into a temp dir and compare with out_dir; returns (ok, unified diff)."""
    with tempfile.TemporaryDirectory() as tmp:
        fresh = Path(tmp) / "generated"
        regenerate(fresh, jobs=jobs)
        diffs = []
        a_files = {p.relative_to(out_dir).as_posix() for p in generated_files(out_dir)}
        b_files = {p.relative_to(fresh).as_posix() for p in generated_files(fresh)}
        for rel in sorted(a_files | b_files):
            a, b = Path(out_dir) / rel, fresh / rel
            if rel not in a_files or rel not in b_files:
                diffs.append(f"only in {'fresh' if rel in b_files else 'committed'}: {rel}\n")
            elif not filecmp.cmp(a, b, shallow=False):
                try:
                    diffs.extend(difflib.unified_diff(a.read_text().splitlines(True), b.read_text().splitlines(True),
                                                      f"committed/{rel}", f"fresh/{rel}", n=1))
                except UnicodeDecodeError:
                    diffs.append(f"binary file differs: {rel}\n")
        return not diffs, "".join(diffs)


def audit(names: list[str] | None = None, out_dir: Path = GENERATED, jobs: int | None = None,
          catalogue: Path = CATALOGUE) -> list[Path]:
    """Derive the named mechanisms (all when None) alone into out_dir (their solvers, CasADi functions and
    reports: the bytes a full regeneration writes) and refresh the manifest; returns the report paths."""
    known = registry(catalogue)
    unknown = sorted(set(names or ()) - set(known))
    if unknown:
        raise KeyError(f"unknown mechanism(s) {unknown} (known: {', '.join(sorted(known))})")
    out = Path(out_dir)
    written = generate(out, names, jobs, catalogue)
    _manifest(out)
    return [p for p in written if p.parent.name == "audit" and p.suffix == ".md"]
