// pwm_center_phase: simulation-only wrapper for tb/test_pwm_center.py: two pwm_center
// instances with the same inputs (reset and sync_in included), u_a with PHASE = 0 and u_b
// with PHASE = PHASE (the carrier stagger of docs/four_axes.md D4).  Outputs a_*, b_*; the
// test reads the counters u_a.cnt / u_b.cnt through the hierarchy.
`default_nettype none
`timescale 1ns / 1ps
module pwm_center_phase #(
    parameter integer NCH = 3,
    parameter integer PWM_HALF_PERIOD = 13,
    parameter integer CW = $clog2(PWM_HALF_PERIOD + 1),
    parameter integer DEAD_W = 4,
    parameter integer SYNC_STAGES = 0,
    parameter integer SYNC_LEAD = 2,
    parameter integer PHASE = 5
) (
    input  wire              clk,
    input  wire              rst,
    input  wire              enable,
    input  wire              mode,
    input  wire [DEAD_W-1:0] dead,
    input  wire [NCH*CW-1:0] cmp_in,
    input  wire              cmp_load,
    input  wire              sync_in,
    input  wire              fault,
    input  wire              fault_clear,
    output wire [NCH-1:0]    a_hi,
    output wire [NCH-1:0]    a_lo,
    output wire              a_period_start,
    output wire              a_adc_trig,
    output wire              a_sync_out,
    output wire              a_fault_latched,
    output wire              a_mode_eff,
    output wire              a_cmp_clip,
    output wire              a_on,
    output wire [NCH-1:0]    b_hi,
    output wire [NCH-1:0]    b_lo,
    output wire              b_period_start,
    output wire              b_adc_trig,
    output wire              b_sync_out,
    output wire              b_fault_latched,
    output wire              b_mode_eff,
    output wire              b_cmp_clip,
    output wire              b_on
);
    pwm_center #(
        .NCH(NCH), .PWM_HALF_PERIOD(PWM_HALF_PERIOD), .CW(CW), .DEAD_W(DEAD_W),
        .SYNC_STAGES(SYNC_STAGES), .SYNC_LEAD(SYNC_LEAD), .PHASE(0)
    ) u_a (
        .clk(clk), .rst(rst), .enable(enable), .mode(mode), .dead(dead),
        .cmp_in(cmp_in), .cmp_load(cmp_load), .sync_in(sync_in),
        .fault(fault), .fault_clear(fault_clear),
        .hi(a_hi), .lo(a_lo), .period_start(a_period_start), .adc_trig(a_adc_trig),
        .sync_out(a_sync_out), .fault_latched(a_fault_latched), .mode_eff(a_mode_eff), .on(a_on),
        .cmp_clip(a_cmp_clip)
    );
    pwm_center #(
        .NCH(NCH), .PWM_HALF_PERIOD(PWM_HALF_PERIOD), .CW(CW), .DEAD_W(DEAD_W),
        .SYNC_STAGES(SYNC_STAGES), .SYNC_LEAD(SYNC_LEAD), .PHASE(PHASE)
    ) u_b (
        .clk(clk), .rst(rst), .enable(enable), .mode(mode), .dead(dead),
        .cmp_in(cmp_in), .cmp_load(cmp_load), .sync_in(sync_in),
        .fault(fault), .fault_clear(fault_clear),
        .hi(b_hi), .lo(b_lo), .period_start(b_period_start), .adc_trig(b_adc_trig),
        .sync_out(b_sync_out), .fault_latched(b_fault_latched), .mode_eff(b_mode_eff), .on(b_on),
        .cmp_clip(b_cmp_clip)
    );
endmodule
`default_nettype wire
