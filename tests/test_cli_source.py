"""The command line's runtime source (runtime/python/cli.py) imported and run as it is (cli_stand_in binds the
derivation commands' table from derive/cli_commands.py), and the generated wristkin/cli.py carrying it verbatim
with that table as a literal (tests/test_cli.py runs the generated one end to end)."""

from __future__ import annotations

import ast
import json
import sys
from pathlib import Path

import pytest

from derive import cli_commands, runtime_files

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def cli():
    sys.path.insert(0, str(ROOT / "runtime" / "python"))
    try:
        import cli as source
    finally:
        sys.path.remove(str(ROOT / "runtime" / "python"))
    return source


def test_the_source_solves_and_reports_bad_input(cli, capsys):
    assert cli.main(["ik", "underactuated_wrist", "--pose", "-35.99", "0.26", "38.93", "--json"]) == cli.EXIT_OK
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "ok" and len(out["solutions"]) == 8
    assert cli.main(["fk", "underactuated_wrist", "--joints", "1", "2"]) == cli.EXIT_USAGE
    assert "error" in capsys.readouterr().err
    assert cli.main(["list"]) == cli.EXIT_OK and "puma560" in capsys.readouterr().out


def test_the_source_offers_every_derivation_command(cli):
    sub = next(a for a in cli.build_parser()._actions if a.dest == "command")
    assert {verb for verb, _, _ in cli_commands.COMMANDS} <= set(sub.choices)


def test_the_generated_cli_is_the_source_and_the_derived_table():
    text = (ROOT / "generated" / "python" / "wristkin" / "cli.py").read_text()
    assert runtime_files.inline("python/cli.py") in text
    table = text[text.index("_DERIVATION_COMMANDS = ") + len("_DERIVATION_COMMANDS = "):text.index("\n\n\nif __name__")]
    assert ast.literal_eval(table) == cli_commands.COMMANDS
    assert len((ROOT / "templates" / "python" / "cli.py.jinja").read_text().splitlines()) <= 400
