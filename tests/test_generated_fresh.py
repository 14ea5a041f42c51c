"""generated/ must equal what the pipeline produces now, byte for byte, and regeneration is deterministic."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def test_generated_is_fresh_and_deterministic(tmp_path):
    """Regenerate under two hash seeds: both equal each other and the committed generated/."""
    outs = []
    for seed in ("0", "12345"):
        out = tmp_path / f"gen{seed}"
        env = {**os.environ, "PYTHONHASHSEED": seed}
        subprocess.run([sys.executable, "-m", "derive.cli", "regenerate", "--out", str(out)], cwd=ROOT, env=env,
                       check=True, capture_output=True, text=True)
        outs.append(out)
    files = sorted(p.relative_to(outs[0]).as_posix() for p in outs[0].rglob("*") if p.is_file())
    assert files, "regeneration produced nothing"
    for rel in files:
        assert (outs[0] / rel).read_bytes() == (outs[1] / rel).read_bytes(), f"non-deterministic: {rel}"
    committed = sorted(p.relative_to(ROOT / "generated").as_posix() for p in (ROOT / "generated").rglob("*")
                       if p.is_file() and "__pycache__" not in p.parts)
    assert committed == files, "generated/ has missing or extra files: run `make regenerate`"
    stale = [rel for rel in files if (ROOT / "generated" / rel).read_bytes() != (outs[0] / rel).read_bytes()]
    assert not stale, f"generated/ is stale ({stale}): run `make regenerate` and commit"


def test_no_timestamps_paths_or_hosts_in_generated():
    import socket

    host = socket.gethostname()
    for p in (ROOT / "generated").rglob("*"):
        if p.is_file() and p.suffix in {".py", ".c", ".h", ".md", ".json"}:
            text = p.read_text()
            assert str(ROOT) not in text and "/tmp/" not in text, p
            assert host not in text or len(host) < 4, p
