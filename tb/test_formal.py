"""Runs every SymbiYosys proof (formal/*.sby) and its mutation checks through flow/formal.py.

Skipped only when yowasp-sby is not installed (it is part of requirements.txt).
Same checks as `make formal`; see flow/formal.py for what PASS means.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "flow"))
import formal  # noqa: E402  (flow/formal.py)


@pytest.mark.skipif(formal.sby_cmd() is None, reason="yowasp-sby not installed")
def test_formal():
    r = subprocess.run([sys.executable, str(ROOT / "flow" / "formal.py")], cwd=ROOT,
                       capture_output=True, text=True, timeout=1200)
    print(r.stdout[-20000:])
    print(r.stderr[-5000:], file=sys.stderr)
    lines = [l for l in r.stdout.splitlines() if l.startswith(("PASS", "FAIL"))]
    assert lines, "flow/formal.py ran no proof"
    assert r.returncode == 0, "formal proofs failed:\n" + "\n".join(l for l in lines if l.startswith("FAIL"))
