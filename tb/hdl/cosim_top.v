// cosim_top: simulation wrapper for the RTL-in-the-loop motor co-simulation.
//
// lx_rocon_top (one axis) plus the plant-side pin emulators that must run every
// clock: quad_gen (encoder A/B/index from a target count written by Python once
// per half PWM period) and adc_spi_slave (answers the ADC SPI) fed by adc_ripple (the
// phase currents' codes written by Python once per PWM period, plus PWM ripple and noise
// per frame, and an optional single-frame fault code).  The CPU bus pins are driven by the EMC
// bus-functional model (tb/emc_bfm.py) through cpu_* and the resolved bus emc_d.
// HALL pins and the power-stage fault pin are driven directly from Python (slow signals).
//
// The clock runs here (Verilog delay, Verilator --timing), so Python never wakes up per clock
// edge.  Python wakes once per PWM period, at dbg_period_start: the per-period observation
// registers below hold what it used to wait for inside the period (the compare values loaded,
// the trigger-to-load latency and the latency from the ADC's valid (tb/test_closed_loop.py adds the
// fixed clocks from the window's last bit to valid), the run flag at the trigger, how many triggers and loads the
// period had) and a sticky monitor checks the bridges off on every clock after a trip.
// Fault co-simulations (issue 14) wait for pin events inside the fault's period only: the
// dbg_* ports below expose the events (ADC frame start, encoder error, watchdog expiry, ADC
// sample) so that nothing but the harness's ports needs VPI (tb/hdl/cosim_top.vlt).  clk_stop
// stops the fabric clock (clock-loss run); osc_run starts the loss-of-clock monitor's
// oscillator stand-in (u_top.u_clkmon.osc_sim, ~50 MHz), otherwise the monitor stays idle.
`default_nettype none
`timescale 1ns / 1ps
`include "empc_formats.vh"
module cosim_top #(
    parameter integer CPR = 4000,
    parameter integer STEP_CLKS = 16,
    parameter integer CLK_HALF_PS = 5000,
    parameter integer OSC_HALF_PS = 9985        // clk_mon's oscillator stand-in: ~50 MHz, not a multiple of clk
) (
    output reg         clk,            // fabric clock, generated here (clk_gen passes clk_in through)
    input  wire        rst_n,
    input  wire        clk_stop,       // fault injection: the fabric clock stops (low) while 1
    input  wire        osc_run,        // clk_mon's oscillator stand-in runs while 1
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
    output wire        dbg_adc_sclk,
    output wire        dbg_adc_cs_n,
    output wire        dbg_adc_valid,  // the sequencer's ADC sample is ready (mpc_axis.adc_valid)
    output wire        dbg_enc_err,    // encoder illegal-transition pulse (mpc_axis.enc_err_pulse)
    output wire        dbg_wdog_expired,
    // per-period observation (registered; read by Python at the next dbg_period_start)
    // (tb/hdl/cosim_obs.v)
    output wire [35:0] dbg_cmp_q,      // compare values at the last cmp_load
    output wire [15:0] dbg_lat_q,      // clocks from the last adc_trig to that cmp_load
    output wire [15:0] dbg_lat_valid_q, // clocks from the last ADC valid to that cmp_load
    output wire        dbg_run_trig,   // `running` at the last adc_trig
    output wire [3:0]  dbg_n_trig,     // adc_trig pulses since the last period start
    output wire [3:0]  dbg_n_load,     // cmp_load pulses since the last period start
    output wire        dbg_unsafe      // sticky: a bridge enable or PWM output high in a clock after one with trip
`ifdef COSIM_LOCKSTEP
    ,
    // proof of the MPC core's simulation-only clock gating (EMPC_SIM_GATE): an ungated copy on the
    // same inputs, every output compared every clock
    output reg  [31:0] dbg_ls_clocks,  // clocks compared
    output reg  [31:0] dbg_ls_gated,   // of them with the gated core's clock stopped
    output reg  [31:0] dbg_ls_errors,  // clocks with any output different
    output reg  [31:0] dbg_ls_first    // first such clock (dbg_ls_clocks at that time)
`endif
);
    // the clock runs in the simulator (Verilator --timing), not as a Python/GPI callback per edge
    initial clk = 1'b0;
    always #(CLK_HALF_PS / 1000.0) clk = ~clk & ~clk_stop;
    // clk_mon's oscillator stand-in (a register no RTL drives in simulation); idle unless osc_run
    always begin
        if (!osc_run) @(posedge osc_run);
        #(OSC_HALF_PS / 1000.0) u_top.u_clkmon.osc_sim = ~u_top.u_clkmon.osc_sim;
    end

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
    assign dbg_adc_cs_n = adc_cs_n;

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
    assign dbg_trip = u_top.g_axis[0].u_axis.u_per.trip;
    assign dbg_out_reg = {u_top.lo_r, u_top.hi_r};
    assign dbg_adc_valid = u_top.g_axis[0].u_axis.adc_valid;
    assign dbg_enc_err = u_top.g_axis[0].u_axis.u_per.enc_err_pulse;
    assign dbg_wdog_expired = u_top.wdog_expired;

    // the per-period observation registers and the MPC core's input words as the sequencer last wrote
    // them (core word map EMPC_IN_*): Python checks them against the model's every control period and
    // names the words that differ
    localparam integer IN_AW = $clog2(`EMPC_IN_WORDS);
    wire [`EMPC_IN_WORDS*`EMPC_SIG_W-1:0] dbg_in_words;
    cosim_obs #(.IN_AW(IN_AW)) u_obs (
        .clk(clk), .rst_n(rst_n), .period_start(dbg_period_start), .adc_trig(dbg_adc_trig),
        .adc_valid(u_top.g_axis[0].u_axis.adc_valid), .cmp_load(dbg_cmp_load), .cmp(dbg_cmp),
        .running(dbg_running), .trip(dbg_trip), .pins({pwm_en, pwm_out}),
        .in_we(u_top.g_axis[0].u_axis.u_core.in_we), .in_addr(u_top.g_axis[0].u_axis.u_core.in_addr[IN_AW-1:0]),
        .in_wdata(u_top.g_axis[0].u_axis.u_core.in_wdata), .cmp_q(dbg_cmp_q), .lat_q(dbg_lat_q),
        .lat_valid_q(dbg_lat_valid_q), .run_trig(dbg_run_trig), .n_trig(dbg_n_trig), .n_load(dbg_n_load),
        .unsafe(dbg_unsafe), .in_words(dbg_in_words));

`ifdef COSIM_LOCKSTEP
`ifndef EMPC_SIM_GATE
    COSIM_LOCKSTEP_needs_EMPC_SIM_GATE error_no_gating_to_prove();
`endif
    // the axis's core (gated) and an ungated reference fed from the same nets
    localparam integer LS_SW = `EMPC_SIG_W, LS_UW = `EMPC_U_W;
    localparam integer LS_W = 13 + 6 * LS_UW + 3 * LS_SW + `EMPC_OPW + 11 + 8;   // all outputs
    wire                  ls_busy, ls_done, ls_ready, ls_bank, ls_swap_pending, ls_boot_ok, ls_task_pos;
    wire                  ls_img_ok, ls_upl_ok, ls_swap_refused, ls_refused;
    wire                  ls_fw_hi, ls_fw_lo;
    wire [2*LS_UW-1:0]    ls_u, ls_du, ls_u_raw;
    wire [3*LS_SW-1:0]    ls_ebar;
    wire signed [`EMPC_OPW-1:0] ls_wn;
    wire [10:0]           ls_flags;
    wire [7:0]            ls_latency;
    mpc_core #(.SIM_GATE(0)) u_ls_ref (
        .clk(clk), .rst(u_top.g_axis[0].u_axis.u_core.rst), .start(u_top.g_axis[0].u_axis.u_core.start),
        .in_we(u_top.g_axis[0].u_axis.u_core.in_we), .in_addr(u_top.g_axis[0].u_axis.u_core.in_addr),
        .in_wdata(u_top.g_axis[0].u_axis.u_core.in_wdata), .busy(ls_busy), .done(ls_done), .u(ls_u),
        .du(ls_du), .u_raw(ls_u_raw), .ebar(ls_ebar), .wn(ls_wn), .flags(ls_flags), .latency(ls_latency),
        .fw_thr(u_top.g_axis[0].u_axis.u_core.fw_thr), .fw_hi(ls_fw_hi), .fw_lo(ls_fw_lo),
        .aw(u_top.g_axis[0].u_axis.u_core.aw),
        .cfg_we(u_top.g_axis[0].u_axis.u_core.cfg_we), .cfg_addr(u_top.g_axis[0].u_axis.u_core.cfg_addr),
        .cfg_wdata(u_top.g_axis[0].u_axis.u_core.cfg_wdata), .cfg_swap(u_top.g_axis[0].u_axis.u_core.cfg_swap),
        .swap_at(u_top.g_axis[0].u_axis.u_core.swap_at),
        .ready(ls_ready), .bank(ls_bank), .swap_pending(ls_swap_pending), .boot_ok(ls_boot_ok),
        .img_ok(ls_img_ok), .upl_ok(ls_upl_ok), .swap_refused(ls_swap_refused), .refused(ls_refused),
        .task_pos(ls_task_pos), .pwm_per_control(u_top.g_axis[0].u_axis.u_core.pwm_per_control));
    wire [LS_W-1:0] ls_out_ref = {ls_img_ok, ls_upl_ok, ls_swap_refused, ls_refused,
                               ls_busy, ls_done, ls_ready, ls_bank, ls_swap_pending, ls_boot_ok, ls_task_pos,
                               ls_u, ls_du, ls_u_raw, ls_ebar, ls_wn, ls_flags, ls_latency, ls_fw_hi, ls_fw_lo};
    wire [LS_W-1:0] ls_out_dut = {u_top.g_axis[0].u_axis.u_core.img_ok, u_top.g_axis[0].u_axis.u_core.upl_ok,
                               u_top.g_axis[0].u_axis.u_core.swap_refused, u_top.g_axis[0].u_axis.u_core.refused,
                               u_top.g_axis[0].u_axis.u_core.busy, u_top.g_axis[0].u_axis.u_core.done,
                               u_top.g_axis[0].u_axis.u_core.ready, u_top.g_axis[0].u_axis.u_core.bank,
                               u_top.g_axis[0].u_axis.u_core.swap_pending, u_top.g_axis[0].u_axis.u_core.boot_ok,
                               u_top.g_axis[0].u_axis.u_core.task_pos, u_top.g_axis[0].u_axis.u_core.u,
                               u_top.g_axis[0].u_axis.u_core.du, u_top.g_axis[0].u_axis.u_core.u_raw,
                               u_top.g_axis[0].u_axis.u_core.ebar, u_top.g_axis[0].u_axis.u_core.wn,
                               u_top.g_axis[0].u_axis.u_core.flags, u_top.g_axis[0].u_axis.u_core.latency,
                               u_top.g_axis[0].u_axis.u_core.fw_hi, u_top.g_axis[0].u_axis.u_core.fw_lo};
    initial begin
        dbg_ls_clocks = 32'd0;
        dbg_ls_gated = 32'd0;
        dbg_ls_errors = 32'd0;
        dbg_ls_first = 32'd0;
    end
    // sampled on the falling edge: both cores' outputs settled after the rising edge
    always @(negedge clk) begin
        dbg_ls_clocks <= dbg_ls_clocks + 32'd1;
        if (!u_top.g_axis[0].u_axis.u_core.sim_en) dbg_ls_gated <= dbg_ls_gated + 32'd1;
        if (ls_out_ref != ls_out_dut) begin
            if (dbg_ls_errors == 32'd0) dbg_ls_first <= dbg_ls_clocks;
            dbg_ls_errors <= dbg_ls_errors + 32'd1;
        end
    end
`endif
endmodule
`default_nettype wire
