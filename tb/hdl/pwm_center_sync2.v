// pwm_center_sync2: simulation-only wrapper for tb/test_pwm_center.py: two
// pwm_center instances, the slave's sync_in driven by the master's sync_out
// (gated by `link`, so the slave can be started out of phase first).  Shared
// configuration inputs; separate resets so the two counters start at an
// arbitrary phase offset.  Master outputs m_*, slave outputs s_*.
`default_nettype none
`timescale 1ns / 1ps
module pwm_center_sync2 #(
    parameter integer NCH = 2,
    parameter integer PWM_HALF_PERIOD = 11,
    parameter integer CW = $clog2(PWM_HALF_PERIOD + 1),
    parameter integer DEAD_W = 4,
    parameter integer SLAVE_SYNC_STAGES = 2,
    parameter integer MASTER_SYNC_LEAD = 4
) (
    input  wire              clk,
    input  wire              rst_m,
    input  wire              rst_s,
    input  wire              enable,
    input  wire              mode,
    input  wire [DEAD_W-1:0] dead,
    input  wire [NCH*CW-1:0] cmp_in,
    input  wire              cmp_load,
    input  wire              sync_ext,
    input  wire              link,
    input  wire              fault,
    input  wire              fault_clear,
    output wire [NCH-1:0]    m_hi,
    output wire [NCH-1:0]    m_lo,
    output wire              m_period_start,
    output wire              m_adc_trig,
    output wire              m_sync_out,
    output wire              m_fault_latched,
    output wire              m_mode_eff,
    output wire              m_cmp_clip,
    output wire              m_on,
    output wire [NCH-1:0]    s_hi,
    output wire [NCH-1:0]    s_lo,
    output wire              s_period_start,
    output wire              s_adc_trig,
    output wire              s_sync_out,
    output wire              s_fault_latched,
    output wire              s_mode_eff,
    output wire              s_cmp_clip,
    output wire              s_on
);
    pwm_center #(
        .NCH(NCH), .PWM_HALF_PERIOD(PWM_HALF_PERIOD), .CW(CW), .DEAD_W(DEAD_W),
        .SYNC_STAGES(0), .SYNC_LEAD(MASTER_SYNC_LEAD)
    ) u_master (
        .clk(clk), .rst(rst_m), .enable(enable), .mode(mode), .dead(dead),
        .cmp_in(cmp_in), .cmp_load(cmp_load), .sync_in(sync_ext),
        .fault(fault), .fault_clear(fault_clear),
        .hi(m_hi), .lo(m_lo), .period_start(m_period_start), .adc_trig(m_adc_trig),
        .sync_out(m_sync_out), .fault_latched(m_fault_latched), .mode_eff(m_mode_eff), .on(m_on),
        .cmp_clip(m_cmp_clip)
    );
    pwm_center #(
        .NCH(NCH), .PWM_HALF_PERIOD(PWM_HALF_PERIOD), .CW(CW), .DEAD_W(DEAD_W),
        .SYNC_STAGES(SLAVE_SYNC_STAGES), .SYNC_LEAD(MASTER_SYNC_LEAD)
    ) u_slave (
        .clk(clk), .rst(rst_s), .enable(enable), .mode(mode), .dead(dead),
        .cmp_in(cmp_in), .cmp_load(cmp_load), .sync_in(m_sync_out & link),
        .fault(fault), .fault_clear(fault_clear),
        .hi(s_hi), .lo(s_lo), .period_start(s_period_start), .adc_trig(s_adc_trig),
        .sync_out(s_sync_out), .fault_latched(s_fault_latched), .mode_eff(s_mode_eff), .on(s_on),
        .cmp_clip(s_cmp_clip)
    );
endmodule
`default_nettype wire
