"""A stand-in for the one name the generated wristkin/cli.py defines after the runtime source it inlines
(runtime/python/cli.py): the derivation commands' table, here taken from derive/cli_commands.py itself (the
generated module carries it as a literal: the runtime cannot import derive). Never inlined: it lets the source be
imported, linted and tested as it is (tests/test_cli_source.py)."""

from __future__ import annotations

from derive.cli_commands import COMMANDS as _DERIVATION_COMMANDS  # noqa: F401  (re-exported)
