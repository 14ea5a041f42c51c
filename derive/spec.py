"""Spec files: a mechanism described as TOML (the catalogue in catalogue/*.toml, or a user's own file).

Every spec names its `family`, its `name` (the generated files' stem, a C identifier) and a `title`; the rest is
the family's (docs/specs.md). This module reads TOML and gives the families typed accessors that turn every
problem into a `SpecError` naming the file, the field and what was expected, so a malformed spec never ends in a
traceback. It knows no family and no mechanism.
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

IDENTIFIER = re.compile(r"[a-z][a-z0-9_]{0,62}")
_MISSING = object()


class SpecError(ValueError):
    """A spec file that cannot describe a mechanism: names the file, the field and what was expected."""

    def __init__(self, file: str | Path, field: str, expected: str, got: object = _MISSING, option: str = ""):
        self.file, self.field, self.expected = str(file), field, expected
        # a value given on the command line is named as the option the user typed, not as a spec field
        where = f"{self.file}: {option}" if option else f"{self.file}: field '{field}'" if field else self.file
        text = f"{where}: expected {expected}"
        if got is not _MISSING:
            shown = repr(got)
            text += f", got {shown if len(shown) <= 80 else shown[:77] + '...'}"
        super().__init__(text)


def _kind(value) -> str:
    return {bool: "a boolean", int: "an integer", float: "a number", str: "a string", list: "an array",
            dict: "a table"}.get(type(value), type(value).__name__)


class Spec:
    """One table of a spec file (the whole file, or a sub-table), with the path of its fields for errors."""

    def __init__(self, data: dict, file: str | Path, prefix: str = "", options: dict[str, str] | None = None):
        self.data, self.file, self.prefix = data, str(file), prefix
        self.options = dict(options or {})  # field -> the command-line option that gave it (e.g. "free": "--free")

    def given(self, field: str, value, option: str) -> None:
        """Set `field` from the command-line `option` (its errors then name the option)."""
        self.data[field] = value
        self.options[field] = option

    # ---------------------------------------------------------------------------------------------- loading
    @classmethod
    def load(cls, path: str | Path) -> Spec:
        path = Path(path)
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            raise SpecError(path, "", "a readable TOML file", exc.strerror or str(exc)) from None
        except UnicodeDecodeError:
            raise SpecError(path, "", "UTF-8 text") from None
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise SpecError(path, "", f"valid TOML ({exc})") from None
        return cls(data, path)

    # ------------------------------------------------------------------------------------------- accessors
    def path(self, field: str) -> str:
        return f"{self.prefix}.{field}" if self.prefix else field

    def error(self, field: str, expected: str, got: object = _MISSING) -> SpecError:
        option = self.options.get(field, "") if not self.prefix else ""
        return SpecError(self.file, self.path(field) if field else self.prefix, expected, got, option)

    def has(self, field: str) -> bool:
        return field in self.data

    def raw(self, field: str, default=_MISSING):
        if field in self.data:
            return self.data[field]
        if default is _MISSING:
            raise self.error(field, "this field (it is required)")
        return default

    def only(self, allowed) -> None:
        """Reject fields the family does not know (a typo must not silently fall back to a default)."""
        extra = sorted(set(self.data) - set(allowed))
        if extra:
            raise self.error(extra[0], f"one of the known fields ({', '.join(sorted(allowed))}); unknown field")

    def text(self, field: str, default=_MISSING) -> str:
        v = self.raw(field, default)
        if not isinstance(v, str) or not v.strip():
            raise self.error(field, "a non-empty string", v)
        return v

    def identifier(self, field: str) -> str:
        v = self.raw(field)
        if not isinstance(v, str) or not IDENTIFIER.fullmatch(v):
            raise self.error(field, "a lower-case identifier ([a-z][a-z0-9_]*, at most 63 characters)", v)
        return v

    def choice(self, field: str, options, default=_MISSING) -> str:
        v = self.raw(field, default)
        if v not in options:
            raise self.error(field, f"one of {', '.join(repr(o) for o in options)}", v)
        return v

    def number(self, field: str, default=_MISSING, *, lo: float | None = None, hi: float | None = None,
               unit: str = "") -> float:
        v = self.raw(field, default)
        what = "a number" + (f" ({unit})" if unit else "")
        if isinstance(v, bool) or not isinstance(v, int | float):
            raise self.error(field, what, v)
        x = float(v)
        if not math.isfinite(x):
            raise self.error(field, f"a finite {what[2:]}", v)
        if (lo is not None and x < lo) or (hi is not None and x > hi):
            raise self.error(field, f"{what} in [{lo if lo is not None else '-inf'}, "
                                    f"{hi if hi is not None else 'inf'}]", v)
        return x

    def vector(self, field: str, length: int, default=_MISSING, *, unit: str = "") -> tuple[float, ...]:
        v = self.raw(field, default)
        if not isinstance(v, list) or len(v) != length:
            raise self.error(field, f"an array of {length} numbers" + (f" ({unit})" if unit else ""), v)
        sub = Spec({str(i): x for i, x in enumerate(v)}, self.file, self.path(field))
        return tuple(sub.number(str(i), unit=unit) for i in range(length))

    def table(self, field: str, default=_MISSING) -> Spec:
        v = self.raw(field, {} if default is not _MISSING else _MISSING)
        if not isinstance(v, dict):
            raise self.error(field, "a table", _kind(v))
        return Spec(v, self.file, self.path(field))

    def tables(self, field: str, default=_MISSING) -> list[Spec]:
        """An array of tables ([[field]] blocks)."""
        v = self.raw(field, [] if default is not _MISSING else _MISSING)
        if not isinstance(v, list) or not all(isinstance(x, dict) for x in v):
            raise self.error(field, "an array of tables ([[" + self.path(field) + "]] blocks)", _kind(v))
        return [Spec(x, self.file, f"{self.path(field)}[{i}]") for i, x in enumerate(v)]


# names the generated package and C folder already use for the runtime
RESERVED_NAMES = ("cli", "wristkin", "wristkin_common", "wristkin_runtime")


def common(spec: Spec) -> dict:
    """The fields every spec has: family, name, title and (optional) source."""
    name = spec.identifier("name")
    if name in RESERVED_NAMES:
        raise spec.error("name", f"a name other than {', '.join(RESERVED_NAMES)} (the runtime's files)", name)
    return {"family": spec.identifier("family"), "name": name, "title": spec.text("title"),
            "source": spec.text("source", "user spec")}


COMMON_FIELDS = ("family", "name", "title", "source")
