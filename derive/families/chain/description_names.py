"""Names a chain's joints may have (they are labels in the generated code: strings, never identifiers)."""

import re

JOINT_NAME = re.compile(r"[A-Za-z0-9_.:/-]{1,63}")
