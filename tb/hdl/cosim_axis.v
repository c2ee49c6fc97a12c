// cosim_axis: the plant side of one axis of the four-axis co-simulation (tb/hdl/cosim4_top.v,
// tb/test_closed_loop_4axes.py): the pin emulators that must run every clock and the per-period
// observation registers, with the same names as tb/hdl/cosim_top.v's ports, so that the one-axis
// co-simulation's Python (tb/test_closed_loop.py CoSim, FaultRun) drives and reads an instance of this
// module as it does cosim_top.
//
// quad_gen: encoder A/B/index from a target count written by Python once per half PWM period;
// adc_ripple + adc_spi_slave: the axis's three converters on the drive's shared SCLK / CS (the period's
// base codes written by Python once per PWM period of this axis, plus PWM ripple and noise per frame on
// this axis's own period, an optional single-frame fault code); HALL written by Python.  Python writes
// the registers below marked VPI (tb/hdl/cosim4_top.vlt); nothing in the design drives them.
// Observation: cosim_obs on this axis's signals of the drive (the harness wires them from mx_axes).
`default_nettype none
`timescale 1ns / 1ps
`include "empc_formats.vh"
module cosim_axis #(
    parameter integer CPR = 4000,
    parameter integer STEP_CLKS = 16,
    parameter integer IN_AW = $clog2(`EMPC_IN_WORDS)
) (
    input  wire        clk,
    input  wire        rst_n,
    // this axis's signals of the drive
    input  wire        period_start,
    input  wire        adc_trig,
    input  wire        adc_valid,
    input  wire        cmp_load,
    input  wire [35:0] cmp,
    input  wire [7:0]  per_cnt,
    input  wire        running,
    input  wire        trip,
    input  wire        in_we,
    input  wire [IN_AW-1:0] in_addr,
    input  wire [`EMPC_SIG_W-1:0] in_wdata,
    input  wire [2:0]  pwm_out,
    input  wire [2:0]  pwm_en,
    input  wire        adc_sclk,
    input  wire        adc_cs_n,
    // pins into the drive
    output wire        enc_a,
    output wire        enc_b,
    output wire        enc_idx,
    output wire [2:0]  hall_pins,
    output wire [2:0]  adc_miso,
    // observation (cosim_top's names)
    output wire        dbg_period_start,
    output wire [7:0]  dbg_per_cnt,
    output wire        dbg_adc_sclk,
    output wire        dbg_adc_cs_n,
    output wire        dbg_adc_valid,
    output wire [35:0] dbg_cmp_q,
    output wire [15:0] dbg_lat_q,
    output wire [15:0] dbg_lat_valid_q,
    output wire        dbg_run_trig,
    output wire [3:0]  dbg_n_trig,
    output wire [3:0]  dbg_n_load,
    output wire        dbg_unsafe,
    output wire [`EMPC_IN_WORDS*`EMPC_SIG_W-1:0] dbg_in_words
);
    // ---- written by Python (VPI) ----
    /* verilator lint_off UNDRIVEN */    // driven through VPI only (tb/hdl/cosim4_top.vlt)
    reg [31:0]        enc_target;
    reg               idx_enable;
    reg [2:0]         hall;
    reg [11:0]        adc_code0, adc_code1, adc_code2;    // period base codes
    reg signed [15:0] adc_amp0, adc_amp1, adc_amp2;       // ripple amplitudes (tb/hdl/adc_ripple.v)
    reg [31:0]        adc_seed;
    reg [3:0]         adc_noise;
    reg               adc_inj_en;                         // one frame: adc_inj_code on adc_inj_ch at adc_inj_tau
    reg signed [15:0] adc_inj_tau;
    reg [1:0]         adc_inj_ch;
    reg [11:0]        adc_inj_code;
    reg [2:0]         adc_hold;                           // channel i outputs adc_code<i> exactly
    reg [11:0]        adc_lead;                           // frames' leading-bit pattern (0 = correct)
    /* verilator lint_on UNDRIVEN */

    wire [31:0] enc_count;
    wire        enc_at_target;
    quad_gen #(.CPR(CPR), .STEP_CLKS(STEP_CLKS)) u_enc (
        .clk(clk), .rst(!rst_n), .target(enc_target), .idx_enable(idx_enable), .a(enc_a), .b(enc_b), .idx(enc_idx),
        .count(enc_count), .at_target(enc_at_target));
    assign hall_pins = hall;

    wire [11:0] rc0, rc1, rc2;
    adc_ripple #(.HALF_PERIOD(`EMPC_PWM_HALF_PERIOD)) u_ripple (
        .clk(clk), .period_start(period_start), .base0(adc_code0), .base1(adc_code1), .base2(adc_code2),
        .amp0(adc_amp0), .amp1(adc_amp1), .amp2(adc_amp2), .seed(adc_seed), .noise(adc_noise),
        .inj_en(adc_inj_en), .inj_tau(adc_inj_tau), .inj_ch(adc_inj_ch), .inj_code(adc_inj_code), .hold(adc_hold),
        .code0(rc0), .code1(rc1), .code2(rc2));
    adc_spi_slave u_adc (.sclk(adc_sclk), .cs_n(adc_cs_n), .code0(rc0), .code1(rc1), .code2(rc2),
                         .lead(adc_lead), .miso(adc_miso));

    assign dbg_period_start = period_start;
    assign dbg_per_cnt = per_cnt;
    assign dbg_adc_sclk = adc_sclk;
    assign dbg_adc_cs_n = adc_cs_n;
    assign dbg_adc_valid = adc_valid;
    cosim_obs #(.IN_AW(IN_AW)) u_obs (
        .clk(clk), .rst_n(rst_n), .period_start(period_start), .adc_trig(adc_trig), .adc_valid(adc_valid),
        .cmp_load(cmp_load), .cmp(cmp), .running(running), .trip(trip), .pins({pwm_en, pwm_out}),
        .in_we(in_we), .in_addr(in_addr), .in_wdata(in_wdata), .cmp_q(dbg_cmp_q), .lat_q(dbg_lat_q),
        .lat_valid_q(dbg_lat_valid_q), .run_trig(dbg_run_trig), .n_trig(dbg_n_trig), .n_load(dbg_n_load),
        .unsafe(dbg_unsafe), .in_words(dbg_in_words));
    wire unused = &{1'b0, enc_count, enc_at_target};
endmodule
`default_nettype wire
