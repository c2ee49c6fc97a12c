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


def pytest_collection_modifyitems(session, config, items):
    """Costliest first (marker ``cost``), the rest in collection order: pytest-xdist
    hands tests out in this order, so the long co-simulations start at once and the short tests fill the
    gaps, and both workers finish at about the same time."""
    def cost(item):
        m = item.get_closest_marker("cost")
        return -float(m.args[0]) if m else 0.0
    items.sort(key=cost)
