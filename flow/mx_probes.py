"""Area probes behind docs/four_axes.md (section 1.3): scratch RTL synthesised out of context.

Not deliverables: each probe copies rtl/ and flow/ into build/mx_probes/<probe>/, changes the copy
and runs the same flow/synth.py there, so the figures are comparable with `make bench` / `make synth`.

  core4   mpc_core with the coefficient banks of four axes in the same block RAMs (bank index
          {axis, bank}: memories 512 deep, header LUT-RAM 64 x 32, CFG registers 8 x 12), the input
          buffer {axis, word} (256 x 32) and bank / swap_pending per axis (a swap waits only for an
          update of its own axis).  Measured: 1195 / 1198 LUT (two runs), 1400 FF, 6 DSP48A1, 7.5 RAMB16
          (3 + 9 RAMB8), 117.6 / 122.0 MHz proxy; the unmodified core 1118 LUT, 1318 FF, 7.5 RAMB16,
          116.3 MHz.
  route   out_route: 16 outputs selected from 12 (axis, phase) pairs with the owner's trip, ADC channel,
          encoder and HALL input selects (section 5).  Measured: 374 LUT, 160 FF, 253 MHz proxy.

  Register read path (branch regslim, 2026-11-27; docs/four_axes.md section 8), out of context, yosys 0.70:
  regs_mux  axis_regs generated with the "mux" read style (one read register, a case) instead of the
            gated copies: 475 LUT / 348 FF (the copies: `flow/synth.py --top axis_regs`, 345 / 887).
  regs_nord axis_regs with its reg_rdata left open (what mx_axes keeps of it): 113 LUT / 316 FF, so the
            copies cost 232 LUT / 571 FF per axis.
  rd4       rtl/axis_rd.v (the read path shared by the axes) at NAXES = 4, copies: 805 LUT / 571 FF.
  rd4_mux   the same generated with the "mux" read style: 1004 LUT / 32 FF.
  eng_ff    the engine registers of four axes (KDC, KACC, ID_REF, IQ_REF, FW, FW_R2, IQ_HOLD: 133 bits)
            in flip-flops with the job_axis and the CPU (rax) multiplexers: 294 LUT / 532 FF.
  eng_ram   the same in LUT-RAM {axis} (a memory per register, read at job_axis and rax) with a written-since-
            reset flag per register and axis for the reset values: 48 RAM32M + 312 LUT = 504 LUT / 28 FF.

    .venv/bin/python flow/mx_probes.py [core4|route|base|regs_mux|regs_nord|rd4|rd4_mux|eng_ff|eng_ram ...]
    (about 1 min each; the register probes take PYTHONPATH=gen for the generator)
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from files import BUILD, ROOT, roms_dir  # noqa: E402

OUT_ROUTE = r"""// out_route (area probe for docs/four_axes.md, not a deliverable): routing table of issue 16 item 4.
// Output-centric select OUT_SEL[k] (0 = off, 1 + 3 a + p), per-(axis, phase) ADC channel, per-axis
// encoder and HALL input select; written only with every bridge off.
`default_nettype none
module out_route #(
    parameter integer NAX = 4, parameter integer NOUT = 16, parameter integer NENC = 8, parameter integer NMISO = 16
) (
    input  wire clk, input wire rst,
    input  wire sel_we, input wire [1:0] sel_word, input wire [31:0] wdata, input wire all_off,
    input  wire [3*NAX-1:0] hi, input wire [3*NAX-1:0] lo, input wire [NAX-1:0] trip,
    output reg  [NOUT-1:0] pin_hi, output reg [NOUT-1:0] pin_lo,
    input  wire [NMISO-1:0] miso, output wire [3*NAX-1:0] ax_miso,
    input  wire [4*NENC-1:0] enc, output wire [4*NAX-1:0] ax_enc,
    input  wire [3*NAX-1:0] hall, output wire [3*NAX-1:0] ax_hall
);
    reg [4*NOUT-1:0] osel;             // OUT_SEL0/1: 8 outputs x 4 bits per word
    reg [4*3*NAX-1:0] asel;            // ADC_SEL0/1: (axis, phase) -> channel
    reg [3*NAX-1:0] esel;              // ENC_SEL: axis -> encoder input
    reg [2*NAX-1:0] hsel;              // HALL_SEL: axis -> HALL set
    always @(posedge clk) begin
        if (rst) begin
            osel <= 0; asel <= 0; esel <= 0; hsel <= 0;
        end else if (sel_we && all_off) begin
            case (sel_word)
                2'd0: osel[31:0] <= wdata;
                2'd1: osel[63:32] <= wdata;
                2'd2: asel[31:0] <= wdata;
                default: {hsel, esel, asel[47:32]} <= wdata[8*NAX/2+4*NAX+15:0];
            endcase
        end
    end
    wire [3*NAX-1:0] tp;
    genvar b;
    generate for (b = 0; b < 3*NAX; b = b + 1) begin : g_tp
        assign tp[b] = trip[b/3];
    end endgenerate
    wire [15:0] hv = {{(15-3*NAX){1'b0}}, hi & ~tp, 1'b0};
    wire [15:0] lv = {{(15-3*NAX){1'b0}}, lo & ~tp, 1'b0};
    integer i;
    always @(posedge clk) begin
        for (i = 0; i < NOUT; i = i + 1) begin
            pin_hi[i] <= !rst && hv[osel[4*i +: 4]];
            pin_lo[i] <= !rst && lv[osel[4*i +: 4]];
        end
    end
    genvar a, q;
    generate for (a = 0; a < NAX; a = a + 1) begin : g_ax
        for (q = 0; q < 3; q = q + 1) begin : g_ph
            assign ax_miso[3*a+q] = miso[asel[4*(3*a+q) +: 4]];
            assign ax_hall[3*a+q] = hall[3*hsel[2*a +: 2]+q];
        end
        for (q = 0; q < 4; q = q + 1) begin : g_enc
            assign ax_enc[4*a+q] = enc[4*esel[3*a +: 3]+q];
        end
    end endgenerate
endmodule
`default_nettype wire
"""


def _edit_core(R: Path) -> None:
    """mpc_core for four axes: bank index {axis, bank}, input buffer {axis, word}, bank / swap per axis."""
    def sub(f, a, b, n=1):
        t = (R / f).read_text()
        c = t.count(a)
        assert c >= 1 and (n != 1 or c == 1), (f, a, c)
        (R / f).write_text(t.replace(a, b))

    # coefficient memory: bank index BB = 3 bits (two banks per axis, the axis as the high bits)
    f = "mpc_coef_mem.v"
    sub(f, "    parameter integer N = `EMPC_N,\n",
        "    parameter integer N = `EMPC_N,\n    parameter integer BB = 3,\n")
    sub(f, "input  wire                        wbank,", "input  wire [BB-1:0]               wbank,")
    sub(f, "input  wire                        rbank,", "input  wire [BB-1:0]               rbank,")
    sub(f, "wire [6:0] wa_col  = {wbank, coff[5:0]};", "wire [BB+5:0] wa_col  = {wbank, coff[5:0]};")
    sub(f, "wire [6:0] wa_gain = {wbank, goff[7:2]};", "wire [BB+5:0] wa_gain = {wbank, goff[7:2]};")
    for nm in ("alg2_b", "pos_b", "ncols_b", "neff_b"):
        txt = (R / f).read_text()
        (R / f).write_text(re.sub(nm + r" \[0:1\]", nm + " [0:(1<<BB)-1]", txt))
    sub(f, "for (b = 0; b < 2; b = b + 1) begin", "for (b = 0; b < (1<<BB); b = b + 1) begin")
    sub(f, "wbank == b[0]", "wbank == b[BB-1:0]", n=0)
    sub(f, "reg [SW-1:0] m_hdr [0:15];", "reg [SW-1:0] m_hdr [0:(8<<BB)-1];")
    sub(f, "for (hi = 0; hi < 16; hi = hi + 1)", "for (hi = 0; hi < (8<<BB); hi = hi + 1)")
    sub(f, "[0:2*MAXC-1]", "[0:(1<<BB)*MAXC-1]", n=0)
    # operand ALU: input buffer {axis, word}
    f = "mpc_operand.v"
    sub(f, "    input  wire [5:0]                    in_addr,",
        "    input  wire [7:0]                    in_addr,\n    input  wire [1:0]                    rax,")
    sub(f, "reg [SW-1:0] abuf [0:`EMPC_IN_WORDS-1];", "reg [SW-1:0] abuf [0:4*`EMPC_IN_WORDS-1];")
    sub(f, "for (bi = 0; bi < `EMPC_IN_WORDS; bi = bi + 1) abuf[bi]",
        "for (bi = 0; bi < 4*`EMPC_IN_WORDS; bi = bi + 1) abuf[bi]")
    sub(f, "wire [SW-1:0] a_rd = abuf[a_addr];", "wire [SW-1:0] a_rd = abuf[{rax, a_addr}];")
    # core: the update's axis latched at start, bank / swap_pending per axis
    f = "mpc_core.v"
    sub(f, "    input  wire [5:0]                      in_addr,",
        "    input  wire [7:0]                      in_addr,\n    input  wire [1:0]                      axis,\n"
        "    input  wire [1:0]                      cfg_axis,")
    sub(f, "    output reg                             bank,\n    output reg                             swap_pending,",
        "    output reg  [3:0]                      bank,\n    output reg  [3:0]                      swap_pending,")
    sub(f, "    reg         w_bank;", "    reg  [2:0]  w_bank;\n    reg  [1:0]  ax_r;")
    sub(f, "        if (rst) w_bank <= 1'b0;\n        else     w_bank <= ready_r & ~bank;",
        "        if (rst) w_bank <= 3'd0;\n        else     w_bank <= {cfg_axis, ready_r & ~bank[cfg_axis]};")
    sub(f, "            bank <= 1'b0;\n            swap_pending <= 1'b0;",
        "            bank <= 4'd0;\n            swap_pending <= 4'd0;\n            ax_r <= 2'd0;")
    sub(f, "            if (!busy && ready_r && (swap_pending || cfg_swap)) begin\n"
           "                bank <= ~bank;\n"
           "                swap_pending <= 1'b0;\n"
           "            end else if (cfg_swap && ready_r) begin\n"
           "                swap_pending <= 1'b1;\n"
           "            end",
        "            if (start_ok) ax_r <= axis;\n"
        "            for (sa = 0; sa < 4; sa = sa + 1)\n"
        "                if (!(busy && ax_r == sa[1:0]) && ready_r &&\n"
        "                    (swap_pending[sa] || (cfg_swap && cfg_axis == sa[1:0]))) begin\n"
        "                    bank[sa] <= ~bank[sa];\n"
        "                    swap_pending[sa] <= 1'b0;\n"
        "                end else if (cfg_swap && cfg_axis == sa[1:0] && ready_r) begin\n"
        "                    swap_pending[sa] <= 1'b1;\n"
        "                end")
    sub(f, "    always @(posedge clk) begin\n        if (rst) begin\n            busy <= 1'b0;",
        "    integer sa;\n    always @(posedge clk) begin\n        if (rst) begin\n            busy <= 1'b0;")
    sub(f, "mpc_coef_mem #(.N(N)) u_mem (", "mpc_coef_mem #(.N(N), .BB(3)) u_mem (")
    sub(f, ".rbank(bank),", ".rbank({ax_r, bank[ax_r]}),")
    sub(f, "        .in_we(in_we), .in_addr(in_addr), .in_wdata(in_wdata),\n        .kind(kind0)",
        "        .in_we(in_we), .in_addr(in_addr), .in_wdata(in_wdata), .rax(ax_r),\n        .kind(kind0)")


ENG_PROBE = r"""// eng_probe (area probe for docs/four_axes.md, not a deliverable): the engine registers of four axes
// in flip-flops (LUTRAM = 0: per-axis registers, the job_axis and CPU multiplexers) or in LUT-RAM {axis}
// (LUTRAM = 1: a memory per register read at job_axis and rax; written-since-reset flags give the reset values)
`default_nettype none
module eng_probe #(parameter integer LUTRAM = 0) (
    input wire clk, input wire rst, input wire [1:0] wax, input wire [6:0] we, input wire [31:0] wd,
    input wire [1:0] jax, input wire [1:0] rax, output wire [132:0] j, output wire [132:0] c);
    localparam [132:0] RST = {12'd1000, 32'h12345678, 8'd3, 18'd0, 18'd0, 27'h1234567, 18'h10000};
    localparam integer NR = 7;
    function integer W; input integer i; W = (i==0)?18:(i==1)?27:(i==2)?18:(i==3)?18:(i==4)?8:(i==5)?32:12; endfunction
    function integer LSB; input integer i; integer k; begin LSB = 0; for (k = 0; k < i; k = k + 1) LSB = LSB + W(k); end
    endfunction
    genvar i;
    generate if (LUTRAM == 0) begin : g_ff
        reg [132:0] r0, r1, r2, r3;
        for (i = 0; i < NR; i = i + 1) begin : g_r
            always @(posedge clk)
                if (rst) begin
                    r0[LSB(i) +: W(i)] <= RST[LSB(i) +: W(i)]; r1[LSB(i) +: W(i)] <= RST[LSB(i) +: W(i)];
                    r2[LSB(i) +: W(i)] <= RST[LSB(i) +: W(i)]; r3[LSB(i) +: W(i)] <= RST[LSB(i) +: W(i)];
                end else if (we[i]) case (wax)
                    2'd0: r0[LSB(i) +: W(i)] <= wd[W(i)-1:0];
                    2'd1: r1[LSB(i) +: W(i)] <= wd[W(i)-1:0];
                    2'd2: r2[LSB(i) +: W(i)] <= wd[W(i)-1:0];
                    default: r3[LSB(i) +: W(i)] <= wd[W(i)-1:0];
                endcase
        end
        assign j = (jax == 0) ? r0 : (jax == 1) ? r1 : (jax == 2) ? r2 : r3;
        assign c = (rax == 0) ? r0 : (rax == 1) ? r1 : (rax == 2) ? r2 : r3;
    end else begin : g_ram
        for (i = 0; i < NR; i = i + 1) begin : g_r
            reg [W(i)-1:0] m [0:3];
            reg [3:0] vf;
            always @(posedge clk) begin
                if (we[i]) m[wax] <= wd[W(i)-1:0];
                if (rst) vf <= 4'd0; else if (we[i]) vf[wax] <= 1'b1;
            end
            assign j[LSB(i) +: W(i)] = vf[jax] ? m[jax] : RST[LSB(i) +: W(i)];
            assign c[LSB(i) +: W(i)] = vf[rax] ? m[rax] : RST[LSB(i) +: W(i)];
        end
    end endgenerate
endmodule
`default_nettype wire
"""


def _regs_probe(d: Path, name: str) -> tuple[str, list[str]]:
    """Scratch RTL of the register read-path probes: (top, synth.py --param arguments)."""
    from dataclasses import replace
    from empc import regblock, regmap
    b = next(x for x in regmap.BLOCKS if x.module == "axis_regs")
    rtl, args = d / "rtl", []
    if name == "regs_mux":
        (rtl / "axis_regs.v").write_text(regblock.render(replace(b, read="mux")))
        return "axis_regs", args
    if name in ("rd4", "rd4_mux"):
        (rtl / "axis_rd.v").write_text(regblock.render_shared(replace(b, read="mux") if name == "rd4_mux" else b))
        return "axis_rd", ["--param", "NAXES=4"]
    if name == "regs_nord":             # axis_regs with its read data unused (a wrapper without the port)
        P = regblock.ports(b)
        ins = [(n, w) for dr, n, w, _, _ in P if dr == "input"]
        outs = [(n, w) for dr, n, w, _, _ in P if dr == "output" and n not in ("reg_rdata", "rd_vals", "sh_we")]
        text = "\n".join(["module regs_nord (", ",\n".join([f"    input wire [{w - 1}:0] {n}" for n, w in ins] +
                                                            [f"    output wire [{w - 1}:0] {n}" for n, w in outs]),
                          ");", "    /* verilator lint_off PINCONNECTEMPTY */",
                          "    axis_regs u (" + ", ".join(f".{n}({n})" for n, _ in ins + outs) +
                          ", .reg_rdata(), .rd_vals()" + (", .sh_we()" if regblock.sh_n(b) else "") + ");",
                          "endmodule", ""])
        new, top = rtl / "regs_nord.v", "regs_nord"
    else:
        new, top = rtl / "eng_probe.v", "eng_probe"
        new.write_text(ENG_PROBE)
        args = ["--param", f"LUTRAM={int(name == 'eng_ram')}"]
        text = None
    if text is not None:
        new.write_text(text)
    filelist = next(rtl.glob("*.f"))
    with open(filelist, "a") as f:
        f.write(f"{new.relative_to(d)}\n")
    return top, args


def probe(name: str) -> Path:
    """Build the scratch tree of probe ``name`` and synthesise it; returns the report path."""
    d = BUILD / "mx_probes" / name
    shutil.rmtree(d, ignore_errors=True)
    (d / "constraints").mkdir(parents=True)
    shutil.copytree(ROOT / "rtl", d / "rtl")
    shutil.copytree(ROOT / "flow", d / "flow", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "constraints" / "resource_budget.json", d / "constraints")
    top = {"core4": "mpc_core", "base": "mpc_core", "route": "out_route"}.get(name, "")
    args: list[str] = []
    if name in ("regs_mux", "regs_nord", "rd4", "rd4_mux", "eng_ff", "eng_ram"):
        top, args = _regs_probe(d, name)
    elif name == "core4":
        _edit_core(d / "rtl")
    elif name == "route":
        new = d / "rtl" / "out_route.v"
        new.write_text(OUT_ROUTE)
        filelist = next((d / "rtl").glob("*.f"))            # the scratch copy's file list (flow/files.py)
        with open(filelist, "a") as f:
            f.write(f"{new.relative_to(d)}\n")
    env = dict(os.environ, EMPC_ROMS=str(roms_dir()))
    subprocess.run([sys.executable, str(d / "flow" / "synth.py"), "--top", top, "--no-budget"] + args, cwd=d, env=env,
                   check=True)
    return max((d / "build" / "reports").glob(f"synth_{top}*.json"), key=lambda f: f.stat().st_mtime)


if __name__ == "__main__":
    for n in sys.argv[1:] or ["base", "core4", "route"]:
        print(n, probe(n))
