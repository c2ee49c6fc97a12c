// cosim_top: simulation wrapper for the RTL-in-the-loop motor co-simulation.
//
// lx_rocon_top (one axis) plus the plant-side pin emulators that must run every
// clock: quad_gen (encoder A/B/index from a target count written by Python once
// per half PWM period) and adc_spi_slave (answers the ADC SPI with the phase
// currents' codes written by Python).  The CPU bus pins are driven by the EMC
// bus-functional model (tb/emc_bfm.py) through cpu_* and the resolved bus emc_d.
// HALL pins are driven directly from Python (slow signals).
`default_nettype none
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
    input  wire [11:0] adc_code0,
    input  wire [11:0] adc_code1,
    input  wire [11:0] adc_code2,
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
    output wire        dbg_adc_sclk,   // the ADC's SCLK (its last rising edge: the last bit of the frame)
    output wire        dbg_adc_valid
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
    adc_spi_slave u_adc (.sclk(adc_sclk), .cs_n(adc_cs_n), .code0(adc_code0), .code1(adc_code1), .code2(adc_code2),
                         .lead(12'd0), .miso(adc_miso));

    lx_rocon_top #(.NAXES(1)) u_top (
        .clk_in(clk), .rst_n_in(rst_n), .emc_cs_n(cpu_cs_n), .emc_oe_n(cpu_oe_n), .emc_we_n(cpu_we_n),
        .emc_a(cpu_a), .emc_d(emc_d), .cpu_irq(cpu_irq), .irc_a(enc_a), .irc_b(enc_b), .irc_idx(enc_idx),
        .irc_mark(mark), .hall(hall), .pwm_out(pwm_out), .pwm_en(pwm_en), .adc_sclk(adc_sclk),
        .adc_cs_n(adc_cs_n), .adc_miso(adc_miso), .led(led));

    assign dbg_period_start = u_top.g_axis[0].u_axis.period_start;
    assign dbg_adc_trig = u_top.g_axis[0].u_axis.adc_trig;
    assign dbg_cmp_load = u_top.g_axis[0].u_axis.cmp_load;
    assign dbg_cmp = u_top.g_axis[0].u_axis.cmp;
    assign dbg_per_cnt = u_top.g_axis[0].u_axis.u_seq.per_cnt;
    assign dbg_running = u_top.g_axis[0].u_axis.running;
    assign dbg_trip = u_top.g_axis[0].u_axis.trip;
    assign dbg_adc_sclk = adc_sclk;
    assign dbg_adc_valid = u_top.g_axis[0].u_axis.adc_valid;
endmodule
`default_nettype wire
