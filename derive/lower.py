"""Kernels: named SymPy expression blocks, lowered to straight-line code per target.

A kernel has grouped inputs (each group a C array / Python sequence) and named
outputs. Lowering runs canonical CSE, folds irrational constants to floats and
prints each assignment with the target's printer. The result is plain data the
templates loop over.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import sympy as sp

from .printers import CPrinter, NumpyPrinter, PyMathPrinter


@dataclass(frozen=True)
class Kernel:
    name: str
    doc: str
    inputs: tuple[tuple[str, tuple[sp.Symbol, ...]], ...]  # (group name, symbols in order)
    outputs: tuple[tuple[str, sp.Expr], ...]
    # whether irrational constants may appear (sqrt(3)/2 ...): folded to floats before CSE. A kernel built from
    # floats and integers only (a robot's product of exponentials) skips the walk, which on its deep products
    # costs seconds
    irrational: bool = True
    # whether the Python module prints it too (False: a kernel only the C runtime calls)
    python: bool = True

    @property
    def n_out(self) -> int:
        return len(self.outputs)


@dataclass(frozen=True)
class Lowered:
    name: str
    doc: str
    unpack: tuple[tuple[str, str, int], ...]  # (symbol name, group, index): only inputs actually used
    temps: tuple[tuple[str, str], ...]  # (temp name, code)
    outputs: tuple[tuple[str, str], ...]  # (output name, code)
    groups: tuple[str, ...]
    n_out: int
    ops: int  # operation count after CSE, for the audit


def distinct_nodes(exprs):
    """Every distinct node of the expressions, each once: shared subtrees (a matrix product's entries share most of
    theirs) are walked once, by identity, where atoms() and preorder_traversal walk the whole tree."""
    seen, stack = set(), list(exprs)
    while stack:
        a = stack.pop()
        if id(a) in seen:
            continue
        seen.add(id(a))
        yield a
        stack.extend(a.args)


def _has_irrational(e: sp.Expr) -> bool:
    """Whether e holds an exact irrational constant: a named one (pi), a number's non-integer power (sqrt(2)) or a
    function of a number (cos(pi / 36)). Floats and rationals are what the printers print as they are. One walk over
    the distinct nodes, stopping at the first (a calibrated arm's FK on its true axes, a tree of 1e6 nodes over a few
    thousand distinct ones, took 6 s in three atoms() walks)."""
    return any(isinstance(a, sp.NumberSymbol) or (a.is_Pow and a.base.is_number and not a.exp.is_Integer)
               or (isinstance(a, sp.Function) and a.args and all(x.is_number for x in a.args))
               for a in distinct_nodes([e]))


def _fold_constants(e: sp.Expr) -> sp.Expr:
    """Irrational constants (sqrt(3)/2 ...) become 17-digit floats so no target recomputes them. An expression
    without any is returned as it is (walking a general 6R's float-laden kernels for none took seconds)."""
    if not _has_irrational(e):
        return e
    return e.replace(lambda a: a.is_number and not a.is_Rational and a.free_symbols == set(),
                     lambda a: sp.Float(sp.N(a, 25), 17))


def cse_kernel(kernel: Kernel):
    exprs = [_fold_constants(sp.sympify(e)) if kernel.irrational else sp.sympify(e) for _, e in kernel.outputs]
    temps, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("t"), order="canonical")
    # CSE can leave a temp no output needs (its uses cancelled after extraction): drop those, last first
    needed = set().union(*(e.free_symbols for e in reduced))
    kept = []
    for sym, e in reversed(temps):
        if sym in needed:
            kept.append((sym, e))
            needed |= sp.sympify(e).free_symbols
    return kept[::-1], reduced


@dataclass(frozen=True)
class _Reduced:
    temps: tuple
    reduced: tuple
    unpack: tuple[tuple[str, str, int], ...]
    ops: int


@functools.lru_cache(maxsize=64)  # a mechanism has about a dozen kernels
def _reduce(kernel: Kernel) -> _Reduced:
    """The target-independent part of lowering, done once per kernel (it is immutable): each kernel is printed
    for up to three targets and measured by the audit, and CSE is most of the cost."""
    temps, reduced = cse_kernel(kernel)
    used = set().union(*(sp.sympify(e).free_symbols for _, e in temps), *(e.free_symbols for e in reduced))
    unpack = tuple((s.name, g, i) for g, syms in kernel.inputs for i, s in enumerate(syms) if s in used)
    ops = sum(sp.count_ops(e) for _, e in temps) + sum(sp.count_ops(e) for e in reduced)
    return _Reduced(tuple(temps), tuple(reduced), unpack, int(ops))


# filled by lower_ahead's worker processes, for the last emission only: (kernel, target) -> Lowered, which lower()
# takes from here, and kernel -> its CSE (reduced() takes it)
_AHEAD: dict[tuple[Kernel, str], Lowered] = {}
_AHEAD_REDUCED: dict[Kernel, _Reduced] = {}
_PENDING: list[tuple[Kernel, tuple[str, ...]]] = []  # what the forked workers lower (inherited, not pickled)


def reduced(kernel: Kernel) -> _Reduced:
    """The kernel's CSE (temporaries, reduced outputs), as lower() prints it."""
    return _AHEAD_REDUCED.get(kernel) or _reduce(kernel)


def _lower_pending(i: int) -> tuple[_Reduced, list[Lowered]]:
    kernel, targets = _PENDING[i]
    return _reduce(kernel), [lower(kernel, t) for t in targets]


def lower_ahead(work: list[tuple[Kernel, tuple[str, ...]]], jobs: int) -> None:
    """Lower each (kernel, targets) in up to `jobs` forked processes, largest kernels first, so that lower() then
    returns them at once: CSE is most of an emission (a calibrated 7-joint arm's FK and Jacobians, 4 s on one core).
    The workers' results are the same data lower() computes (plain strings): the bytes do not depend on `jobs`.
    Off Linux (fork is unsafe on macOS, missing on Windows) or with jobs <= 1 nothing is done ahead."""
    import multiprocessing as mp
    import sys

    _AHEAD.clear()
    _AHEAD_REDUCED.clear()
    todo = list(work)
    if jobs <= 1 or len(todo) < 2 or not sys.platform.startswith("linux"):
        return
    size = {id(k): sum(1 for _ in distinct_nodes([sp.sympify(e) for _, e in k.outputs])) for k, _ in todo}
    _PENDING[:] = sorted(todo, key=lambda kt: -size[id(kt[0])])
    try:
        with mp.get_context("fork").Pool(min(jobs, len(todo))) as pool:
            for i, (red, done) in enumerate(pool.map(_lower_pending, range(len(_PENDING)), chunksize=1)):
                kernel, targets = _PENDING[i]
                _AHEAD_REDUCED[kernel] = red
                for t, low in zip(targets, done, strict=True):
                    _AHEAD[(kernel, t)] = low
    finally:
        _PENDING.clear()


def lower(kernel: Kernel, target: str) -> Lowered:
    ahead = _AHEAD.get((kernel, target))
    if ahead is not None:
        return ahead
    printer = {"c": CPrinter(), "python": PyMathPrinter(), "numpy": NumpyPrinter()}[target]
    r = reduced(kernel)
    return Lowered(
        kernel.name, kernel.doc, r.unpack,
        tuple((str(t), printer.doprint(e)) for t, e in r.temps),
        tuple((n, printer.doprint(e)) for (n, _), e in zip(kernel.outputs, r.reduced, strict=True)),
        tuple(g for g, _ in kernel.inputs), kernel.n_out, r.ops)
