"""Each mechanism's declared C verbs (Mechanism.C_API, which the CPython binding is rendered from) are the ones its
generated header declares: the core never reads a header to learn them, so this holds the two together."""

from __future__ import annotations

from pathlib import Path

import derived_cache
import pytest

from derive import own_robot
from derive.catalogue import registry
from derive.mechanism import SERIAL_C_API

ROOT = Path(__file__).resolve().parent.parent


def declared_in(header: str, name: str) -> dict:
    """The optional verbs a header declares (read from its text: the test's independent reading)."""
    def has(fn: str) -> bool:
        return f"wk_{name}_{fn}(" in header
    return {"pose12": f"#define WK_{name.upper()}_N_POSE 12" in header, "ik_near": has("ik_near"),
            "jacobian": has("jacobian"), "fk_matrix": has("fk_matrix"), "frames": has("design_set_frames"),
            "atlas": has("atlas_batch"), "atlas_conditioning": has("atlas_conditioning"),
            "atlas_home": has("atlas_home_batch")}


@pytest.mark.parametrize("name", sorted(registry()))
def test_the_catalogue_declares_the_verbs_its_header_has(name):
    api = registry()[name].C_API
    header = (ROOT / "generated" / "c" / f"{name}.h").read_text()
    assert {f: getattr(api, f) for f in api.__dataclass_fields__} == declared_in(header, name)


def test_a_derived_robot_declares_the_verbs_its_header_has(tmp_path):
    """A user robot's module (its IK derived as straight-line stages): the serial family's verbs."""
    urdf = ROOT / "tests" / "robots" / "ur5e" / "ur5e.urdf"
    derived_cache.derive(urdf, tmp_path, name="ur", native=False)
    api = own_robot.load(urdf, name="ur").C_API
    assert api == SERIAL_C_API
    header = (tmp_path / "c" / "ur.h").read_text()
    assert {f: getattr(api, f) for f in api.__dataclass_fields__} == declared_in(header, "ur")


def test_a_derive_folder_keeps_every_robots_declared_verbs(tmp_path):
    """Two robots derived one command at a time into one folder: native/api.json holds both records, and the
    folder's extension, rendered from them, serves both (the second derive used to re-read every header)."""
    import json
    import os

    for robot in ("ur5e", "kr6"):
        own_robot.derive(ROOT / "tests" / "robots" / robot / f"{robot}.urdf", tmp_path, progress=lambda _: None)
    assert sorted(json.loads((tmp_path / "native" / "api.json").read_text())) == ["kr6", "ur5e"]
    for robot in ("ur5e", "kr6"):
        m = own_robot.import_solver(tmp_path, robot)
        if os.environ.get("WRISTKIN_BACKEND") != "numpy":  # make test-portable runs the numpy fallback
            assert m.BACKEND == "c"
        q = [0.3] * 6
        assert m.ik(m.fk_matrix(q)).count >= 1
