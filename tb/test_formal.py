"""Runs every SymbiYosys proof task (formal/*.sby) and every mutation check through flow/formal.py, one per test.

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


# seconds on one idle core (make sim starts the costliest first; the rest are 2-5 s): CPU s of
# `flow/formal.py <label>` with smtbmc yices (measured one at a time on a shared machine, see flow/formal.py)
COST = {"axis_periph/prove_cp": 18, "axis_periph/bmc_pe": 15, "axis_periph/mutant4:bmc_pe": 12, "axis_periph/prove_pe": 11,
        "axis_periph/mutant3:prove_pe": 10, "axis_periph/mutant6:bmc_pe": 10, "axis_periph/cover": 8,
        "axis_periph/mutant0:prove_pe": 7, "axis_periph/mutant2:prove_pe": 7, "out_route/prove": 6,
        "out_route/map": 15}


@pytest.mark.skipif(formal.sby_cmd() is None, reason="yowasp-sby not installed")
@pytest.mark.parametrize("label", [pytest.param(l, marks=pytest.mark.cost(COST.get(l, 5))) for l in formal.labels()])
def test_formal(label):
    """One proof task or one mutant per test, so pytest-xdist spreads them over the workers."""
    r = subprocess.run([sys.executable, str(ROOT / "flow" / "formal.py"), label], cwd=ROOT,
                       capture_output=True, text=True, timeout=1200)
    print(r.stdout[-20000:])
    print(r.stderr[-5000:], file=sys.stderr)
    lines = [l for l in r.stdout.splitlines() if l.startswith(("PASS", "FAIL"))]
    assert lines, f"flow/formal.py ran nothing for {label}"
    assert r.returncode == 0, f"{label}:\n" + "\n".join(l for l in lines if l.startswith("FAIL"))


def test_every_proof_has_mutants():
    """A proof without a mutant it must catch could be vacuous (rules: mutants for every safety proof)."""
    for sby in sorted(formal.FORMAL.glob("*.sby")):
        assert formal.mutants_of(sby.read_text()), f"{sby.name} has no '# mutant:' line"


def test_every_engine_uses_the_pinned_solver():
    """One solver for every proof (SOLVER in flow/formal.py, installed by requirements.txt): yices-smt2 is 4-15x
    faster than z3 on these proofs; a task left on another solver would quietly cost make sim minutes."""
    import re
    for sby in sorted(formal.FORMAL.glob("*.sby")):
        m = re.search(r"^\[engines\]\s*\n(.*?)(?=^\[|\Z)", sby.read_text(), re.M | re.S)
        assert m, f"{sby.name} has no [engines] section"
        for line in m.group(1).splitlines():
            line = line.split("#", 1)[0].strip()
            if line:
                engine = line.split(":", 1)[-1].split() if re.match(r"\S+:\s", line) else line.split()
                assert engine[:2] == ["smtbmc", formal.SOLVER], f"{sby.name}: [engines] '{line}' (expected smtbmc {formal.SOLVER})"
