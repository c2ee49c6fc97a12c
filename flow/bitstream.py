"""`make bitstream`: Xilinx ISE 14.7 back end for the Yosys netlist of lx_rocon_top.

    ngdbuild -> map -> par -> trce -> bitgen     (in build/bitstream/)

Inputs: build/synth/lx_rocon_top.edf (`make synth`) and constraints/lx_rocon.ucf.
Outputs: build/bitstream/lx_rocon_top.bit (+ .bin), lx_rocon_top.twr (trce timing
report), the ISE reports (.bld, _map.mrp, .par), build/reports/bitstream.json.

Order of checks (each one refuses with exit status 1 and a clear message):
 1. every top-level port bit has a LOC and an IOSTANDARD in the UCF.  The port bits come
    from the Yosys JSON netlist (build/synth/lx_rocon_top.json) or, without it, from a
    port parse of rtl/lx_rocon_top.v with its default parameters.  Done first, so it is
    testable without ISE; the committed UCF has only placeholder LOCs (the LX_RoCoN pin
    map is not public) and is refused until the pins are filled in.
 2. the EDIF netlist exists (run `make synth`).
 3. the ISE tools (ngdbuild map par trce bitgen) are on PATH (source ISE's settings64.sh).
Timing errors reported by trce make the exit status 1 (the .bit is still written, so it
can be inspected), unless --allow-timing-errors.

Part: EMPC_PART or --part, default xc6slx9-2-tqg144 (speed grade -2, TQG144: the smallest
XC6SLX9 package; set the one on the board, e.g. xc6slx9-2-csg324).
Extra bitgen options: EMPC_BITGEN_OPTS (e.g. "-g StartupClk:CClk").
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
from pathlib import Path

from files import ROOT  # flow/ is on sys.path

TOP = "lx_rocon_top"
UCF = ROOT / "constraints" / "lx_rocon.ucf"
SYNTH_DIR = ROOT / "build" / "synth"
OUT_DIR = ROOT / "build" / "bitstream"
REPORT = ROOT / "build" / "reports" / "bitstream.json"
TOOLS = ("ngdbuild", "map", "par", "trce", "bitgen")
DEFAULT_PART = "xc6slx9-2-tqg144"


# ---- ports --------------------------------------------------------------------------------
def _bit_names(name: str, width: int, lsb: int = 0, upto: bool = False) -> list[str]:
    """EDIF/UCF names of a port's bits as Yosys writes them: scalar if 1 bit wide, else name[i]."""
    if width == 1:
        return [name]
    idx = [lsb + width - 1 - i for i in range(width)] if upto else [lsb + i for i in range(width)]
    return [f"{name}[{i}]" for i in sorted(idx)]


def ports_from_json(netlist: Path, top: str = TOP) -> dict[str, dict]:
    """{port: {direction, bits: [names]}} from a Yosys JSON netlist."""
    data = json.loads(netlist.read_text())
    mod = data["modules"].get(top)
    if mod is None:
        mod = next(m for m in data["modules"].values() if str(m.get("attributes", {}).get("top", "0")).lstrip("0") == "1")
    out = {}
    for name, p in mod["ports"].items():
        out[name] = {"direction": p["direction"],
                     "bits": _bit_names(name, len(p["bits"]), int(p.get("offset", 0)), bool(p.get("upto", 0)))}
    return out


def _eval_int(expr: str, params: dict[str, int]) -> int:
    expr = expr.strip()
    # `(A == k) ? x : y` (lx_rocon_top's board-line counts by NAXES): only the chosen branch is evaluated,
    # so a header macro in the other one does not matter
    m = re.fullmatch(r"\((\w+)\s*==\s*(\w+)\)\s*\?\s*([^:?]+?)\s*:\s*([^:?]+)", expr)
    if m:
        a, b = (_eval_int(x, params) for x in m.group(1, 2))
        return _eval_int(m.group(3) if a == b else m.group(4), params)
    if not re.fullmatch(r"[\w\s+\-*/()]+", expr):
        raise ValueError(f"cannot evaluate port range expression {expr!r}")
    expr = expr.replace("/", "//")
    return int(eval(expr, {"__builtins__": {}}, dict(params)))  # noqa: S307 - digits, names, + - * / only


def ports_from_verilog(path: Path, overrides: dict[str, int] | None = None) -> dict[str, dict]:
    """Port bits of an ANSI-style Verilog module with its default (or overridden) parameters.

    Handles ``input|output|inout [wire|reg] [signed] [msb:lsb] name`` with integer
    parameter expressions in the range; enough for lx_rocon_top.
    """
    text = path.read_text()
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    params: dict[str, int] = dict(overrides or {})      # overrides first: derived defaults follow them
    for m in re.finditer(r"\bparameter\s+(?:integer\s+)?(\w+)\s*=\s*((?:\([^()]*\)|[^,;()])+)", text):
        if m.group(1) in params:
            continue
        try:
            params[m.group(1)] = _eval_int(m.group(2), params)
        except (ValueError, NameError):      # e.g. a header macro: a port using it needs an override
            pass
    out = {}
    for m in re.finditer(r"\b(input|output|inout)\s+(?:wire\s+|reg\s+)?(?:signed\s+)?(\[[^\]]+\])?\s*(\w+)", text):
        direction, rng, name = m.group(1), m.group(2), m.group(3)
        if rng:
            msb, lsb = (_eval_int(x, params) for x in rng[1:-1].split(":"))
            width, low, upto = abs(msb - lsb) + 1, min(msb, lsb), msb < lsb
        else:
            width, low, upto = 1, 0, False
        out[name] = {"direction": direction, "bits": _bit_names(name, width, low, upto)}
    return out


def top_ports(netlist: Path | None = None, verilog: Path | None = None) -> tuple[dict[str, dict], str]:
    """Port bits of the top: from the JSON netlist when it exists, else from the Verilog source."""
    netlist = netlist if netlist is not None else SYNTH_DIR / f"{TOP}.json"
    if netlist.exists():
        return ports_from_json(netlist), str(netlist)
    verilog = verilog or ROOT / "rtl" / f"{TOP}.v"
    return ports_from_verilog(verilog), str(verilog)


# ---- UCF ----------------------------------------------------------------------------------
def _norm(name: str) -> str:
    """UCF bus bits may be written name<3> or name[3]."""
    return re.sub(r"<(\d+)>$", r"[\1]", name.strip())


def parse_ucf(text: str) -> list[tuple[str, str, str]]:
    """(kind, name, constraints) for every ``NET``/``INST``/``PIN`` statement, comments removed."""
    body = "\n".join(line.split("#", 1)[0] for line in text.splitlines())
    out = []
    for stmt in body.split(";"):
        stmt = " ".join(stmt.split())
        m = re.match(r'^(NET|INST|PIN)\s+"?([^"\s]+)"?\s*(.*)$', stmt, re.I)
        if m:
            out.append((m.group(1).upper(), m.group(2), m.group(3)))
    return out


def ucf_net_constraints(text: str) -> dict[str, dict[str, str]]:
    """{net: {LOC: ..., IOSTANDARD: ..., ...}} from NET statements (``a | b`` lists split)."""
    nets: dict[str, dict[str, str]] = {}
    for kind, name, cons in parse_ucf(text):
        if kind != "NET":
            continue
        d = nets.setdefault(_norm(name), {})
        for c in cons.split("|"):
            c = c.strip()
            if not c:
                continue
            k, _, v = c.partition("=")
            d[k.strip().upper()] = v.strip().strip('"')
    return nets


def check_pins(ports: dict[str, dict], ucf_text: str) -> dict[str, list[str]]:
    """Port bits without a LOC / without an IOSTANDARD, LOCs on names that are no port bit,
    and package pins used twice.  All lists empty: the UCF is complete."""
    nets = ucf_net_constraints(ucf_text)
    bits = [b for p in ports.values() for b in p["bits"]]
    bitset = set(bits)
    no_loc = [b for b in bits if not nets.get(b, {}).get("LOC")]
    no_std = [b for b in bits if not nets.get(b, {}).get("IOSTANDARD")]
    unknown = sorted(n for n, c in nets.items() if c.get("LOC") and n not in bitset)
    seen: dict[str, str] = {}
    dup = []
    for b in bits:
        loc = nets.get(b, {}).get("LOC", "").upper()
        if loc:
            if loc in seen:
                dup.append(f"{loc}: {seen[loc]} and {b}")
            seen.setdefault(loc, b)
    return {"missing_loc": no_loc, "missing_iostandard": no_std, "unknown_loc_nets": unknown, "duplicate_loc": dup}


def edif_net_names(edif: Path) -> set[str]:
    """Net and port names as ISE will see them in the EDIF (``rename`` strings or plain ids)."""
    text = edif.read_text(errors="replace")
    names = set(re.findall(r'\((?:net|port)\s+\(rename\s+\S+\s+"([^"]+)"\)', text))
    names |= set(re.findall(r"\((?:net|port)\s+([A-Za-z_][\w]*)\b", text))
    names |= set(re.findall(r'\(port\s+\(array\s+\(rename\s+\S+\s+"([^"\[]+)', text))
    names |= set(re.findall(r"\(port\s+\(array\s+([A-Za-z_]\w*)\b", text))
    return {n.split("[")[0] if re.search(r"\[\d+:\d+\]$", n) else n for n in names}


# ---- ISE ----------------------------------------------------------------------------------
def find_tools(path: str | None = None) -> tuple[dict[str, str], list[str]]:
    found, missing = {}, []
    for t in TOOLS:
        p = shutil.which(t, path=path)
        if p:
            found[t] = p
        else:
            missing.append(t)
    return found, missing


def ise_commands(tools: dict[str, str], part: str, edif: Path, ucf: Path, top: str = TOP,
                 bitgen_opts: list[str] | None = None) -> list[tuple[str, list[str]]]:
    """The ISE command lines, in order, to run in the output directory."""
    return [
        ("ngdbuild", [tools["ngdbuild"], "-intstyle", "xflow", "-dd", "_ngo", "-p", part,
                      "-uc", str(ucf), str(edif), f"{top}.ngd"]),
        ("map", [tools["map"], "-intstyle", "xflow", "-w", "-p", part, "-o", f"{top}_map.ncd",
                 f"{top}.ngd", f"{top}.pcf"]),
        ("par", [tools["par"], "-intstyle", "xflow", "-w", f"{top}_map.ncd", f"{top}.ncd", f"{top}.pcf"]),
        ("trce", [tools["trce"], "-intstyle", "xflow", "-v", "20", "-fastpaths", "-o", f"{top}.twr",
                  f"{top}.ncd", f"{top}.pcf"]),
        ("bitgen", [tools["bitgen"], "-intstyle", "xflow", "-w", "-g", "Binary:Yes"] + list(bitgen_opts or [])
                   + [f"{top}.ncd", f"{top}.bit", f"{top}.pcf"]),
    ]


def timing_errors(twr: Path) -> int | None:
    """Number of timing errors in a trce report (None if it cannot be read)."""
    if not twr.exists():
        return None
    m = re.search(r"Timing errors:\s*(\d+)", twr.read_text(errors="replace"))
    return int(m.group(1)) if m else None


def fabric_clock_constrained(twr: Path) -> bool:
    """True if trce analysed a period derived from TS_clk_in for the PLL output (TS_clk_in / 2)."""
    if not twr.exists():
        return False
    return re.search(r"TS_clk_in\s*/\s*2\b", twr.read_text(errors="replace")) is not None


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description="ISE 14.7 ngdbuild/map/par/trce/bitgen for lx_rocon_top")
    ap.add_argument("--part", default=os.environ.get("EMPC_PART", DEFAULT_PART))
    ap.add_argument("--ucf", type=Path, default=UCF)
    ap.add_argument("--edif", type=Path, default=SYNTH_DIR / f"{TOP}.edf")
    ap.add_argument("--netlist", type=Path, default=SYNTH_DIR / f"{TOP}.json", help="Yosys JSON (port widths)")
    ap.add_argument("--out", type=Path, default=OUT_DIR)
    ap.add_argument("--report", type=Path, default=REPORT)
    ap.add_argument("--check-only", action="store_true", help="only check the UCF pins (no ISE)")
    ap.add_argument("--allow-timing-errors", action="store_true")
    args = ap.parse_args(argv)

    # 1. pins
    ports, source = top_ports(args.netlist)
    if not args.ucf.exists():
        print(f"bitstream: REFUSED - constraints file {args.ucf} not found", file=sys.stderr)
        return 1
    res = check_pins(ports, args.ucf.read_text())
    nbits = sum(len(p["bits"]) for p in ports.values())
    bad = False
    if res["missing_loc"]:
        bad = True
        print(f"bitstream: REFUSED - {len(res['missing_loc'])} of {nbits} top-level port bits have no LOC in "
              f"{os.path.relpath(args.ucf, ROOT)} (ports from {os.path.relpath(source, ROOT)}):\n  "
              + "\n  ".join(res["missing_loc"])
              + "\nFill in the '==== PIN LOCATIONS' section from the LX_RoCoN schematic.", file=sys.stderr)
    if res["missing_iostandard"]:
        bad = True
        print("bitstream: REFUSED - port bits without IOSTANDARD:\n  " + "\n  ".join(res["missing_iostandard"]),
              file=sys.stderr)
    if res["unknown_loc_nets"]:
        bad = True
        print("bitstream: REFUSED - LOC on names that are not port bits of the top (stale UCF or bus naming; "
              "1-bit ports are scalar, wider ones name[i]):\n  " + "\n  ".join(res["unknown_loc_nets"]), file=sys.stderr)
    if res["duplicate_loc"]:
        bad = True
        print("bitstream: REFUSED - package pin used twice:\n  " + "\n  ".join(res["duplicate_loc"]), file=sys.stderr)
    if bad:
        return 1
    print(f"bitstream: all {nbits} port bits have LOC and IOSTANDARD")
    if args.check_only:
        return 0

    # 2. netlist
    if not args.edif.exists():
        print(f"bitstream: ERROR - no netlist {args.edif}: run `make synth` first", file=sys.stderr)
        return 1
    nets = edif_net_names(args.edif)
    missing_nets = sorted({_norm(n) for k, n, _ in parse_ucf(args.ucf.read_text())
                           if k == "NET" and "*" not in n and _norm(n).split("[")[0] not in nets and _norm(n) not in nets})
    if missing_nets:
        print("bitstream: WARNING - UCF nets not found in the EDIF (ngdbuild will stop on them): "
              + ", ".join(missing_nets), file=sys.stderr)

    # 3. tools
    tools, missing = find_tools()
    if missing:
        print(f"bitstream: ERROR - Xilinx ISE 14.7 tools not on PATH: {', '.join(missing)}.\n"
              f"  Source <ISE>/14.7/ISE_DS/settings64.sh (ISE is the only flow for Spartan-6) and rerun.\n"
              f"  Without ISE, `make synth` already gives the netlist {os.path.relpath(args.edif, ROOT)} and the "
              f"resource/timing-proxy report build/reports/synth.json.", file=sys.stderr)
        return 2

    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    bitgen_opts = os.environ.get("EMPC_BITGEN_OPTS", "").split()
    steps = ise_commands(tools, args.part, args.edif.resolve(), args.ucf.resolve(), bitgen_opts=bitgen_opts)
    report = {"part": args.part, "edif": str(args.edif), "ucf": str(args.ucf), "steps": []}
    for name, cmd in steps:
        print(f"bitstream: {name}: {' '.join(cmd)}", flush=True)
        t0 = time.time()
        with open(out / f"{name}.out", "w") as log:
            r = subprocess.run(cmd, cwd=out, stdout=log, stderr=subprocess.STDOUT)
        report["steps"].append({"tool": name, "rc": r.returncode, "seconds": round(time.time() - t0, 1)})
        if r.returncode != 0:
            print(f"bitstream: ERROR - {name} failed (exit {r.returncode}), log {out / (name + '.out')}", file=sys.stderr)
            _write(args.report, report)
            return 1
    nerr = timing_errors(out / f"{TOP}.twr")
    report["timing_errors"] = nerr
    report["fabric_clock_constrained"] = fabric_clock_constrained(out / f"{TOP}.twr")
    if not report["fabric_clock_constrained"]:
        print("bitstream: WARNING - the trce report shows no period derived from TS_clk_in for the PLL "
              "output (expected 'TS_clk_in / 2'): the 100 MHz fabric clock may be unconstrained", file=sys.stderr)
    report["bit"] = str(out / f"{TOP}.bit")
    _write(args.report, report)
    print(f"bitstream: {out / (TOP + '.bit')}, timing report {out / (TOP + '.twr')}, timing errors: {nerr}")
    if nerr and not args.allow_timing_errors:
        print(f"bitstream: FAIL - {nerr} timing errors (see {TOP}.twr)", file=sys.stderr)
        return 1
    return 0


def _write(path: Path, data: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    sys.exit(main())
