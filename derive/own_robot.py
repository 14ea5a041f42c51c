"""`wristkin derive`: one description (a URDF, or a spec file of any family) -> verified, emitted, audited solvers
in a folder of the user's:

    OUT/python/NAME.py (+ _wristkin_runtime.py beside it: importable on its own, numpy only)
    OUT/c/NAME.h, OUT/c/NAME.c (+ wristkin_common.h, wristkin_runtime.c)
    OUT/casadi/NAME.casadi (+ NAME.json index)
    OUT/audit/NAME.md

Progress goes to `progress` (one line per stage, with the seconds it took)."""

from __future__ import annotations

import importlib.util
import os
import sys
import sysconfig
import time
from pathlib import Path

from .families import FAMILIES
from .render import header_lines, render
from .spec import Spec, SpecError


def load(source: str | Path, name=None, base=None, tip=None, free=None, geometry_tol=None):
    """The mechanism of a URDF or a spec file (command-line options override the spec's own fields)."""
    path = Path(source)
    readers = [f for f in FAMILIES.values() if path.suffix.lower() in getattr(f, "SOURCE_SUFFIXES", ())]
    if readers:  # a description file a family reads itself (a URDF)
        spec = readers[0].spec_for_file(path, name=name, base=base, tip=tip, free=free, geometry_tol=geometry_tol)
    else:
        spec = Spec.load(path)
        for key, value in (("name", name), ("free", free), ("geometry_tol", geometry_tol)):
            if value is not None:
                spec.data[key] = value
        for key, value in (("base_link", base), ("tip_link", tip)):
            if value is not None:
                if "base_link" not in spec.data and "tip_link" not in spec.data and "urdf" not in spec.data:
                    raise SpecError(path, key, "--base / --tip only for a description with links (a URDF)")
                spec.data[key] = value
    family = FAMILIES.get(spec.data.get("family"))
    if family is None:
        raise spec.error("family", f"one of the families {', '.join(sorted(FAMILIES))}", spec.data.get("family"))
    return family.from_spec(spec)


def _write(path: Path, text: str | bytes) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    return path


def import_solver(out: Path, name: str, backend: str | None = None):
    """The solver just written to out/python (its runtime and extension beside it), imported under a private name;
    backend "numpy" forces the numpy path (the audit's numbers must not depend on a compiler)."""
    folder = out / "python"
    saved, sys.dont_write_bytecode = sys.dont_write_bytecode, True
    sys.path.insert(0, str(folder))
    env = os.environ.get("WRISTKIN_BACKEND")
    if backend:
        os.environ["WRISTKIN_BACKEND"] = backend
    try:
        key = f"_wristkin_own_{name}_{backend or 'auto'}_{abs(hash(str(folder.resolve())))}"
        spec = importlib.util.spec_from_file_location(key, folder / f"{name}.py")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[key] = mod  # dataclasses look their module up there
        spec.loader.exec_module(mod)
        return mod
    finally:
        sys.path.remove(str(folder))
        sys.dont_write_bytecode = saved
        if backend:
            if env is None:
                del os.environ["WRISTKIN_BACKEND"]
            else:
                os.environ["WRISTKIN_BACKEND"] = env


def _extension(out: Path, progress) -> list[Path]:
    """OUT/native/_native.c over every solver in OUT/c, compiled into OUT/python/_wristkin_native: the Python
    solvers then run the C. Without a compiler they run on numpy (said, not an error)."""
    from .native_build import BuildError, build
    from .pipeline import _native_binding

    binding = _native_binding(out, "_wristkin_native")
    target = out / "python" / f"_wristkin_native{sysconfig.get_config_var('EXT_SUFFIX') or '.so'}"
    try:
        build(out, target=target)
    except BuildError as exc:
        progress(f"  no C extension ({str(exc).splitlines()[0]}): the Python solvers run on numpy")
        return [binding]
    return [binding, target]


def derive(source, out, name=None, base=None, tip=None, free=None, geometry_tol=None, progress=print,
           native: bool = True) -> list[Path]:
    """Derive, emit and audit one description into `out`; returns the files written. `native`: also compile the
    folder's C into the Python extension the solvers call (skipped with native=False: they run on numpy)."""
    from . import audit, casadi_export, pipeline

    t0 = time.perf_counter()
    last = [t0]

    def stage(text):
        now = time.perf_counter()
        progress(f"  {text} ({now - last[0]:.1f} s)")
        last[0] = now

    mech = load(source, name, base, tip, free, geometry_tol)
    out = Path(out)
    nm = mech.NAME
    progress(f"wristkin derive: {nm} from {source}")
    stage("read the description")
    dv = mech.derive()
    stage(f"derived {len(dv.steps)} steps, {sum(len(s.checks) for s in dv.steps)} checks passed")
    ks = mech.kernels(dv)
    ctx = pipeline._context(mech, ks)
    t_py, t_h, t_c = pipeline._templates(nm, mech)
    hdr = header_lines()
    written = [_write(out / "python" / "_wristkin_runtime.py", render("python/_runtime.py.jinja", header=hdr)),
               _write(out / "python" / f"{nm}.py", render(t_py, **ctx)),
               _write(out / "c" / f"{nm}.h", render(t_h, **ctx)), _write(out / "c" / f"{nm}.c", render(t_c, **ctx)),
               _write(out / "c" / "wristkin_common.h", render("c/wristkin_common.h.jinja", header=hdr)),
               _write(out / "c" / "wristkin_runtime.c", render("c/wristkin_runtime.c.jinja", header=hdr))]
    stage("emitted Python and C")
    if native:
        written += _extension(out, progress)
        stage("compiled the C into the folder's Python extension (_wristkin_native)")
    fns = mech.casadi_functions(dv, ks)
    solver = import_solver(out, nm, backend="numpy")
    names = getattr(mech, "CASADI_DESIGN_NAMES", None) or solver.DESIGN_NAMES
    written += casadi_export.write_casadi(fns, out / "casadi", name=nm, design_names=names,
                                          docs=getattr(mech, "CASADI_DOCS", None))
    stage("wrote the CasADi functions")
    written += audit.write_report(mech, dv, out, solver=solver)
    stage("audited the generated solver")
    progress(f"wrote {len(written)} files to {out} in {time.perf_counter() - t0:.1f} s")
    return written
