"""`wristkin derive`: one description (a URDF, or a spec file of any family) -> verified, emitted, audited solvers
in a folder of the user's:

    OUT/python/NAME.py (+ _wristkin_runtime.py beside it: importable on its own, numpy only)
    OUT/c/NAME.h, OUT/c/NAME.c (+ wristkin_common.h, wristkin_runtime.c)
    OUT/casadi/NAME.casadi (+ NAME.json index)
    OUT/audit/NAME.md

Progress goes to `progress` (one line per stage, with the seconds it took)."""

from __future__ import annotations

import dataclasses
import importlib.util
import json
import os
import sys
import sysconfig
import time
from pathlib import Path

from . import runtime_files
from .families import FAMILIES
from .mechanism import Mechanism
from .native_build import BuildError, start
from .render import header_lines
from .spec import Spec, SpecError


def load(source: str | Path, name=None, base=None, tip=None, free=None, geometry_tol=None, xacro_args=None,
         packages=None, redundancy=None):
    """The mechanism of a URDF / xacro or a spec file (command-line options override the spec's own fields): a
    catalogue mechanism as its family builds it, a robot description with its IK derived as straight-line stages
    (a robot the stages do not cover is refused: NotDerivable, naming why)."""
    return to_mechanism(description(source, name, base, tip, free, geometry_tol, xacro_args, packages, redundancy))


def description(source: str | Path, name=None, base=None, tip=None, free=None, geometry_tol=None, xacro_args=None,
                packages=None, redundancy=None):
    """What the family reads from the source before anything is derived: a robot description (its joints, its
    planned decomposition, its robot_table) or a catalogue mechanism."""
    path = Path(source)
    readers = [f for f in FAMILIES.values() if path.suffix.lower() in f.SOURCE_SUFFIXES]
    if readers:  # a description file a family reads itself (a URDF, a xacro file)
        spec = readers[0].spec_for_file(path, name=name, base=base, tip=tip, free=free, geometry_tol=geometry_tol,
                                        xacro_args=xacro_args, packages=packages, redundancy=redundancy)
    else:
        spec = Spec.load(path)
        for key, option, value in (("name", "--name", name), ("free", "--free", free),
                                   ("redundancy", "--redundancy", redundancy),
                                   ("geometry_tol", "--geometry-tol", geometry_tol)):
            if value is not None:
                spec.given(key, value, option)
        links = "base_link" in spec.data or "tip_link" in spec.data or "urdf" in spec.data
        for key, option, value in (("base_link", "--base", base), ("tip_link", "--tip", tip),
                                   ("xacro_args", "--xacro-arg", xacro_args or None),
                                   ("packages", "--package", packages or None)):
            if value is not None:
                if not links:
                    raise SpecError(path, key, f"{option} only for a description with links (a URDF or xacro "
                                               "file)", option=option)
                spec.given(key, {**spec.data.get(key, {}), **value} if isinstance(value, dict) else value, option)
    family = FAMILIES.get(spec.data.get("family"))
    if family is None:
        raise spec.error("family", f"one of the families {', '.join(sorted(FAMILIES))}", spec.data.get("family"))
    return family.from_spec(spec)


def to_mechanism(read):
    """A robot description's mechanism with derived straight-line stages (its robot_table handed to the family
    with from_table); a catalogue mechanism as it is (its stages are derived already)."""
    if isinstance(read, Mechanism):
        return read
    emitter = next(f for f in FAMILIES.values() if f.from_table is not None)
    return emitter.from_table(read.robot_table())


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


def _no_extension(progress, exc) -> None:
    progress(f"  no C extension ({str(exc).splitlines()[0]}): the Python solvers run on numpy")


def _extension(out: Path, mech, progress):
    """OUT/native/_native.c over every solver in OUT/c, its compile into OUT/python/_wristkin_native started: the
    Python solvers then run the C. Returns (the files written, the PendingBuild, or None without a compiler: the
    solvers then run on numpy, said, not an error). A folder may hold robots derived one command at a time:
    OUT/native/api.json keeps each one's declared C verbs (Mechanism.C_API), so the binding is rendered from
    declarations, not from reading the headers."""
    from .mechanism import CApi
    from .pipeline import native_binding, solver_names, write_file

    record = out / "native" / "api.json"
    known = json.loads(record.read_text()) if record.is_file() else {}
    known[mech.NAME] = dataclasses.asdict(mech.C_API)
    known = {n: known[n] for n in solver_names(out) if n in known}
    api_file = write_file(record, json.dumps(known, indent=1, sort_keys=True) + "\n")
    binding = native_binding(out, {n: CApi(**v) for n, v in known.items()}, "_wristkin_native")
    target = out / "python" / f"_wristkin_native{sysconfig.get_config_var('EXT_SUFFIX') or '.so'}"
    try:
        return [api_file, binding], start(out, target=target)
    except BuildError as exc:
        _no_extension(progress, exc)
        return [api_file, binding], None


def derive(source, out, name=None, base=None, tip=None, free=None, geometry_tol=None, progress=print,
           native: bool = True, xacro_args=None, packages=None, redundancy=None, jobs: int = 1) -> list[Path]:
    """Derive, emit and audit one description into `out`; returns the files written. `native`: also compile the
    folder's C into the Python extension the solvers call (skipped with native=False: they run on numpy). `jobs`:
    processes that lower the kernels side by side (the same bytes; the command line takes the machine's cores)."""
    from . import audit
    from .pipeline import emit_c_runtime, emit_casadi, emit_solvers, write_file

    t0 = time.perf_counter()
    last = [t0]

    def stage(text):
        now = time.perf_counter()
        progress(f"  {text} ({now - last[0]:.1f} s)")
        last[0] = now

    mech = load(source, name, base, tip, free, geometry_tol, xacro_args, packages, redundancy)
    out = Path(out)
    nm = mech.NAME
    progress(f"wristkin derive: {nm} from {source}")
    stage("read the description")
    dv = mech.derive()
    stage(f"derived {len(dv.steps)} steps, {sum(len(s.checks) for s in dv.steps)} checks passed")
    ks = mech.kernels(dv)
    written = [write_file(out / "python" / "_wristkin_runtime.py", runtime_files.emit("python/_runtime.py",
                                                                                   header_lines())),
               *emit_solvers(nm, mech, ks, out / "python", out / "c", jobs=jobs),
               *emit_c_runtime(out / "c", mech.c_shared_files())]
    stage("emitted Python and C")
    pending = None
    if native:  # the compile runs beside the CasADi functions and the audit (they run the numpy solver)
        files, pending = _extension(out, mech, progress)
        written += files
    try:
        solver = import_solver(out, nm, backend="numpy")
        written += emit_casadi(nm, mech, dv, ks, out / "casadi", solver)
        stage("wrote the CasADi functions")
        written += audit.write_report(mech, dv, out, solver=solver)
        stage("audited the generated solver")
    except BaseException:
        if pending is not None:  # no compiler left running behind a failed derivation
            pending.cancel()
        raise
    if pending is not None:
        try:
            written.append(pending.wait())
            stage("compiled the C into the folder's Python extension (_wristkin_native), begun after emitting")
        except BuildError as exc:
            _no_extension(progress, exc)
    progress(f"wrote {len(written)} files to {out} in {time.perf_counter() - t0:.1f} s")
    return written
