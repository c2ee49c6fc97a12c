// cosim4_top: simulation wrapper of the four-axis RTL-in-the-loop co-simulation
// (tb/test_closed_loop_4axes.py, issue 16): lx_rocon_top at NAXES (mx_axes: one shared engine, carriers
// staggered by EMPC_PWM_STAGGER_<NAXES>, one ADC SCLK / CS for 3 x NAXES MISO) and per axis a
// cosim_axis (g_ax[n].u_ax: encoder, HALL and ADC pin emulators on the shared SCLK / CS, the axis's
// per-period observation registers).  The CPU bus pins are driven by the EMC bus-functional model
// (tb/emc_bfm.py) through cpu_* and the resolved bus emc_d, as in tb/hdl/cosim_top.v.
// The clock runs here (Verilog delay, Verilator --timing); Python wakes once per PWM period of each
// axis, at that axis's period start.  The axis's drive signals are taken from lx_rocon_top's mx_axes
// instance (hierarchical, simulation only).
`default_nettype none
`timescale 1ns / 1ps
`include "empc_formats.vh"
`include "empc_regs.vh"
module cosim4_top #(
    parameter integer NAXES = 4,
    parameter integer CPR = 4000,
    parameter integer STEP_CLKS = 16,
    parameter integer CLK_HALF_PS = 5000
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
    // IRC 0, HALL 000, MISO 1 (what out_route reads for a line the build lacks)
    localparam integer NENC = `EMPC_ROUTE_ENC, NHALL = `EMPC_ROUTE_HALL, NADC = `EMPC_ROUTE_ADC;
    wire [NENC-1:0]    b_enc_a = {{(NENC-NAXES){1'b0}}, enc_a};
    wire [NENC-1:0]    b_enc_b = {{(NENC-NAXES){1'b0}}, enc_b};
    wire [NENC-1:0]    b_enc_idx = {{(NENC-NAXES){1'b0}}, enc_idx};
    wire [3*NHALL-1:0] b_hall;
    wire [NADC-1:0]    b_miso = {{(NADC-3*NAXES){1'b1}}, adc_miso};     // NADC = 16 > 3 NAXES
    generate if (NHALL > NAXES) begin : g_hpad
        assign b_hall = {{(3*NHALL-3*NAXES){1'b0}}, hall};
    end else begin : g_hfull
        assign b_hall = hall;
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
