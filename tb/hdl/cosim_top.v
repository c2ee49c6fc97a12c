// cosim_top: simulation wrapper for the RTL-in-the-loop motor co-simulation.
//
// lx_rocon_top (one axis) plus the plant-side pin emulators that must run every
// clock: quad_gen (encoder A/B/index from a target count written by Python once
// per half PWM period) and adc_spi_slave (answers the ADC SPI) fed by adc_ripple (the
// phase currents' codes written by Python once per PWM period, plus PWM ripple and noise
// per frame, and an optional single-frame fault code).  The CPU bus pins are driven by the EMC
// bus-functional model (tb/emc_bfm.py) through cpu_* and the resolved bus emc_d.
// HALL pins and the power-stage fault pin are driven directly from Python (slow signals).
// The loss-of-clock monitor's oscillator stand-in is u_top.u_clkmon.osc_sim (clk_mon): a test
// that wants the monitor starts a clock on it; otherwise the monitor stays disarmed-idle.
`default_nettype none
`include "empc_formats.vh"
module cosim_top #(
    parameter integer CPR = 4000,
    parameter integer STEP_CLKS = 16
) (
    input  wire        clk,            // fabric clock (clk_gen passes clk_in through in simulation)
    input  wire        rst_n,
    // CPU bus (BFM)
    input  wire        cpu_cs_n,
    input  wire        cpu_oe_n,
    input  wire        cpu_we_n,
    input  wire [13:0] cpu_a,
    input  wire [31:0] cpu_d,
    input  wire        cpu_d_oe,
    output wire [31:0] emc_d_seen,
    output wire        cpu_irq,
    // plant side
    input  wire [31:0] enc_target,
    input  wire        idx_enable,
    input  wire        mark,
    input  wire        enc_glitch,     // fault injection: toggle A and B together
    input  wire [2:0]  hall,
    input  wire        pwr_fault_n,    // power-stage fault pin (active low)
    input  wire [11:0] adc_code0,      // period base codes (ADC code of the period's mean current)
    input  wire [11:0] adc_code1,
    input  wire [11:0] adc_code2,
    input  wire signed [15:0] adc_amp0,   // ripple amplitudes (LSB, signed; see tb/hdl/adc_ripple.v)
    input  wire signed [15:0] adc_amp1,
    input  wire signed [15:0] adc_amp2,
    input  wire [31:0] adc_seed,
    input  wire [3:0]  adc_noise,
    input  wire        adc_inj_en,     // one frame: code adc_inj_code on channel adc_inj_ch at adc_inj_tau
    input  wire signed [15:0] adc_inj_tau,
    input  wire [1:0]  adc_inj_ch,
    input  wire [11:0] adc_inj_code,
    input  wire [2:0]  adc_hold,       // channel i outputs adc_code<i> exactly (frozen / stuck ADC)
    input  wire [11:0] adc_lead,       // leading-bit pattern of the frames (0 = correct; else frame error)
    output wire [31:0] enc_count,
    output wire        enc_at_target,
    output wire [2:0]  pwm_out,
    output wire [2:0]  pwm_en,
    output wire [1:0]  led,
    // observation points (hierarchical, simulation only)
    output wire        dbg_period_start,
    output wire        dbg_adc_trig,
    output wire        dbg_cmp_load,
    output wire [35:0] dbg_cmp,
    output wire [7:0]  dbg_per_cnt,
    output wire        dbg_running,
    output wire        dbg_trip,
    output wire [5:0]  dbg_out_reg,    // the bridge-command registers before the kill gate {lo, hi}
    output wire        dbg_adc_sclk
);
    wire [31:0] emc_d;
    assign emc_d = cpu_d_oe ? cpu_d : 32'bz;
    assign emc_d_seen = emc_d;

    wire enc_a0, enc_b0, enc_idx;
    wire enc_a = enc_a0 ^ enc_glitch;
    wire enc_b = enc_b0 ^ enc_glitch;
    quad_gen #(.CPR(CPR), .STEP_CLKS(STEP_CLKS)) u_enc (
        .clk(clk), .rst(!rst_n), .target(enc_target), .idx_enable(idx_enable), .a(enc_a0), .b(enc_b0), .idx(enc_idx),
        .count(enc_count), .at_target(enc_at_target));

    wire adc_sclk, adc_cs_n;
    wire [2:0] adc_miso;
    wire [11:0] rc0, rc1, rc2;
    adc_ripple #(.HALF_PERIOD(`EMPC_PWM_HALF_PERIOD)) u_ripple (
        .clk(clk), .period_start(dbg_period_start), .base0(adc_code0), .base1(adc_code1), .base2(adc_code2),
        .amp0(adc_amp0), .amp1(adc_amp1), .amp2(adc_amp2), .seed(adc_seed), .noise(adc_noise),
        .inj_en(adc_inj_en), .inj_tau(adc_inj_tau), .inj_ch(adc_inj_ch), .inj_code(adc_inj_code), .hold(adc_hold),
        .code0(rc0), .code1(rc1), .code2(rc2));
    adc_spi_slave u_adc (.sclk(adc_sclk), .cs_n(adc_cs_n), .code0(rc0), .code1(rc1), .code2(rc2),
                         .lead(adc_lead), .miso(adc_miso));
    assign dbg_adc_sclk = adc_sclk;

    lx_rocon_top #(.NAXES(1)) u_top (
        .clk_in(clk), .rst_n_in(rst_n), .emc_cs_n(cpu_cs_n), .emc_oe_n(cpu_oe_n), .emc_we_n(cpu_we_n),
        .emc_a(cpu_a), .emc_d(emc_d), .cpu_irq(cpu_irq), .irc_a(enc_a), .irc_b(enc_b), .irc_idx(enc_idx),
        .irc_mark(mark), .hall(hall), .pwr_fault_n(pwr_fault_n), .pwm_out(pwm_out), .pwm_en(pwm_en), .adc_sclk(adc_sclk),
        .adc_cs_n(adc_cs_n), .adc_miso(adc_miso), .led(led));

    assign dbg_period_start = u_top.g_axis[0].u_axis.period_start;
    assign dbg_adc_trig = u_top.g_axis[0].u_axis.adc_trig;
    assign dbg_cmp_load = u_top.g_axis[0].u_axis.cmp_load;
    assign dbg_cmp = u_top.g_axis[0].u_axis.cmp;
    assign dbg_per_cnt = u_top.g_axis[0].u_axis.u_seq.per_cnt;
    assign dbg_running = u_top.g_axis[0].u_axis.running;
    assign dbg_trip = u_top.g_axis[0].u_axis.trip;
    assign dbg_out_reg = {u_top.lo_r, u_top.hi_r};
endmodule
`default_nettype wire
