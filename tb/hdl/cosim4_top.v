// cosim4_top: simulation wrapper of the four-axis RTL-in-the-loop co-simulation
// (tb/test_closed_loop_4axes.py, issue 16): lx_rocon_top at NAXES (mx_axes: one shared engine, carriers
// staggered by EMPC_PWM_STAGGER_<NAXES>, one ADC SCLK / CS for 3 x NAXES MISO) and per axis a
// cosim_axis (g_ax[n].u_ax: encoder, HALL and ADC pin emulators on the shared SCLK / CS, the axis's
// per-period observation registers).  The CPU bus pins are driven by the EMC bus-functional model
// (tb/emc_bfm.py) through cpu_* and the resolved bus emc_d, as in tb/hdl/cosim_top.v.
// The clock runs here (Verilog delay, Verilator --timing); Python wakes once per PWM period of each
// axis, at that axis's period start.  The axis's drive signals are taken from lx_rocon_top's mx_axes
// instance (hierarchical, simulation only).
// SPARE = 1 (tb/test_route_top.py): one more pin emulator, g_spare.u_ax (a cosim_axis with no axis of the
// drive behind it: its observation inputs tied off), on the first board lines beyond the axes' (IRC input
// NAXES, HALL set NAXES if the board has it, MISO lines 3 NAXES .. 3 NAXES + 2), so that the routing test
// can move an axis's inputs to lines it drives.  SPARE = 0 (the co-simulation): those lines are constant.
`default_nettype none
`timescale 1ns / 1ps
`include "empc_formats.vh"
`include "empc_regs.vh"
module cosim4_top #(
    parameter integer NAXES = 4,
    parameter integer CPR = 4000,
    parameter integer STEP_CLKS = 16,
    parameter integer CLK_HALF_PS = 5000,
    parameter integer SPARE = 0                 // 1: a spare pin emulator on the first unused board lines
) (
    output reg                  clk,            // fabric clock, generated here (clk_gen passes clk_in through)
    input  wire                 rst_n,
    // CPU bus (BFM)
    input  wire                 cpu_cs_n,
    input  wire                 cpu_oe_n,
    input  wire                 cpu_we_n,
    input  wire [13:0]          cpu_a,
    input  wire [31:0]          cpu_d,
    input  wire                 cpu_d_oe,
    output wire [31:0]          emc_d_seen,
    output wire                 cpu_irq,
    input  wire                 pwr_fault_n,    // power-stage fault pin (active low)
    output wire [`EMPC_ROUTE_OUTPUTS-1:0] pwm_out,   // the board's 16 outputs (out_route; reset map: 3a + p)
    output wire [`EMPC_ROUTE_OUTPUTS-1:0] pwm_en,
    output wire [1:0]           led
);
    initial clk = 1'b0;
    always #(CLK_HALF_PS / 1000.0) clk = ~clk;

    wire [31:0] emc_d;
    assign emc_d = cpu_d_oe ? cpu_d : 32'bz;
    assign emc_d_seen = emc_d;

    localparam integer IN_AW = $clog2(`EMPC_IN_WORDS);
    wire              adc_sclk, adc_cs_n;
    wire [NAXES-1:0]  enc_a, enc_b, enc_idx;
    wire [3*NAXES-1:0] hall, adc_miso;
    // the board's lines beyond the axes' (reset map: axis a on IRC a, HALL set a, ADC channels 3a + p):
    // IRC 0, HALL 000, MISO 1 (what out_route reads for a line the build lacks), except the spare's (SPARE)
    localparam integer NENC = `EMPC_ROUTE_ENC, NHALL = `EMPC_ROUTE_HALL, NADC = `EMPC_ROUTE_ADC;
    wire               sp_a, sp_b, sp_idx;     // the spare emulator's lines (SPARE = 0: the constants)
    wire [2:0]         sp_hall, sp_miso;
    wire [NENC-1:0]    b_enc_a = {{(NENC-NAXES){1'b0}}, enc_a} | ({{(NENC-1){1'b0}}, sp_a} << NAXES);
    wire [NENC-1:0]    b_enc_b = {{(NENC-NAXES){1'b0}}, enc_b} | ({{(NENC-1){1'b0}}, sp_b} << NAXES);
    wire [NENC-1:0]    b_enc_idx = {{(NENC-NAXES){1'b0}}, enc_idx} | ({{(NENC-1){1'b0}}, sp_idx} << NAXES);
    wire [3*NHALL-1:0] b_hall;
    wire [NADC-1:0]    b_miso = ({{(NADC-3*NAXES){1'b1}}, adc_miso} & ~({{(NADC-3){1'b0}}, 3'b111} << 3*NAXES))
                                | ({{(NADC-3){1'b0}}, sp_miso} << 3*NAXES);   // NADC = 16 >= 3 NAXES + 3
    generate if (NHALL > NAXES) begin : g_hpad
        assign b_hall = {{(3*NHALL-3*NAXES){1'b0}}, hall} | ({{(3*NHALL-3){1'b0}}, sp_hall} << 3*NAXES);
    end else begin : g_hfull
        assign b_hall = hall;
        wire unused_sp = &{1'b0, sp_hall};     // no HALL set left for the spare
    end endgenerate
    generate if (SPARE != 0) begin : g_spare
        cosim_axis #(.CPR(CPR), .STEP_CLKS(STEP_CLKS), .IN_AW(IN_AW)) u_ax (
            .clk(clk), .rst_n(rst_n), .period_start(u_top.g_mx.u_mx.period_start[0]), .adc_trig(1'b0),
            .adc_valid(1'b0), .cmp_load(1'b0), .cmp(36'd0), .per_cnt(8'd0), .running(1'b0), .trip(1'b0),
            .in_we(1'b0), .in_addr({IN_AW{1'b0}}), .in_wdata({`EMPC_SIG_W{1'b0}}), .pwm_out(3'b000),
            .pwm_en(3'b000), .adc_sclk(adc_sclk), .adc_cs_n(adc_cs_n), .enc_a(sp_a), .enc_b(sp_b),
            .enc_idx(sp_idx), .hall_pins(sp_hall), .adc_miso(sp_miso),
            /* verilator lint_off PINCONNECTEMPTY */
            .dbg_period_start(), .dbg_per_cnt(), .dbg_adc_sclk(), .dbg_adc_cs_n(), .dbg_adc_valid(), .dbg_cmp_q(),
            .dbg_lat_q(), .dbg_lat_valid_q(), .dbg_run_trig(), .dbg_n_trig(), .dbg_n_load(), .dbg_unsafe(),
            .dbg_in_words());
            /* verilator lint_on PINCONNECTEMPTY */
    end else begin : g_nospare
        assign {sp_a, sp_b, sp_idx, sp_hall} = 6'd0;
        assign sp_miso = 3'b111;
    end endgenerate
    genvar n;
    generate for (n = 0; n < NAXES; n = n + 1) begin : g_ax
        // core input words: mx_seq's address is {axis, word}
        wire [5+$clog2(NAXES):0] ia = u_top.g_mx.u_mx.core_in_addr;
        cosim_axis #(.CPR(CPR), .STEP_CLKS(STEP_CLKS), .IN_AW(IN_AW)) u_ax (
            .clk(clk), .rst_n(rst_n),
            .period_start(u_top.g_mx.u_mx.period_start[n]), .adc_trig(u_top.g_mx.u_mx.adc_trig[n]),
            .adc_valid(u_top.g_mx.u_mx.adc_valid[n]), .cmp_load(u_top.g_mx.u_mx.cmp_load[n]),
            .cmp(u_top.g_mx.u_mx.cmp), .per_cnt(u_top.g_mx.u_mx.u_seq.per_cnt[8*n +: 8]),
            .running(u_top.g_mx.u_mx.running[n]), .trip(u_top.g_mx.u_mx.g_ax[n].u_per.trip),
            .in_we(u_top.g_mx.u_mx.core_in_we && ia[5+$clog2(NAXES):6] == n),
            .in_addr(ia[IN_AW-1:0]), .in_wdata(u_top.g_mx.u_mx.core_in_wdata),
            .pwm_out(pwm_out[3*n +: 3]), .pwm_en(pwm_en[3*n +: 3]), .adc_sclk(adc_sclk), .adc_cs_n(adc_cs_n),
            .enc_a(enc_a[n]), .enc_b(enc_b[n]), .enc_idx(enc_idx[n]), .hall_pins(hall[3*n +: 3]),
            .adc_miso(adc_miso[3*n +: 3]),
            /* verilator lint_off PINCONNECTEMPTY */   // the observation ports: Python reads them by name
            .dbg_period_start(), .dbg_per_cnt(), .dbg_adc_sclk(), .dbg_adc_cs_n(), .dbg_adc_valid(), .dbg_cmp_q(),
            .dbg_lat_q(), .dbg_lat_valid_q(), .dbg_run_trig(), .dbg_n_trig(), .dbg_n_load(), .dbg_unsafe(),
            .dbg_in_words());
            /* verilator lint_on PINCONNECTEMPTY */
    end endgenerate

    lx_rocon_top #(.NAXES(NAXES)) u_top (
        .clk_in(clk), .rst_n_in(rst_n), .emc_cs_n(cpu_cs_n), .emc_oe_n(cpu_oe_n), .emc_we_n(cpu_we_n),
        .emc_a(cpu_a), .emc_d(emc_d), .cpu_irq(cpu_irq), .irc_a(b_enc_a), .irc_b(b_enc_b), .irc_idx(b_enc_idx),
        .irc_mark({NENC{1'b0}}), .hall(b_hall), .pwr_fault_n(pwr_fault_n), .pwm_out(pwm_out), .pwm_en(pwm_en),
        .adc_sclk(adc_sclk), .adc_cs_n(adc_cs_n), .adc_miso(b_miso), .led(led));
endmodule
`default_nettype wire
