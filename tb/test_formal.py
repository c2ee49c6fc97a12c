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


# seconds on one idle core (make sim starts the costliest first; the rest are a few seconds).  prove_cp as in
# the clean-clone .ci/run of c9990f2 (88 s); the others scaled from one loaded make sim run
# (build/reports/formal.json "seconds" x 88 / 190): the mutants of the deep axis_periph tasks run as long as a
# proof (a counterexample near the task's depth), not the default 5 s.
COST = {"axis_periph/prove_cp": 88, "axis_periph/prove_pe": 74, "axis_periph/cover": 62, "axis_periph/mutant6:bmc_pe": 49,
        "axis_periph/mutant3:prove_pe": 44, "axis_periph/mutant0:prove_pe": 36, "axis_periph/bmc_pe": 37,
        "axis_periph/mutant4:bmc_pe": 29, "axis_periph/mutant2:prove_pe": 22, "out_route/prove": 8, "out_kill/bmc": 7,
        "axis_periph/mutant1:prove_pe": 6}


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
