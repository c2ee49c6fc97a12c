"""Measure the single-axis control period clock by clock (issue 16 item 3; docs/four_axes.md).

Runs today's ctrl_seq + xform + ref_gen + mpc_core + axis_status (tb/hdl/ctrl_seq_tb.v) in Icarus for a
few PWM periods with one control period per PWM period and logs, relative to the ADC trigger, every
engine step (pc, state entered), the xform front / mod, ref_ok, the core start / done, cmp_load and
the counter sweep.  From the log it derives the budget the four-axis design starts from:

    trigger -> cmp_load                 (LATENCY)
    engine steps that need no ADC sample (POS, ZERO, COPY, REF: could run before the trigger)
    ADC-dependent path: adc_valid -> cmp_load (front, DIFF, OM, FIX3, W6, ZPOS, END, core, mod)
    counter sweep length after cmp_load

for both tasks (speed: boot image, algorithm 1; position: algorithm-2 image uploaded and swapped in)
and for two ADC sample times: 68 clocks after the trigger (one SPI frame, main today) and 195 (the mean
of 4 back-to-back frames centred on the trigger, issue 14).

    .venv/bin/python flow/seq_timeline.py [--json build/reports/seq_timeline.json]

Needs Icarus Verilog and `make roms`.  About 3 s per case (4 cases).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import BUILD, HDL_TB, REPORTS, ROOT, rtl_sources, roms_dir  # noqa: E402

sys.path.insert(0, str(ROOT / "gen"))

HALF = 2500            # PWM half period (clocks) of the default configuration
PERIODS = 4            # PWM periods simulated; the last two are measured (steady state)

TB = r"""
`timescale 1ns/1ps
`default_nettype none
module seq_timeline;
    reg clk = 0, rst = 1;
    always #5 clk = ~clk;
    reg adc_trig = 0, period_start = 0, adc_valid = 0;
    reg cfg_we = 0, cfg_swap = 0; reg [9:0] cfg_addr = 0; reg [31:0] cfg_wdata = 0;
    wire cmp_load, ref_busy, front_sat, task_pos, core_ready, swap_pending, st_wr, st_sh, st_d, control_done;
    wire [35:0] cmp; wire [15:0] latency; wire [5:0] st_addr, sync_idx;
    ctrl_seq_tb dut (.clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .ppc(8'd1), .run(1'b1),
        .theta(16'd1234), .pos(32'd1000), .adc_valid(adc_valid), .cur0(13'sd100), .cur1(-13'sd40), .cur2(-13'sd60),
        .kdc(18'd65536), .kacc(18'sd0), .kacc_shift(5'd0), .id_ref(18'sd0), .iq_ref(18'sd16),
        .seg_we(1'b0), .seg_slot(4'd0), .seg_field(3'd0), .seg_wdata(32'd0), .start(1'b0), .start_slot(4'd0),
        .sync(1'b0), .sync_bit(1'b0), .sync_idx(sync_idx),
        .cfg_we(cfg_we), .cfg_addr(cfg_addr), .cfg_wdata(cfg_wdata), .cfg_swap(cfg_swap), .cnt_clear(1'b0),
        .cmp_load(cmp_load), .cmp(cmp), .ref_busy(ref_busy), .latency(latency), .front_sat(front_sat),
        .task_pos(task_pos), .core_ready(core_ready), .swap_pending(swap_pending), .st_wr(st_wr), .st_addr(st_addr),
        .st_sh(st_sh), .st_d(st_d), .control_done(control_done));
    reg [31:0] img [0:1023];
    integer i, t0, k;
    reg [2:0] est_d; reg [6:0] pc_d; reg ref_ok_d;
    initial begin
        for (i = 0; i < 1024; i = i + 1) img[i] = 0;
        if (`IMG != 0) $readmemh(`IMG_FILE, img);
        repeat (5) @(posedge clk);
        rst <= 0;
        wait (core_ready);
        @(posedge clk);
        if (`IMG != 0) begin
            for (i = 0; i < 768; i = i + 1) begin
                cfg_we <= 1; cfg_addr <= i; cfg_wdata <= img[i]; @(posedge clk);
            end
            cfg_we <= 0; cfg_swap <= 1; @(posedge clk); cfg_swap <= 0;
            wait (!swap_pending);
        end
        repeat (2000) @(posedge clk);             // ref_gen's reset sync, zero sweep
        for (k = 0; k < `PERIODS; k = k + 1) begin
            period_start <= 1; @(posedge clk); period_start <= 0;
            repeat (`HALF - 1) @(posedge clk);
            adc_trig <= 1; t0 = $time / 10; $display("P %0d", k); @(posedge clk); adc_trig <= 0;
            repeat (`ADC_LAT - 1) @(posedge clk);
            adc_valid <= 1; @(posedge clk); adc_valid <= 0;
            repeat (`HALF - `ADC_LAT - 1) @(posedge clk);
        end
        $finish;
    end
    always @(posedge clk) begin
        est_d <= dut.u_seq.est; pc_d <= dut.u_seq.pc; ref_ok_d <= dut.ref_ok;
        if (!rst) begin
            if (dut.u_seq.est != est_d || dut.u_seq.pc != pc_d)
                $display("E %0d %0d %0d", $time / 10 - t0, dut.u_seq.pc, dut.u_seq.est);
            if (dut.u_seq.xf_front) $display("X front %0d", $time / 10 - t0);
            if (dut.u_seq.xf_mod) $display("X mod %0d", $time / 10 - t0);
            if (dut.u_seq.xf_done) $display("X done %0d", $time / 10 - t0);
            if (dut.ref_ok && !ref_ok_d) $display("R ok %0d", $time / 10 - t0);
            if (dut.ref_advance) $display("R adv %0d", $time / 10 - t0);
            if (dut.core_start) $display("C start %0d", $time / 10 - t0);
            if (dut.core_done) $display("C done %0d", $time / 10 - t0);
            if (cmp_load) $display("L %0d %0d", $time / 10 - t0, latency);
            if (dut.sw_go) $display("S go %0d", $time / 10 - t0);
            if (dut.sw_end) $display("S end %0d", $time / 10 - t0);
            if (adc_valid) $display("A %0d", $time / 10 - t0);
        end
    end
endmodule
"""

ESTATE = {0: "IDLE", 1: "OP", 2: "STG", 3: "LD", 4: "PASS", 5: "FIX", 6: "WR", 7: "WR2"}


def run(img: str | None, adc_lat: int, work: Path) -> list[str]:
    work.mkdir(parents=True, exist_ok=True)
    roms = roms_dir()
    tb = work / "seq_timeline.v"
    tb.write_text(TB)
    srcs = [p for p in rtl_sources() if p.stem in ("ctrl_seq", "xform", "ref_gen", "axis_status", "mpc_core",
                                                   "mpc_operand", "mpc_lane", "mpc_mul18", "mpc_limiter",
                                                   "mpc_coef_mem", "mpc_boot")]
    defs = [f"-DIMG={1 if img else 0}", f"-DIMG_FILE=\"{roms / img}\"" if img else "-DIMG_FILE=\"\"",
            f"-DPERIODS={PERIODS}", f"-DHALF={HALF}", f"-DADC_LAT={adc_lat}"]
    out = work / "tl.vvp"
    subprocess.run(["iverilog", "-g2005", "-Wnone", "-o", str(out), f"-I{roms}", f"-I{ROOT / 'rtl'}", *defs,
                    "-s", "seq_timeline", str(tb), str(HDL_TB / "ctrl_seq_tb.v"), *map(str, srcs)],
                   check=True, cwd=work, capture_output=True)
    # BOOT_FILE / RSQRT_FILE resolve against the working directory: run in the ROM directory
    res = subprocess.run(["vvp", "-n", str(out)], check=True, cwd=roms, capture_output=True, text=True)
    return res.stdout.splitlines()


def analyse(lines: list[str], task_pos: bool) -> dict:
    """The last measured period: step table and the budget figures."""
    per = []
    for ln in lines:
        if ln.startswith("P "):
            per.append([])
        elif per:
            per[-1].append(ln)
    ev = per[-1]
    from empc.rtlmodel import ctrl_seq as cs  # noqa: PLC0415 (gen/ on sys.path above)
    steps = cs.programs(4)
    # engine steps: (pc, first clock in E_OP, first clock of the next step)
    enter = []
    for ln in ev:
        m = re.match(r"E (-?\d+) (\d+) (\d+)", ln)
        if m:
            t, pc, est = map(int, m.groups())
            if ESTATE[est] == "OP" and (not enter or enter[-1][0] != pc):
                enter.append((pc, t))
            if ESTATE[est] == "IDLE" and enter:
                enter.append((-1, t))
    tab = []
    for (pc, t), nxt in zip(enter, enter[1:]):
        if pc < 0:
            continue
        s = steps.get(pc)
        tab.append({"pc": pc, "op": s.op if s else "?", "src": s.src if s else "", "m": s.m if s else 0,
                    "start": t, "clocks": nxt[1] - t})

    def first(prefix):
        for ln in ev:
            if ln.startswith(prefix):
                return int(ln.split()[-1]) if not ln.startswith("L ") else int(ln.split()[1])
        return None

    t_adc = first("A ")
    t_front = first("X front")
    t_cstart, t_cdone = first("C start"), first("C done")
    t_mod = first("X mod")
    t_load = first("L ")
    t_sw, t_swend = first("S go"), first("S end")
    indep = sum(r["clocks"] for r in tab if r["pc"] < 64 and r["op"] in ("POS", "ZERO", "COPY", "REF"))
    dep = [r for r in tab if r["pc"] < 64 and r["op"] not in ("POS", "ZERO", "COPY", "REF")]
    return {
        "task": "position" if task_pos else "speed",
        "adc_valid": t_adc, "front_start": t_front, "core_start": t_cstart, "core_done": t_cdone,
        "mod_start": t_mod, "cmp_load": t_load, "sweep_start": t_sw, "sweep_end": t_swend,
        "engine_first_step": tab[0]["start"] if tab else None,
        "engine_end": next((r["start"] for r in tab if r["op"] == "END"), None),
        "engine_clocks_adc_independent": indep,
        "engine_steps_adc_dependent": dep,
        "adc_to_cmp_load": t_load - t_adc,
        "core_clocks": t_cdone - t_cstart,
        "mod_clocks": t_load - t_mod,
        "sweep_clocks": (t_swend - t_sw) if t_sw is not None and t_swend is not None else None,
        "steps": tab,
    }


CASES = {"speed_alg1": (None, False), "position_alg2": ("coef_alg2_position.hex", True)}


def measure(task: str, adc_lat: int) -> dict:
    """One case: ``task`` in CASES, the ADC sample ``adc_lat`` clocks after the trigger."""
    img, tp = CASES[task]
    return analyse(run(img, adc_lat, BUILD / "seq_timeline" / f"{task}_adc{adc_lat}"), tp)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", default=str(REPORTS / "seq_timeline.json"))
    a = ap.parse_args(argv)
    os.environ.setdefault("PYTHONPATH", str(ROOT / "gen"))
    rep = {}
    for task in CASES:
        for lat in (68, 195):
            key = f"{task}_adc{lat}"
            r = rep[key] = measure(task, lat)
            print(f"{key}: trig->cmp_load {r['cmp_load']}, adc_valid {r['adc_valid']} -> cmp_load "
                  f"{r['adc_to_cmp_load']}, front {r['front_start']}, core {r['core_start']}..{r['core_done']}, "
                  f"mod {r['mod_start']}, engine ADC-independent {r['engine_clocks_adc_independent']}, "
                  f"engine end {r['engine_end']}, sweep {r['sweep_start']}..{r['sweep_end']}")
    Path(a.json).parent.mkdir(parents=True, exist_ok=True)
    Path(a.json).write_text(json.dumps(rep, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
