"""The derivation commands and their arguments, as data: one table for `python -m derive.cli` and the generated
`wristkin` command. The runtime package cannot import derive, so the generator writes the table into
wristkin/cli.py (`literal`); both build their parsers from it with the same loop (`add_commands`)."""

from __future__ import annotations

import pprint

JOBS_HELP = "derivation processes (default: WRISTKIN_JOBS, else one per core); the bytes do not depend on it"
OUT_HELP = "output directory (default: the checkout's generated/; required outside a checkout)"
CATALOGUE_HELP = "derive the *.toml spec files in DIR (docs/specs.md) instead of the catalogue"

_OUT = (("--out",), {"metavar": "DIR", "help": OUT_HELP})
_JOBS = (("--jobs",), {"type": "int", "metavar": "N", "help": JOBS_HELP})
_CATALOGUE = (("--catalogue",), {"metavar": "DIR", "help": CATALOGUE_HELP})

# (verb, help, ((flags, options), ...)); an option "type" names a builtin ("int", "float"): the table is a literal
COMMANDS = (
    ("regenerate", "derive and write every generated file", (_OUT, _JOBS, _CATALOGUE)),
    ("check", "regenerate into a temporary directory and diff against generated/", (_JOBS,)),
    ("audit", "derive mechanism M alone (all without M): its solvers, CasADi functions and audit report; print "
              "the report paths",
     ((("mechanism",), {"nargs": "?", "metavar": "M"}), _OUT, _JOBS, _CATALOGUE)),
    ("derive", "derive your own robot (a URDF or a spec file) into DIR: Python, C, CasADi and an audit report",
     ((("source",), {"metavar": "SOURCE", "help": "ROBOT.urdf, ROBOT.urdf.xacro or a spec file (docs/specs.md)"}),
      (("--out",), {"metavar": "DIR", "required": True, "help": "output directory"}),
      (("--name",), {"help": "the solver's name (default: the spec's name / the URDF file's stem)"}),
      (("--base",), {"metavar": "LINK", "help": "URDF: the base link (default: the root)"}),
      (("--tip",), {"metavar": "LINK", "help": "URDF: the tip link (default: the only leaf)"}),
      (("--free",), {"metavar": "JOINT", "help": "a redundant arm's joint held as a run-time parameter (without it, "
                                                 "a 7-joint arm's error lists the joints that work)"}),
      (("--redundancy",), {"choices": ["joint", "arm-angle"],
                           "help": "a 7-joint arm's run-time parameter: a held joint (joint, the default: --free) or "
                                   "the arm angle of an arm with a spherical shoulder and wrist (arm-angle)"}),
      (("--xacro-arg",), {"action": "append", "metavar": "NAME=VALUE", "dest": "xacro_args",
                          "help": "a .xacro file's $(arg NAME) (repeat for more)"}),
      (("--package",), {"action": "append", "metavar": "NAME=DIR", "dest": "packages",
                        "help": "where a .xacro file's $(find NAME) is (default: package.xml files and folders "
                                "near the file, then ROS_PACKAGE_PATH / AMENT_PREFIX_PATH)"}),
      (("--geometry-tol",), {"type": "float", "metavar": "TOL",
                             "help": "axes within TOL count as parallel / meeting (default 1e-6: metres and sin "
                                     "of angles)"}),
      (("--no-native",), {"action": "store_true",
                          "help": "do not compile the C into the folder's Python extension (the solvers then "
                                  "run on numpy)"}),
      _JOBS)),
)

_TYPES = {"int": int, "float": float}


def add_commands(sub) -> None:
    """Add each command to the subparsers `sub`: its help, its arguments and verb=name. (wristkin/cli.py carries a
    copy of this loop, adding its note and handler: the runtime cannot import derive; a test holds them equal.)"""
    for verb, helptext, arguments in COMMANDS:
        s = sub.add_parser(verb, help=helptext)
        for flags, options in arguments:
            s.add_argument(*flags, **{k: _TYPES.get(v, v) if k == "type" else v for k, v in options.items()})
        s.set_defaults(verb=verb)


def literal() -> str:
    """COMMANDS as Python source, for the generated wristkin/cli.py (deterministic, within 110 columns)."""
    return pprint.pformat(COMMANDS, width=110, sort_dicts=False)
