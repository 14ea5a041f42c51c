"""The catalogue: the mechanisms `make regenerate` derives are exactly the spec files in catalogue/*.toml (a
checkout's, else the copy an install ships as derive/specs). Any other spec file goes through the same
path (`load`)."""

from __future__ import annotations

from pathlib import Path

from .families import FAMILIES
from .render import CATALOGUE
from .spec import Spec, SpecError, common


def load(path: str | Path):
    """The mechanism a spec file describes (its family reads and validates the rest)."""
    spec = Spec.load(path)
    fields = common(spec)
    family = FAMILIES.get(fields["family"])
    if family is None:
        raise spec.error("family", f"one of the families {', '.join(sorted(FAMILIES))}", fields["family"])
    return family.from_spec(spec)


_REGISTRY: dict[Path, dict] = {}


def registry(folder: str | Path = CATALOGUE) -> dict:
    """name -> mechanism for every spec in `folder` (loaded once per process); a spec's name is its file's stem,
    so two files cannot claim one name."""
    folder = Path(folder)
    if folder not in _REGISTRY:
        mechs = {}
        files = sorted(folder.glob("*.toml"))
        if not files:
            raise SpecError(folder, "", "a folder of *.toml spec files")
        for path in files:
            mech = load(path)
            if mech.NAME != path.stem:
                raise SpecError(path, "name", f"the file's stem {path.stem!r} (a catalogue spec is named by its file)",
                                mech.NAME)
            mechs[mech.NAME] = mech
        _REGISTRY[folder] = mechs
    return _REGISTRY[folder]
