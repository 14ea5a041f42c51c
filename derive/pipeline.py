"""regenerate / check / audit: mechanism -> derivation -> kernels -> rendered files in generated/."""

from __future__ import annotations

import difflib
import filecmp
import hashlib
import json
import math
import shutil
import tempfile
from pathlib import Path

from .lower import lower
from .mechanisms import REGISTRY
from .render import ROOT, header_lines, render, tool_versions

GENERATED = ROOT / "generated"
TOLERANCES = {"singular": "1e-6", "gimbal": "1e-10", "tangent": "1e-12", "fk_residual": "1e-10",
              "fk_duplicate": "1e-7", "fk_fold": "1e-8", "touch": "1e-8", "degenerate": "1e-12",
              "ik_verify": "1e-9", "rotation": "1e-9", "stage_tangent": "1e-9", "double_root": "1e-12",
              "wrist_exact": "1e-13", "design_scale_min": "1e-3", "length_max": "1e6"}


def _write(path: Path, text: str | bytes) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    data = text.encode() if isinstance(text, str) else text
    path.write_bytes(data)
    return path


def _context(mod, ks) -> dict:
    ctx = {
        "header": "\n".join(header_lines()),
        "header_lines": header_lines(),
        "kernels": [lower(k, "python") for k in ks],
        "vkernels": [lower(k, "numpy") for k in ks if k.name in mod.VECTORISED_KERNELS],
        "ckernels": [lower(k, "c") for k in ks],
        "tol": TOLERANCES,
    }
    if hasattr(mod, "DESIGN_DEFAULT_DEG"):
        ctx["design_default"] = [repr(math.radians(v)) for v in mod.DESIGN_DEFAULT_DEG]
        ctx["n_design_constants"] = len(mod.DESIGN_CONSTANTS)
    ctx.update(mod.extra_context(ks))
    return ctx


def _templates(name: str, mod) -> tuple[str, str, str]:
    return getattr(mod, "TEMPLATES", (f"python/{name}.py.jinja", f"c/{name}.h.jinja", f"c/{name}.c.jinja"))


def generate_code(out: Path, names=None) -> tuple[list[Path], dict, dict]:
    """Render every mechanism's solvers; returns (files, derivations, kernels) for the later products."""
    written, derivations, kernels = [], {}, {}
    for name, mod in sorted(REGISTRY.items()):
        if names and name not in names:
            continue
        dv = mod.derive()
        derivations[name] = dv
        kernels[name] = mod.kernels(dv)
        ctx = _context(mod, kernels[name])
        t_py, t_h, t_c = _templates(name, mod)
        written.append(_write(out / "python" / "wristkin" / f"{name}.py", render(t_py, **ctx)))
        written.append(_write(out / "c" / f"{name}.h", render(t_h, **ctx)))
        written.append(_write(out / "c" / f"{name}.c", render(t_c, **ctx)))
    written.append(_write(out / "python" / "wristkin" / "__init__.py",
                          render("python/__init__.py.jinja", header=header_lines(), names=sorted(REGISTRY))))
    written.append(_write(out / "c" / "wristkin_common.h", render("c/wristkin_common.h.jinja",
                                                                  header=header_lines())))
    return written, derivations, kernels


def _manifest(out: Path) -> Path:
    files = sorted(p for p in out.rglob("*") if p.is_file() and p.name != "MANIFEST.json"
                   and "__pycache__" not in p.parts)
    entries = {p.relative_to(out).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest() for p in files}
    return _write(out / "MANIFEST.json", json.dumps({"tools": tool_versions(), "files": entries},
                                                    sort_keys=True, indent=2) + "\n")


def regenerate(out_dir: Path = GENERATED) -> list[Path]:
    out = Path(out_dir)
    for sub in ("python", "c", "casadi", "audit"):
        if (out / sub).exists():
            shutil.rmtree(out / sub)
    written, derivations, kernels = generate_code(out)
    written += _post_code_products(out, derivations, kernels)
    written.append(_manifest(out))
    return written


def _post_code_products(out: Path, derivations: dict, kernels: dict) -> list[Path]:
    """CasADi functions and audit reports (they import the freshly generated solvers)."""
    extra: list[Path] = []
    from . import audit, to_casadi

    for name, dv in derivations.items():
        mod = REGISTRY[name]
        if hasattr(mod, "casadi_functions"):  # a mechanism may build its own CasADi functions
            fns = mod.casadi_functions(dv, kernels[name])
        elif name == "underactuated_wrist":
            fns = to_casadi.casadi_functions(dv, kernels[name])
        else:
            fns = to_casadi.serial_functions(name, kernels[name])
        # the entries of the functions' design input: the solver's DESIGN_NAMES unless the mechanism's CasADi
        # functions take fewer (the 3-RSR wrist's take only L)
        design_names = getattr(mod, "CASADI_DESIGN_NAMES", None) or audit.load_generated(out, name).DESIGN_NAMES
        extra += list(to_casadi.write_casadi(fns, out / "casadi", name=name, design_names=design_names))
    extra += audit.write_reports(derivations, out)
    return extra


def check(out_dir: Path = GENERATED) -> tuple[bool, str]:
    """Regenerate into a temp dir and compare with out_dir; returns (ok, unified diff)."""
    with tempfile.TemporaryDirectory() as tmp:
        fresh = Path(tmp) / "generated"
        regenerate(fresh)
        diffs = []
        a_files = {p.relative_to(out_dir).as_posix() for p in Path(out_dir).rglob("*")
                   if p.is_file() and "__pycache__" not in p.parts}
        b_files = {p.relative_to(fresh).as_posix() for p in fresh.rglob("*")
                   if p.is_file() and "__pycache__" not in p.parts}
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


def audit(names: list[str] | None = None) -> list[Path]:
    """Regenerate everything (the audit depends on freshly generated solvers) and return report paths."""
    written = regenerate(GENERATED)
    return [p for p in written if p.parent.name == "audit" and p.suffix == ".md"
            and (not names or p.stem in names)]
