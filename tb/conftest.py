"""pytest configuration for the cocotb testbenches: makes tb/ (runner), flow/ (flow tools) and gen/ importable."""
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
for p in (ROOT / "flow", ROOT / "tb", ROOT / "gen"):
    if str(p) not in sys.path:
        sys.path.insert(0, str(p))

# subprocesses (empc CLI, simulators) must import this checkout's generator too, whatever the shared
# venv's editable install points at
os.environ["PYTHONPATH"] = os.pathsep.join([str(ROOT / "gen")] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])


def pytest_configure(config):
    config.addinivalue_line("markers", "full: long scenario, run by `make sim-full` only")
    config.addinivalue_line("markers", "cost(seconds): estimated run time; make sim starts the costliest tests first")


# Seconds on an idle core of long tests without a ``cost`` mark in their file (a mark there wins): measured
# with -n 1 beside a loaded make sim (x 0.42, the factor of the marked tests' measured idle times).  Without
# them these Icarus runs were handed out last, in collection order (tb/test_ref_gen*.py sort late), and
# test_ref_gen alone (~150 s) could start when everything else was done.
COST_UNMARKED = {
    "tb/test_ref_gen.py::test_ref_gen": 150, "tb/test_ref_gen_axes.py::test_ref_gen_axes": 93,
    "tb/test_sens_check.py::test_sens_check": 29, "tb/test_ref_gen.py::test_ref_gen_n1": 17,
    "tb/test_ref_gen.py::test_ref_gen_governed": 17, "tb/test_pwm_center.py::test_pwm_center_phase": 12,
    "tb/test_pwm_center.py::test_pwm_center_phase_default": 11, "tb/test_xform.py::test_xform": 7,
    "tb/test_regblock.py::test_axis_regs": 7,
}


def pytest_collection_modifyitems(session, config, items):
    """Costliest first (marker ``cost``, else COST_UNMARKED), the rest in collection order: pytest-xdist
    hands tests out in this order, so the long co-simulations start at once and the short tests fill the
    gaps, and both workers finish at about the same time."""
    def cost(item):
        m = item.get_closest_marker("cost")
        if m:
            return -float(m.args[0])
        return -float(COST_UNMARKED.get(item.nodeid, 0.0))
    items.sort(key=cost)
